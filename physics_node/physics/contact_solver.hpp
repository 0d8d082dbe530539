#pragma once
// The paper's contact model (eqs. 11-19) integrated implicitly: each contact point's penalty
// spring-damper, and its stick spring while the pair sticks, is a soft constraint with the same
// k_pt and c_pt (soft_constraint.hpp), solved at the full step by a few Gauss-Seidel iterations
// (Catto's soft step, Solver2D 2024; Box2D v3): velocities with gravity, warm start, biased
// iterations, positions, relax iterations without the bias, restitution. Friction keeps the
// pair's stick/slide state machine (friction_force.hpp): a sticking pair's points pull to their
// anchors, capped at mu_s sum(lambda_n) over the patch; once the cap binds the pair slides for the
// rest of the step, with mu_d sum(lambda_n) against its motion; it sticks again when its
// load-weighted speed is below epsilon. Rolling and spinning resistance are velocity rows capped at
// mu_roll and mu_spin times the pair's load. docs/design/soft_contacts.md is the design.
//
// A control's body moves on its joint (solver_joint.hpp): the solver finds the contacts' impulse
// on it with its rate's answer to that impulse, and the control system then moves it.
//
// Bodies that are not dynamic (static, held, hand links) are kinematic: their velocity is
// given and their pose is already at the step's end when the narrowphase ran; the separation of
// a point is shifted back by their motion over the step, so that only the dynamic bodies' motion
// closes it. A pair of two kinematic bodies is one closed-form update: the penalty force itself.

#include <Eigen/Geometry>
#include <vector>

#include "physics_node/physics/body.hpp"
#include "physics_node/physics/contact.hpp"
#include "physics_node/physics/anchor_match.hpp"
#include "physics_node/physics/friction_force.hpp"
#include "physics_node/physics/soft_constraint.hpp"
#include "physics_node/physics/solver_joint.hpp"

namespace vcockpit::physics {

struct SoftSolverParams {
  int iterations = 8;                        // biased Gauss-Seidel sweeps
  int relax_iterations = 2;                  // sweeps without the bias (remove push-out speed)
  double restitution_threshold_mps = 0.1;    // slower impacts get no restitution pass
  double slip_speed_mps = 1.0e-3;            // eq. 15's epsilon
};

class SoftContactSolver {
 public:
  explicit SoftContactSolver(const SoftSolverParams& params) : params_(params) {}

  // One step h of the dynamic bodies in `bodies` (ContactBody::dynamic; the others are
  // kinematic) under gravity and `contacts` (sorted by pair). In: each body's velocity at the
  // step's start (kinematic: over the step). Out: v_G, w_G of every dynamic body after the
  // contacts (gravity included: integrate positions with them), `applied` (each point's force
  // over the step, lambda / h, for eqs. 18-19 and the grasp rule) and `anchors` (stick anchors
  // with their impulses, for the next step's warm start; the previous step's in). `touched[b]`
  // is set for every dynamic body in a contact (the others integrate on their own). `joints`:
  // the controls' bodies in a contact, which move on their joints (their ContactBody is dynamic;
  // its mass and inertia are not used); out: each one's generalised impulse (move_impulse).
  void solve(const std::vector<ContactPoint>& contacts, std::vector<ContactBody>& bodies,
             std::vector<SolverJoint>& joints, const Eigen::Vector3d& gravity_mps2, double h_s,
             std::vector<AppliedContact>& applied, std::vector<StickAnchor>& anchors,
             std::vector<uint8_t>& touched);
  // After solve(): a touched body's v_G, w_G in `bodies` are what its position moves with (the
  // springs' push-out in them); these are its velocities at the step's end.
  const Eigen::Vector3d& v_end(int body) const { return v_[static_cast<std::size_t>(body)]; }
  const Eigen::Vector3d& w_end(int body) const { return w_[static_cast<std::size_t>(body)]; }

 private:
  // One direction u of a point's impulse, found once a step: r x u for each body (a velocity's
  // part along u is (v_b - v_a).u + w_b.(r_b x u) - w_a.(r_a x u)) and I^-1 (r x u) (the spin
  // an impulse along u gives). Each sweep then needs no cross product and no inertia product.
  struct Row {
    Eigen::Vector3d u = Eigen::Vector3d::UnitZ();
    Eigen::Vector3d ra_u = Eigen::Vector3d::Zero(), rb_u = Eigen::Vector3d::Zero();
    Eigen::Vector3d spin_a = Eigen::Vector3d::Zero(), spin_b = Eigen::Vector3d::Zero();
  };
  // What the sweeps read first (the rows, their masses and impulses, in the order the sweeps
  // take them), then what only prepare and store read: a point spans several cache lines, and
  // a sweep should touch as few of them as it can.
  struct Point {
    int a = -1, b = -1;
    bool on_joint = false;  // a or b moves on a control's joint
    Row row_n;
    double K_n = 0.0;  // inverse effective mass along n
    // the sweeps multiply by these rather than divide (a division's latency is on the sweeps'
    // critical path): 1 / K (0 where K is 0: nothing moves along that row) for the rigid rows,
    // 1 / (K + gamma) for the soft ones
    double mass_n = 0.0, soft_mass_n = 0.0;
    SoftSpring spring;
    double s0 = 0.0;  // separation (m, < 0 overlapping), shifted back by the kinematic motion
    double lambda_n = 0.0;
    double lambda_n_spring = 0.0;  // what the biased sweeps left (a slow point relaxes below it)
    double v_n_own = 0.0;  // its dynamic bodies' part of v_n_before (an impact or rebound if fast)
    Row row_t1, row_t2;
    double K_t1 = 0.0, K_t2 = 0.0;
    double mass_t1 = 0.0, mass_t2 = 0.0, soft_mass_t1 = 0.0, soft_mass_t2 = 0.0;
    Eigen::Vector2d delta_t = Eigen::Vector2d::Zero();  // stick spring's stretch along t1, t2
    Eigen::Vector2d lambda_t = Eigen::Vector2d::Zero();
    Eigen::Vector3d p_G = Eigen::Vector3d::Zero();  // where it acts
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ(), t1 = Eigen::Vector3d::UnitX(),
                    t2 = Eigen::Vector3d::UnitY();
    Eigen::Vector3d r_a = Eigen::Vector3d::Zero(), r_b = Eigen::Vector3d::Zero();
    double v_n_before = 0.0;   // the normal speed before the solve (< 0 approaching)
    double restitution = 0.0;  // the dashpot's e for this point's zeta
  };
  struct Pair {
    std::size_t first = 0, end = 0;  // its points
    int a = -1, b = -1;
    PairFriction mu;
    bool sliding = false;      // this step: kinetic friction
    bool kinematic = false;    // both bodies kinematic: the penalty force in closed form
    Eigen::Vector3d n_mean = Eigen::Vector3d::UnitZ();  // the patch's normal (rolling, spinning)
    Eigen::Vector3d u1 = Eigen::Vector3d::UnitX(), u2 = Eigen::Vector3d::UnitY();  // rolling axes
    double K_roll1 = 0.0, K_roll2 = 0.0, K_spin = 0.0;  // inverse inertias about u1, u2, n_mean
    double inertia_roll1 = 0.0, inertia_roll2 = 0.0, inertia_spin = 0.0;  // their inverses (or 0)
    Eigen::Vector2d lambda_roll = Eigen::Vector2d::Zero();
    double lambda_spin = 0.0;
  };

  void prepare(const std::vector<ContactPoint>& contacts, const std::vector<ContactBody>& bodies,
               double h_s, const std::vector<StickAnchor>& previous);
  void warm_start();
  void solve_normal(Point& p, bool use_bias);
  // `load`: the pair's normal impulse after this sweep's normal rows (the cones' size)
  void solve_friction(Pair& pair, double load, bool use_bias);
  void solve_rolling(Pair& pair, double load);
  void restitution();
  void store(const std::vector<ContactPoint>& contacts, const std::vector<ContactBody>& bodies,
             double h_s, std::vector<AppliedContact>& applied);

  Eigen::Vector3d relative_velocity(const Point& p) const;
  Row make_row(const Point& p, const Eigen::Vector3d& u) const;
  // The sweeps' innermost operations, inlined into them (GCC kept them as calls).
  // the relative velocity along u
  [[gnu::always_inline]] double row_velocity(const Point& p, const Row& row) const {
    return (v_[p.b] - v_[p.a]).dot(row.u) + w_[p.b].dot(row.rb_u) - w_[p.a].dot(row.ra_u);
  }
  // impulse * u on b, -it on a. Kinematic bodies and joint bodies have zero inverse mass and
  // inertia, and are skipped: 0 * NaN is NaN, and a static floor would carry one body's fault to
  // the others.
  [[gnu::always_inline]] void apply_row(const Point& p, const Row& row, double impulse) {
    if (inv_m_[p.b] > 0.0) {
      v_[p.b] += (inv_m_[p.b] * impulse) * row.u;
      w_[p.b] += impulse * row.spin_b;
    }
    if (inv_m_[p.a] > 0.0) {
      v_[p.a] -= (inv_m_[p.a] * impulse) * row.u;
      w_[p.a] -= impulse * row.spin_a;
    }
    if (p.on_joint) push_joints(p, impulse * row.u);
  }
  void push_joints(const Point& p, const Eigen::Vector3d& P);
  void apply_angular_impulse(int a, int b, const Eigen::Vector3d& L);
  // a generalised impulse on joint body `body`'s joint; its velocity follows
  void push_joint(int body, double impulse);
  // a point's inverse effective mass along its row's u, and the pair's for a couple about u
  double inverse_mass_along(const Point& p, const Row& row) const;
  double inverse_inertia_along(int a, int b, const Eigen::Vector3d& u) const;
  const StickAnchor* match_anchor(const std::vector<StickAnchor>& previous, const ContactPoint& c,
                                  const Eigen::Vector3d& p_A);

  SoftSolverParams params_;
  // per body (indexed like the contacts): velocity being solved, inverse mass and world inverse
  // inertia (0: kinematic)
  std::vector<Eigen::Vector3d> v_, w_;
  std::vector<double> inv_m_;
  std::vector<Eigen::Matrix3d> inv_I_G_;
  std::vector<int> joint_of_;  // per body: its index in joints_, -1
  std::vector<SolverJoint>* joints_ = nullptr;
  std::vector<Point> points_;
  std::vector<Pair> pairs_;
  std::vector<StickAnchor> next_anchors_;
  std::vector<uint8_t> anchor_used_;
};

}  // namespace vcockpit::physics
