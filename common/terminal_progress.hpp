#pragma once
// A one-line progress display on stderr, redrawn at most 4 times a second, only when stderr is a
// terminal (logs and pipes stay clean).

#include <cstdint>
#include <string>

namespace vcockpit {

class TerminalProgress {
 public:
  TerminalProgress();
  // position and total in seconds of simulated or log time; rate = those seconds per wall second
  void update(int64_t now_ns, double position_s, double total_s, double rate, uint64_t samples);
  void finish();

 private:
  bool enabled_;
  int64_t last_draw_ns_ = 0;
  bool drawn_ = false;
};

}  // namespace vcockpit
