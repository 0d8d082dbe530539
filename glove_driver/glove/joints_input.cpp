#include "glove_driver/glove/joints_input.hpp"

#include <stdexcept>

#include "hand/tracking/joints_replay.hpp"

namespace vcockpit::glove {

JointsInput joints_input(const std::string& path, const hand::HandModel& right,
                         const JointsInputOptions& options) {
  using namespace hand::tracking;
  const JointsLog log = read_joints_log(path);
  bool has[2] = {false, false};
  for (const JointsFrame& f : log.frames) has[f.left_hand ? 1 : 0] = true;
  bool left = false;
  if (options.left_hand) {
    left = *options.left_hand;
    if (!has[left ? 1 : 0])
      throw std::invalid_argument(path + ": the log has no " + (left ? "left" : "right") + " hand");
  } else if (has[0] && has[1]) {
    throw std::invalid_argument(path + ": the log has both hands: give --side (a glove driver per hand)");
  } else {
    left = has[1];
  }
  std::vector<JointsFrame> frames;
  for (const JointsFrame& f : log.frames)
    if (f.left_hand == left) frames.push_back(f);
  const JointsReplay replay = replay_joints(frames, log.space, right, options.calibrate, options.palm_G);
  const ReplayedHand& replayed = replay.hands[left ? 1 : 0];
  if (replayed.samples.empty())
    throw JointsLogError(path + ": no frame of the " + (left ? "left" : "right") + " hand has a palm to place");
  JointsInput out;
  out.log.path = path;
  out.log.left_hand = left;
  out.log.samples = replayed.samples;
  out.frames_G = replayed.frames_G;
  out.hand = replayed.model;
  out.tip_error_p50_m = replayed.tip_error_p50_m;
  out.tip_error_p99_m = replayed.tip_error_p99_m;
  out.unplaced_frames = replayed.unplaced_frames;
  return out;
}

}  // namespace vcockpit::glove
