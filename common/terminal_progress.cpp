#include "common/terminal_progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace vcockpit {

TerminalProgress::TerminalProgress() : enabled_(isatty(STDERR_FILENO) == 1) {}

void TerminalProgress::update(int64_t now_ns, double position_s, double total_s, double rate,
                              uint64_t samples) {
  if (!enabled_ || now_ns - last_draw_ns_ < 250'000'000) return;
  last_draw_ns_ = now_ns;
  drawn_ = true;
  const double eta_s = rate > 0 ? (total_s - position_s) / rate : 0.0;
  std::fprintf(stderr, "\r  %8.2f / %.2f s  %5.1f%%  x%.2f  %llu samples  ETA %6.1f s ",
               position_s, total_s, total_s > 0 ? 100.0 * position_s / total_s : 100.0, rate,
               static_cast<unsigned long long>(samples), eta_s);
  std::fflush(stderr);
}

void TerminalProgress::finish() {
  if (drawn_) std::fputc('\n', stderr);
  drawn_ = false;
}

}  // namespace vcockpit
