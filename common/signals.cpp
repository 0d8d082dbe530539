#include "common/signals.hpp"

#include "common/crash_backtrace.hpp"

#include <atomic>
#include <csignal>

namespace vcockpit {
namespace {

std::atomic<bool> g_shutdown{false};
static_assert(std::atomic<bool>::is_always_lock_free, "flag must be safe in a signal handler");

extern "C" void on_shutdown_signal(int) { g_shutdown.store(true); }

}  // namespace

void install_shutdown_handlers() {
  struct sigaction action {};
  action.sa_handler = on_shutdown_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // a reader that went away must not kill a writer of files or sockets
  signal(SIGPIPE, SIG_IGN);
  install_crash_backtrace();  // and a crash says where, in the node's log
}

bool shutdown_requested() { return g_shutdown.load(std::memory_order_relaxed); }

void request_shutdown() { g_shutdown.store(true); }

}  // namespace vcockpit
