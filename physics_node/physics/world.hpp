#pragma once
// One world step (paper §4, Box2D's b2World_Step in spirit), in named, timed stages:
//   hand kinematics -> broadphase -> narrowphase -> virtual forces -> (grasp) -> motion
// repeated over substeps short enough for the stiffest contact that can happen within the step
// (dt_sub <= safety sqrt(m/k) over the pairs whose boxes, grown by how far they can move, meet),
// then the grasp test on the last substep's contacts: attach (eqs. 28-29) or release.
//
// Deterministic: fixed steps, no clock in the results (stage timings are observations only),
// every container iterated in a fixed order. The same scene and inputs give bit-identical states.

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/collision.hpp"
#include "physics_node/physics/contact_forces.hpp"
#include "physics_node/physics/grasp.hpp"
#include "physics_node/physics/grasp_tracker.hpp"
#include "physics_node/physics/scene.hpp"
#include "physics_node/physics/substep_choice.hpp"

namespace vcockpit::physics {

// What the tracked hand looks like now: the wrist in the world and the 22 joint angles.
struct HandInput {
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  JointAngles q_rad{};
  bool tracking = true;  // false: glove lost; the hand stays, held objects are let go
};

enum class Stage : uint8_t {
  kHandKinematics, kBroadphase, kNarrowphase, kForces, kGrasp, kIntegrate, kCount
};
constexpr int kStageCount = static_cast<int>(Stage::kCount);
const char* stage_name(Stage stage);

struct StageTimes {
  std::array<int64_t, kStageCount> ns{};  // wall time per stage over the last step
};

// Hand-object penetration over the last step (m).
struct PenetrationStats {
  double max_m = 0.0;
  double sum_m = 0.0;
  int points = 0;
};

class World {
 public:
  explicit World(Scene scene);
  ~World();

  // The hand from now on (applied over the next step, interpolated across its substeps).
  void set_hand_input(const HandInput& input);
  void step();

  const Scene& scene() const { return scene_; }
  int64_t time_ns() const { return time_ns_; }
  uint64_t step_count() const { return steps_; }
  int substeps() const { return substeps_; }  // of the last step (chosen every step)
  int hand_id() const { return hand_id_; }
  bool hand_active() const { return hand_active_; }

  const std::vector<BodyState>& bodies() const { return bodies_; }
  const Eigen::Isometry3d& X_GH() const { return X_GH_; }
  const std::array<Eigen::Isometry3d, kLinkCount>& X_GL() const { return X_GL_; }
  // Pose of the held object in the hand frame (eq. 28), valid while held.
  const Eigen::Isometry3d& X_HO(int object) const { return grasp_[object].X_HO; }

  const std::vector<GraspEvent>& step_events() const { return events_; }
  const std::vector<AppliedContact>& contacts() const { return applied_; }
  const StageTimes& stage_times() const { return stage_times_; }
  const PenetrationStats& hand_penetration() const { return penetration_; }

 private:
  int choose_substeps();
  void substep(double dt_s, double alpha, bool skip_held_hand_pairs);
  void move_hand(double alpha);
  void move_held_objects(double dt_s);
  void build_contact_bodies();
  void integrate(double dt_s);
  void grasp_stage();

  Scene scene_;
  CollisionWorld collision_;
  SubstepChoice substep_choice_;
  ContactForceModel forces_;
  GraspTracker grasp_tracker_;
  int object_count_;
  int substeps_;
  int hand_id_ = 0;
  int64_t step_ns_;
  int64_t time_ns_ = 0;
  uint64_t steps_ = 0;

  std::vector<BodyState> bodies_;
  std::vector<Eigen::Isometry3d> X_GO_;  // collision input, all objects
  std::vector<Eigen::Isometry3d> X_GO_before_;  // held objects' pose one substep ago
  std::vector<GraspHold> grasp_;
  std::vector<Eigen::Matrix3d> I_O_inv_;  // inverse body-frame inertia, dynamic objects
  std::vector<uint8_t> held_mask_;        // 1 for the objects held at the start of this step

  bool hand_active_ = false;
  HandInput hand_from_;  // at the start of the step
  HandInput hand_to_;    // at its end
  Eigen::Isometry3d X_GH_ = Eigen::Isometry3d::Identity();
  std::array<Eigen::Isometry3d, kLinkCount> X_GL_;
  std::array<Eigen::Isometry3d, kLinkCount> X_GL_before_;
  HandLinkPoses link_poses_;

  std::vector<ContactPoint> contacts_;
  std::vector<ContactBody> contact_bodies_;
  std::vector<Eigen::Vector3d> F_G_;
  std::vector<Eigen::Vector3d> M_G_;
  std::vector<AppliedContact> applied_;
  std::vector<HandContact> hand_contacts_;
  std::vector<GraspEvent> events_;
  StageTimes stage_times_;
  PenetrationStats penetration_;
};

}  // namespace vcockpit::physics
