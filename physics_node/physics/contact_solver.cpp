#include "physics_node/physics/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/assert.hpp"
#include "physics_node/physics/anchor_match.hpp"
#include "physics_node/physics/normal_force.hpp"
#include "physics_node/physics/soft_constraint.hpp"

namespace vcockpit::physics {
namespace {

// Two unit vectors completing n to a right-handed orthonormal basis.
void tangent_basis(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  t1 = std::abs(n.x()) < 0.57735 ? Eigen::Vector3d::UnitX().cross(n) : Eigen::Vector3d::UnitY().cross(n);
  t1.normalize();
  t2 = n.cross(t1);
}

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

double along(const Eigen::Matrix3d& inv_I_G, const Eigen::Vector3d& u) { return u.dot(inv_I_G * u); }

}  // namespace

Eigen::Vector3d SoftContactSolver::relative_velocity(const Point& p) const {
  return (v_[p.b] + w_[p.b].cross(p.r_b)) - (v_[p.a] + w_[p.a].cross(p.r_a));
}

void SoftContactSolver::push_joints(const Point& p, const Eigen::Vector3d& P) {
  if (const int j = joint_of_[p.b]; j >= 0) push_joint(p.b, (*joints_)[j].along(p.p_G, P));
  if (const int j = joint_of_[p.a]; j >= 0) push_joint(p.a, -(*joints_)[j].along(p.p_G, P));
}

SoftContactSolver::Row SoftContactSolver::make_row(const Point& p, const Eigen::Vector3d& u) const {
  Row row;
  row.u = u;
  row.ra_u = p.r_a.cross(u);
  row.rb_u = p.r_b.cross(u);
  row.spin_a = inv_I_G_[p.a] * row.ra_u;
  row.spin_b = inv_I_G_[p.b] * row.rb_u;
  return row;
}

void SoftContactSolver::apply_angular_impulse(int a, int b, const Eigen::Vector3d& L) {
  if (inv_m_[b] > 0.0) w_[b] += inv_I_G_[b] * L;
  if (inv_m_[a] > 0.0) w_[a] -= inv_I_G_[a] * L;
  if (const int j = joint_of_[b]; j >= 0) push_joint(b, (*joints_)[j].along_couple(L));
  if (const int j = joint_of_[a]; j >= 0) push_joint(a, -(*joints_)[j].along_couple(L));
}

void SoftContactSolver::push_joint(int body, double impulse) {
  SolverJoint& joint = (*joints_)[static_cast<std::size_t>(joint_of_[body])];
  joint.impulse += impulse;
  joint.velocity(joint.qd(), v_[body], w_[body]);
}

double SoftContactSolver::inverse_mass_along(const Point& p, const Row& row) const {
  // u.(I^-1 u) for u = r x row.u, from the row's own r x u and I^-1 (r x u)
  double K = inv_m_[p.a] + inv_m_[p.b] + row.ra_u.dot(row.spin_a) + row.rb_u.dot(row.spin_b);
  if (!p.on_joint) return K;
  for (const int i : {p.a, p.b}) {
    if (const int j = joint_of_[i]; j >= 0) {
      const SolverJoint& joint = (*joints_)[static_cast<std::size_t>(j)];
      const double J = joint.along(p.p_G, row.u);
      K += joint.mobility * J * J;
    }
  }
  return K;
}

double SoftContactSolver::inverse_inertia_along(int a, int b, const Eigen::Vector3d& u) const {
  double K = along(inv_I_G_[a], u) + along(inv_I_G_[b], u);
  for (const int i : {a, b}) {
    if (const int j = joint_of_[i]; j >= 0) {
      const SolverJoint& joint = (*joints_)[static_cast<std::size_t>(j)];
      const double J = joint.along_couple(u);
      K += joint.mobility * J * J;
    }
  }
  return K;
}

const StickAnchor* SoftContactSolver::match_anchor(const std::vector<StickAnchor>& previous,
                                                   const ContactPoint& c,
                                                   const Eigen::Vector3d& p_A) {
  return match_stick_anchor(previous, anchor_used_, c, p_A, kStickAnchorMatch_m);
}

void SoftContactSolver::solve(const std::vector<ContactPoint>& contacts,
                              std::vector<ContactBody>& bodies, std::vector<SolverJoint>& joints,
                              const Eigen::Vector3d& gravity_mps2, double h_s,
                              std::vector<AppliedContact>& applied,
                              std::vector<StickAnchor>& anchors, std::vector<uint8_t>& touched) {
  const std::size_t count = bodies.size();
  v_.resize(count);
  w_.resize(count);
  inv_m_.resize(count);
  inv_I_G_.resize(count);
  joint_of_.assign(count, -1);
  joints_ = &joints;
  touched.assign(count, 0);
  // only the bodies in a contact are read
  for (const ContactPoint& c : contacts) {
    for (const int i : {c.body_a, c.body_b}) {
      const ContactBody& body = bodies[static_cast<std::size_t>(i)];
      v_[i] = body.v_G;
      w_[i] = body.w_G;
      if (body.dynamic) {
        const Eigen::Matrix3d& R = body.X_GB.linear();
        inv_m_[i] = body.inv_mass;
        inv_I_G_[i] = R * body.inv_I_O * R.transpose();
        v_[i] += gravity_mps2 * h_s;
      } else {
        inv_m_[i] = 0.0;
        inv_I_G_[i].setZero();
      }
    }
  }
  // a control's body moves on its joint: its rate without contacts (gravity and its mechanism
  // are in it), which the contacts' impulses then change
  for (std::size_t j = 0; j < joints.size(); ++j) {
    SolverJoint& joint = joints[j];
    const auto i = static_cast<std::size_t>(joint.body);
    VCOCKPIT_ASSERT(bodies[i].dynamic, "a joint body responds to its contacts");
    joint_of_[i] = static_cast<int>(j);
    joint.impulse = 0.0;
    inv_m_[i] = 0.0;
    inv_I_G_[i].setZero();
    joint.velocity(joint.qd(), v_[i], w_[i]);
  }
  prepare(contacts, bodies, h_s, anchors);
  for (const Pair& pair : pairs_) {
    if (pair.kinematic) continue;
    for (const int i : {pair.a, pair.b})
      if (bodies[static_cast<std::size_t>(i)].dynamic) touched[static_cast<std::size_t>(i)] = 1;
  }
  warm_start();
  const auto sweep = [&](bool use_bias) {
    for (Pair& pair : pairs_) {
      if (pair.kinematic) continue;
      double load = 0.0;  // the pair's normal impulse: the friction's and the rolling rows' cap
      for (std::size_t i = pair.first; i < pair.end; ++i) {
        solve_normal(points_[i], use_bias);
        load += points_[i].lambda_n;
      }
      solve_friction(pair, load, use_bias);
      solve_rolling(pair, load);
    }
  };
  for (int it = 0; it < params_.iterations; ++it) sweep(true);
  for (SolverJoint& joint : joints) joint.move_impulse = joint.impulse;
  // the positions move with these velocities (the spring's push-out included)
  for (std::size_t i = 0; i < count; ++i) {
    if (touched[i] == 0) continue;
    bodies[i].v_G = v_[i];
    bodies[i].w_G = w_[i];
  }
  for (Point& p : points_) p.lambda_n_spring = p.lambda_n;
  for (int it = 0; it < params_.relax_iterations; ++it) sweep(false);
  restitution();
  store(contacts, bodies, h_s, applied);
  std::swap(anchors, next_anchors_);
}

void SoftContactSolver::prepare(const std::vector<ContactPoint>& contacts,
                                const std::vector<ContactBody>& bodies, double h_s,
                                const std::vector<StickAnchor>& previous) {
  points_.clear();
  pairs_.clear();
  anchor_used_.assign(previous.size(), 0);
  next_anchors_.clear();
  std::size_t i = 0;
  int last_a = -1, last_b = -1;
  while (i < contacts.size()) {
    std::size_t end = i + 1;
    while (end < contacts.size() && contacts[end].body_a == contacts[i].body_a &&
           contacts[end].body_b == contacts[i].body_b)
      ++end;
    Pair pair;
    pair.first = points_.size();
    pair.a = contacts[i].body_a;
    pair.b = contacts[i].body_b;
    VCOCKPIT_ASSERT(pair_before(last_a, last_b, pair.a, pair.b), "contacts must be sorted by pair");
    last_a = pair.a;
    last_b = pair.b;
    const ContactBody& A = bodies[static_cast<std::size_t>(pair.a)];
    const ContactBody& B = bodies[static_cast<std::size_t>(pair.b)];
    const NormalPair k = normal_pair(A, B, static_cast<int>(end - i));
    pair.mu = pair_friction(A, B);
    pair.kinematic = !A.dynamic && !B.dynamic;
    const double restitution = dashpot_restitution(0.5 * (A.material->damping_ratio + B.material->damping_ratio));
    const SoftSpring spring = soft_from_spring(k.k_pt, k.c_pt, h_s);
    const Eigen::Isometry3d X_AG = A.X_GB.inverse();
    const Eigen::Isometry3d X_BG = B.X_GB.inverse();
    // the kinematic bodies' part of the relative velocity at a point (they are at the step's end)
    const auto kinematic_velocity = [&](const Eigen::Vector3d& p_G) -> Eigen::Vector3d {
      return (B.dynamic ? Eigen::Vector3d::Zero() : B.point_velocity(p_G)) -
             (A.dynamic ? Eigen::Vector3d::Zero() : A.point_velocity(p_G));
    };
    bool was_sliding = false;
    double load_sum = 0.0, speed_weighted = 0.0;
    Eigen::Vector3d n_sum = Eigen::Vector3d::Zero();
    for (std::size_t j = i; j < end; ++j) {
      const ContactPoint& c = contacts[j];
      Point p;
      p.a = pair.a;
      p.b = pair.b;
      p.n = c.n_G;
      tangent_basis(p.n, p.t1, p.t2);
      p.p_G = c.p_G;
      p.r_a = c.p_G - A.X_GB.translation();
      p.r_b = c.p_G - B.X_GB.translation();
      p.on_joint = joint_of_[p.a] >= 0 || joint_of_[p.b] >= 0;
      p.row_n = make_row(p, p.n);
      p.row_t1 = make_row(p, p.t1);
      p.row_t2 = make_row(p, p.t2);
      p.K_n = inverse_mass_along(p, p.row_n);
      p.K_t1 = inverse_mass_along(p, p.row_t1);
      p.K_t2 = inverse_mass_along(p, p.row_t2);
      p.mass_n = p.K_n > 0.0 ? 1.0 / p.K_n : 0.0;
      p.mass_t1 = p.K_t1 > 0.0 ? 1.0 / p.K_t1 : 0.0;
      p.mass_t2 = p.K_t2 > 0.0 ? 1.0 / p.K_t2 : 0.0;
      p.soft_mass_n = 1.0 / (p.K_n + spring.gamma);
      p.soft_mass_t1 = 1.0 / (p.K_t1 + spring.gamma);
      p.soft_mass_t2 = 1.0 / (p.K_t2 + spring.gamma);
      p.spring = spring;
      p.restitution = restitution;
      // the kinematic bodies are at the step's end already: take their motion out of the gap
      const Eigen::Vector3d v_kinematic = kinematic_velocity(c.p_G);
      p.s0 = -c.depth_m - h_s * v_kinematic.dot(p.n);
      const Eigen::Vector3d v_rel = relative_velocity(p);
      p.v_n_before = v_rel.dot(p.n);
      p.v_n_own = p.v_n_before - v_kinematic.dot(p.n);
      const Eigen::Vector3d v_t = v_rel - p.v_n_before * p.n;
      // the penalty force now weighs the pair's speed for eq. 15's test
      const double N_now = normal_force_N(k, c.depth_m, p.v_n_before);
      load_sum += N_now;
      speed_weighted += N_now * v_t.norm();
      n_sum += c.n_G;

      StickAnchor anchor;
      anchor.body_a = pair.a;
      anchor.body_b = pair.b;
      anchor.p_A = X_AG * c.p_G;
      if (const StickAnchor* before = match_anchor(previous, c, anchor.p_A)) {
        // The spring's stretch carried over, re-based on this step's contact point: a rolling
        // ball carries its contact round its surface, and anchors left on the material points
        // would stretch with no slip at all (a drag of 1.2 % on the rolling-resistance stop).
        // Where the contact stays on both bodies (a box sticking on an incline) this is the
        // material anchors' stretch. (Kinematic bodies are at the step's end: their anchors go
        // where the point will be, so the stretch below is d_t at the step's start.)
        const Eigen::Vector3d v_kinematic = kinematic_velocity(c.p_G);
        const Eigen::Vector3d d = B.X_GB * before->r_B - A.X_GB * before->r_A - h_s * v_kinematic;
        const Eigen::Vector3d d_t = d - d.dot(c.n_G) * c.n_G;
        const auto ahead = [&](const ContactBody& body) -> Eigen::Vector3d {
          return body.dynamic ? Eigen::Vector3d::Zero() : Eigen::Vector3d(h_s * body.point_velocity(c.p_G));
        };
        const Eigen::Vector3d ahead_A = ahead(A), ahead_B = ahead(B);
        anchor.r_A = X_AG * (c.p_G + ahead_A);
        anchor.r_B = X_BG * (c.p_G + d_t + ahead_B);
        was_sliding = was_sliding || !before->sticking;
        p.lambda_n = before->lambda_n;
        const Eigen::Vector3d lambda_t_G = A.X_GB.linear() * before->lambda_t_A;
        p.lambda_t = {lambda_t_G.dot(p.t1), lambda_t_G.dot(p.t2)};
      } else {
        anchor.r_A = anchor.p_A;
        anchor.r_B = X_BG * c.p_G;
      }
      next_anchors_.push_back(anchor);
      points_.push_back(p);
    }
    pair.end = points_.size();
    pair.n_mean = n_sum.normalized();
    // the rolling and spinning rows' axes and inverse inertias are the step's (not each sweep's)
    if (pair.mu.mu_roll_m > 0.0) {
      tangent_basis(pair.n_mean, pair.u1, pair.u2);
      pair.K_roll1 = inverse_inertia_along(pair.a, pair.b, pair.u1);
      pair.K_roll2 = inverse_inertia_along(pair.a, pair.b, pair.u2);
      pair.inertia_roll1 = pair.K_roll1 > 0.0 ? 1.0 / pair.K_roll1 : 0.0;
      pair.inertia_roll2 = pair.K_roll2 > 0.0 ? 1.0 / pair.K_roll2 : 0.0;
    }
    if (pair.mu.mu_spin_m > 0.0) {
      pair.K_spin = inverse_inertia_along(pair.a, pair.b, pair.n_mean);
      pair.inertia_spin = pair.K_spin > 0.0 ? 1.0 / pair.K_spin : 0.0;
    }
    // eq. 15: a sliding pair sticks again once slower than epsilon (anchors start over); a new
    // or sticking pair sticks until its springs pull past the cap (inside the iterations)
    const bool slow = load_sum > 0.0 ? speed_weighted / load_sum < params_.slip_speed_mps : true;
    pair.sliding = was_sliding && !slow;
    if (was_sliding) {
      for (std::size_t j = pair.first; j < pair.end; ++j) {
        StickAnchor& anchor = next_anchors_[j];
        anchor.r_A = anchor.p_A;
        anchor.r_B = X_BG * contacts[i + (j - pair.first)].p_G;
      }
    }
    // the stick springs' stretch, the kinematic motion taken out as for the gap
    for (std::size_t j = pair.first; j < pair.end; ++j) {
      Point& p = points_[j];
      const ContactPoint& c = contacts[i + (j - pair.first)];
      const StickAnchor& anchor = next_anchors_[j];
      const Eigen::Vector3d v_kinematic = kinematic_velocity(c.p_G);
      const Eigen::Vector3d delta = B.X_GB * anchor.r_B - A.X_GB * anchor.r_A - h_s * v_kinematic;
      p.delta_t = {delta.dot(p.t1), delta.dot(p.t2)};
    }
    if (pair.kinematic) {
      // nothing moves in response: the penalty force at the step's end, in closed form (what a
      // held object's grip is judged by)
      Eigen::Vector3d trial_sum = Eigen::Vector3d::Zero();
      double N_sum = 0.0;
      for (std::size_t j = pair.first; j < pair.end; ++j) {
        Point& p = points_[j];
        const double N = normal_force_N(k, contacts[i + (j - pair.first)].depth_m, p.v_n_before);
        p.lambda_n = N * h_s;
        N_sum += N;
        const Eigen::Vector3d v_rel = relative_velocity(p);
        const Eigen::Vector2d v_t(v_rel.dot(p.t1), v_rel.dot(p.t2));
        const Eigen::Vector2d stretch = p.delta_t + h_s * v_t;
        p.lambda_t = N > 0.0 ? Eigen::Vector2d(-h_s * (k.k_pt * stretch + k.c_pt * v_t)) : Eigen::Vector2d::Zero();
        trial_sum += p.lambda_t.x() * p.t1 + p.lambda_t.y() * p.t2;
      }
      if (pair.sliding || trial_sum.norm() > pair.mu.mu_s * N_sum * h_s) {
        // sliding on: against the motion (eq. 17); just broken loose: along the springs' pull
        // (it has no motion of its own yet to go against)
        const bool broke_loose = !pair.sliding;
        pair.sliding = true;
        for (std::size_t j = pair.first; j < pair.end; ++j) {
          Point& p = points_[j];
          const Eigen::Vector3d v_rel = relative_velocity(p);
          const Eigen::Vector2d v_t(v_rel.dot(p.t1), v_rel.dot(p.t2));
          Eigen::Vector2d dir = Eigen::Vector2d::Zero();
          if (broke_loose && p.lambda_t.norm() > 0.0)
            dir = p.lambda_t.normalized();
          else if (v_t.norm() > 0.0)
            dir = -v_t.normalized();
          p.lambda_t = pair.mu.mu_d * p.lambda_n * dir;
        }
      }
    }
    pairs_.push_back(pair);
    i = end;
  }
}

void SoftContactSolver::warm_start() {
  for (const Pair& pair : pairs_) {
    if (pair.kinematic) continue;
    for (std::size_t i = pair.first; i < pair.end; ++i) {
      Point& p = points_[i];
      if (pair.sliding) p.lambda_t.setZero();  // (kinetic friction is found afresh)
      apply_row(p, p.row_n, p.lambda_n);
      apply_row(p, p.row_t1, p.lambda_t.x());
      apply_row(p, p.row_t2, p.lambda_t.y());
    }
  }
}

void SoftContactSolver::solve_normal(Point& p, bool use_bias) {
  if (!(p.K_n > 0.0)) return;
  const double v_n = row_velocity(p, p.row_n);
  double step = use_bias ? -(v_n + p.spring.beta * p.s0 + p.spring.gamma * p.lambda_n) * p.soft_mass_n
                         : -v_n * p.mass_n;  // relax: rigid, keeps what the spring did
  // The relax sweeps take out what the dashpot's restitution puts back: an impact is stopped
  // rigidly, and a rebound loses the springs' push-out. A slow point keeps the spring's own
  // end-of-step speed, or a heavy body would reach its rest depth by creep. (A moving kinematic
  // body, a hand link or a held object, pushes through its spring only: the proxy bounds that
  // spring's force, and a rigid stop would throw what it touches at the hand's speed.)
  double upper = kUnbounded;
  if (!use_bias) {
    const double threshold = params_.restitution_threshold_mps;
    if (p.v_n_own > threshold) upper = p.lambda_n_spring;
    else if (p.v_n_own >= -threshold) return;
  }
  const double next = std::clamp(p.lambda_n + step, 0.0, upper);
  apply_row(p, p.row_n, next - p.lambda_n);
  p.lambda_n = next;
}

void SoftContactSolver::solve_friction(Pair& pair, double load, bool use_bias) {
  for (std::size_t i = pair.first; i < pair.end; ++i) {
    Point& p = points_[i];
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    if (p.lambda_n <= 0.0) {
      step = -p.lambda_t;  // an unloaded point holds nothing
    } else {
      const Eigen::Vector2d v_t(row_velocity(p, p.row_t1), row_velocity(p, p.row_t2));
      const double g = p.spring.gamma;
      if (!pair.sliding && use_bias) {
        // the stick spring (eq. 16), implicit: same k_pt, c_pt as the normal
        step.x() = -(v_t.x() + p.spring.beta * p.delta_t.x() + g * p.lambda_t.x()) * p.soft_mass_t1;
        step.y() = -(v_t.y() + p.spring.beta * p.delta_t.y() + g * p.lambda_t.y()) * p.soft_mass_t2;
      } else {
        // sliding (eq. 17 on the end-of-step velocity), or relax: stop the tangential motion
        step.x() = -v_t.x() * p.mass_t1;
        step.y() = -v_t.y() * p.mass_t2;
        if (pair.sliding) {
          // eq. 17 point by point: at most mu_d N here (a sliding, spinning patch's points pull
          // different ways, which a cap on their sum alone would never meet)
          const Eigen::Vector2d next = p.lambda_t + step;
          const double limit = pair.mu.mu_d * p.lambda_n;
          if (next.norm() > limit) step = next * (limit / next.norm()) - p.lambda_t;
        }
      }
    }
    apply_row(p, p.row_t1, step.x());
    apply_row(p, p.row_t2, step.y());
    p.lambda_t += step;
  }
  if (pair.sliding) return;  // (each point capped above)
  // the patch's cone (eq. 16 over the pair): past mu_s sum(N) a sticking pair breaks loose and
  // slides from here on in this step, at mu_d sum(N); in the relax sweeps (rigid rows, which may
  // ask for more than the springs pulled) it is only held to the cone
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = pair.first; i < pair.end; ++i) {
    const Point& p = points_[i];
    sum += p.lambda_t.x() * p.row_t1.u + p.lambda_t.y() * p.row_t2.u;
  }
  const double size = sum.norm();
  if (use_bias && size > pair.mu.mu_s * load) pair.sliding = true;
  const double cap = (pair.sliding ? pair.mu.mu_d : pair.mu.mu_s) * load;
  if (size <= cap || !(size > 0.0)) return;
  const double scale = cap / size;
  for (std::size_t i = pair.first; i < pair.end; ++i) {
    Point& p = points_[i];
    const Eigen::Vector2d change = p.lambda_t * (scale - 1.0);
    apply_row(p, p.row_t1, change.x());
    apply_row(p, p.row_t2, change.y());
    p.lambda_t += change;
  }
}

void SoftContactSolver::solve_rolling(Pair& pair, double load) {
  const double mu_roll = pair.mu.mu_roll_m, mu_spin = pair.mu.mu_spin_m;
  if (!(mu_roll > 0.0) && !(mu_spin > 0.0)) return;
  const Eigen::Vector3d& n = pair.n_mean;
  const Eigen::Vector3d w_rel = w_[pair.b] - w_[pair.a];
  if (mu_roll > 0.0) {
    const Eigen::Vector3d& u1 = pair.u1;
    const Eigen::Vector3d& u2 = pair.u2;
    const Eigen::Vector2d before = pair.lambda_roll;
    Eigen::Vector2d next = before;
    next.x() -= w_rel.dot(u1) * pair.inertia_roll1;
    next.y() -= w_rel.dot(u2) * pair.inertia_roll2;
    const double cap = mu_roll * load;
    if (next.norm() > cap) next *= cap / next.norm();
    const Eigen::Vector2d change = next - before;
    apply_angular_impulse(pair.a, pair.b, change.x() * u1 + change.y() * u2);
    pair.lambda_roll = next;
  }
  if (mu_spin > 0.0) {
    const double K = pair.K_spin;
    if (K > 0.0) {
      const double w_spin = (w_[pair.b] - w_[pair.a]).dot(n);
      const double cap = mu_spin * load;
      const double next = std::clamp(pair.lambda_spin - w_spin * pair.inertia_spin, -cap, cap);
      apply_angular_impulse(pair.a, pair.b, (next - pair.lambda_spin) * n);
      pair.lambda_spin = next;
    }
  }
}

void SoftContactSolver::restitution() {
  // the relax pass took out the spring's push-out speed; the dashpot's own bounce goes back in
  // (Box2D's b2ApplyRestitution): the approach speed times the dashpot's e, for an impact
  const double threshold = params_.restitution_threshold_mps;
  for (const Pair& pair : pairs_) {
    if (pair.kinematic) continue;
    for (std::size_t i = pair.first; i < pair.end; ++i) {
      Point& p = points_[i];
      if (!(p.K_n > 0.0) || p.v_n_own > -threshold || p.lambda_n <= 0.0) continue;
      const double v_n = row_velocity(p, p.row_n);
      const double next = std::max(0.0, p.lambda_n - (v_n + p.restitution * p.v_n_before) * p.mass_n);
      apply_row(p, p.row_n, next - p.lambda_n);
      p.lambda_n = next;
    }
  }
}

void SoftContactSolver::store(const std::vector<ContactPoint>& contacts,
                              const std::vector<ContactBody>& bodies, double h_s,
                              std::vector<AppliedContact>& applied) {
  applied.clear();
  for (const Pair& pair : pairs_) {
    const ContactBody& A = bodies[static_cast<std::size_t>(pair.a)];
    const ContactBody& B = bodies[static_cast<std::size_t>(pair.b)];
    const Eigen::Isometry3d X_BG = B.X_GB.inverse();
    for (std::size_t i = pair.first; i < pair.end; ++i) {
      const Point& p = points_[i];
      const ContactPoint& c = contacts[i];
      const Eigen::Vector3d lambda_t = p.lambda_t.x() * p.t1 + p.lambda_t.y() * p.t2;
      applied.push_back({c, (p.lambda_n * p.n + lambda_t) / h_s, p.lambda_n / h_s, pair.sliding});
      StickAnchor& anchor = next_anchors_[i];
      anchor.sticking = !pair.sliding;
      anchor.lambda_n = p.lambda_n;
      anchor.lambda_t_A = A.X_GB.linear().transpose() * lambda_t;
      // a sliding point's anchor follows it; an unloaded one starts over
      if (pair.sliding || p.lambda_n <= 0.0) {
        anchor.r_A = anchor.p_A;
        anchor.r_B = X_BG * c.p_G;
      }
    }
  }
}

}  // namespace vcockpit::physics
