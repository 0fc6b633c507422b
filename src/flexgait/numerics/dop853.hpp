#pragma once
/// \file dop853.hpp
/// The DOP853 stepper: Dormand–Prince 8(5,3) with its 7th-order dense output and the step-size
/// control of Hairer–Nørsett–Wanner's code dop853.f (Solving ODEs I, 2nd ed., Sec. II.4–II.6):
/// local error |h|·‖err5‖² / sqrt(‖err5‖² + 0.01‖err3‖²) in the RMS norm with weights
/// 1/(atol + rtol·size_i), new step h·min(6, max(1/3, 0.9·err^(-1/8))), no growth right after a
/// rejection. Buffers are allocated once at construction: a step allocates nothing.
///
/// The state may carry more components than the error test sees (`controlled` < dim): the
/// variational equations ride along on the same steps, as CVODES's sensitivities do outside its
/// error test.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace flexgait::numerics {

struct Dop853Options {
  double rtol = 1e-10;    ///< relative tolerance
  double atol = 1e-12;    ///< absolute tolerance (state units)
  double max_step = 0.0;  ///< largest step [s]; 0: no limit
  int controlled = 0;     ///< leading components in the error test; 0: all
  /// Per controlled component (empty: none): where > 0 the size rtol refers to, instead of
  /// max(|y_i|) over the step (OdeOptions::error_scale).
  std::vector<double> error_scale;
  std::int64_t max_attempts = 100'000;  ///< rejected attempts allowed in one step() call
};

class Dop853 {
 public:
  /// ẏ = f(t, y), y and ẏ of dim `dim`; false: y is outside the model's domain (the step is
  /// retried 4 times smaller).
  using Rhs = std::function<bool(double t, std::span<const double> y, std::span<double> ydot)>;

  /// lead (optional, with options.controlled < dim): the flow of the controlled components alone,
  /// when they do not depend on the others (a state and its variational equations): the dense
  /// output of those components then never evaluates the whole of f (dense()).
  Dop853(Rhs f, int dim, Dop853Options options, Rhs lead = {});

  /// Starts a new smooth segment at (t, y) (dim): f(t, y) and the initial step of dop853.f's
  /// hinit (one more evaluation of f), at most the last accepted step of an earlier segment.
  void start(double t, std::span<const double> y);
  /// Takes one accepted step, ending at t_max if it would pass it (within 1 % of the step).
  /// Throws std::runtime_error if the step size underflows or f keeps failing.
  void step(double t_max);
  /// Ends the last step at t in (previous_time(), time()]: the state becomes the dense output
  /// there, which stays the interpolant of the shortened step; the next step starts at t.
  void truncate(double t);

  double time() const { return t_; }
  double previous_time() const { return t_old_; }
  std::span<const double> state() const { return y_; }
  /// The dense output (order 7) over the last step: the first y.size() components of y(t),
  /// t in [previous_time(), time()]. The first call after a step costs three evaluations of f;
  /// with `lead` and y.size() <= controlled, three of `lead` (the whole of f only once more
  /// components are asked for).
  void dense(double t, std::span<double> y) const;

  std::int64_t steps() const { return steps_; }          ///< accepted steps
  std::int64_t rhs_evals() const { return rhs_evals_; }  ///< evaluations of f
  double step_size() const { return h_next_; }           ///< the step the controller proposes next

 private:
  double* stage(int i) { return k_.data() + static_cast<std::size_t>(i) * dim_; }
  const double* stage(int i) const { return k_.data() + static_cast<std::size_t>(i) * dim_; }
  bool eval(double t, const std::vector<double>& y, double* ydot) const;
  /// out = base + h Σ_j a_ij k_j over j < i, its first n components
  void combine(const std::vector<double>& base, int i, double h, std::vector<double>& out, std::size_t n) const;
  double error_norm(double h) const;
  double initial_step(double t);
  void prepare_dense(std::size_t n) const;

  Rhs f_;
  Rhs lead_;  // the controlled components' own flow, or empty
  std::size_t dim_;
  std::size_t controlled_;
  Dop853Options opt_;
  double t_ = 0, t_old_ = 0;
  double h_ = 0;       // length of the last step's polynomial (before any truncation)
  double h_next_ = 0;  // proposed next step
  double h_last_ = 0;  // the last accepted step, kept across restarts (bounds the next start's step)
  enum class NextStage0 { Valid, FromLastStage, Evaluate };  // where the next step's f(t, y) comes from
  NextStage0 next_k0_ = NextStage0::Evaluate;
  bool rejected_ = false;                          // the last attempt was rejected (no growth on the next accept)
  std::vector<double> y_, y_old_, y_new_, y_tmp_;  // dim each; y_new_: the last step's end (untruncated)
  mutable std::vector<double> dense_tmp_;          // dim
  mutable std::vector<double> k_;                  // 16 stages × dim (stages 13..15 for dense output)
  mutable std::vector<double> cont_;               // dense-output coefficients r4..r8 (5 × dim)
  mutable std::vector<double> err5_, err3_;        // error_norm's scratch (controlled components)
  mutable std::size_t dense_ready_ = 0;            // components of the dense output prepared
  std::int64_t steps_ = 0;
  mutable std::int64_t rhs_evals_ = 0;
};

}  // namespace flexgait::numerics
