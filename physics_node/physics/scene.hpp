#pragma once
// The constant model of a world (MuJoCo's mjModel, in spirit): objects with shape, mass,
// material and initial state, the hand, gravity, the step, and every contact and grasp
// threshold. Built once from config (physics_config) and never changed by stepping.

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physics_node/physics/control.hpp"
#include "physics_node/physics/hand_names.hpp"
#include "model/triangle_mesh.hpp"

namespace vcockpit::physics {

enum class ShapeKind : uint8_t { kBox, kSphere, kCapsule, kCylinder, kMesh };

// Dimensions in metres. Box: full extents x, y, z. Sphere: radius. Capsule and cylinder:
// radius and length along the object's z axis (a capsule's length excludes its end caps).
// Mesh: triangles from a model file in the object's frame (model/import); a static object
// collides with its triangles (a BVH), a moving one with their convex hull, whose solid also
// gives its volume and inertia (a moving mesh's frame is its hull's centroid).
struct Shape {
  ShapeKind kind = ShapeKind::kBox;
  Eigen::Vector3d box_size_m = Eigen::Vector3d::Zero();
  double radius_m = 0.0;
  double length_m = 0.0;
  std::shared_ptr<const model::TriangleMesh> mesh;  // kMesh
  std::shared_ptr<const model::TriangleMesh> hull;  // kMesh, moving: the convex hull of `mesh`
  model::Bounds mesh_bounds;                        // kMesh: of both (the same extremes)
  // kMesh: the file it came from (the image generator loads the same), and where the file's
  // node origin is in the object's frame (not at it for a moving mesh, framed at its centroid)
  struct MeshSource {
    std::string file;
    std::string node;
    double scale = 1.0;
    bool z_up = false;
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
  } mesh_source;

  static Shape box(const Eigen::Vector3d& size_m);
  static Shape sphere(double radius_m);
  static Shape capsule(double radius_m, double length_m);
  static Shape cylinder(double radius_m, double length_m);
  // `hull`: the convex hull of `mesh` (model::convex_hull), in the same frame; null for a static
  // object (volume and inertia are then 0, reaches over the mesh's vertices)
  static Shape triangle_mesh(std::shared_ptr<const model::TriangleMesh> mesh,
                             std::shared_ptr<const model::TriangleMesh> hull);

  double volume_m3() const;
  // Inertia about the centroid in the shape's own frame for a uniform density (kg m^2).
  Eigen::Matrix3d unit_density_inertia() const;
  // Radius of the smallest centred sphere holding the shape (m).
  double bounding_radius_m() const;
  // For each of the shape's own axes, the largest distance of a point of the shape from it (m):
  // the longest lever a contact force can have about that axis.
  Eigen::Vector3d axis_reach_m() const;
};

// Contact material (paper §4.2). A pair's stiffness is k1 k2 / (k1 + k2) (eqs. 11-14), its
// friction coefficients the geometric means (Box2D, Jolt), its damping from the damping ratio.
struct Material {
  double stiffness_Npm = 1.0e5;
  double damping_ratio = 0.7;
  double mu_s = 0.6;  // static
  double mu_d = 0.4;  // dynamic (sliding)
  // Rolling and spinning resistance (the contact solver's rolling rows), lengths: the couples against
  // rolling and against spinning about the normal are at most mu_roll N and mu_spin N. 0 turns
  // either off. mu_roll: 0.1 mm is MuJoCo's default: a 3 cm ball rolling at 0.5 m/s on a hard
  // top stops after ~5 m (rolling resistance coefficient mu_roll / r = 0.003). mu_spin: a
  // pressed patch of radius a resists spinning with (3 pi / 16) mu_d a N; a ~ 1 mm.
  double mu_roll_m = 1.0e-4;
  double mu_spin_m = 5.0e-4;
};

// A pair's stiffness: the two materials as springs in series, k1 k2 / (k1 + k2).
inline double pair_stiffness(const Material& a, const Material& b) {
  return a.stiffness_Npm * b.stiffness_Npm / (a.stiffness_Npm + b.stiffness_Npm);
}

struct ObjectSpec {
  std::string name;
  bool dynamic = false;
  Shape shape;
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();  // initial pose of the centroid frame
  double mass_kg = 0.0;                                     // 0 for static objects
  Eigen::Matrix3d I_O = Eigen::Matrix3d::Zero();            // inertia about the centroid, frame O
  Eigen::Vector3d v_G = Eigen::Vector3d::Zero();            // initial linear velocity (m/s)
  Eigen::Vector3d w_G = Eigen::Vector3d::Zero();            // initial angular velocity (rad/s)
  Material material;
  std::array<float, 4> color_rgba{0.6f, 0.6f, 0.6f, 1.0f};
  // A static object's look, when it is not its shape: a model's part drawn in its place, placed
  // as the shape is (the node's origin at the object's frame); the object still collides as
  // `shape` (the renderer's model, the physics' box: docs/models.md, "A look")
  std::optional<Shape> look;
  int control = -1;  // >= 0: the moving part of Scene::controls[control], which owns its motion
};

// Stable grasp (paper §4.4) and the hysteresis around it. Forces in N, torques in N m.
// How the gesture constraint of §4.4 is read (docs/ARCHITECTURE.md, "Stable grasp").
enum class GestureRule : uint8_t {
  kNone,     // no gesture constraint: any hand contact meeting eqs. 30-31 grasps (the paper's
             // relaxed test without its fix, kept for the study)
  kPaper,    // the literal reading: more than 2 links, the thumb among them, and every other
             // touching finger's normal more than alpha0 from the thumb's
  kProject,  // the thumb (or, for a power grasp, the palm) and the fingers opposed to it by more
             // than alpha0 make more than 2 links; a finger touching at less than alpha0 (a ring
             // finger wrapping round a bar's end) neither counts nor vetoes
};

// What may let go of an object once it is held.
enum class HoldRule : uint8_t {
  // the stable-grasp test on the proxy's contacts every step, at its looser held thresholds
  // (the paper's re-evaluation; the study's paper rules)
  kContactTest,
  // the grip the tracked hand makes: only the glove opening from its grip, the tracked thumb (or
  // palm) or every opposed finger leaving the object's surface, a handover, a reset or a lost
  // glove. The proxy's fingers rest on an attached object that cannot move to balance them, so
  // the forces on it say nothing about whether the pilot still holds it.
  kTrackedGrip,
};

struct GraspParams {
  double xi_N = 3.0;           // eq. 30: |sum F| over hand contacts + gravity
  double eta_Nm = 0.3;         // eq. 31: |sum M| about the centroid
  double alpha0_deg = 120.0;   // thumb vs each finger contact-normal angle must exceed this
  GestureRule gesture_rule = GestureRule::kProject;
  HoldRule hold_rule = HoldRule::kTrackedGrip;
  bool palm_opposition = true;  // the palm may oppose the fingers instead of the thumb
  int min_contacts = 3;        // hand links touching the object ("more than 2")
  // kContactTest only: while held, this many links suffice (a pinch holds what it lifted); a
  // control's joint is taken by this many (a pinch turns a knob)
  int exit_min_contacts = 2;
  double exit_scale = 4.0;     // while held, xi and eta are this much looser (hysteresis)
  double exit_alpha_margin_deg = 15.0;  // kContactTest: while held, the angle may drop this far
  double min_hold_s = 0.2;     // no release (but for a lost glove) before this
  double release_delay_s = 0.03;  // the condition must fail this long before a release
  double regrab_cooldown_s = 0.3;  // no new grasp of the same object for this long after release
  double velocity_window_s = 0.02;  // released object takes the hand's velocity over this window
  // ... unless the hand was slower than settle_speed_mps over settle_window_s: then it is setting
  // the object down, and the object takes that longer window's mean velocity, over which a
  // tracker's jitter averages out (0.5 mm at 60 Hz reads as 0.05-0.1 m/s over 20 ms, and a ball
  // set down that way rolled off the console). settle_speed_mps 0: off.
  double settle_speed_mps = 0.15;
  double settle_window_s = 0.1;
  // A held object is let go when the tracked fingers that gripped it have opened by
  // release_opening_share of the flexion they had at the grasp (the sum of each finger's flexion
  // angles, averaged over those fingers), and by at least release_opening_deg (a grip of nearly
  // straight fingers would otherwise let go at a tracker's jitter): the pilot's own hand opening,
  // which the proxy's fingers, resting on the object's surface, do not show. share 0: off.
  // A release for the tracked thumb or fingers leaving (release_gap_m) is named the hand opening
  // too when they have opened by release_opening_deg from the tightest they closed to since.
  double release_opening_share = 0.2;
  double release_opening_deg = 15.0;
  // kTrackedGrip: let go when the tracked thumb (or the opposing palm), or every finger that was
  // opposed at the grasp, is this much farther from the object's surface than it was at the
  // grasp (the hand moved off it; GraspHold::grip_gap_m).
  double release_gap_m = 0.005;
};

// Contact model details beyond the paper's equations. The contact springs are soft constraints
// at the full step (contact_solver.hpp: the same springs, backward Euler): one solve a step.
struct ContactParams {
  double slip_speed_mps = 1.0e-3;  // eq. 15-17 epsilon: |v_t| at or above it is sliding
  int max_points_per_pair = 4;
  // Gauss-Seidel sweeps with the springs' bias, then relax sweeps without it on impacts
  // and rebounds (faster than the threshold), then the dashpot's restitution for those impacts
  int iterations = 8;
  int relax_iterations = 2;
  double restitution_threshold_mps = 0.1;
};

// Sleeping (sleep.hpp; Box2D's and Jolt's): a free object that has stayed slower than these for
// time_s, with everything it touches as still (its island), is put to sleep: it costs no
// collision, force or integration until something that moves touches it.
struct SleepParams {
  bool enabled = true;
  // the fastest point of it: centroid speed plus spin times its farthest reach (Box2D v3's
  // test; a ball rolling at this speed counts as moving whatever its size)
  double speed_mps = 0.01;
  double time_s = 0.5;  // Box2D's time to sleep
};

// The proxy hand (proxy_hand.hpp): the hand that touches the world follows the tracked hand
// through bounded coupling, a god-object per link in the spirit of Borst & Indugula (2005) and
// Jacobs & Froehlich (2011): it goes where the tracked hand goes as far as the world lets it.
struct ProxyParams {
  bool enabled = true;             // false: the links are where the tracked hand is (the paper's)
  double max_speed_mps = 3.0;      // the wrist's catch-up speed toward the tracked hand
  double max_spin_radps = 30.0;    // the wrist's catch-up rotation rate
  double push_speed_mps = 0.3;     // how fast the hand moves while it pushes a free object
  double grip_force_N = 8.0;       // a link goes into an object only as deep as this force needs,
  double grip_weight_ratio = 3.0;  // or this many times the object's weight (at 1 g), if less
  double static_depth_m = 2.0e-4;  // how deep a link may rest in a static object
  // A finger link that a loose object weighing at least grip_force_N, or a pivoting lever's
  // handle, holds back short of the tracked finger pulls the wrist away from the object (a
  // lighter one is pushed along): the fingers' coupling is this many times as stiff as the
  // wrist's, so a finger held back by u alone moves the wrist by u r / (1 + r) along the contact
  // normal. A grip closing round a heavy object or a handle centres on it (a thumb stopped by a
  // bar draws the fingers in onto its far side) instead of stopping short on one side; the hand
  // keeps that pull while it holds. 0: the wrist ignores the fingers.
  double finger_pull_ratio = 1.0;
  // A hand whose links are in a loose object by more than this when it appears (its first input,
  // or an instructor's reset that puts the object back round it) passes through it until they
  // are in it no deeper than this (GraspHold::passing_through); shallower, its contacts push it
  // out as any other. With or without the proxy.
  double pass_through_depth_m = 0.005;
};

// Beyond these a body's state is taken as broken (nothing in a cockpit gets there; a blown-up
// contact or a bad state does): after each step such a body is put back where it was at the
// step's start, at rest, and counted (MuJoCo's mj_checkPos / mj_checkVel warn and reset).
struct SanityLimits {
  double max_speed_mps = 100.0;    // a thrown object ~20 m/s, a hand ~10 m/s
  double max_spin_radps = 1000.0;  // ~160 rev/s: a spun knob or a tossed pen stays well below
  double max_distance_m = 1000.0;  // from the world origin: a cockpit is a few metres across
};

struct Scene {
  Eigen::Vector3d gravity_mps2{0.0, 0.0, -9.81};
  double step_s = 0.001;
  std::vector<ObjectSpec> objects;
  std::vector<ControlSpec> controls;  // each moves one dynamic object (ControlSpec::body)
  // The simulated hands, each with its own model (hand.yaml, or its mirror for a left hand):
  // none (objects only), one, or a right and a left (hand_id_of: 0 right, 1 left, as the topics
  // name them; no two of the same side).
  std::vector<HandModel> hands;
  Material hand_material{2.0e4, 0.7, 1.0, 0.8};  // skin on a glove: grippy and soft
  GraspParams grasp;
  ContactParams contact;
  ProxyParams proxy;
  SleepParams sleep;
  SanityLimits limits;

  // -1 when no object has that name.
  int find_object(const std::string& name) const;
  int find_control(const std::string& name) const;
  bool has_hands() const { return !hands.empty(); }
};

// A hand's id on the topics: 0 for a right hand, 1 for a left one.
inline int hand_id_of(const HandModel& hand) { return hand.left ? 1 : 0; }

// Mass properties from density: mass and inertia about the centroid.
void mass_properties_from_density(const Shape& shape, double density_kgpm3, double& mass_kg,
                                  Eigen::Matrix3d& I_O);

}  // namespace vcockpit::physics
