#pragma once
/// \file step_adjustment.hpp
/// Capture-point step adjustment (docs/guide/humanoid.md; Englsberger et al., IEEE T-RO 2015, "Three-dimensional
/// bipedal walking control based on divergent component of motion"; Khadiv et al., Humanoids 2016,
/// "Step timing adjustment: a step toward generating robust gaits"). In the linear inverted
/// pendulum the DCM error e = ξ − ξ_ref obeys ė = ω (e − δ) (eq. D1 of dcm_stabiliser.hpp), δ the
/// centre of pressure's offset from its reference. The stance sole bounds δ: with δ = e clipped to
/// the sole (the most the ankles can do), the error at touchdown, τ seconds ahead, is
///
///   e(τ) = δ + (e − δ) e^{ωτ}.                                                        (S1)
///
/// While e stays inside the sole the stabiliser absorbs it (e − δ = 0: no adjustment). Once it
/// leaves, the foot lands shifted by the part the sole cannot absorb,
///
///   Δ = (e − δ) e^{ωτ},                                                                (S2)
///
/// so that the DCM keeps its planned offset from the new stance foot. Δ is bounded, in the stance
/// sole's frame: each component by `limit`, the landing's distance from the stance sole centre by
/// `reach`, and the swing foot stays on its own side at least `min_width` from the stance foot
/// (the feet never cross; min_width < reach). Pure arithmetic: no allocation.
///
/// (S3) Early landing (step timing, Khadiv et al. 2016: the step ends when its foot is down). A
/// push toward the swing foot rolls the robot about the stance sole's edge, and the swing foot
/// meets the floor before its planned touchdown. Once a step has been adjusted and its swing foot
/// is loaded past the arc's apex, the step has landed: its landing is where the foot is (no longer
/// moved; the swing path would drag the loaded foot), and until the next step lifts the load is
/// split between the feet by the stabiliser's centre of pressure, not by the reference, which
/// would keep the weight on the old stance foot while the DCM runs over the new one (the
/// controller, WalkingController::adjust_steps and load_split_point).
#include <Eigen/Dense>

#include "flexgait/walking/footstep_plan.hpp"

namespace flexgait::walking {

struct StepLimits {
  double limit = 0.15;      ///< |Δ| along each axis of the stance sole [m]
  double reach = 0.4;       ///< landing to stance sole centre, at most [m]
  double min_width = 0.17;  ///< landing to stance sole centre across the heading, at least [m]
};

/// The part of the DCM error `e` (world, [m]) beyond the sole of `stance` (half-extents `half`
/// along and across its heading [m]): e − δ of (S1).
Eigen::Vector2d dcm_error_beyond_sole(const Eigen::Vector2d& e, const Footprint& stance, const Eigen::Vector2d& half);

/// The landing of a swing foot of side `swing` (0 left, 1 right) planned at `planned`, moved by
/// Δ = `beyond` e^{ω τ} (S2) within `limits` around the stance foot `stance`. ω [1/s], τ ≥ 0 [s].
Footprint adjusted_landing(const Footprint& planned, const Footprint& stance, int swing, const Eigen::Vector2d& beyond,
                           double omega, double tau, const StepLimits& limits);

}  // namespace flexgait::walking
