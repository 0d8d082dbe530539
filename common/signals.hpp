#pragma once
// SIGINT/SIGTERM turn into a flag the main loops poll, so nodes shut down cleanly (DDS entities
// deleted, files renamed into place) instead of dying mid-write.

namespace vcockpit {

// Installs the handlers (and install_crash_backtrace's); call once from main before the loop.
void install_shutdown_handlers();

// True once SIGINT or SIGTERM arrived (or request_shutdown was called).
bool shutdown_requested();

// Lets code (and tests) ask for the same clean shutdown a signal would.
void request_shutdown();

}  // namespace vcockpit
