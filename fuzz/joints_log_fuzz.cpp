// Hand-joints logs (hand/tracking/joints_log_reader.cpp) and what retargeting makes of them
// (hand/tracking/retarget.cpp): any bytes are either a log or a JointsLogError, and any frame of a
// log within a room's reach retargets to angles within the joints' ranges and a finite hand.

#include <cmath>

#include "fuzz/fuzz_support.hpp"
#include "hand/tracking/joints_log.hpp"
#include "hand/tracking/retarget.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  using namespace vcockpit::hand::tracking;
  static const hand::HandModel right = fuzz::default_hand();
  static const hand::HandModel left = hand::mirrored(right);
  const fuzz::MemFile file(fuzz::as_text(data, size));
  try {
    const JointsLog log = read_joints_log(file.path());
    fuzz::require(!log.frames.empty(), "a log has frames");
    Retargeter retarget[2] = {Retargeter(right), Retargeter(left)};
    for (const JointsFrame& f : log.frames) {
      bool in_reach = true;
      for (const TrackedJoint& j : f.joints) {
        fuzz::require(!j.valid || j.p_m.allFinite(), "finite valid joints");
        fuzz::require(!j.has_orientation || std::abs(j.q.norm() - 1.0) < 1e-9, "unit orientations");
        in_reach = in_reach && (!j.valid || j.p_m.norm() < 100.0);
      }
      if (!in_reach) continue;
      const hand::HandModel& model = f.left_hand ? left : right;
      const RetargetResult& r = retarget[f.left_hand ? 1 : 0].fit(f);
      fuzz::require(r.X_GH.matrix().allFinite(), "a finite hand");
      for (int j = 0; j < hand::kJointCount; ++j) {
        const double q = r.q_rad[static_cast<std::size_t>(j)];
        fuzz::require(q >= model.joints[static_cast<std::size_t>(j)].min_rad &&
                          q <= model.joints[static_cast<std::size_t>(j)].max_rad,
                      "angles within the joints' ranges");
      }
    }
  } catch (const JointsLogError&) {
  }
  return 0;
}
