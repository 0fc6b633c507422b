/// \file dop853_backend.cpp
/// OdeIntegrator on the DOP853 stepper (dop853.hpp) with guard location on its dense output
/// (guard_crossings.hpp). With sensitivities the stepper carries the augmented state
/// (y, S), S column-major n×(n + m), Ṡ = (∂f/∂y) S (+ ∂f/∂p in the m parameter columns) by
/// centered directional differences (as the CVODES backend), the error test on y only: the
/// sensitivities take y's steps.
#include <algorithm>
#include <cmath>

#include "flexgait/numerics/dop853.hpp"
#include "flexgait/numerics/guard_crossings.hpp"
#include "flexgait/numerics/ode_backend.hpp"

namespace flexgait::numerics {
namespace {

Dop853Options stepper_options(int n, const OdeOptions& o) {
  Dop853Options d;
  d.rtol = o.rtol;
  d.atol = o.atol;
  d.max_step = o.max_step;
  d.controlled = n;
  d.error_scale = o.error_scale;
  d.max_attempts = o.max_steps;
  return d;
}

class Dop853Backend final : public OdeBackend {
 public:
  Dop853Backend(OdeSystem& system, int n, const OdeOptions& options)
      : system_(system),
        n_(static_cast<std::size_t>(n)),
        sensitivities_(options.sensitivities),
        columns_(static_cast<std::size_t>(n + options.parameter_columns)),
        stepper_([this](double t, std::span<const double> y, std::span<double> yd) { return rhs(t, y, yd); },
                 static_cast<int>(options.sensitivities ? n_ + n_ * columns_ : n_), stepper_options(n, options),
                 // The state's own flow: the guards' samples and interpolate() read the state alone,
                 // so the dense output's stages never differentiate the sensitivity columns for them.
                 [this](double t, std::span<const double> y, std::span<double> yd) { return system_.rhs(t, y, yd); }),
        guard_values_([this](double t, std::span<double> g) {
          stepper_.dense(t, y_dense_);
          evaluate_guards(t, y_dense_, g);
        }),
        guard_value_([this](double t, int i) {
          stepper_.dense(t, y_dense_);
          ++guard_evals_;
          return system_.guard(t, y_dense_, i, g_scratch_);
        }),
        y_start_(options.sensitivities ? n_ + n_ * columns_ : n_),
        y_dense_(n_),
        work_(n_),
        work2_(n_) {}

  void restart(double t, std::span<const double> y, std::span<const int> directions,
               std::span<const double> S) override {
    std::copy(y.begin(), y.end(), y_start_.begin());
    if (sensitivities_) {
      if (!S.empty())
        std::copy(S.begin(), S.end(), y_start_.begin() + static_cast<std::ptrdiff_t>(n_));
      else
        std::copy(stepper_.state().begin() + static_cast<std::ptrdiff_t>(n_), stepper_.state().end(),
                  y_start_.begin() + static_cast<std::ptrdiff_t>(n_));
    }
    stepper_.start(t, y_start_);
    g_.resize(directions.size());
    g_scratch_.resize(directions.size());
    if (!directions.empty()) evaluate_guards(t, y, g_);
    guards_.start(t, directions, g_);
    ++restarts_;
  }

  void sensitivities(std::span<double> S) const override {
    const auto Y = stepper_.state();
    std::copy(Y.begin() + static_cast<std::ptrdiff_t>(n_), Y.end(), S.begin());
  }

  StepStatus step(double t_stop) override {
    stepper_.step(t_stop);
    const double t = stepper_.time();
    if (!g_.empty()) {
      evaluate_guards(t, stepper_.state().first(n_), g_);
      if (const auto crossing = guards_.check(t, g_, guard_values_, guard_value_)) {
        if (*crossing < t) stepper_.truncate(*crossing);
        return StepStatus::Guard;
      }
    }
    return t >= t_stop ? StepStatus::StopTime : StepStatus::Step;
  }

  double time() const override { return stepper_.time(); }
  std::span<const double> state() const override { return stepper_.state().first(n_); }
  void interpolate(double t, std::span<double> y) const override { stepper_.dense(t, y.first(n_)); }
  std::span<const int> guards_fired() const override { return guards_.fired(); }
  OdeStats stats() const override {
    OdeStats s;
    s.steps = stepper_.steps();
    s.rhs_evals = stepper_.rhs_evals();
    s.guard_evals = guard_evals_;
    s.restarts = restarts_;
    return s;
  }

 private:
  void evaluate_guards(double t, std::span<const double> y, std::span<double> g) {
    ++guard_evals_;
    system_.guards(t, y, g);
  }
  // The flow, and with sensitivities Ṡ_j = (∂f/∂y) s_j by a centered directional difference of
  // the linearisation flow, its step ≈ ε^(1/3) relative to y and s_j (as the CVODES backend).
  bool rhs(double t, std::span<const double> Y, std::span<double> Yd) {
    const auto y = Y.first(n_);
    if (!system_.rhs(t, y, Yd.first(n_))) return false;
    if (!sensitivities_) return true;
    double y_norm = 0.0;
    for (double v : y) y_norm = std::max(y_norm, std::abs(v));
    for (std::size_t j = 0; j < columns_; ++j) {
      const auto s = Y.subspan(n_ * (j + 1), n_);
      const auto sd = Yd.subspan(n_ * (j + 1), n_);
      double s_norm = 0.0;
      for (double v : s) s_norm = std::max(s_norm, std::abs(v));
      if (s_norm == 0.0) {
        std::fill(sd.begin(), sd.end(), 0.0);
      } else {
        const double delta = 6e-6 * std::max(y_norm, 1.0) / s_norm;
        for (std::size_t i = 0; i < n_; ++i) work_[i] = y[i] + delta * s[i];
        if (!system_.linearization_rhs(t, work_, sd)) return false;
        for (std::size_t i = 0; i < n_; ++i) work_[i] = y[i] - delta * s[i];
        if (!system_.linearization_rhs(t, work_, work2_)) return false;
        for (std::size_t i = 0; i < n_; ++i) sd[i] = (sd[i] - work2_[i]) * (0.5 / delta);
      }
      if (j < n_) continue;  // a parameter column: + ∂f/∂p
      if (!system_.parameter_derivative(t, y, static_cast<int>(j - n_), work_)) return false;
      for (std::size_t i = 0; i < n_; ++i) sd[i] += work_[i];
    }
    return true;
  }

  OdeSystem& system_;
  std::size_t n_;        // state dimension
  bool sensitivities_;   // the stepper's state is (y, S)
  std::size_t columns_;  // S's columns: n states, then OdeOptions::parameter_columns
  Dop853 stepper_;
  GuardCrossings guards_;
  GuardCrossings::Values guard_values_;  // guard values on the dense output
  GuardCrossings::Value guard_value_;    // one guard's value on the dense output
  std::vector<double> y_start_;          // scratch: the augmented state at a restart
  std::vector<double> y_dense_;          // scratch: y on the dense output (dim n)
  std::vector<double> g_;                // guard values at the step's end
  std::vector<double> g_scratch_;        // scratch: all guards, for OdeSystem::guard()
  std::vector<double> work_, work2_;     // scratch for the directional differences (dim n)
  std::int64_t guard_evals_ = 0;
  std::int64_t restarts_ = 0;
};

}  // namespace

std::unique_ptr<OdeBackend> make_dop853_backend(OdeSystem& system, int n, const OdeOptions& options) {
  return std::make_unique<Dop853Backend>(system, n, options);
}

}  // namespace flexgait::numerics
