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

}  // namespace

bool solve_constrained(const WheelParams& w, int rows, const std::array<std::array<double, 3>, kMaxContacts>& A,
                       const std::array<double, 3>& F, const std::array<double, kMaxContacts>& b,
                       std::array<double, 3>& a, std::array<double, kMaxContacts>& lambda) {
  const std::array<double, 3> mass{w.m, w.m, w.I};
  if (w.I > 0) {
    // Schur complement: (A M⁻¹ Aᵀ) λ = b - A M⁻¹ F, then a = M⁻¹ (F + Aᵀ λ).
    const std::array<double, 3> minv{1.0 / mass[0], 1.0 / mass[1], 1.0 / mass[2]};
    if (rows == 0) {
      for (int j = 0; j < 3; ++j) a[j] = F[j] * minv[j];
      return true;
    }
    std::array<double, kMaxContacts> lam{};
    const bool solved = rows == 1   ? solve_schur<1>(A, minv, F, b, lam)
                        : rows == 2 ? solve_schur<2>(A, minv, F, b, lam)
                                    : solve_schur<3>(A, minv, F, b, lam);
    if (!solved) return false;
    for (int j = 0; j < 3; ++j) {
      double s = F[j];
      for (int i = 0; i < rows; ++i) s += A[i][j] * lam[i];
      a[j] = s * minv[j];
    }
    for (int i = 0; i < rows; ++i) lambda[i] = lam[i];
    return true;
  }
  // I = 0: the θ row is a torque balance; solve the full KKT system and reject a singular one.
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

namespace {

// Legs, applied forces F and stick-constraint rows of the contact set at state q (q, q̇).
struct Assembly {
  std::array<double, 3> F{};
  std::array<std::array<double, 3>, kMaxContacts> A{};
  std::array<double, kMaxContacts> b{};
  std::array<int, kMaxContacts> stick_index{};
  int rows = 0;
};

// (sin φ, cos φ) of the slope, remembered in the workspace d (Dynamics::slope_trig).
const Dynamics::SlopeTrig& slope_trig(double slope, Dynamics& d) {
  if (!(d.slope_trig.slope == slope)) d.slope_trig = {slope, std::sin(slope), std::cos(slope)};
  return d.slope_trig;
}

Assembly assemble(const WheelParams& w, const ContactSet& contacts, std::span<const double> q, Dynamics& d) {
  Assembly a;
  const Dynamics::SlopeTrig& slope = slope_trig(w.slope, d);
  a.F = {w.m * w.g * slope.sin, -w.m * w.g * slope.cos, 0.0};
  constexpr double wb = kStickStabilization;
  d.failure.reset();
  d.jammed = false;
  for (int i = 0; i < contacts.count; ++i) {
    leg_kinematics(w, contacts.leg[i], q, d.leg[i]);
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
      return;
    }
    q[StateIndex::thetad] = d.thetad = -q0 / (q1 - q0);
    d.algebraic_thetad = true;
    a = assemble(w, contacts, q, d);
    if (d.failure) return;
    d.qdd = {a.F[0] / w.m, a.F[1] / w.m, 0.0};
  } else {
    std::array<double, kMaxContacts> lambda{};
    if (!solve_constrained(w, a.rows, a.A, a.F, a.b, d.qdd, lambda)) {
      d.failure = FailureReason::PointMassSingular;
      return;
    }
    for (int r = 0; r < a.rows; ++r) d.force[a.stick_index[r]].T = lambda[r];
  }
  for (int i = 0; i < contacts.count; ++i) {
    ContactForce& cf = d.force[i];
    cf.N = (cf.f - cf.T * d.leg[i].sb) / d.leg[i].cb;
  }
}

}  // namespace flexgait::rimless
