#include "physics_node/physics/collision.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

// What FCL 0.7.0 (Debian, libccd solver) does, measured here (tests/unit/collision_test.cpp
// keeps the measurements honest):
//
// - Normal: from the first object passed to fcl::collide to the second, for every pair we use, in
//   both argument orders: box-box, box-sphere, box-cylinder, box-capsule, capsule-cylinder,
//   capsule-sphere, capsule-capsule, sphere-cylinder. So body_a = lower index goes first and
//   no flip is needed. (For exactly concentric bodies the direction is arbitrary, but unit.)
// - Algorithms: box-box (4-point manifold for a face, points midway between the surfaces),
//   sphere-box, sphere-sphere, sphere-capsule and sphere-cylinder are closed-form and exact,
//   but for sphere-capsule's point (corrected below, see contact_point). Sphere-sphere and
//   sphere-capsule give a zero normal for a sphere centred on the other's centre or axis: such
//   points are dropped and counted (skipped_contacts).
//   Every other pair goes through libccd's MPR (ccdMPRPenetration), not EPA: the normal is that
//   of the Minkowski-difference face crossed by the ray between the two centres, and the depth
//   that face's distance from the origin. That is exact for a flat face (a capsule or cylinder
//   on a box) and sensible, if not minimal, for deep overlaps.
// - MPR's depth error at FCL's default gjk_tolerance (1e-6) reached 7e-7 m for a capsule lying
//   on a box, a pose-dependent few percent of a resting depth m g / k_eff; at 1e-9 it is below
//   1e-10 m for +0.1-0.4 us per pair (about 0.8-1.7 us per MPR pair, 0.1-0.2 us for the
//   closed-form sphere pairs, 0.6 us for box-box).
// - FCL's own GJK/EPA (GST_INDEP) returns negative depths and normals along the wrong axis for
//   capsule and cylinder pairs in 0.7.0: not usable.

namespace vcockpit::physics {
namespace {

using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

constexpr double kMprTolerance_m = 1e-9;  // see above

enum class BodyKind : uint8_t { kStatic, kDynamic, kHand };

// What an FCL object's user data points at.
struct Body {
  int index = -1;
  BodyKind kind = BodyKind::kStatic;
  ShapeKind shape = ShapeKind::kBox;
  double radius_m = 0.0;  // sphere and capsule
};

struct BodyPair {
  int lo = -1;
  int hi = -1;
  friend bool operator<(const BodyPair& x, const BodyPair& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi;
  }
};

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("CollisionWorld: " + message);
}

Geometry object_geometry(const ObjectSpec& spec) {
  const Shape& s = spec.shape;
  const std::string what = "object '" + spec.name + "': ";
  switch (s.kind) {
    case ShapeKind::kBox:
      require((s.box_size_m.array() > 0.0).all(), what + "box size must be positive");
      return std::make_shared<fcl::Boxd>(s.box_size_m);
    case ShapeKind::kSphere:
      require(s.radius_m > 0.0, what + "sphere radius must be positive");
      return std::make_shared<fcl::Sphered>(s.radius_m);
    case ShapeKind::kCapsule:
      require(s.radius_m > 0.0 && s.length_m >= 0.0, what + "bad capsule radius or length");
      return std::make_shared<fcl::Capsuled>(s.radius_m, s.length_m);
    case ShapeKind::kCylinder:
      require(s.radius_m > 0.0 && s.length_m > 0.0, what + "bad cylinder radius or length");
      return std::make_shared<fcl::Cylinderd>(s.radius_m, s.length_m);
  }
  throw std::invalid_argument(what + "unknown shape kind");
}

// Ry(+90 deg), exactly: FCL's capsule axis z onto the phalanx axis x_L.
Eigen::Matrix3d z_onto_x() {
  Eigen::Matrix3d R;
  // clang-format off
  R << 0.0, 0.0, 1.0,
       0.0, 1.0, 0.0,
      -1.0, 0.0, 0.0;
  // clang-format on
  return R;
}

}  // namespace

struct CollisionWorld::Impl {
  std::vector<Body> bodies;  // never resized after construction: user data points into it
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;  // body order
  std::array<Eigen::Isometry3d, kLinkCount> X_LC{};  // link frame -> collision geometry frame
  fcl::DynamicAABBTreeCollisionManagerd manager;
  bool hand_enabled = false;

  std::vector<BodyPair> pairs;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  std::size_t contact_capacity = 0;
  std::uint64_t skipped = 0;

  // The pairs that can act: at least one dynamic object, and the hand only while enabled.
  bool can_act(const Body& a, const Body& b) const {
    if (a.kind != BodyKind::kDynamic && b.kind != BodyKind::kDynamic) return false;
    const bool hand = a.kind == BodyKind::kHand || b.kind == BodyKind::kHand;
    return !hand || hand_enabled;
  }

  static bool collect_pair(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
    auto* self = static_cast<Impl*>(data);
    const auto* a = static_cast<const Body*>(o1->getUserData());
    const auto* b = static_cast<const Body*>(o2->getUserData());
    if (self->can_act(*a, *b))
      self->pairs.push_back({std::min(a->index, b->index), std::max(a->index, b->index)});
    return false;  // never stop early
  }

  void add_body(const Geometry& geometry, const Eigen::Isometry3d& X_GC, BodyKind kind,
                ShapeKind shape, double radius_m) {
    const int index = static_cast<int>(bodies.size());
    bodies.push_back({index, kind, shape, radius_m});
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(geometry, X_GC));
  }

  void place(int body, const Eigen::Isometry3d& X_GC) {
    fcl::CollisionObjectd& object = *objects[static_cast<std::size_t>(body)];
    object.setTransform(X_GC);
    object.computeAABB();
  }

  // Appends the pair's points with positive depth; bad ones are counted and dropped.
  void narrowphase(const BodyPair& pair, std::vector<ContactPoint>& out) {
    result.clear();
    fcl::collide(objects[static_cast<std::size_t>(pair.lo)].get(),
                 objects[static_cast<std::size_t>(pair.hi)].get(), request, result);
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      const fcl::Contactd& c = result.getContact(i);
      const double depth_m = c.penetration_depth;
      if (depth_m <= 0.0) continue;  // touching: no force
      const double norm = c.normal.norm();
      if (!std::isfinite(depth_m) || !c.pos.allFinite() || !(norm > 0.5 && norm < 2.0)) {
        ++skipped;  // zero or NaN normal (or NaN depth, point): no direction to push along
        continue;
      }
      const Eigen::Vector3d n = c.normal / norm;
      out.push_back({pair.lo, pair.hi, contact_point(pair, c.pos, n, depth_m), n, depth_m});
    }
  }

  // FCL 0.7's sphere-capsule routine puts the point at the capsule's axis point moved `depth`
  // toward the sphere, i.e. inside the capsule, a capsule radius away from the overlap. That
  // skews friction torques, so it is replaced by the midpoint of the overlap along the normal,
  // as FCL's other closed-form pairs place it: the sphere's deepest point backed off depth / 2.
  Eigen::Vector3d contact_point(const BodyPair& pair, const Eigen::Vector3d& p_fcl,
                                const Eigen::Vector3d& n_ab, double depth_m) const {
    const Body& a = bodies[static_cast<std::size_t>(pair.lo)];
    const Body& b = bodies[static_cast<std::size_t>(pair.hi)];
    const bool a_sphere = a.shape == ShapeKind::kSphere && b.shape == ShapeKind::kCapsule;
    const bool b_sphere = b.shape == ShapeKind::kSphere && a.shape == ShapeKind::kCapsule;
    if (!a_sphere && !b_sphere) return p_fcl;
    const Body& sphere = a_sphere ? a : b;
    const Eigen::Vector3d n_sc = a_sphere ? n_ab : Eigen::Vector3d(-n_ab);  // sphere -> capsule
    const Eigen::Vector3d c_s = objects[static_cast<std::size_t>(sphere.index)]->getTranslation();
    return c_s + (sphere.radius_m - 0.5 * depth_m) * n_sc;
  }
};

CollisionWorld::CollisionWorld(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  object_count_ = static_cast<int>(scene.objects.size());
  has_hand_ = scene.hand.has_value();
  require(scene.contact.max_points_per_pair >= 1, "contact.max_points_per_pair must be >= 1");

  const std::size_t body_count =
      scene.objects.size() + (has_hand_ ? static_cast<std::size_t>(kLinkCount) : 0);
  m.bodies.reserve(body_count);
  m.objects.reserve(body_count);

  for (const ObjectSpec& spec : scene.objects)
    m.add_body(object_geometry(spec), spec.X_GO,
               spec.dynamic ? BodyKind::kDynamic : BodyKind::kStatic, spec.shape.kind,
               spec.shape.radius_m);

  if (has_hand_) {
    const HandModel& hand = *scene.hand;
    require((hand.palm_size_m.array() > 0.0).all(), "hand palm size must be positive");
    // link frames start at the identity; the hand stays disabled until the first set_poses
    m.X_LC[static_cast<std::size_t>(Link::kPalm)] = Eigen::Isometry3d::Identity();
    m.add_body(std::make_shared<fcl::Boxd>(hand.palm_size_m), Eigen::Isometry3d::Identity(),
               BodyKind::kHand, ShapeKind::kBox, 0.0);
    for (int l = 1; l < kLinkCount; ++l) {
      const Capsule& capsule = hand.capsules[static_cast<std::size_t>(l)];
      require(capsule.radius_m > 0.0 && capsule.length_m >= 0.0,
              "bad capsule for hand link " + std::string(link_name(static_cast<Link>(l))));
      // the capsule spans [0, length] on x_L; FCL's is centred on its own z
      Eigen::Isometry3d X_LC = Eigen::Isometry3d::Identity();
      X_LC.translation() = Eigen::Vector3d(0.5 * capsule.length_m, 0.0, 0.0);
      X_LC.linear() = z_onto_x();
      m.X_LC[static_cast<std::size_t>(l)] = X_LC;
      m.add_body(std::make_shared<fcl::Capsuled>(capsule.radius_m, capsule.length_m), X_LC,
                 BodyKind::kHand, ShapeKind::kCapsule, capsule.radius_m);
    }
  }

  // user data only once the vector is final; one tree, registered in body order
  std::vector<fcl::CollisionObjectd*> registered;
  registered.reserve(body_count);
  for (std::size_t i = 0; i < m.objects.size(); ++i) {
    m.objects[i]->setUserData(&m.bodies[i]);
    registered.push_back(m.objects[i].get());
  }
  m.manager.registerObjects(registered);
  m.manager.setup();

  m.pairs.reserve(8 * body_count);
  m.request = fcl::CollisionRequestd(static_cast<std::size_t>(scene.contact.max_points_per_pair),
                                     /*enable_contact=*/true);
  m.request.gjk_tolerance = kMprTolerance_m;
  m.contact_capacity = 4 * body_count * static_cast<std::size_t>(scene.contact.max_points_per_pair);
}

CollisionWorld::~CollisionWorld() = default;

void CollisionWorld::set_poses(const std::vector<Eigen::Isometry3d>& X_GO,
                               const std::array<Eigen::Isometry3d, kLinkCount>* X_GL) {
  Impl& m = *impl_;
  assert(static_cast<int>(X_GO.size()) == object_count_);
  const int n = std::min(object_count_, static_cast<int>(X_GO.size()));
  for (int i = 0; i < n; ++i)
    if (m.bodies[static_cast<std::size_t>(i)].kind == BodyKind::kDynamic)
      m.place(i, X_GO[static_cast<std::size_t>(i)]);

  m.hand_enabled = has_hand_ && X_GL != nullptr;
  if (m.hand_enabled) {
    for (int l = 0; l < kLinkCount; ++l)
      m.place(hand_link_body(static_cast<Link>(l)),
              (*X_GL)[static_cast<std::size_t>(l)] * m.X_LC[static_cast<std::size_t>(l)]);
  }
  m.manager.update();
}

void CollisionWorld::find_candidate_pairs() {
  Impl& m = *impl_;
  m.pairs.clear();
  m.manager.collide(&m, &Impl::collect_pair);
  // the tree's traversal order depends on its shape; the output must not
  std::sort(m.pairs.begin(), m.pairs.end());
}

void CollisionWorld::compute_contacts(std::vector<ContactPoint>& out) {
  Impl& m = *impl_;
  out.clear();
  if (out.capacity() < m.contact_capacity) out.reserve(m.contact_capacity);
  for (const BodyPair& pair : m.pairs)
    m.narrowphase(pair, out);
}

std::size_t CollisionWorld::candidate_pair_count() const { return impl_->pairs.size(); }

std::uint64_t CollisionWorld::skipped_contacts() const { return impl_->skipped; }

}  // namespace vcockpit::physics
