/// \file cvode_backend.cpp
/// OdeIntegrator on SUNDIALS CVODE/CVODES: variable-order Adams (fixed-point corrector) or BDF
/// (dense Newton), with root finding on CVODE's dense output and forward sensitivities.
///
/// CVODE's root finding sees a guard's sign at its internal steps' ends only; every step that it
/// ends without a root is watched by GuardCrossings as well (guard_crossings.hpp: the interior
/// samples of the step on CVODE's interpolant), which finds a crossing and its return within the
/// step. Such a crossing ends the step there (time(), state() and the sensitivities interpolated to
/// it); CVODE itself stays at its step's end, so the caller restarts at the crossing, as after any
/// guard.
#include "flexgait/numerics/guard_crossings.hpp"
#include "flexgait/numerics/ode_backend.hpp"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace flexgait::numerics {
namespace {

struct CvodeSolver {
  OdeSystem* system = nullptr;
  int n = 0;
  OdeOptions options;
  SUNContext ctx = nullptr;
  void* cvode = nullptr;
  N_Vector y = nullptr;
  int columns = 0;          // sensitivity columns: n states, then OdeOptions::parameter_columns
  N_Vector* yS = nullptr;   // sensitivity columns when enabled
  N_Vector work = nullptr;  // scratch for the sensitivity right-hand side
  N_Vector work2 = nullptr;
  SUNNonlinearSolver sens_solver = nullptr;
  SUNMatrix jac = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  SUNNonlinearSolver nonlinear_solver = nullptr;
  int n_guards = -1;
  std::vector<int> directions;       // as given to restart() (the watch's)
  std::vector<int> root_directions;  // CVODE's: kNoGuard as 0 (the slot's constant never crosses)
  std::vector<int> fired;
  double t = 0.0;
  std::int64_t restarts = 0;
  GuardCrossings watch;            // the interior samples of CVODE's steps (above)
  std::vector<double> g_end;       // the guards at the latest step's end
  std::vector<double> y_dense;     // scratch: the interpolant at one time
  std::vector<double> g_scratch;   // scratch: all guards, for OdeSystem::guard()
  bool interior_crossing = false;  // the last step ended at a crossing GuardCrossings found
  double watch_t = 0.0;            // where the watch's current step starts [s]
  std::int64_t watch_evals = 0;    // guard evaluations of the watch
  double root_t = 0.0;             // CVODE's latest evaluation of the guards: time, state, values
  std::vector<double> root_y, root_g;
  OdeStats finished;  // counts of the segments before the current one (CVodeReInit zeroes CVODE's)
  std::string last_error;

  OdeStats segment_stats() const {
    OdeStats s;
    long v = 0;
    CVodeGetNumSteps(cvode, &v);
    s.steps = v;
    CVodeGetNumRhsEvals(cvode, &v);
    s.rhs_evals = v;
    CVodeGetNumGEvals(cvode, &v);
    s.guard_evals = v;
    return s;
  }

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
    auto* self = static_cast<CvodeSolver*>(data);
    const std::span<const double> ys(N_VGetArrayPointer(y), static_cast<std::size_t>(self->n));
    const std::span<double> yd(N_VGetArrayPointer(ydot), static_cast<std::size_t>(self->n));
    return self->system->rhs(t, ys, yd) ? 0 : 1;  // 1: recoverable, CVODE retries a smaller step
  }
  static int linearization_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
    auto* self = static_cast<CvodeSolver*>(data);
    const std::span<const double> ys(N_VGetArrayPointer(y), static_cast<std::size_t>(self->n));
    const std::span<double> yd(N_VGetArrayPointer(ydot), static_cast<std::size_t>(self->n));
    return self->system->linearization_rhs(t, ys, yd) ? 0 : 1;
  }
  // ∂f/∂y · s by a centered directional difference; step scaled to y and s. A parameter column
  // (iS >= n) adds ∂f/∂p.
  static int sens_rhs(int, sunrealtype t, N_Vector y, N_Vector ydot, int iS, N_Vector s, N_Vector sdot, void* data,
                      N_Vector, N_Vector) {
    auto* self = static_cast<CvodeSolver*>(data);
    if (directional_derivative(t, y, s, sdot, data) != 0) return 1;
    if (iS < self->n) return 0;
    const std::span<const double> ys(N_VGetArrayPointer(y), static_cast<std::size_t>(self->n));
    const std::span<double> fp(N_VGetArrayPointer(self->work), static_cast<std::size_t>(self->n));
    if (!self->system->parameter_derivative(t, ys, iS - self->n, fp)) return 1;
    N_VLinearSum(1.0, sdot, 1.0, self->work, sdot);
    (void)ydot;
    return 0;
  }
  static int directional_derivative(sunrealtype t, N_Vector y, N_Vector s, N_Vector sdot, void* data) {
    auto* self = static_cast<CvodeSolver*>(data);
    const double snorm = N_VMaxNorm(s);
    if (snorm == 0.0) {
      N_VConst(0.0, sdot);
      return 0;
    }
    const double ynorm = N_VMaxNorm(y);
    const double delta = 6e-6 * std::max(ynorm, 1.0) / snorm;  // ≈ ε^(1/3) relative
    N_VLinearSum(1.0, y, delta, s, self->work);
    if (linearization_rhs(t, self->work, sdot, data) != 0) return 1;
    N_VLinearSum(1.0, y, -delta, s, self->work);
    if (linearization_rhs(t, self->work, self->work2, data) != 0) return 1;
    N_VLinearSum(0.5 / delta, sdot, -0.5 / delta, self->work2, sdot);
    return 0;
  }
  static int guards(sunrealtype t, N_Vector y, sunrealtype* g, void* data) {
    auto* self = static_cast<CvodeSolver*>(data);
    const std::span<const double> ys(N_VGetArrayPointer(y), static_cast<std::size_t>(self->n));
    const std::span<double> gs(g, static_cast<std::size_t>(self->n_guards));
    self->system->guards(t, ys, gs);
    // Kept: CVODE's root check evaluates the guards at its step's end, which the watch needs too.
    self->root_t = t;
    self->root_y.assign(ys.begin(), ys.end());
    self->root_g.assign(gs.begin(), gs.end());
    return 0;
  }
  // The guards at (t, y): CVODE's latest evaluation if it was at this very point, else computed.
  void guards_at(double t, std::span<const double> y, std::span<double> g) {
    if (t == root_t && root_y.size() == y.size() && std::equal(y.begin(), y.end(), root_y.begin())) {
      std::copy(root_g.begin(), root_g.end(), g.begin());
      return;
    }
    system->guards(t, y, g);
    ++watch_evals;
  }
  // CVODE's error weights with OdeOptions::error_scale (CVodeWFtolerances).
  static int error_weights(N_Vector y, N_Vector ewt, void* data) {
    const CvodeSolver& m = *static_cast<const CvodeSolver*>(data);
    const double* yv = N_VGetArrayPointer(y);
    double* w = N_VGetArrayPointer(ewt);
    for (int i = 0; i < m.n; ++i) {
      const double scale = m.options.error_scale[static_cast<std::size_t>(i)];
      const double tol = m.options.rtol * (scale > 0 ? scale : std::abs(yv[i])) + m.options.atol;
      if (!(tol > 0)) return -1;
      w[i] = 1.0 / tol;
    }
    return 0;
  }
  static void on_error(int, const char* module, const char* function, char* msg, void* data) {
    static_cast<CvodeSolver*>(data)->last_error = std::string(module) + "." + function + ": " + msg;
  }
  void check(int flag, const char* what) const {
    if (flag < 0) {
      throw std::runtime_error(std::string("CVODE ") + what + " failed (flag " + std::to_string(flag) + ")" +
                               (last_error.empty() ? "" : ": " + last_error));
    }
  }
  ~CvodeSolver() {
    if (cvode != nullptr) CVodeFree(&cvode);
    if (nonlinear_solver != nullptr) SUNNonlinSolFree(nonlinear_solver);
    if (sens_solver != nullptr) SUNNonlinSolFree(sens_solver);
    if (yS != nullptr) N_VDestroyVectorArray(yS, columns);
    if (work != nullptr) N_VDestroy(work);
    if (work2 != nullptr) N_VDestroy(work2);
    if (linear_solver != nullptr) SUNLinSolFree(linear_solver);
    if (jac != nullptr) SUNMatDestroy(jac);
    if (y != nullptr) N_VDestroy(y);
    if (ctx != nullptr) SUNContext_Free(&ctx);
  }
};

class CvodeBackend final : public OdeBackend {
 public:
  CvodeBackend(OdeSystem& system, int n, const OdeOptions& options);
  void restart(double t, std::span<const double> y, std::span<const int> directions,
               std::span<const double> S) override;
  void sensitivities(std::span<double> S) const override;
  StepStatus step(double t_stop) override;
  double time() const override { return impl_->t; }
  std::span<const double> state() const override {
    return {N_VGetArrayPointer(impl_->y), static_cast<std::size_t>(impl_->n)};
  }
  void interpolate(double t, std::span<double> y) const override;
  std::span<const int> guards_fired() const override { return impl_->fired; }
  OdeStats stats() const override;

 private:
  void restart_state(double t, std::span<const double> y, std::span<const int> directions);
  std::unique_ptr<CvodeSolver> impl_;
};

CvodeBackend::CvodeBackend(OdeSystem& system, int n, const OdeOptions& options)
    : impl_(std::make_unique<CvodeSolver>()) {
  CvodeSolver& m = *impl_;
  m.system = &system;
  m.n = n;
  m.options = options;
  if (SUNContext_Create(nullptr, &m.ctx) != 0) throw std::runtime_error("SUNContext_Create failed");
  m.y = N_VNew_Serial(n, m.ctx);
  N_VConst(0.0, m.y);
  N_VEnableFusedOps_Serial(m.y, SUNTRUE);  // fewer calls per Nordsieck update (~10 % here)
  m.cvode = CVodeCreate(options.method == OdeMethod::Adams ? CV_ADAMS : CV_BDF, m.ctx);
  if (m.cvode == nullptr || m.y == nullptr) throw std::runtime_error("CVodeCreate failed");
  m.check(CVodeSetErrHandlerFn(m.cvode, &CvodeSolver::on_error, &m), "SetErrHandlerFn");
  m.check(CVodeInit(m.cvode, &CvodeSolver::rhs, 0.0, m.y), "Init");
  m.check(CVodeSetUserData(m.cvode, &m), "SetUserData");
  if (options.error_scale.empty()) {
    m.check(CVodeSStolerances(m.cvode, options.rtol, options.atol), "SStolerances");
  } else {
    if (static_cast<int>(options.error_scale.size()) != n) throw std::invalid_argument("OdeOptions::error_scale: size");
    m.check(CVodeWFtolerances(m.cvode, &CvodeSolver::error_weights), "WFtolerances");
  }
  m.check(CVodeSetMaxNumSteps(m.cvode, static_cast<long>(options.max_steps)), "SetMaxNumSteps");
  if (options.max_step > 0) m.check(CVodeSetMaxStep(m.cvode, options.max_step), "SetMaxStep");
  if (options.max_order > 0) m.check(CVodeSetMaxOrd(m.cvode, options.max_order), "SetMaxOrd");
  if (options.method == OdeMethod::Adams) {
    m.nonlinear_solver = SUNNonlinSol_FixedPoint(m.y, 0, m.ctx);
    m.check(CVodeSetNonlinearSolver(m.cvode, m.nonlinear_solver), "SetNonlinearSolver");
  } else {
    m.jac = SUNDenseMatrix(n, n, m.ctx);
    m.linear_solver = SUNLinSol_Dense(m.y, m.jac, m.ctx);
    m.check(CVodeSetLinearSolver(m.cvode, m.linear_solver, m.jac), "SetLinearSolver");
  }
  m.check(CVodeSetNoInactiveRootWarn(m.cvode), "SetNoInactiveRootWarn");
  if (options.sensitivities) {
    m.columns = n + options.parameter_columns;
    m.yS = N_VCloneVectorArray(m.columns, m.y);
    m.work = N_VClone(m.y);
    m.work2 = N_VClone(m.y);
    for (int i = 0; i < m.columns; ++i) {
      N_VConst(0.0, m.yS[i]);
      if (i < n) N_VGetArrayPointer(m.yS[i])[i] = 1.0;
    }
    m.check(CVodeSensInit1(m.cvode, m.columns, CV_STAGGERED, &CvodeSolver::sens_rhs, m.yS), "SensInit1");
    m.check(CVodeSensEEtolerances(m.cvode), "SensEEtolerances");
    // Sensitivities stay out of the error test (CVODES's default): the steps that resolve the
    // state resolve its linearisation; with them in, the map Jacobian cost 26x more for no accuracy.
    m.check(CVodeSetSensErrCon(m.cvode, SUNFALSE), "SetSensErrCon");
    if (options.method == OdeMethod::Adams) {
      m.sens_solver = SUNNonlinSol_FixedPointSens(m.columns, m.y, 0, m.ctx);
      m.check(CVodeSetNonlinearSolverSensStg(m.cvode, m.sens_solver), "SetNonlinearSolverSensStg");
    }
  }
}

void CvodeBackend::restart(double t, std::span<const double> y, std::span<const int> directions,
                           std::span<const double> S) {
  CvodeSolver& m = *impl_;
  restart_state(t, y, directions);
  if (S.empty()) return;
  for (int j = 0; j < m.columns; ++j)
    std::copy(S.begin() + j * m.n, S.begin() + (j + 1) * m.n, N_VGetArrayPointer(m.yS[j]));
  m.check(CVodeSensReInit(m.cvode, CV_STAGGERED, m.yS), "SensReInit");
}

void CvodeBackend::sensitivities(std::span<double> S) const {
  CvodeSolver& m = *impl_;
  sunrealtype t = 0;
  if (m.interior_crossing)
    m.check(CVodeGetSensDky(m.cvode, m.t, 0, m.yS), "GetSensDky");  // at the crossing, before CVODE's step end
  else
    m.check(CVodeGetSens(m.cvode, &t, m.yS), "GetSens");
  for (int j = 0; j < m.columns; ++j) {
    const double* col = N_VGetArrayPointer(m.yS[j]);
    std::copy(col, col + m.n, S.begin() + j * m.n);
  }
}

void CvodeBackend::restart_state(double t, std::span<const double> y, std::span<const int> directions) {
  CvodeSolver& m = *impl_;
  std::copy(y.begin(), y.end(), N_VGetArrayPointer(m.y));
  m.t = t;
  const OdeStats seg = m.segment_stats();
  m.finished.steps += seg.steps;
  m.finished.rhs_evals += seg.rhs_evals;
  m.finished.guard_evals += seg.guard_evals;
  m.check(CVodeReInit(m.cvode, t, m.y), "ReInit");
  const int n_guards = static_cast<int>(directions.size());
  if (n_guards != m.n_guards) {
    m.check(CVodeRootInit(m.cvode, n_guards, n_guards > 0 ? &CvodeSolver::guards : nullptr), "RootInit");
    m.n_guards = n_guards;
    m.fired.assign(directions.size(), 0);
  }
  m.directions.assign(directions.begin(), directions.end());
  m.root_directions.resize(directions.size());
  std::transform(directions.begin(), directions.end(), m.root_directions.begin(),
                 [](int d) { return d == kNoGuard ? 0 : d; });
  if (n_guards > 0) m.check(CVodeSetRootDirection(m.cvode, m.root_directions.data()), "SetRootDirection");
  ++m.restarts;
  m.interior_crossing = false;
  m.g_end.resize(directions.size());
  m.y_dense.resize(static_cast<std::size_t>(m.n));
  if (n_guards > 0) {
    m.system->guards(t, y, m.g_end);
    ++m.watch_evals;
  }
  m.watch.start(t, directions, m.g_end);
  m.watch_t = t;
}

StepStatus CvodeBackend::step(double t_stop) {
  CvodeSolver& m = *impl_;
  m.check(CVodeSetStopTime(m.cvode, t_stop), "SetStopTime");
  m.last_error.clear();
  m.root_y.clear();  // only this step's evaluations are reused (the model's guards may change between steps)
  sunrealtype t_reached = m.t;
  const int flag = CVode(m.cvode, t_stop, m.y, &t_reached, CV_ONE_STEP);
  m.check(flag, "step");
  m.t = t_reached;
  m.interior_crossing = false;
  const std::span<const double> y_end(N_VGetArrayPointer(m.y), static_cast<std::size_t>(m.n));
  if (flag == CV_ROOT_RETURN) {
    m.check(CVodeGetRootInfo(m.cvode, m.fired.data()), "GetRootInfo");
    // CVODE goes on from its root if the caller does not restart: the watch starts there too.
    m.system->guards(m.t, y_end, m.g_end);
    ++m.watch_evals;
    m.watch.start(m.t, m.directions, m.g_end);
    m.watch_t = m.t;
    return StepStatus::Guard;
  }
  if (m.n_guards > 0) {
    // The interpolant covers CVODE's last internal step only: a watch that started before it
    // (CVODE's step after its root return ends the internal step the root was in) starts again
    // at its beginning, where CVODE's own step-end check has looked.
    sunrealtype h_last = 0, t_cur = 0;
    m.check(CVodeGetLastStep(m.cvode, &h_last), "GetLastStep");
    m.check(CVodeGetCurrentTime(m.cvode, &t_cur), "GetCurrentTime");
    if (m.watch_t < t_cur - h_last) {
      interpolate(t_cur - h_last, m.y_dense);
      m.system->guards(t_cur - h_last, m.y_dense, m.g_end);
      ++m.watch_evals;
      m.watch.start(t_cur - h_last, m.directions, m.g_end);
    }
    m.guards_at(m.t, y_end, m.g_end);
    const auto values = [&m, this](double ts, std::span<double> g) {
      interpolate(ts, m.y_dense);
      m.system->guards(ts, m.y_dense, g);
      ++m.watch_evals;
    };
    std::vector<double>& scratch = m.g_scratch;
    const auto value = [&m, &scratch, this](double ts, int i) {
      interpolate(ts, m.y_dense);
      ++m.watch_evals;
      return m.system->guard(ts, m.y_dense, i, scratch);
    };
    scratch.resize(m.g_end.size());
    if (const auto crossing = m.watch.check(m.t, m.g_end, values, value)) {
      if (*crossing < m.t) {
        interpolate(*crossing, m.y_dense);
        std::copy(m.y_dense.begin(), m.y_dense.end(), N_VGetArrayPointer(m.y));
        m.t = *crossing;
        m.interior_crossing = true;
      }
      const auto fired = m.watch.fired();
      std::copy(fired.begin(), fired.end(), m.fired.begin());
      m.watch_t = m.t;
      return StepStatus::Guard;
    }
    m.watch_t = m.t;
  }
  return flag == CV_TSTOP_RETURN ? StepStatus::StopTime : StepStatus::Step;
}

void CvodeBackend::interpolate(double t, std::span<double> y) const {
  CvodeSolver& m = *impl_;
  N_Vector out = N_VMake_Serial(m.n, y.data(), m.ctx);
  const int flag = CVodeGetDky(m.cvode, t, 0, out);
  N_VDestroy(out);
  m.check(flag, "GetDky");
}

OdeStats CvodeBackend::stats() const {
  OdeStats s = impl_->segment_stats();
  s.steps += impl_->finished.steps;
  s.rhs_evals += impl_->finished.rhs_evals;
  s.guard_evals += impl_->finished.guard_evals + impl_->watch_evals;
  s.restarts = impl_->restarts;
  return s;
}

}  // namespace

std::unique_ptr<OdeBackend> make_cvode_backend(OdeSystem& system, int n, const OdeOptions& options) {
  return std::make_unique<CvodeBackend>(system, n, options);
}

}  // namespace flexgait::numerics
