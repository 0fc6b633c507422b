#pragma once
/// \file poincare.hpp
/// Poincaré maps of the rimless wheel (docs/theory/rimless.md, "Poincaré map, fixed points, stability").
///
/// Translation invariance removes x: the stance foot is put at c = 0, leg indices are shifted so
/// that the stance leg is 0. The free legs' leftover compressions are set to 0 at the section:
/// a free leg does not act on the hub until it lands again, a revolution later, by which time
/// its compression has decayed by exp(-K T_rev / C) (about e^-130 with the defaults).
///
/// Reduced state z (dimension 3 when the stance foot sticks at the section: ċ = 0 fixes ẋ):
///   touchdown section, just before leg N-1 lands:  z = (β_{N-1}, [ẋ,] ẏ, θ̇),
///       with y = L0 cos β_{N-1} (the landing foot touches the ground), θ = β_{N-1} + 2α;
///   upright section, leg 0 at β = 0 in single support:  z = (y, [ẋ,] ẏ, θ̇).
/// The discrete part of the section state is the stance foot's mode (or flight).
/// The rigid wheel's reduced state is z = (θ̇): ω⁺ after the impact (touchdown) or ω at β = 0.
#include <Eigen/Dense>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/simulation.hpp"

namespace flexgait::rimless {

struct SectionState {
  Model model = Model::Flexible;
  Section section = Section::Touchdown;
  bool flight = false;              ///< no foot down before the touchdown (touchdown only)
  FootMode mode = FootMode::Stick;  ///< the stance foot's mode at the section
  Eigen::VectorXd z;                ///< reduced state, see the header

  /// Names of z's components, e.g. {"beta", "yd", "thetad"}.
  std::vector<std::string> names() const;
  /// Typical magnitudes of z's components (for finite-difference steps).
  Eigen::VectorXd scale(const WheelParams& w) const;
};

/// "stick", "slip+", "slip-" or "flight": the section point's discrete mode.
std::string mode_text(const SectionState& point);

/// The same physical section point written in the discrete mode of `like` (its model and section):
/// the full state of section_run(w, point) reduced to like's components, e.g. a sticking point's
/// ẋ (fixed by ċ = 0) added to make it a slipping point's state, or ẋ dropped the other way (exact
/// only where ċ = 0). Used to carry a fixed point across a change of the section's foot mode.
SectionState in_mode(const WheelParams& w, const SectionState& point, const SectionState& like);

/// The flexible wheel's full state at a section point, its feet on the ground, and the events
/// pending there (the landing at a touchdown section).
RunSpec section_run(const WheelParams& w, const SectionState& point);

/// Reduces a section crossing of the flexible wheel to a SectionState (leg indices shifted).
/// Returns an error message if the crossing cannot be reduced (e.g. two feet down).
std::optional<std::string> reduce_crossing(const WheelParams& w, Section section, const SectionHit& hit,
                                           SectionState& out);

/// One application of the map, with what happened on the way.
struct MapStep {
  std::optional<Failure> failure;  ///< why the next crossing was not reached
  SectionState next;
  std::string gait;       ///< stance-foot phases over the cycle
  double period = 0;      ///< time between the crossings [s]
  double distance = 0;    ///< hub travel along the slope [m]
  double dissipated = 0;  ///< energy that left the body over the cycle [J]: W_damp + W_fric
                          ///< + the free legs' spring energy at the end
  int jams = 0;
};

/// The Poincaré map of one model on one section: a simulator kept for repeated evaluations.
class PoincareMap {
 public:
  PoincareMap(const WheelParams& w, const SimulationOptions& options, Model model, Section section);
  ~PoincareMap();
  PoincareMap(PoincareMap&&) noexcept;
  /// P(point). The map keeps the discrete mode: arriving in another mode is a failure, unless
  /// `keep_mode` is false (then `next` carries the mode it arrived in: for following transients).
  MapStep apply(const SectionState& point, bool keep_mode = true);
  /// ∂P/∂z at `point` from the variational equations: CVODES forward sensitivities along the flow,
  /// saltation matrices at every event and the crossing-time correction at the section
  /// (variational.hpp); the section reconstruction z -> y is differentiated by central
  /// differences (it is algebraic). Flexible wheel with I > 0, or the rigid wheel at touchdown
  /// (analytic). Returns why not, otherwise.
  std::optional<std::string> jacobian(const SectionState& point, Eigen::MatrixXd& J);
  /// The parameter that jacobian_and_parameter_derivative() differentiates in (docs/guide/rimless.md, "Orbit diagram
  /// and basin of attraction").
  void set_parameter(const ParameterDirection& parameter);
  bool has_parameter() const { return parameter_.has_value(); }
  /// ∂P/∂z and ∂P/∂p from one variational run (after set_parameter; otherwise why not): the
  /// sensitivities' parameter column (flexible_wheel.hpp, ParameterDirection) and the section
  /// reconstruction's own dependence on p (y = L0 cos β at touchdown), the latter by central
  /// differences (it is algebraic). The rigid wheel at touchdown: the closed-form step map's
  /// central difference in p (rigid_wheel.hpp).
  std::optional<std::string> jacobian_and_parameter_derivative(const SectionState& point, Eigen::MatrixXd& J,
                                                               Eigen::VectorXd& J_p);
  /// The map as a VectorMap on z with the discrete part of `like` (for Newton).
  std::optional<std::string> operator()(const SectionState& like, const Eigen::VectorXd& z, Eigen::VectorXd& out);
  Model model() const { return model_; }
  Section section() const { return section_; }
  const WheelParams& params() const { return w_; }
  const SimulationOptions& options() const { return options_; }
  /// The flexible wheel's simulator (the map's and a SectionWalk's runs; null for the rigid wheel).
  FlexibleWheelSimulator* simulator() { return sim_.get(); }

 private:
  WheelParams w_;
  SimulationOptions options_;
  Model model_;
  Section section_;
  std::unique_ptr<FlexibleWheelSimulator> sim_;
  std::unique_ptr<FlexibleWheelSimulator> sens_sim_;  // with sensitivities, made on first use
  std::optional<ParameterDirection> parameter_;       // set_parameter()
  std::optional<std::string> linearise(const SectionState& point, Eigen::MatrixXd& J, Eigen::VectorXd* J_p);
};

/// Follows one orbit from section crossing to section crossing in the full hybrid state: each
/// run starts where the last one crossed the section, with the free legs' compressions and rates,
/// every foot on the ground and the landing pending at a touchdown section, so the crossings are
/// those of one uninterrupted simulation (the integrator restarts at a touchdown anyway). The
/// Poincaré map instead restarts every cycle from the reduced state (free legs relaxed, one foot
/// down), which is exact on the section's definition only for Newton's iteration on a fixed point;
/// where a free leg is still compressed or a second foot is down at the crossing (e.g. past a
/// Neimark–Sacker point) the reduced restart leaves the orbit. The rigid wheel's reduced state is
/// its full state: there a step is the map's.
class SectionWalk {
 public:
  SectionWalk(const WheelParams& w, const SimulationOptions& options, Model model, Section section);
  ~SectionWalk();
  SectionWalk(SectionWalk&&) noexcept;
  /// Simulates `transient_steps` from `initial` and runs on to the next crossing, reduced into
  /// `out` (failures as settle_on_section's). The walk continues from there.
  std::optional<Failure> settle(const InitialState& initial, int transient_steps, SectionState& out);
  /// The walk continues from a given section point (e.g. a perturbed fixed point): its first run
  /// starts at the point's reconstruction (section_run), as the map's; the later ones at the
  /// crossings' full states.
  void start_at(const SectionState& point);
  /// From the last crossing to the next: `next` is the new crossing reduced (in whatever mode it
  /// arrived), `gait` and `period` as the map's, `distance` the hub's travel, `dissipated` the
  /// work of the dampers and of friction over the cycle (free legs' stored energy is carried).
  MapStep step();
  /// The full state at the last crossing (flexible wheel; empty before settle()).
  const std::vector<double>& state() const { return next_.y0; }

 private:
  PoincareMap map_;     // the wheel, options, model, section and simulator; the rigid wheel's step
  SectionState point_;  // the last crossing, reduced
  RunSpec next_;        // the run from the last crossing (flexible)
  std::optional<Failure> to_section(const SimulationResult& r, const SectionHit& hit, SectionState& out);
};

/// A first section point: simulate `transient_steps` from `initial` and reduce the next crossing.
/// Returns why not: the transient's failure in stage "transient", the run to the section's in
/// "reaching the section", an infeasible start (InitialFootBelowGround) without a stage.
std::optional<Failure> settle_on_section(const WheelParams& w, const SimulationOptions& options, Model model,
                                         Section section, const InitialState& initial, int transient_steps,
                                         SectionState& out);

}  // namespace flexgait::rimless
