#include "flexgait/numerics/dop853.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "flexgait/numerics/dop853_tableau.hpp"

namespace flexgait::numerics {
namespace {

using namespace dop853;

constexpr double kSafety = 0.9;         // dop853.f: SAFE
constexpr double kMinShrink = 1.0 / 3;  // dop853.f: FAC1, the smallest h_new/h
constexpr double kMaxGrowth = 6.0;      // dop853.f: FAC2, the largest h_new/h
constexpr double kUround = std::numeric_limits<double>::epsilon();
constexpr int kMaxRhsFailures = 40;  // consecutive domain failures of f before giving up

// The stages of the dense output's r4..r8 (dop853.f's CONTD8): those with a nonzero d in some row.
constexpr std::array<std::size_t, 12> kDenseColumns{0, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
constexpr bool skipped_columns_are_zero() {
  for (const auto& row : kD)
    for (std::size_t j = 0; j < row.size(); ++j) {
      bool listed = false;
      for (const std::size_t c : kDenseColumns) listed = listed || c == j;
      if (!listed && row[j] != 0.0) return false;
    }
  return true;
}
static_assert(skipped_columns_are_zero());

}  // namespace

Dop853::Dop853(Rhs f, int dim, Dop853Options options, Rhs lead)
    : f_(std::move(f)),
      lead_(std::move(lead)),
      dim_(static_cast<std::size_t>(dim)),
      controlled_(options.controlled > 0 ? static_cast<std::size_t>(options.controlled) : dim_),
      opt_(std::move(options)),
      y_(dim_),
      y_old_(dim_),
      y_new_(dim_),
      y_tmp_(dim_),
      dense_tmp_(dim_),
      k_(dim_ * kDenseStages),
      cont_(dim_ * 7),
      err5_(controlled_),
      err3_(controlled_) {
  if (dim <= 0 || controlled_ > dim_) throw std::invalid_argument("Dop853: bad dimensions");
  if (!opt_.error_scale.empty() && opt_.error_scale.size() != controlled_)
    throw std::invalid_argument("Dop853: error_scale must have one entry per controlled component");
}

bool Dop853::eval(double t, const std::vector<double>& y, double* ydot) const {
  ++rhs_evals_;
  return f_(t, y, std::span<double>(ydot, dim_));
}

namespace {

// out = base + h Σ_j a_ij k_j for one row i of A, its coefficients compile-time constants: per
// component the row's nonzero terms added in j's order in a register (the numbers of adding one
// stage at a time to base, without storing and reloading out for every stage), the components
// vectorised. k: stage j at k + j·stride; the first n components.
template <std::size_t I, std::size_t... J>
void combine_row(const double* __restrict base, double h, const double* __restrict k, double* __restrict out,
                 std::size_t n, std::size_t stride, std::index_sequence<J...>) {
  constexpr auto& a = kA[I];
  const std::array<double, sizeof...(J) + 1> ha{h * a[J]..., 0.0};
  for (std::size_t c = 0; c < n; ++c) {
    double s = base[c];
    const auto term = [&]<std::size_t j>() {
      if constexpr (a[j] != 0.0) s += ha[j] * k[j * stride + c];
    };
    (term.template operator()<J>(), ...);
    (void)term;  // row 0 has no terms
    out[c] = s;
  }
}

using CombineRow = void (*)(const double*, double, const double*, double*, std::size_t, std::size_t);
template <std::size_t I>
void combine_row(const double* base, double h, const double* k, double* out, std::size_t n, std::size_t stride) {
  combine_row<I>(base, h, k, out, n, stride, std::make_index_sequence<I>());
}
template <std::size_t... I>
constexpr std::array<CombineRow, sizeof...(I)> combine_rows(std::index_sequence<I...>) {
  return {&combine_row<I>...};
}
constexpr std::array<CombineRow, kDenseStages> kCombineRows = combine_rows(std::make_index_sequence<kDenseStages>());

}  // namespace

void Dop853::combine(const std::vector<double>& base, int i, double h, std::vector<double>& out, std::size_t n) const {
  // out is never a stage or base (the restrict pointers of combine_row)
  kCombineRows[static_cast<std::size_t>(i)](base.data(), h, k_.data(), out.data(), n, dim_);
}

namespace {

// Per component c < n, err5/sk and err3/sk of dop853.f's error estimate into q5 and q3: the
// stages' products added in j's order in registers (compile-time weights, as combine_row; the
// stages whose weight is 0, 1..4 of e5 and of b, left out: adding 0·k_j changes no sum), the
// components vectorised. k: stage j at k + j·stride; scale: error_scale's sizes (Scaled only).
template <bool Scaled, std::size_t... J>
void scaled_errors(const double* __restrict k, std::size_t stride, const double* __restrict y_old,
                   const double* __restrict y_new, const double* __restrict scale, double atol, double rtol,
                   double* __restrict q5, double* __restrict q3, std::size_t n, std::index_sequence<J...>) {
  constexpr auto& b = kA[kStages];
  for (std::size_t c = 0; c < n; ++c) {
    const double own = std::max(std::abs(y_old[c]), std::abs(y_new[c]));
    double size = own;
    if constexpr (Scaled) size = scale[c] > 0 ? scale[c] : own;
    const double sk = atol + rtol * size;
    double err5 = 0.0, b_sum = 0.0;
    const auto term = [&]<std::size_t j>() {
      if constexpr (kE5[j] != 0.0) err5 += kE5[j] * k[j * stride + c];
    };
    (term.template operator()<J>(), ...);
    const auto b_term = [&]<std::size_t j>() {
      if constexpr (b[j] != 0.0) b_sum += b[j] * k[j * stride + c];
    };
    (b_term.template operator()<J>(), ...);
    const double err3 = b_sum - kBhh[0] * k[c] - kBhh[1] * k[8 * stride + c] - kBhh[2] * k[11 * stride + c];
    q5[c] = err5 / sk;
    q3[c] = err3 / sk;
  }
}

}  // namespace

// dop853.f's error estimate (Hairer–Nørsett–Wanner II.10, eq. (10.17)): the 5th-order estimator
// err5 = Σ e5_j k_j, corrected by the 3rd-order one err3 = Σ (b_j - bhh_j) k_j; the scaled
// errors of all components first (vectorised), then their squares summed in the components' order.
double Dop853::error_norm(double h) const {
  const std::size_t n = controlled_;
  constexpr auto stages = std::make_index_sequence<kStages>();
  if (opt_.error_scale.empty())
    scaled_errors<false>(k_.data(), dim_, y_.data(), y_new_.data(), nullptr, opt_.atol, opt_.rtol, err5_.data(),
                         err3_.data(), n, stages);
  else
    scaled_errors<true>(k_.data(), dim_, y_.data(), y_new_.data(), opt_.error_scale.data(), opt_.atol, opt_.rtol,
                        err5_.data(), err3_.data(), n, stages);
  double e5 = 0.0, e3 = 0.0;
  for (std::size_t c = 0; c < n; ++c) {
    e5 += err5_[c] * err5_[c];
    e3 += err3_[c] * err3_[c];
  }
  double denominator = e5 + 0.01 * e3;
  if (denominator <= 0.0) denominator = 1.0;
  return std::abs(h) * e5 / std::sqrt(static_cast<double>(controlled_) * denominator);
}

// dop853.f's HINIT: h0 = 0.01‖y‖/‖f‖, one explicit Euler step to estimate ‖y''‖, then
// h = min(100 h0, (0.01 / max(‖f‖, ‖y''‖))^(1/8)).
double Dop853::initial_step(double t) {
  const double* f0 = stage(0);
  double dnf = 0.0, dny = 0.0;
  for (std::size_t c = 0; c < controlled_; ++c) {
    const double size = !opt_.error_scale.empty() && opt_.error_scale[c] > 0 ? opt_.error_scale[c] : std::abs(y_[c]);
    const double sk = opt_.atol + opt_.rtol * size;
    dnf += (f0[c] / sk) * (f0[c] / sk);
    dny += (y_[c] / sk) * (y_[c] / sk);
  }
  double h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
  if (opt_.max_step > 0) h = std::min(h, opt_.max_step);
  for (int attempt = 0;; ++attempt) {
    for (std::size_t c = 0; c < dim_; ++c) y_tmp_[c] = y_[c] + h * f0[c];
    if (eval(t + h, y_tmp_, stage(1))) break;
    if (attempt == kMaxRhsFailures) throw std::runtime_error("DOP853: the right-hand side fails near the start");
    h *= 0.25;
  }
  double der2 = 0.0;
  for (std::size_t c = 0; c < controlled_; ++c) {
    const double size = !opt_.error_scale.empty() && opt_.error_scale[c] > 0 ? opt_.error_scale[c] : std::abs(y_[c]);
    const double d = (stage(1)[c] - f0[c]) / (opt_.atol + opt_.rtol * size);
    der2 += d * d;
  }
  der2 = std::sqrt(der2) / h;
  const double der12 = std::max(der2, std::sqrt(dnf));
  const double h1 = der12 <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / der12, 1.0 / 8.0);
  h = std::min(100.0 * h, h1);
  if (opt_.max_step > 0) h = std::min(h, opt_.max_step);
  return h;
}

void Dop853::start(double t, std::span<const double> y) {
  if (y.size() != dim_) throw std::invalid_argument("Dop853::start: wrong state size");
  std::copy(y.begin(), y.end(), y_.begin());
  std::copy(y.begin(), y.end(), y_old_.begin());
  t_ = t_old_ = t;
  h_ = 0.0;
  if (!eval(t, y_, stage(0))) throw std::runtime_error("DOP853: the right-hand side fails at the start");
  next_k0_ = NextStage0::Valid;
  rejected_ = false;
  dense_ready_ = 0;
  // A restart after an event: the flow's time scale is rarely shorter than the last accepted
  // step's, and hinit alone overshoots (its first step was rejected at almost every event of the
  // walking wheel; bounded by the last step, 4.8 % fewer evaluations of f over 2000 steps).
  h_next_ = initial_step(t);
  if (h_last_ > 0) h_next_ = std::min(h_next_, h_last_);
}

void Dop853::step(double t_max) {
  if (next_k0_ == NextStage0::FromLastStage) {
    std::copy(stage(kStages), stage(kStages) + dim_, stage(0));
  } else if (next_k0_ == NextStage0::Evaluate) {
    if (!eval(t_, y_, stage(0))) throw std::runtime_error("DOP853: the right-hand side fails at the step's start");
  }
  next_k0_ = NextStage0::Valid;
  double h = h_next_;
  int rhs_failures = 0;
  for (std::int64_t attempt = 0;; ++attempt) {
    if (attempt > opt_.max_attempts) throw std::runtime_error("DOP853: too many rejected steps");
    if (opt_.max_step > 0) h = std::min(h, opt_.max_step);
    bool last = false;
    if (t_ + 1.01 * h >= t_max) {
      h = t_max - t_;
      last = true;
    }
    if (!(h > 0) || 0.1 * h <= std::abs(t_) * kUround)
      throw std::runtime_error("DOP853: step size too small at t = " + std::to_string(t_));
    // Stages 1..11, then the 8th-order solution y_new = y + h Σ b_j k_j (b: row 12 of A).
    bool ok = true;
    for (int i = 1; i < kStages && ok; ++i) {
      combine(y_, i, h, y_tmp_, dim_);
      ok = eval(t_ + kC[static_cast<std::size_t>(i)] * h, y_tmp_, stage(i));
    }
    double err = 0.0;
    if (ok) {
      combine(y_, kStages, h, y_new_, dim_);
      err = error_norm(h);
      // Stage 12: f at the new point (the next step's stage 0), only for an accepted step.
      if (err <= 1.0) ok = eval(last ? t_max : t_ + h, y_new_, stage(kStages));
    }
    if (!ok) {
      if (++rhs_failures > kMaxRhsFailures)
        throw std::runtime_error("DOP853: the right-hand side keeps failing at t = " + std::to_string(t_));
      h *= 0.25;
      rejected_ = true;
      continue;
    }
    const double fac11 = std::pow(err, 1.0 / 8.0);
    if (err > 1.0) {
      h /= std::min(1.0 / kMinShrink, fac11 / kSafety);
      rejected_ = true;
      continue;
    }
    double h_new = h / std::max(1.0 / kMaxGrowth, std::min(1.0 / kMinShrink, fac11 / kSafety));
    if (opt_.max_step > 0) h_new = std::min(h_new, opt_.max_step);
    if (rejected_) h_new = std::min(h_new, h);
    rejected_ = false;
    y_old_.swap(y_);
    std::copy(y_new_.begin(), y_new_.end(), y_.begin());
    t_old_ = t_;
    t_ = last ? t_max : t_ + h;
    h_ = h;
    h_last_ = h;
    h_next_ = h_new;
    ++steps_;
    dense_ready_ = 0;
    // FSAL: the next step's stage 0 is this step's stage 12, copied when the next step starts
    // (this step's dense output needs both).
    next_k0_ = NextStage0::FromLastStage;
    return;
  }
}

// The extra stages 13..15 and the coefficients of dop853.f's CONTD8:
// y(t_old + s h) = y_old + s (r2 + (1-s) (r3 + s (r4 + (1-s) (r5 + s (r6 + (1-s) (r7 + s r8)))))),
// for the first n components: n = controlled_ by the leading block's own flow (lead_; its stages
// are the same numbers as the full flow's leading components), or all of them.
void Dop853::prepare_dense(std::size_t n) const {
  for (int i = kStages + 1; i < kDenseStages; ++i) {
    combine(y_old_, i, h_, dense_tmp_, n);
    const double t = t_old_ + kC[static_cast<std::size_t>(i)] * h_;
    double* k = k_.data() + static_cast<std::size_t>(i) * dim_;
    ++rhs_evals_;
    const bool ok = n < dim_ ? lead_(t, std::span<const double>(dense_tmp_.data(), n), std::span<double>(k, n))
                             : f_(t, dense_tmp_, std::span<double>(k, dim_));
    if (!ok) throw std::runtime_error("DOP853: the right-hand side fails in the dense output");
  }
  const double* k0 = stage(0);
  const double* k12 = stage(kStages);
  for (std::size_t c = 0; c < n; ++c) {
    const double diff = y_new_[c] - y_old_[c];
    const double bspl = h_ * k0[c] - diff;
    cont_[c] = diff;
    cont_[dim_ + c] = bspl;
    cont_[2 * dim_ + c] = diff - h_ * k12[c] - bspl;
  }
  // r4..r8 = h Σ_j d_rj k_j, per component in four registers, summed in j's order over the
  // stages whose d_rj are not all 0 (adding 0·k_j changes no sum).
  for (std::size_t c = 0; c < n; ++c) {
    std::array<double, kD.size()> sum{};
    for (const std::size_t j : kDenseColumns) {
      const double kj = k_[j * dim_ + c];
      for (std::size_t r = 0; r < kD.size(); ++r) sum[r] += kD[r][j] * kj;
    }
    for (std::size_t r = 0; r < kD.size(); ++r) cont_[(3 + r) * dim_ + c] = h_ * sum[r];
  }
  dense_ready_ = n;
}

void Dop853::dense(double t, std::span<double> y) const {
  const std::size_t n = std::min(y.size(), dim_);
  if (h_ == 0.0) {  // no step yet: the start point
    std::copy(y_.begin(), y_.begin() + static_cast<std::ptrdiff_t>(n), y.begin());
    return;
  }
  const std::size_t needed = lead_ && n <= controlled_ ? controlled_ : dim_;
  if (dense_ready_ < needed) prepare_dense(needed);
  const double s = (t - t_old_) / h_, s1 = 1.0 - s;
  const double* r = cont_.data();
  for (std::size_t c = 0; c < n; ++c) {
    double p = r[6 * dim_ + c];
    p = r[5 * dim_ + c] + s * p;
    p = r[4 * dim_ + c] + s1 * p;
    p = r[3 * dim_ + c] + s * p;
    p = r[2 * dim_ + c] + s1 * p;
    p = r[dim_ + c] + s * p;
    p = r[c] + s1 * p;
    y[c] = y_old_[c] + s * p;
  }
}

void Dop853::truncate(double t) {
  dense(t, y_);
  t_ = t;
  next_k0_ = NextStage0::Evaluate;
}

}  // namespace flexgait::numerics
