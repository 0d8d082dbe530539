#pragma once
// Forward kinematics with its last few answers kept. A physics step asks for the same joint
// angles several times: the proxy's pose now (to bound its fingers' speed), the tracked hand's
// (its goal, and later the grasp rule's view of the glove), and the goal it then takes. Each
// forward kinematics is a sine and cosine per DH row; a repeat is a compare and a copy.
//
// A repeat is the same angles bit for bit, so an answer is exactly what forward_kinematics
// gives. The model is fixed for the memo's life (a memo per hand).

#include <array>
#include <cstdint>

#include "hand/hand_model.hpp"

namespace vcockpit::hand {

class KinematicsMemo {
 public:
  explicit KinematicsMemo(const HandModel& model) : model_(&model) {}

  // forward_kinematics(model, q, out), from a kept answer when q is one of the last few asked.
  void solve(const JointAngles& q, HandLinkPoses& out);
  // Keeps `links` as the answer for `q` (computed elsewhere, e.g. moved with a proxy's fingers).
  void remember(const JointAngles& q, const HandLinkPoses& links);
  void forget() { entries_ = {}; }

  uint64_t hits() const { return hits_; }
  uint64_t misses() const { return misses_; }

 private:
  struct Entry {
    bool valid = false;
    JointAngles q{};
    HandLinkPoses links;
  };
  static constexpr int kEntries = 4;

  Entry& next_slot();

  const HandModel* model_;
  std::array<Entry, kEntries> entries_{};
  int next_ = 0;  // the slot the next new answer takes (first in, first out)
  uint64_t hits_ = 0;
  uint64_t misses_ = 0;
};

}  // namespace vcockpit::hand
