#include "common/crash_backtrace.hpp"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <initializer_list>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define VCOCKPIT_SANITIZER_REPORTS_CRASHES 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define VCOCKPIT_SANITIZER_REPORTS_CRASHES 1
#endif
#endif

namespace vcockpit {
namespace {

void write_text(const char* text) {
  const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

// Only async-signal-safe calls: write, backtrace (loaded before, see below), backtrace_symbols_fd.
extern "C" void on_fatal_signal(int signal_number) {
  char text[64] = "\nfatal signal ";
  char digits[8];
  int n = 0;
  for (int v = signal_number; v > 0 && n < 7; v /= 10) digits[n++] = static_cast<char>('0' + v % 10);
  std::size_t at = std::strlen(text);
  while (n > 0 && at < sizeof text - 16) text[at++] = digits[--n];
  std::strcpy(text + at, "; the stack:\n");
  write_text(text);
  void* frames[64];
  const int count = backtrace(frames, 64);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // SA_RESETHAND put the default action back: the signal again ends the process as it would have
  ::raise(signal_number);
}

}  // namespace

bool crash_backtrace_available() {
#ifdef VCOCKPIT_SANITIZER_REPORTS_CRASHES
  return false;
#else
  return true;
#endif
}

void install_crash_backtrace() {
#ifndef VCOCKPIT_SANITIZER_REPORTS_CRASHES
  // backtrace() loads libgcc's unwinder on its first call: make that call here, not in a handler
  void* frame[1];
  backtrace(frame, 1);
  // a stack of its own, so that a stack overflow is reported too
  static char alternate_stack[64 * 1024];
  stack_t stack{};
  stack.ss_sp = alternate_stack;
  stack.ss_size = sizeof alternate_stack;
  sigaltstack(&stack, nullptr);
  struct sigaction action {};
  action.sa_handler = on_fatal_signal;
  action.sa_flags = SA_RESETHAND | SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  for (const int signal_number : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) sigaction(signal_number, &action, nullptr);
#endif
}

}  // namespace vcockpit
