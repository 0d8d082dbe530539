#include "hand/kinematics_memo.hpp"

#include <cstring>

namespace vcockpit::hand {
namespace {

bool same_bits(const JointAngles& a, const JointAngles& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

}  // namespace

KinematicsMemo::Entry& KinematicsMemo::next_slot() {
  Entry& slot = entries_[static_cast<std::size_t>(next_)];
  next_ = (next_ + 1) % kEntries;
  return slot;
}

void KinematicsMemo::solve(const JointAngles& q, HandLinkPoses& out) {
  for (const Entry& e : entries_) {
    if (e.valid && same_bits(e.q, q)) {
      out = e.links;
      ++hits_;
      return;
    }
  }
  ++misses_;
  forward_kinematics(*model_, q, out);
  Entry& slot = next_slot();
  slot.valid = true;
  slot.q = q;
  slot.links = out;
}

void KinematicsMemo::remember(const JointAngles& q, const HandLinkPoses& links) {
  for (Entry& e : entries_) {
    if (e.valid && same_bits(e.q, q)) {
      e.links = links;
      return;
    }
  }
  Entry& slot = next_slot();
  slot.valid = true;
  slot.q = q;
  slot.links = links;
}

}  // namespace vcockpit::hand
