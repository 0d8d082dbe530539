#pragma once
// Collision detection (paper §4.2): sweep and prune (broadphase.hpp) over the objects and each
// hand's 16 links (bodies: the objects, then hand 0's links, then hand 1's), then narrowphase contacts (point, normal, depth) from FCL (libccd MPR for
// general convex pairs, FCL's box-box manifold for boxes). Where FCL gives one point for a flat
// contact (a cylinder's cap or side, or a capsule, lying on a face), a manifold of up to
// max_points_per_pair points is built on the face, so such bodies rest without rocking.
//
// Pairs that cannot act are never reported: static-static and link-link (of one hand or two). Hand-static pairs, on
// which no force acts, are reported apart, and only to a world whose proxy hand asks for them. The output
// is ordered (by body_a, body_b, then the pair's own order: FCL's, or the manifold's deepest
// first), so the same poses always give the same contacts in the same order.

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics {

class CollisionWorld {
 public:
  explicit CollisionWorld(const Scene& scene);
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

  int object_count() const { return object_count_; }
  int hand_count() const { return hand_count_; }
  bool has_hand() const { return hand_count_ > 0; }
  int hand_link_body(int hand, Link link) const {
    return object_count_ + hand * kLinkCount + static_cast<int>(link);
  }
  bool is_hand_body(int body) const { return body >= object_count_; }
  int hand_of_body(int body) const { return (body - object_count_) / kLinkCount; }
  Link link_of_body(int body) const {
    return static_cast<Link>((body - object_count_) % kLinkCount);
  }
  // Moves the dynamic objects (X_GO for every object; static ones are ignored).
  void set_object_poses(const std::vector<Eigen::Isometry3d>& X_GO);
  // Moves hand `hand`'s links (X_GL in world), or disables them (null: the hand is not active).
  void set_hand_poses(int hand, const std::array<Eigen::Isometry3d, kLinkCount>* X_GL);
  // Both, for a world of at most one hand (its links: X_GL, or null).
  void set_poses(const std::vector<Eigen::Isometry3d>& X_GO,
                 const std::array<Eigen::Isometry3d, kLinkCount>* X_GL);
  // Broadphase: candidate pairs whose AABBs overlap (stage "broadphase").
  void find_candidate_pairs();
  // Narrowphase over the candidates: contact points appended to `out` after clearing it
  // (stage "narrowphase"). Allocation-free once `out` and the internals have warmed up.
  // Hand-static contacts (body_a the static object, body_b the link) go to `hand_static` (also
  // cleared first) when it is given and the world was built to report them.
  void compute_contacts(std::vector<ContactPoint>& out,
                        std::vector<ContactPoint>* hand_static = nullptr);
  // The hand-static contacts again (into `out`, cleared first) with the links moved to X_GL,
  // over the hand-static pairs the last broadphase found: for a proxy whose fingers moved after
  // the narrowphase (only away from static objects, so no new pair can arise).
  // Of hand `hand`'s links only.
  void compute_hand_static_contacts(int hand, const std::array<Eigen::Isometry3d, kLinkCount>& X_GL,
                                    std::vector<ContactPoint>& out);
  // Whether the broadphase reports hand-static pairs (the proxy hand's), from construction.
  bool reports_hand_static() const { return report_hand_static_; }

  // A sleeping object (sleep.hpp) pairs only with bodies that move; every object starts awake.
  void set_object_asleep(int object, bool asleep);

  // The box around a hand link's collision shape with the link frame at X_GL (a capsule on
  // [0, length] along x_L, the palm box on its frame).
  Aabb hand_link_box(int hand, Link link, const Eigen::Isometry3d& X_GL) const;

  // Whether hand link `link`, its frame at X_GL, overlaps object `object` where the last
  // set_poses put it: for a hand that is not a body of this world (the tracked one).
  bool link_overlaps(int hand, Link link, const Eigen::Isometry3d& X_GL, int object) const;
  // Whether it is within gap_m of the object's surface (or in it), the same way.
  bool link_within(int hand, Link link, const Eigen::Isometry3d& X_GL, int object, double gap_m) const;
  // How far it is off the object's surface, the same way (0 touching or in it).
  double link_gap_m(int hand, Link link, const Eigen::Isometry3d& X_GL, int object) const;

  std::size_t candidate_pair_count() const;
  // Narrowphase points dropped since construction for a zero, NaN or non-unit normal (or a NaN
  // depth or point): a run-time counter, never an exception.
  std::uint64_t skipped_contacts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int object_count_ = 0;
  int hand_count_ = 0;
  bool report_hand_static_ = false;
};

}  // namespace vcockpit::physics
