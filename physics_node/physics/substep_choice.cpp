#include "physics_node/physics/substep_choice.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

#include "common/assert.hpp"

namespace vcockpit::physics {
namespace {

// The reach broadphase's bodies: the objects, then each hand's links.
std::vector<BroadphaseBody> reach_kinds(const Scene& scene) {
  std::vector<BroadphaseBody> kinds;
  for (const ObjectSpec& o : scene.objects)
    kinds.push_back(o.control >= 0 ? BroadphaseBody::kControl
                                   : (o.dynamic ? BroadphaseBody::kDynamic : BroadphaseBody::kStatic));
  kinds.insert(kinds.end(), scene.hands.size() * kLinkCount, BroadphaseBody::kHand);
  return kinds;
}

}  // namespace

// The lever about each principal axis is at most the shape's reach from that axis, and |r x n|
// is at most the bounding radius. (Inertia from the shape is diagonal in the shape's frame.)
// Smooth shapes are exact: a contact's normal is the surface normal at the contact, so its line
// passes through a sphere's centre (no lever: m) or through a capsule's axis segment, r x n =
// t (a x n) with |t| <= half length, a turn about an axis across the capsule.
double worst_contact_mass(const ObjectSpec& o) {
  if (o.shape.kind == ShapeKind::kSphere) return o.mass_kg;
  if (o.shape.kind == ShapeKind::kCapsule) {
    const double half_m = 0.5 * o.shape.length_m;
    const double I_across = std::min(o.I_O(0, 0), o.I_O(1, 1));
    return 1.0 / (1.0 / o.mass_kg + half_m * half_m / I_across);
  }
  if (o.shape.kind == ShapeKind::kMesh) {
    // a model part's inertia is not diagonal in its frame: |r x n|^2 / I at most r^2 / I_min,
    // I_min its least principal moment
    const double r = o.shape.bounding_radius_m();
    const double I_min = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(o.I_O).eigenvalues().minCoeff();
    return 1.0 / (1.0 / o.mass_kg + r * r / I_min);
  }
  const Eigen::Vector3d reach = o.shape.axis_reach_m();
  double per_axis = 0.0;
  for (int i = 0; i < 3; ++i) per_axis += reach[i] * reach[i] / o.I_O(i, i);
  const double r = o.shape.bounding_radius_m();
  const double I_min = o.I_O.diagonal().minCoeff();
  return 1.0 / (1.0 / o.mass_kg + std::min(per_axis, r * r / I_min));
}

SubstepChoice::SubstepChoice(const Scene& scene, const CollisionWorld& collision)
    : scene_(scene),
      collision_(collision),
      object_count_(static_cast<int>(scene.objects.size())),
      contact_mass_(scene.objects.size(), 0.0),
      reach_(reach_kinds(scene)) {
  // static boxes once, the rest every step
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    if (o.dynamic) {
      contact_mass_[i] = worst_contact_mass(o);
    } else {
      reach_.set_box(i, shape_aabb(o.shape, o.X_GO));
    }
  }
  reach_pairs_.reserve(64);
  may_wake_.assign(scene.objects.size(), 0);
}

// Boxes around each body's sweep over the step (a dynamic body: where it is, grown by how far it
// can move; a hand link: its box at the start and at the end of the step), plus a margin.
void SubstepChoice::find_reachable_pairs(const std::vector<BodyState>& bodies,
                                         const std::vector<HandSweep>& hands) {
  const double step_s = scene_.step_s;
  for (int i = 0; i < object_count_; ++i) {
    const ObjectSpec& o = scene_.objects[i];
    if (!o.dynamic) continue;  // static boxes were set once
    const BodyState& body = bodies[i];
    // a sleeping body counts only where something that moves may reach it (and wake it)
    reach_.set_asleep(i, body.asleep);
    Aabb box = shape_aabb(o.shape, body.X_GO);
    // the farthest a point of it can go in one step: centroid speed, spin times reach, gravity
    const double reach_m = (body.v_G.norm() + body.w_G.norm() * o.shape.bounding_radius_m()) * step_s +
                           0.5 * scene_.gravity_mps2.norm() * step_s * step_s + kReachMargin_m;
    box.lo.array() -= reach_m;
    box.hi.array() += reach_m;
    reach_.set_box(i, box);
  }
  for (std::size_t h = 0; h < scene_.hands.size(); ++h) {
    const HandSweep* sweep = h < hands.size() ? &hands[h] : nullptr;
    const bool active = sweep != nullptr && sweep->X_GL_now != nullptr;
    const int first = object_count_ + static_cast<int>(h) * kLinkCount;
    for (int l = 0; l < kLinkCount; ++l) reach_.set_enabled(first + l, active);
    if (!active) continue;
    HandLinkPoses end;
    forward_kinematics(scene_.hands[h], sweep->q_end, end);
    for (int l = 0; l < kLinkCount; ++l) {
      const Link link = static_cast<Link>(l);
      const int hand = static_cast<int>(h);
      const Aabb now = collision_.hand_link_box(hand, link, (*sweep->X_GL_now)[l]);
      const Aabb then = collision_.hand_link_box(hand, link, sweep->X_GH_end * end.X_HL[l]);
      reach_.set_box(first + l, {now.lo.cwiseMin(then.lo).array() - kReachMargin_m,
                                 now.hi.cwiseMax(then.hi).array() + kReachMargin_m});
    }
  }
  reach_.find_pairs(reach_pairs_);
  // A sleeping island that something moving can reach may wake in this step, and then its resting
  // contacts need their substeps from the first: it counts as awake (its pairs found again).
  std::fill(may_wake_.begin(), may_wake_.end(), 0);
  for (bool woken = true; woken;) {
    woken = false;
    for (const BodyPair& pair : reach_pairs_) {
      for (const int body : {pair.lo, pair.hi}) {
        if (body >= object_count_ || !bodies[body].asleep || may_wake_[body] != 0) continue;
        const int island = bodies[body].island;
        for (int i = 0; i < object_count_; ++i) {
          if (!bodies[i].asleep || bodies[i].island != island) continue;
          may_wake_[i] = 1;
          reach_.set_asleep(i, false);
        }
        woken = true;
      }
    }
    if (woken) reach_.find_pairs(reach_pairs_);
  }
}

int SubstepChoice::choose(const std::vector<BodyState>& bodies, const std::vector<HandSweep>& hands) {
  VCOCKPIT_ASSERT(static_cast<int>(bodies.size()) == object_count_, "one body state per object");
  VCOCKPIT_ASSERT(hands.size() <= scene_.hands.size(), "a hand sweep per hand of the scene");
  find_reachable_pairs(bodies, hands);
  double dt_max = scene_.step_s;
  for (const BodyPair& pair : reach_pairs_) {
    const bool a_free = pair.lo < object_count_ && scene_.objects[pair.lo].dynamic &&
                        !bodies[pair.lo].held();
    const bool b_free = pair.hi < object_count_ && scene_.objects[pair.hi].dynamic &&
                        !bodies[pair.hi].held();
    if (!a_free && !b_free) continue;  // held objects move with the hand: nothing to integrate
    const Material& ma = pair.lo < object_count_ ? scene_.objects[pair.lo].material
                                                 : scene_.hand_material;
    const Material& mb = pair.hi < object_count_ ? scene_.objects[pair.hi].material
                                                 : scene_.hand_material;
    const double inv_m = (a_free ? 1.0 / contact_mass_[pair.lo] : 0.0) +
                         (b_free ? 1.0 / contact_mass_[pair.hi] : 0.0);
    const double k = pair_stiffness(ma, mb);
    if (k > 0) dt_max = std::min(dt_max, scene_.contact.substep_safety * std::sqrt(1.0 / (inv_m * k)));
  }
  const int n = static_cast<int>(std::ceil(scene_.step_s / dt_max - 1e-9));
  return std::clamp(n, 1, scene_.contact.max_substeps);
}

}  // namespace vcockpit::physics
