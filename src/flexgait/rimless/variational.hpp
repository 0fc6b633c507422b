#pragma once
/// \file variational.hpp
/// Linearisation of the hybrid flow across events, for exact Poincaré-map Jacobians.
///
/// Between events the sensitivities S = ∂y/∂y0 follow Ṡ = (∂f/∂y) S (CVODES). At an event with
/// guard g, reset y⁺ = R(y⁻) and vector fields f⁻ (old mode) and f⁺ (new mode) the saltation
/// matrix maps them across (Aizerman & Gantmacher; Leine & Nijmeijer 2004, eq. 4.34):
///   S⁺ = [ R_y + (f⁺ - R_y f⁻) g_y / (g_y f⁻) ] S⁻.
/// At the Poincaré section (g the section's guard, no reset) the crossing-time correction is
///   S_section = [ I - f⁻ g_y / (g_y f⁻) ] S⁻.
/// R_y and g_y are central differences of algebraic functions (the reset with its mode decision
/// held fixed, and the guard), not of the flow.
#include <Eigen/Dense>

#include <functional>
#include <optional>
#include <span>
#include <string>

#include "flexgait/rimless/contact.hpp"

namespace flexgait::rimless {

/// Per-component difference steps for state vectors of the wheel.
Eigen::VectorXd state_steps(const WheelParams& w, std::span<const double> y);

/// Gradient of a scalar function of the state by central differences with steps h.
Eigen::RowVectorXd gradient(const std::function<double(std::span<const double>)>& g, std::span<const double> y,
                            const Eigen::VectorXd& h);

/// Jacobian of a map of the state by central differences; the map returns false when its
/// discrete outcome (e.g. the chosen contact modes) would change, which is reported.
std::optional<std::string> jacobian(const std::function<bool(std::span<const double>, std::span<double>)>& R,
                                    std::span<const double> y, const Eigen::VectorXd& h, Eigen::MatrixXd& J);

/// The saltation matrix above; `R_y` may be the identity.
Eigen::MatrixXd saltation(const Eigen::MatrixXd& R_y, const Eigen::VectorXd& f_minus, const Eigen::VectorXd& f_plus,
                          const Eigen::RowVectorXd& g_y);

}  // namespace flexgait::rimless
