#pragma once
// A penalty spring-damper (stiffness k, damping c) stepped by backward Euler over a step h, as a
// soft constraint (Catto, "Soft constraints", GDC 2011; Jolt's SpringPart; Box2D v3's
// b2MakeSoft). With the effective mass m = 1/K of the constrained direction, the separation s0
// at the step's start and v* the velocity before the constraint, the spring's impulse over the
// step is
//   lambda = -(v* + beta s0) / (K + gamma),   gamma = 1 / (h (c + h k)),   beta = k / (c + h k)
// which is h (-k s1 - c v1) at the end-of-step state (s1 = s0 + h v1): the same spring, stable
// for any k h^2 / m. Iterated (Gauss-Seidel) with an accumulated impulse lambda_acc the update is
//   d_lambda = -(v + beta s0 + gamma lambda_acc) / (K + gamma)
// whose fixed point is that lambda. docs/design/soft_contacts.md derives it.

namespace vcockpit::physics {

struct SoftSpring {
  double gamma = 0.0;  // softness: the constraint's compliance over the step (s/kg)
  double beta = 0.0;   // bias rate: how much of the separation is closed per second (1/s)
};

// k > 0 (N/m), c >= 0 (N s/m), h > 0 (s).
inline SoftSpring soft_from_spring(double k_N_per_m, double c_Ns_per_m, double h_s) {
  const double stiff = c_Ns_per_m + h_s * k_N_per_m;
  return {1.0 / (h_s * stiff), k_N_per_m / stiff};
}

// The coefficient of restitution of a linear dashpot that never pulls (the contact lets go when
// its force would turn tensile), damping ratio zeta in [0, 1): Schwager & Poeschel, "Coefficient
// of restitution and linear-dashpot model revisited", Granular Matter 9 (2007). 0.3 -> 0.451,
// 0.7 -> 0.210, 0.9 -> 0.155; 1 and over: 0 (the dashpot stops it).
double dashpot_restitution(double zeta);

}  // namespace vcockpit::physics
