#pragma once
// What the importers of trackers' JSON recordings share (leapjs_import, mediapipe_import): the
// file read as JSON, errors naming the frame and the field, each hand's time kept increasing,
// and what an import counts.

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hand/tracking/joints_log.hpp"

namespace vcockpit::hand::tracking {

// Throws JointsLogError: the file cannot be opened, or is not JSON.
nlohmann::json read_json_file(const std::string& path);

// Errors "<path>: frame N: what".
class FrameErrors {
 public:
  explicit FrameErrors(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void fail(std::size_t frame, const std::string& what) const;
  // A finite number, or fail naming `field`.
  double number(const nlohmann::json& v, std::size_t frame, const std::string& field) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Each hand's frames in increasing time: a row whose time does not pass its hand's last is
// refused (the importers skip and count it).
class HandTimes {
 public:
  bool take(bool left_hand, int64_t t_ns) {
    int64_t& last = last_ns_[left_hand ? 1 : 0];
    if (t_ns <= last) return false;
    last = t_ns;
    return true;
  }

 private:
  std::array<int64_t, 2> last_ns_ = {INT64_MIN, INT64_MIN};
};

struct TrackerImport {
  std::vector<JointsFrame> frames;  // in time order, a row per hand
  int source_frames = 0;            // frames in the file
  int frames_without_hands = 0;
  int frames_out_of_order = 0;      // a hand's time not increasing: skipped
};

}  // namespace vcockpit::hand::tracking
