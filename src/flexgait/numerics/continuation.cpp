#include "flexgait/numerics/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "flexgait/numerics/newton.hpp"

namespace flexgait::numerics {
namespace {

using Error = std::optional<std::string>;

std::string number(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

/// F(x) = P(z, p) - z at x = (z, p).
Error residual(const MapFamily& f, const Eigen::VectorXd& x, Eigen::VectorXd& F) {
  const Eigen::Index n = x.size() - 1;
  const Eigen::VectorXd z = x.head(n);
  Eigen::VectorXd out(n);
  if (auto e = f.map(z, x(n), out)) return e;
  if (out.size() != n || !out.allFinite()) return std::string("the map returned a non-finite or mis-sized state");
  F = out - z;
  return std::nullopt;
}

/// J = [F_z F_p] (n x (n + 1)) at x.
Error linearise(const MapFamily& f, const Eigen::VectorXd& x, const ContinuationOptions& opt, Eigen::MatrixXd& J) {
  const Eigen::Index n = x.size() - 1;
  const Eigen::VectorXd z = x.head(n);
  const double p = x(n);
  J.resize(n, n + 1);
  Eigen::MatrixXd Pz;
  if (f.jacobians) {
    Eigen::VectorXd Pp;
    if (auto e = f.jacobians(z, p, Pz, Pp)) return "the map's Jacobian: " + *e;
    if (Pz.rows() != n || Pz.cols() != n || Pp.size() != n || !Pz.allFinite() || !Pp.allFinite())
      return std::string("the map's Jacobian is not finite");
    J.leftCols(n) = Pz - Eigen::MatrixXd::Identity(n, n);
    J.col(n) = Pp;
    return std::nullopt;
  }
  if (f.state_jacobian) {
    if (auto e = f.state_jacobian(z, p, Pz)) return "the map's Jacobian: " + *e;
    if (Pz.rows() != n || Pz.cols() != n || !Pz.allFinite()) return std::string("the map's Jacobian is not finite");
  } else {
    Eigen::VectorXd h(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double scale = opt.state_scale.size() == n ? opt.state_scale(i) : 1.0;
      h(i) = opt.fd_relative_step * std::max(std::abs(z(i)), scale);
    }
    const VectorMap at_p = [&](const Eigen::VectorXd& zz, Eigen::VectorXd& out) { return f.map(zz, p, out); };
    if (auto e = central_difference_jacobian(at_p, z, h, Pz)) return e;
  }
  J.leftCols(n) = Pz - Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd Pp;
  if (auto e = parameter_derivative(f, z, p, opt.fd_relative_step * std::max(std::abs(p), opt.parameter_scale), Pp))
    return e;
  J.col(n) = Pp;
  return std::nullopt;
}

/// The unit tangent (C3), oriented by t0 (t0 · t > 0).
Error tangent(const Eigen::MatrixXd& J, const Eigen::VectorXd& t0, Eigen::VectorXd& t) {
  const Eigen::Index n = J.rows();
  Eigen::MatrixXd A(n + 1, n + 1);
  A << J, t0.transpose();
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
  b(n) = 1;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (lu.isInvertible()) {
    t = lu.solve(b);
    if (t.allFinite() && t.norm() > 0) {
      t.normalize();
      return std::nullopt;
    }
  }
  // A singular bordered matrix (on a branch point): the right singular vector of J closest to t0.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
  t = svd.matrixV().col(n);
  if (t.dot(t0) < 0) t = -t;
  if (!t.allFinite()) return std::string("no tangent (the Jacobian is not finite)");
  return std::nullopt;
}

/// A point of the branch with everything the step and the test functions need.
struct Solved {
  Eigen::VectorXd x, F, t;
  Eigen::MatrixXd J;
  int iterations = 0;
};

/// Corrector (C2) from the predictor x0 + ds t0; the tangent of the result is oriented by t0.
Error correct(const MapFamily& f, const Eigen::VectorXd& x0, const Eigen::VectorXd& t0, double ds,
              const ContinuationOptions& opt, Solved& out) {
  const Eigen::Index n = x0.size() - 1;
  Eigen::VectorXd x = x0 + ds * t0, F;
  double previous = INFINITY;
  for (int it = 0;; ++it) {
    if (auto e = residual(f, x, F)) return e;
    const double r = F.lpNorm<Eigen::Infinity>();
    Eigen::MatrixXd J;
    if (r <= opt.tolerance) {
      if (auto e = linearise(f, x, opt, J)) return e;
      out.x = x;
      out.F = F;
      out.J = J;
      out.iterations = it;
      return tangent(J, t0, out.t);
    }
    if (it >= opt.max_corrector_iterations)
      return "corrector: no convergence in " + std::to_string(it) + " iterations (residual " + number(r) + ")";
    if (it >= 2 && r > previous) return "corrector diverges (residual " + number(r) + ")";
    previous = r;
    if (auto e = linearise(f, x, opt, J)) return e;
    Eigen::MatrixXd A(n + 1, n + 1);
    A << J, t0.transpose();
    Eigen::VectorXd rhs(n + 1);
    rhs << -F, -(t0.dot(x - x0) - ds);
    const Eigen::VectorXd dx = A.fullPivLu().solve(rhs);
    if (!dx.allFinite()) return std::string("corrector: singular bordered matrix");
    x += dx;
  }
}

double fold_test(const Solved& s) {
  return s.t(s.t.size() - 1);
}
double branch_point_test(const Solved& s) {
  const Eigen::Index n = s.J.rows();
  Eigen::MatrixXd A(n + 1, n + 1);
  A << s.J, s.t.transpose();
  return A.determinant();
}
Eigen::MatrixXd state_jacobian(const Solved& s) {
  const Eigen::Index n = s.J.rows();
  return s.J.leftCols(n) + Eigen::MatrixXd::Identity(n, n);
}
double period_doubling_test(const Solved& s) {
  const Eigen::Index n = s.J.rows();
  return (state_jacobian(s) + Eigen::MatrixXd::Identity(n, n)).determinant();
}
double neimark_sacker_test(const std::vector<std::complex<double>>& m) {
  std::complex<double> product = 1;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = i + 1; j < m.size(); ++j) product *= m[i] * m[j] - 1.0;
  return product.real();  // real: the multipliers come in conjugate pairs
}
double neimark_sacker_test(const Solved& s) {
  return neimark_sacker_test(floquet_multipliers(state_jacobian(s)));
}

BranchPoint make_point(const MapFamily& f, const Solved& s, double arclength) {
  const Eigen::Index n = s.x.size() - 1;
  BranchPoint b;
  b.z = s.x.head(n);
  b.p = s.x(n);
  b.arclength = arclength;
  b.residual = s.F.lpNorm<Eigen::Infinity>();
  b.corrector_iterations = s.iterations;
  b.tangent = s.t;
  b.jacobian = state_jacobian(s);
  b.multipliers = floquet_multipliers(b.jacobian);
  b.stable = std::all_of(b.multipliers.begin(), b.multipliers.end(), [](auto l) { return std::abs(l) < 1.0; });
  if (f.label) b.label = f.label(b.z, b.p);
  return b;
}

/// Unit null vector of the square matrix A (its smallest right singular vector).
Eigen::VectorXd null_vector(const Eigen::MatrixXd& A) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  Eigen::VectorXd v = svd.matrixV().col(A.cols() - 1);
  // A reproducible sign: the largest component positive.
  Eigen::Index k = 0;
  v.cwiseAbs().maxCoeff(&k);
  return v(k) < 0 ? Eigen::VectorXd(-v) : v;
}

Eigen::VectorXd parameter_direction(Eigen::Index n) {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n + 1);
  e(n) = 1;
  return e;
}

struct Walker {
  const MapFamily& f;
  const ContinuationOptions& opt;
  Branch& branch;

  /// The root of ψ on the step from a (tangent ta) of length sb, by Illinois; ψa, ψb of opposite signs.
  template <class Test>
  Error locate(const Solved& a, double sb, double fa, double fb, const Test& psi, Solved& out, double& s_out) {
    double sa = 0, s_prev = -1;
    int side = 0;
    for (int it = 0; it < 100; ++it) {
      double s = (sa * fb - sb * fa) / (fb - fa);
      if (!(s > sa && s < sb)) s = 0.5 * (sa + sb);
      if (auto e = correct(f, a.x, a.t, s, opt, out)) return "locating: " + *e;
      s_out = s;
      const double fs = psi(out);
      if (fs == 0 || std::abs(s - s_prev) <= opt.locate_tolerance || sb - sa <= opt.locate_tolerance)
        return std::nullopt;
      s_prev = s;
      if ((fs > 0) == (fb > 0)) {
        sb = s;
        fb = fs;
        if (side == 1) fa /= 2;
        side = 1;
      } else {
        sa = s;
        fa = fs;
        if (side == -1) fb /= 2;
        side = -1;
      }
    }
    return std::nullopt;  // 100 Illinois steps: the last iterate
  }

  /// Bisection in s on the label between a (label la) and the step's end sb (label lb).
  Error locate_label(const Solved& a, double sb, const std::string& la, Solved& out, double& s_out,
                     std::string& after) {
    double sa = 0;
    after.clear();
    Solved mid, base = a;  // base: the last corrected point with label la (at s = sa)
    while (sb - sa > opt.label_tolerance) {
      // Predicted from the nearest point with the old label: a corrector started at `a` may not
      // converge across the boundary's kink in the map (the label marks a non-smooth change). A
      // map that cannot be evaluated at the midpoint (e.g. an event the integrator misses) is
      // tried at 0.3 and 0.7 of the bracket before giving up: any interior point halves it enough.
      double s = 0;
      Error e;
      for (const double frac : {0.5, 0.3, 0.7}) {
        s = sa + frac * (sb - sa);
        e = correct(f, base.x, base.t, s - sa, opt, mid);
        if (!e) break;
      }
      if (e) return "locating the label change: " + *e;
      const Eigen::Index n = mid.x.size() - 1;
      const std::string l = f.label(mid.x.head(n), mid.x(n));
      if (l == la) {
        sa = s;
        base = mid;
      } else {
        sb = s;
        after = l;
        out = mid;
      }
    }
    if (after.empty()) {  // the end of the step is the first point with the new label
      if (auto e = correct(f, base.x, base.t, sb - sa, opt, out)) return "locating the label change: " + *e;
      const Eigen::Index n = out.x.size() - 1;
      after = f.label(out.x.head(n), out.x(n));
    }
    s_out = sb;
    return std::nullopt;
  }

  /// Special points on the step from a to b (length ds, b not yet on the branch), in order of s.
  void detect(const Solved& a, const Solved& b, double ds) {
    const std::size_t after = branch.points.size() - 1;
    const double s0 = branch.points.back().arclength;
    std::vector<std::pair<double, SpecialPoint>> found;
    const auto check = [&](SpecialKind kind, auto psi) {
      const double fa = psi(a), fb = psi(b);
      if ((fa > 0) == (fb > 0)) return;
      Solved at;
      double s = 0;
      SpecialPoint sp;
      sp.kind = kind;
      sp.after = after;
      if (auto e = locate(a, ds, fa, fb, psi, at, s)) {
        at = b;  // not located: reported at the step's end, the reason in the stop note
        s = ds;
        sp.located = false;
        branch.stop_reason += (branch.stop_reason.empty() ? "" : "; ") + to_string(kind) + " not located: " + *e;
      }
      sp.test_value = psi(at);
      sp.point = make_point(f, at, s0 + s);
      const Eigen::Index n = sp.point.z.size();
      const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
      if (kind == SpecialKind::Fold || kind == SpecialKind::BranchPoint)
        sp.eigenvector = null_vector(sp.point.jacobian - I);
      if (kind == SpecialKind::PeriodDoubling) sp.eigenvector = null_vector(sp.point.jacobian + I);
      if (kind == SpecialKind::NeimarkSacker) {
        // The pair with λᵢλⱼ closest to 1 must be complex: otherwise a neutral saddle.
        const auto& m = sp.point.multipliers;
        double best = INFINITY;
        std::complex<double> critical;
        for (std::size_t i = 0; i < m.size(); ++i)
          for (std::size_t j = i + 1; j < m.size(); ++j)
            if (std::abs(m[i] * m[j] - 1.0) < best) {
              best = std::abs(m[i] * m[j] - 1.0);
              critical = m[i];
            }
        if (std::abs(critical.imag()) <= 1e-9 * std::abs(critical)) return;
        sp.angle = std::abs(std::arg(critical));
      }
      found.emplace_back(s, std::move(sp));
    };
    check(SpecialKind::Fold, [](const Solved& s) { return fold_test(s); });
    check(SpecialKind::BranchPoint, [](const Solved& s) { return branch_point_test(s); });
    check(SpecialKind::PeriodDoubling, [](const Solved& s) { return period_doubling_test(s); });
    check(SpecialKind::NeimarkSacker, [](const Solved& s) { return neimark_sacker_test(s); });
    if (f.label) {
      const Eigen::Index n = a.x.size() - 1;
      const std::string la = branch.points.back().label, lb = f.label(b.x.head(n), b.x(n));
      if (la != lb) {
        Solved at;
        double s = ds;
        SpecialPoint sp;
        sp.kind = SpecialKind::LabelChange;
        sp.after = after;
        sp.label_before = la;
        if (auto e = locate_label(a, ds, la, at, s, sp.label_after)) {
          at = b;
          sp.label_after = lb;
          sp.located = false;
          branch.stop_reason +=
              (branch.stop_reason.empty() ? "" : "; ") + std::string("label change not located: ") + *e;
        }
        sp.point = make_point(f, at, s0 + s);
        found.emplace_back(s, std::move(sp));
      }
    }
    std::sort(found.begin(), found.end(), [](const auto& u, const auto& v) { return u.first < v.first; });
    for (auto& item : found) branch.special.push_back(std::move(item.second));
  }

  /// Continues from `start` (on the branch already) within [lo, hi].
  void run(Solved start, double lo, double hi, double p_end) {
    const Eigen::Index n = start.x.size() - 1;
    Solved a = std::move(start);
    double ds = opt.initial_step;
    const double cos_turn = std::cos(opt.max_turn);
    while (static_cast<int>(branch.points.size()) < opt.max_points) {
      Solved b;
      std::string why;
      for (;;) {
        // A predictor that leaves [lo, hi] where the parameter has no valid value (the interval
        // ends on a bound of the key): Newton at p = bound itself, from the tangent's point there.
        const double predicted = a.x(n) + ds * a.t(n);
        if ((predicted < lo || predicted > hi) && f.valid && !f.valid(predicted)) {
          const double bound = predicted < lo ? lo : hi, s = (bound - a.x(n)) / a.t(n);
          Eigen::VectorXd on = a.x + s * a.t;
          on(n) = bound;
          Solved end;
          if (!correct(f, on, parameter_direction(n), 0.0, opt, end)) {
            if (end.t.dot(a.t) < 0) end.t = -end.t;
            end_on_bound(a, std::move(end), s, bound, p_end);
            return;
          }
        }
        auto e = correct(f, a.x, a.t, ds, opt, b);
        if (!e && b.t.dot(a.t) < cos_turn)
          e = "the tangent turns by " + number(std::acos(std::clamp(b.t.dot(a.t), -1.0, 1.0))) + " rad";
        if (!e) break;
        why = *e;
        ds /= 2;
        if (ds < opt.min_step) {
          stop(BranchEnd::NoStep,
               "no step of " + number(opt.min_step) + " or more from p = " + number(a.x(n)) + ": " + why);
          return;
        }
      }
      // Leaving [lo, hi]: the end point is located on the bound (ψ = p - bound).
      const double pb = b.x(n);
      const bool out_low = pb<lo, out_high = pb> hi;
      if (out_low || out_high) {
        const double bound = out_low ? lo : hi;
        const auto psi = [&](const Solved& s) { return s.x(n) - bound; };
        Solved end;
        double s = ds;
        if (auto e = locate(a, ds, psi(a), psi(b), psi, end, s)) {
          stop(BranchEnd::NotStopped, "could not stop on p = " + number(bound) + ": " + *e);
          return;
        }
        // On the bound exactly: Newton at p = bound from the located point (kept if that fails).
        Solved exact;
        Eigen::VectorXd on = end.x;
        on(n) = bound;
        if (!correct(f, on, parameter_direction(n), 0.0, opt, exact)) {
          if (exact.t.dot(end.t) < 0) exact.t = -exact.t;
          end = std::move(exact);
        }
        end_on_bound(a, std::move(end), s, bound, p_end);
        return;
      }
      const std::size_t folds_before = count_folds();
      if (opt.detect) detect(a, b, ds);
      branch.points.push_back(make_point(f, b, branch.points.back().arclength + ds));
      if (opt.on_point) opt.on_point(branch.points.back());
      if (count_folds() > folds_before && vertical()) {
        stop(BranchEnd::Vertical,
             "a vertical branch at p = " + number(b.x(n)) +
                 ": two folds at the same parameter (a continuum of fixed points there, a multiplier stays at +1)");
        return;
      }
      if (b.iterations <= 3) ds = std::min(1.5 * ds, opt.max_step);
      if (b.iterations >= 6) ds = std::max(0.5 * ds, opt.min_step);
      a = std::move(b);
    }
    stop(BranchEnd::MaxPoints, "max_points (" + std::to_string(opt.max_points) + ") reached");
  }

  /// The branch's last point `end`, on p = bound, s along it after `a`.
  void end_on_bound(const Solved& a, Solved end, double s, double bound, double p_end) {
    if (opt.detect) detect(a, end, s);
    branch.points.push_back(make_point(f, end, branch.points.back().arclength + s));
    branch.reached_end = bound == p_end;
    if (branch.reached_end)
      stop(BranchEnd::ReachedEnd, "reached p = " + number(p_end));
    else
      stop(BranchEnd::TurnedBack, "turned back to p = " + number(bound) + " (left the parameter interval)");
  }

  std::size_t count_folds() const {
    return static_cast<std::size_t>(std::count_if(branch.special.begin(), branch.special.end(),
                                                  [](const SpecialPoint& sp) { return sp.kind == SpecialKind::Fold; }));
  }
  /// The last two folds at the same parameter (to 1e-8 of max(1, |p|)), with a multiplier at +1
  /// (to 1e-6) on the branch between them: the branch runs along a continuum of fixed points.
  bool vertical() const {
    const SpecialPoint* last = nullptr;
    const SpecialPoint* before = nullptr;
    for (const SpecialPoint& sp : branch.special) {
      if (sp.kind != SpecialKind::Fold) continue;
      before = last;
      last = &sp;
    }
    if (before == nullptr || std::abs(last->point.p - before->point.p) > 1e-8 * std::max(1.0, std::abs(last->point.p)))
      return false;
    for (std::size_t i = before->after + 1; i <= last->after && i < branch.points.size(); ++i) {
      const auto& m = branch.points[i].multipliers;
      if (std::none_of(m.begin(), m.end(), [](auto l) { return std::abs(l - 1.0) <= 1e-6; })) return false;
    }
    return true;
  }

  /// Sets why the branch ended, keeping the notes detect() left (a special point not located).
  void stop(BranchEnd end, const std::string& reason) {
    branch.end = end;
    branch.stop_reason = branch.stop_reason.empty() ? reason : reason + "; " + branch.stop_reason;
  }
};

}  // namespace

std::string to_string(SpecialKind kind) {
  switch (kind) {
    case SpecialKind::Fold:
      return "fold";
    case SpecialKind::BranchPoint:
      return "branch point";
    case SpecialKind::PeriodDoubling:
      return "period doubling";
    case SpecialKind::NeimarkSacker:
      return "Neimark-Sacker";
    case SpecialKind::LabelChange:
      return "label change";
  }
  return "?";
}

std::optional<std::string> parameter_derivative(const MapFamily& f, const Eigen::VectorXd& z, double p, double h,
                                                Eigen::VectorXd& J_p) {
  const auto valid = [&](double v) { return !f.valid || f.valid(v); };
  const auto at = [&](double v, Eigen::VectorXd& out) -> Error {
    if (auto e = f.map(z, v, out)) return "parameter derivative: " + *e;
    return std::nullopt;
  };
  for (int halvings = 0; halvings <= 30; ++halvings, h *= 0.5) {
    Eigen::VectorXd plus, minus;
    if (valid(p + h) && valid(p - h)) {
      if (auto e = at(p + h, plus)) return e;
      if (auto e = at(p - h, minus)) return e;
      J_p = (plus - minus) / ((p + h) - (p - h));
      return std::nullopt;
    }
    for (const double side : {1.0, -1.0}) {
      const double d = (p + side * h) - p;  // the step as represented
      if (!valid(p + d) || !valid(p + 2 * d)) continue;
      Eigen::VectorXd at_p, one, two;
      if (auto e = at(p, at_p)) return e;
      if (auto e = at(p + d, one)) return e;
      if (auto e = at(p + 2 * d, two)) return e;
      J_p = (4 * one - 3 * at_p - two) / (2 * d);
      return std::nullopt;
    }
  }
  return "parameter derivative: no difference step around p = " + number(p) + " stays among valid parameter values";
}

MapFamily iterate(const MapFamily& f, int k) {
  MapFamily g;
  g.period = f.period * k;
  g.label = f.label;
  g.valid = f.valid;
  g.map = [f, k](const Eigen::VectorXd& z, double p, Eigen::VectorXd& out) -> std::optional<std::string> {
    Eigen::VectorXd current = z;
    for (int i = 0; i < k; ++i) {
      if (auto e = f.map(current, p, out)) return "iterate " + std::to_string(i + 1) + ": " + *e;
      current = out;
    }
    return std::nullopt;
  };
  if (f.state_jacobian) {
    g.state_jacobian = [f, k](const Eigen::VectorXd& z, double p, Eigen::MatrixXd& J) -> std::optional<std::string> {
      Eigen::VectorXd current = z, next;
      Eigen::MatrixXd Ji;
      J = Eigen::MatrixXd::Identity(z.size(), z.size());
      for (int i = 0; i < k; ++i) {
        if (auto e = f.state_jacobian(current, p, Ji)) return "iterate " + std::to_string(i + 1) + ": " + *e;
        J = Ji * J;
        if (i + 1 < k) {
          if (auto e = f.map(current, p, next)) return "iterate " + std::to_string(i + 1) + ": " + *e;
          current = next;
        }
      }
      return std::nullopt;
    };
  }
  if (f.jacobians) {  // ∂P^k/∂p by the chain rule: dz_{i+1}/dp = P_z(z_i) dz_i/dp + P_p(z_i)
    g.jacobians = [f, k](const Eigen::VectorXd& z, double p, Eigen::MatrixXd& J,
                         Eigen::VectorXd& J_p) -> std::optional<std::string> {
      Eigen::VectorXd current = z, next, Pp;
      Eigen::MatrixXd Pz;
      J = Eigen::MatrixXd::Identity(z.size(), z.size());
      J_p = Eigen::VectorXd::Zero(z.size());
      for (int i = 0; i < k; ++i) {
        if (auto e = f.jacobians(current, p, Pz, Pp)) return "iterate " + std::to_string(i + 1) + ": " + *e;
        J = Pz * J;
        J_p = Pz * J_p + Pp;
        if (i + 1 < k) {
          if (auto e = f.map(current, p, next)) return "iterate " + std::to_string(i + 1) + ": " + *e;
          current = next;
        }
      }
      return std::nullopt;
    };
  }
  return g;
}

std::optional<std::string> fixed_point_at(const MapFamily& f, const Eigen::VectorXd& z0, double p,
                                          const ContinuationOptions& opt, BranchPoint& out) {
  const Eigen::Index n = z0.size();
  Eigen::VectorXd x0(n + 1);
  x0 << z0, p;
  Solved s;
  if (auto e = correct(f, x0, parameter_direction(n), 0.0, opt, s)) return e;
  out = make_point(f, s, 0.0);
  return std::nullopt;
}

std::string Branch::failure() const {
  return start_failure ? reason_text(kStartFailureTable, *start_failure, start_detail) : std::string();
}

Branch continue_fixed_points(const MapFamily& f, const Eigen::VectorXd& z0, double p0, double p_end,
                             const ContinuationOptions& opt) {
  Branch branch;
  branch.period = f.period;
  const Eigen::Index n = z0.size();
  if (!(p_end != p0) || !std::isfinite(p0) || !std::isfinite(p_end)) {
    branch.start_failure = StartFailure::EmptyInterval;
    branch.start_detail = "from " + number(p0) + " to " + number(p_end);
    return branch;
  }
  Eigen::VectorXd x0(n + 1);
  x0 << z0, p0;
  // The start: Newton at p0; the tangent oriented towards p_end.
  const Eigen::VectorXd towards = (p_end > p0 ? 1.0 : -1.0) * parameter_direction(n);
  Solved start;
  if (auto e = correct(f, x0, towards, 0.0, opt, start)) {
    branch.start_failure = StartFailure::NoFixedPoint;
    branch.start_detail = number(p0) + " from the initial guess: " + *e;
    return branch;
  }
  branch.points.push_back(make_point(f, start, 0.0));
  Walker w{f, opt, branch};
  w.run(std::move(start), std::min(p0, p_end), std::max(p0, p_end), p_end);
  return branch;
}

Branch switch_at_period_doubling(const MapFamily& f, const SpecialPoint& pd, double p_end,
                                 const ContinuationOptions& opt, int side) {
  const MapFamily g = iterate(f, 2);
  Branch branch;
  branch.period = g.period;
  if (pd.kind != SpecialKind::PeriodDoubling || pd.eigenvector.size() != pd.point.z.size()) {
    branch.start_failure = StartFailure::NoPeriodDoubling;
    return branch;
  }
  if (!(p_end != pd.point.p)) {
    branch.start_failure = StartFailure::EmptyInterval;
    branch.start_detail = "p_end is the period doubling's parameter";
    return branch;
  }
  const Eigen::Index n = pd.point.z.size();
  Eigen::VectorXd x_pd(n + 1), t_switch = Eigen::VectorXd::Zero(n + 1);
  x_pd << pd.point.z, pd.point.p;
  t_switch.head(n) = (side >= 0 ? 1.0 : -1.0) * pd.eigenvector.normalized();
  // The period-doubling point itself, a fixed point of P² (the branch's root).
  Solved root;
  if (auto e = correct(g, x_pd, t_switch, 0.0, opt, root)) {
    branch.start_failure = StartFailure::PeriodDoublingNotFixed;
    branch.start_detail = *e;
    return branch;
  }
  Solved first;
  double ds = opt.initial_step;
  std::string why;
  for (;;) {
    auto e = correct(g, x_pd, t_switch, ds, opt, first);
    if (!e) {
      // Off the period-1 branch: P(z) ≠ z by more than the corrector's tolerance.
      Eigen::VectorXd F;
      if (auto e1 = residual(f, first.x, F))
        e = "the period-1 map: " + *e1;
      else if (F.lpNorm<Eigen::Infinity>() <= 100 * opt.tolerance)
        e = std::string("landed on the period-1 branch");
    }
    if (!e) break;
    why = *e;
    ds /= 2;
    if (ds < opt.min_step) {
      branch.start_failure = StartFailure::NoPeriodTwoPoint;
      branch.start_detail = number(pd.point.p) + ": " + why;
      return branch;
    }
  }
  root.t = t_switch;
  branch.points.push_back(make_point(g, root, 0.0));
  branch.points.push_back(make_point(g, first, ds));
  const double p0 = pd.point.p;
  if ((first.x(n) - p0) * (p_end - p0) < 0) {
    branch.end = BranchEnd::OtherSide;
    branch.stop_reason =
        "the period-2 branch lies on the other side of the period doubling (p = " + number(first.x(n)) +
        "), away from p_end";
    return branch;
  }
  Walker w{g, opt, branch};
  w.run(std::move(first), std::min(p0, p_end), std::max(p0, p_end), p_end);
  return branch;
}

}  // namespace flexgait::numerics
