#include "flexgait/rimless/dynamics.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace flexgait::rimless {

namespace {

// The Schur complement system (A M⁻¹ Aᵀ) λ = b − A M⁻¹ F of R stick rows, by Eigen's LDLT of
// fixed size R (the hot path of every right-hand side: no dynamic sizes). False when the rows
// are dependent (D not positive, or its smallest entry below 1e-13 of its largest).
template <int R>
bool solve_schur(const std::array<std::array<double, 3>, kMaxContacts>& A, const std::array<double, 3>& minv,
                 const std::array<double, 3>& F, const std::array<double, kMaxContacts>& b,
                 std::array<double, kMaxContacts>& lambda) {
  Eigen::Matrix<double, R, R> S;
  Eigen::Matrix<double, R, 1> r;
  for (int i = 0; i < R; ++i) {
    double AMF = 0;
    for (int j = 0; j < 3; ++j) AMF += A[i][j] * minv[j] * F[j];
    r(i) = b[i] - AMF;
    for (int k = 0; k < R; ++k) {
      double s = 0;
      for (int j = 0; j < 3; ++j) s += A[i][j] * minv[j] * A[k][j];
      S(i, k) = s;
    }
  }
  const Eigen::LDLT<Eigen::Matrix<double, R, R>> ldlt(S);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return false;
  const double dmax = ldlt.vectorD().maxCoeff(), dmin = ldlt.vectorD().minCoeff();
  if (!(dmin > 1e-13 * dmax)) return false;
  const Eigen::Matrix<double, R, 1> lam = ldlt.solve(r);
  for (int i = 0; i < R; ++i) lambda[static_cast<std::size_t>(i)] = lam(i);
  return true;
}

// One stick row (the hot path of single support): the same numbers as solve_schur<1>, whose LDLT
// of a 1×1 matrix S is D = S; it accepts S > 1e-13 S (S > 0, finite) and divides by D where
// |D| exceeds the smallest normal double (Eigen's LDLT solve, else 0).
bool solve_schur_one(const std::array<double, 3>& A, const std::array<double, 3>& minv, const std::array<double, 3>& F,
                     double b, double& lambda) {
  double AMF = 0, S = 0;
  for (int j = 0; j < 3; ++j) AMF += A[j] * minv[j] * F[j];
  for (int j = 0; j < 3; ++j) S += A[j] * minv[j] * A[j];
  if (!(S > 1e-13 * S)) return false;
  const double r = b - AMF;
  lambda = std::abs(S) > std::numeric_limits<double>::min() ? r / S : 0.0;
  return true;
}

// The point mass (I = 0): the θ row is a torque balance; the full KKT system, a singular one
// rejected. Apart from the Schur complement's hot path (its LU's workspace is a large stack frame).
[[gnu::noinline]] bool solve_kkt(const WheelParams& w, int rows,
                                 const std::array<std::array<double, 3>, kMaxContacts>& A,
                                 const std::array<double, 3>& F, const std::array<double, kMaxContacts>& b,
                                 std::array<double, 3>& a, std::array<double, kMaxContacts>& lambda) {
  const std::array<double, 3> mass{w.m, w.m, w.I};
  const int n = 3 + rows;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 + kMaxContacts, 3 + kMaxContacts> K(n, n);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 + kMaxContacts, 1> rhs(n);
  K.setZero();
  for (int j = 0; j < 3; ++j) {
    K(j, j) = mass[j];
    rhs(j) = F[j];
  }
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < 3; ++j) {
      K(j, 3 + i) = -A[i][j];
      K(3 + i, j) = A[i][j];
    }
    rhs(3 + i) = b[i];
  }
  if (rows == 0 && std::abs(F[2]) <= 1e-12 * (std::abs(F[0]) + std::abs(F[1]) + 1e-300)) {
    // Flight with a point mass: no torque acts and θ̈ = 0 (the limit of θ̈ = 0 / I).
    a = {F[0] / w.m, F[1] / w.m, 0.0};
    return true;
  }
  Eigen::FullPivLU<decltype(K)> lu(K);
  lu.setThreshold(1e-12);
  if (!lu.isInvertible()) return false;
  const auto sol = lu.solve(rhs).eval();
  for (int j = 0; j < 3; ++j) a[j] = sol(j);
  for (int i = 0; i < rows; ++i) lambda[i] = sol(3 + i);
  return true;
}

// solve_constrained with M⁻¹ given (minv = diag(1/m, 1/m, 1/I); unused for I = 0).
bool solve_constrained(const WheelParams& w, const std::array<double, 3>& minv, int rows,
                       const std::array<std::array<double, 3>, kMaxContacts>& A, const std::array<double, 3>& F,
                       const std::array<double, kMaxContacts>& b, std::array<double, 3>& a,
                       std::array<double, kMaxContacts>& lambda) {
  if (!(w.I > 0)) return solve_kkt(w, rows, A, F, b, a, lambda);
  // Schur complement: (A M⁻¹ Aᵀ) λ = b - A M⁻¹ F, then a = M⁻¹ (F + Aᵀ λ).
  if (rows == 0) {
    for (int j = 0; j < 3; ++j) a[j] = F[j] * minv[j];
    return true;
  }
  std::array<double, kMaxContacts> lam{};
  const bool solved = rows == 1   ? solve_schur_one(A[0], minv, F, b[0], lam[0])
                      : rows == 2 ? solve_schur<2>(A, minv, F, b, lam)
                                  : solve_schur<3>(A, minv, F, b, lam);
  if (!solved) return false;
  for (int j = 0; j < 3; ++j) {
    double s = F[j];
    for (int i = 0; i < rows; ++i) s += A[i][j] * lam[i];
    a[j] = s * minv[j];
  }
  lambda = lam;  // (0 past the rows; a fixed-size copy)
  return true;
}

}  // namespace

bool solve_constrained(const WheelParams& w, int rows, const std::array<std::array<double, 3>, kMaxContacts>& A,
                       const std::array<double, 3>& F, const std::array<double, kMaxContacts>& b,
                       std::array<double, 3>& a, std::array<double, kMaxContacts>& lambda) {
  const std::array<double, 3> minv{1.0 / w.m, 1.0 / w.m, w.I > 0 ? 1.0 / w.I : 0.0};
  return solve_constrained(w, minv, rows, A, F, b, a, lambda);
}

namespace {

// Legs, applied forces F and stick-constraint rows of the contact set at state q (q, q̇).
// Only the first `rows` stick rows are set and read (not zeroed: zeroing the whole struct was a
// measurable part of every right-hand side).
struct Assembly {
  std::array<double, 3> F{};
  std::array<std::array<double, 3>, kMaxContacts> A;
  std::array<double, kMaxContacts> b;
  std::array<int, kMaxContacts> stick_index;
  int rows = 0;
};

// The wheel's constants for w, remembered in the workspace d (Dynamics::WheelConstants).
const Dynamics::WheelConstants& wheel_constants(const WheelParams& w, Dynamics& d) {
  Dynamics::WheelConstants& c = d.constants;
  if (c.slope == w.slope && c.m == w.m && c.I == w.I && c.K == w.K && c.C == w.C && c.legs == w.legs) return c;
  c = {w.slope, w.m, w.I, w.K, w.C, w.legs};
  c.sin_slope = std::sin(w.slope);
  c.cos_slope = std::cos(w.slope);
  c.minv = {1.0 / w.m, 1.0 / w.m, w.I > 0 ? 1.0 / w.I : 0.0};
  c.leg_spacing = 2.0 * w.alpha();
  c.relax_rate = w.C > 0 ? w.K / w.C : 0.0;
  return c;
}

Assembly assemble(const WheelParams& w, const ContactSet& contacts, std::span<const double> q, Dynamics& d) {
  Assembly a;
  const Dynamics::WheelConstants& constants = wheel_constants(w, d);
  a.F = {w.m * w.g * constants.sin_slope, -w.m * w.g * constants.cos_slope, 0.0};
  constexpr double wb = kStickStabilization;
  d.failure.reset();
  d.jammed = false;
  for (int i = 0; i < contacts.count; ++i) {
    // β = θ + 2αk wrapped (leg_angle), 2α and the turns the wrap removes remembered
    leg_kinematics_at(w, d.wraps[i](q[StateIndex::theta] + constants.leg_spacing * contacts.leg[i]), q, d.leg[i]);
    const LegKinematics& g = d.leg[i];
    ContactForce& cf = d.force[i];
    cf = ContactForce{};
    cf.f = g.f;
    for (int j = 0; j < 3; ++j) a.F[j] += g.f * g.gradL[j];
    const int s = slip_sign(contacts.mode[i]);
    if (s == 0) {
      a.A[a.rows] = g.A;
      a.b[a.rows] = -g.Adot_qdot - 2.0 * wb * g.cdot - wb * wb * (g.c - contacts.anchor[i]);
      a.stick_index[a.rows++] = i;
    } else {
      // Slip law T = -s μ N with μ = μ(ċ) (SlipLaw; μ = μ_k for Coulomb), and the massless
      // leg's axial balance T sin β + N cos β = f (docs/theory/rimless.md, "Equations of motion"):
      //   T = -s μ f / D,   N = f / D,   D = cos β - μ s sin β.
      // ċ is a function of (q, q̇), not of q̈, so T is explicit and D <= 0 remains the Painlevé
      // jam with the velocity-dependent coefficient. The viscous part is load-proportional (in
      // μ): a friction force σ|ċ| that outlives N = 0 would leave a foot at zero load that can
      // neither leave, slip on, nor be stopped (docs/guide/rimless.md, "Stribeck friction").
      const SlipLaw law = slip_law(w, s, g.cdot);
      cf.D = slip_denominator(g, s, law.mu);
      if (!(cf.D > 0)) {
        d.failure = FailureReason::SlipJam;
        d.jammed = true;
      }
      cf.T = -s * law.mu * g.f / cf.D;
      for (int j = 0; j < 3; ++j) a.F[j] += g.A[j] * cf.T;
    }
  }
  return a;
}

}  // namespace

Dynamics contact_dynamics(const WheelParams& w, const ContactSet& contacts, std::span<const double> y) {
  Dynamics d;
  contact_dynamics(w, contacts, y, d);
  return d;
}

void contact_dynamics(const WheelParams& w, const ContactSet& contacts, std::span<const double> y, Dynamics& d) {
  if (contact_accelerations(w, contacts, y, d)) normal_forces(contacts, d);
}

void normal_forces(const ContactSet& contacts, Dynamics& d) {
  for (int i = 0; i < contacts.count; ++i) {
    ContactForce& cf = d.force[i];
    cf.N = (cf.f - cf.T * d.leg[i].sb) / d.leg[i].cb;
  }
}

bool contact_accelerations(const WheelParams& w, const ContactSet& contacts, std::span<const double> y, Dynamics& d) {
  std::array<double, 6> q{y[0], y[1], y[2], y[3], y[4], y[5]};
  d.thetad = q[StateIndex::thetad];
  d.algebraic_thetad = false;
  Assembly a = assemble(w, contacts, q, d);
  if (w.I == 0 && a.rows == 0 && contacts.count >= 2 && !d.failure) {
    // Torque balance Q_θ(θ̇) = Q0 + (Q1 - Q0) θ̇ = 0 fixes θ̇ (see the header).
    q[StateIndex::thetad] = 0.0;
    const double q0 = assemble(w, contacts, q, d).F[2];
    q[StateIndex::thetad] = 1.0;
    const double q1 = assemble(w, contacts, q, d).F[2];
    if (!(std::abs(q1 - q0) > 1e-12 * (std::abs(q0) + std::abs(q1)))) {
      d.failure = FailureReason::PointMassTorqueBalance;
      return false;
    }
    q[StateIndex::thetad] = d.thetad = -q0 / (q1 - q0);
    d.algebraic_thetad = true;
    a = assemble(w, contacts, q, d);
    if (d.failure) return false;
    d.qdd = {a.F[0] / w.m, a.F[1] / w.m, 0.0};
  } else {
    std::array<double, kMaxContacts> lambda{};
    if (!solve_constrained(w, d.constants.minv, a.rows, a.A, a.F, a.b, d.qdd, lambda)) {
      d.failure = FailureReason::PointMassSingular;
      return false;
    }
    for (int r = 0; r < a.rows; ++r) d.force[a.stick_index[r]].T = lambda[r];
  }
  return true;
}

}  // namespace flexgait::rimless
