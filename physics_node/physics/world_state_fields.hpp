#pragma once
// Every field of a WorldState, in one fixed order, for whatever walks them all: the state hash
// (world_state_hash.hpp) and the checkpoint file (physics_io::world_checkpoint). One list, so a
// field added to the state is hashed and saved alike, or by neither.
//
// The visitor V has:
//   num(x)          an arithmetic field (double, bool, an integer of any width)
//   count(vec)      the length of a vector whose length the scene fixes (bodies, hands, ...)
//   var_count(vec)  the length of a vector whose length changes as the world runs (anchors,
//                   blocking planes)
//   fixed(n)        the length of a fixed-size array, which it sees but cannot change
// S is WorldState (a visitor that fills it) or const WorldState (one that reads it).

#include <type_traits>

#include "physics_node/physics/world_state.hpp"

namespace vcockpit::physics {

namespace world_state_fields {

template <class V, class Vec>
void vec3(V& v, Vec& p) {
  for (int i = 0; i < 3; ++i)
    v.num(p[i]);
}

// the 3x4 [R | p], column by column
template <class V, class Pose>
void pose(V& v, Pose& X) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r)
      v.num(X.matrix()(r, c));
}

template <class V, class Input>
void hand_input(V& v, Input& hand) {
  pose(v, hand.X_GH);
  v.fixed(hand.q_rad.size());
  for (auto& q : hand.q_rad)
    v.num(q);
  v.num(hand.tracking);
}

template <class V, class Hold>
void grasp_hold(V& v, Hold& g) {
  pose(v, g.X_HO);
  v.num(g.held_since_ns);
  v.num(g.failing_since_ns);
  v.num(g.released_at_ns);
  v.num(g.history_next);
  v.num(g.history_count);
  v.count(g.history);
  for (auto& X : g.history)
    pose(v, X);
  v.num(g.grip_fingers);
  for (auto& q : g.grip_flexion_rad)
    v.num(q);
  for (auto& q : g.grip_tightest_rad)
    v.num(q);
  v.num(g.opposed_fingers);
  v.num(g.palm_opposed);
  for (auto& d : g.grip_gap_m)
    v.num(d);
  v.num(g.resting_links);
  v.num(g.hand_clearing);
  v.num(g.handed_over);
  v.num(g.passing_through);
}

}  // namespace world_state_fields

template <class V, class S>
void visit_world_state(V& v, S& s) {
  static_assert(std::is_same_v<std::remove_const_t<S>, WorldState>);
  namespace f = world_state_fields;
  v.num(s.time_ns);
  v.num(s.steps);
  v.count(s.bodies);
  for (auto& b : s.bodies) {
    f::pose(v, b.X_GO);
    f::vec3(v, b.v_G);
    f::vec3(v, b.w_G);
    v.num(b.holders);
    v.num(b.held_by);
    v.num(b.still_s);
    v.num(b.asleep);
    v.num(b.island);
  }
  v.count(s.hands);
  for (auto& hand : s.hands) {
    v.num(hand.active);
    f::hand_input(v, hand.from);
    f::hand_input(v, hand.to);
    f::pose(v, hand.X_GH);
    v.fixed(hand.q_rad.size());
    for (auto& q : hand.q_rad)
      v.num(q);
    v.fixed(hand.X_GL.size());
    for (auto& X : hand.X_GL)
      f::pose(v, X);
    v.num(hand.pushing);
    v.var_count(hand.blocking_out_G);
    for (auto& n : hand.blocking_out_G)
      f::vec3(v, n);
    f::vec3(v, hand.finger_pull_G);
    v.count(hand.grasp);
    for (auto& g : hand.grasp)
      f::grasp_hold(v, g);
  }
  v.count(s.controls);
  for (auto& c : s.controls) {
    v.num(c.q);
    v.num(c.qd);
    v.num(c.position);
    v.num(c.latched);
    v.num(c.pressed);
    v.num(c.push_hand);
    v.num(c.push_link);
    v.num(c.push_direction);
    f::pose(v, c.X_GH_grasp);
    v.num(c.q_grasp);
  }
  v.var_count(s.anchors);
  for (auto& a : s.anchors) {
    v.num(a.body_a);
    v.num(a.body_b);
    f::vec3(v, a.p_A);
    f::vec3(v, a.r_A);
    f::vec3(v, a.r_B);
    v.num(a.sticking);
    v.num(a.lambda_n);
    f::vec3(v, a.lambda_t_A);
  }
}

}  // namespace vcockpit::physics
