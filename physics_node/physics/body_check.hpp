#pragma once
// The check of every dynamic body after each step (MuJoCo's mj_checkPos / mj_checkVel: warn and
// recover, never crash): a body whose state is not finite or is beyond the scene's SanityLimits
// is put back where it was at the start of the step (the scene's initial pose if that was broken
// too) at rest, counted, and reported once as data. The physics logs nothing: the adapters name
// the object (step_faults: the objects found broken for the first time in the last step).

#include <cstdint>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

enum class BodyFaultKind : uint8_t {
  kNone,
  kNonFinite,  // a NaN or infinity in the pose or the velocities
  kTooFast,    // |v| > max_speed_mps
  kSpinning,   // |w| > max_spin_radps
  kTooFar,     // |p| > max_distance_m from the world origin
};

const char* body_fault_name(BodyFaultKind what);

// The first thing wrong with a body's state, kNone when it is sound.
BodyFaultKind check_body(const BodyState& body, const SanityLimits& limits);

struct BodyFault {
  int object = -1;
  BodyFaultKind what = BodyFaultKind::kNone;  // what was wrong the first time
  int64_t first_t_ns = 0;                     // the end of the step that first found it
  uint64_t count = 0;                         // steps that found it broken
};

class BodyCheck {
 public:
  explicit BodyCheck(const Scene& scene);  // the scene must outlive this

  // After a step: checks the dynamic bodies, and puts a broken one back to its state in
  // `start` (the step's start), at rest. No allocation.
  void check(std::vector<BodyState>& bodies, const std::vector<BodyState>& start, int64_t t_ns);

  // whether the last check put `object` back (its contacts' cached impulses are not to be trusted)
  bool recovered(int object) const { return recovered_[static_cast<std::size_t>(object)] != 0; }
  bool any_recovered() const { return any_recovered_; }
  const std::vector<BodyFault>& faults() const { return faults_; }          // every object found
  const std::vector<BodyFault>& new_faults() const { return new_faults_; }  // first found now
  void clear_new_faults() { new_faults_.clear(); }

 private:
  void recover(int object, BodyState& body, const BodyState& start) const;

  const Scene& scene_;
  std::vector<uint8_t> recovered_;  // per object: put back by the last check
  bool any_recovered_ = false;
  std::vector<int> fault_of_;  // per object: its index in faults_, -1 before its first fault
  std::vector<BodyFault> faults_;
  std::vector<BodyFault> new_faults_;
};

}  // namespace vcockpit::physics
