#pragma once
// A node that crashes says where: on SIGSEGV, SIGBUS, SIGFPE, SIGILL or SIGABRT the signal and
// the stack (addresses, as binary(+offset): addr2line -e BINARY OFFSET names them) go to stderr,
// which the rig keeps in the node's log; then the signal's default action, so the exit status
// stays 128+N (and a core is dumped where the system keeps them). Not installed under the
// sanitizers, which report these themselves.

namespace vcockpit {

void install_crash_backtrace();
// False under the sanitizers, where install_crash_backtrace leaves their handlers.
bool crash_backtrace_available();

}  // namespace vcockpit
