#include "physics_node/physics/world_state_hash.hpp"

#include <bit>

namespace vcockpit::physics {
namespace {

class Fnv1a64 {
 public:
  uint64_t value() const { return h_; }

  void u64(uint64_t v) {
    for (int byte = 0; byte < 8; ++byte) {
      h_ ^= (v >> (8 * byte)) & 0xffu;
      h_ *= kPrime;
    }
  }
  void i64(int64_t v) { u64(static_cast<uint64_t>(v)); }
  void size(std::size_t n) { u64(static_cast<uint64_t>(n)); }
  void flag(bool b) { u64(b ? 1u : 0u); }
  void f64(double d) { u64(std::bit_cast<uint64_t>(d)); }
  void vec(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i)
      f64(v[i]);
  }
  void pose(const Eigen::Isometry3d& X) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r)
        f64(X.matrix()(r, c));
  }

 private:
  static constexpr uint64_t kOffset = 14695981039346656037ull;
  static constexpr uint64_t kPrime = 1099511628211ull;
  uint64_t h_ = kOffset;
};

void hash_hand(Fnv1a64& h, const HandInput& hand) {
  h.pose(hand.X_GH);
  h.size(hand.q_rad.size());
  for (double q : hand.q_rad)
    h.f64(q);
  h.flag(hand.tracking);
}

void hash_hold(Fnv1a64& h, const GraspHold& g) {
  h.pose(g.X_HO);
  h.i64(g.held_since_ns);
  h.i64(g.failing_since_ns);
  h.i64(g.released_at_ns);
  h.size(g.history_next);
  h.size(g.history_count);
  h.size(g.history.size());
  for (const Eigen::Isometry3d& X : g.history)
    h.pose(X);
  h.size(g.grip_fingers);
  for (double q : g.grip_flexion_rad)
    h.f64(q);
  h.u64(g.resting_links);
  h.flag(g.hand_clearing);
  h.flag(g.handed_over);
}

}  // namespace

uint64_t hash_world_state(const WorldState& s) {
  Fnv1a64 h;
  h.i64(s.time_ns);
  h.u64(s.steps);
  h.i64(s.substeps);
  h.size(s.bodies.size());
  for (const BodyState& b : s.bodies) {
    h.pose(b.X_GO);
    h.vec(b.v_G);
    h.vec(b.w_G);
    h.u64(b.holders);
    h.i64(b.held_by);
  }
  h.size(s.hands.size());
  for (const HandState& hand : s.hands) {
    h.flag(hand.active);
    hash_hand(h, hand.from);
    hash_hand(h, hand.to);
    h.pose(hand.X_GH);
    h.size(hand.q_rad.size());
    for (double q : hand.q_rad)
      h.f64(q);
    h.size(hand.X_GL.size());
    for (const Eigen::Isometry3d& X : hand.X_GL)
      h.pose(X);
    h.flag(hand.pushing);
    h.u64(hand.fingers_on_held);
    h.size(hand.blocking_out_G.size());
    for (const Eigen::Vector3d& n : hand.blocking_out_G)
      h.vec(n);
    h.size(hand.grasp.size());
    for (const GraspHold& g : hand.grasp)
      hash_hold(h, g);
  }
  h.size(s.controls.size());
  for (const ControlState& c : s.controls) {
    h.f64(c.q);
    h.f64(c.qd);
    h.i64(c.position);
    h.flag(c.latched);
    h.flag(c.pressed);
    h.i64(c.push_hand);
    h.i64(c.push_link);
    h.i64(c.push_direction);
    h.pose(c.X_GH_grasp);
    h.f64(c.q_grasp);
  }
  h.size(s.anchors.size());
  for (const StickAnchor& a : s.anchors) {
    h.i64(a.body_a);
    h.i64(a.body_b);
    h.vec(a.p_A);
    h.vec(a.r_A);
    h.vec(a.r_B);
    h.flag(a.sticking);
  }
  return h.value();
}

}  // namespace vcockpit::physics
