#pragma once
// A glove log with known faults, written as a user's file would be: 100 Hz runs with gaps between
// them, every joint column but palm_arch (one missing column), index_mcp past its limit in a
// given number of rows (clamped values), the hand 3 m above the cockpit moving at 0.2 m/s along x
// (it touches nothing).

#include <sstream>
#include <string>
#include <string_view>

#include "hand/hand_joints.hpp"

namespace vcockpit::test {

class CraftedGloveLog {
 public:
  static constexpr double kSpeed_mps = 0.2;

  CraftedGloveLog() {
    csv_ << "# crafted glove log\nt_s,x_m,y_m,z_m,qw,qx,qy,qz";
    for (int j = 0; j < hand::kJointCount; ++j) {
      const std::string_view name = hand::joint_name(static_cast<hand::Joint>(j));
      if (name != "palm_arch") csv_ << ',' << name << "_rad";
    }
    csv_ << '\n';
  }
  // Rows every 10 ms over [from_ms, to_ms]; the first `clamp_rows` with index_mcp at 5 rad.
  void run(int from_ms, int to_ms, int clamp_rows = 0) {
    for (int ms = from_ms; ms <= to_ms; ms += 10) {
      csv_ << ms / 1000.0 << ',' << kSpeed_mps * ms / 1000.0 << ",0,3,1,0,0,0";
      for (int j = 0; j < hand::kJointCount; ++j) {
        const std::string_view name = hand::joint_name(static_cast<hand::Joint>(j));
        if (name == "palm_arch") continue;
        const bool clamp = name == "index_mcp" && clamp_rows > 0;
        csv_ << ',' << (clamp ? 5.0 : 0.1);
        if (clamp) {
          --clamp_rows;
          ++clamped_;
        }
      }
      csv_ << '\n';
      ++rows_;
    }
  }
  std::string text() const { return csv_.str(); }
  int rows() const { return rows_; }
  int clamped() const { return clamped_; }

 private:
  std::ostringstream csv_;
  int rows_ = 0;
  int clamped_ = 0;
};

}  // namespace vcockpit::test
