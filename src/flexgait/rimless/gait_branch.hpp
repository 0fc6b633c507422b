#pragma once
/// \file gait_branch.hpp
/// Continuation of the wheel's periodic gait in one real configuration key (issue 18): the fixed
/// point of the Poincaré map followed by pseudo-arclength continuation (numerics/continuation.hpp)
/// in the normalised parameter q = (p - from)/(to - from) ∈ [0, 1], so that one arclength unit is
/// the whole interval whatever the key's unit. ∂P/∂z is the exact (variational) Jacobian when the
/// map has one at the start, else central differences; ∂P/∂q by central differences.
/// The gait label (stance-foot phases over the cycle) is watched: where it changes (a non-smooth
/// boundary: a phase appears or vanishes) the change is located by bisection. The map keeps the
/// section's discrete mode, so the branch continues through a boundary when the fixed point stays
/// a fixed point of the same-mode map there, and ends (with the map's reason) when it does not.
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/numerics/continuation.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless {

struct GaitContinuationSpec {
  std::string param;                 ///< a real configuration key, or "rimless.mu" (μ_s = μ_k)
  double from = 0, to = 0;           ///< the interval, in the key's unit; the start at `from`
  double step = 0;                   ///< first step in the key's unit (0: |to - from| / 50)
  int max_points = 2000;
  Section section = Section::Touchdown;
};

/// One row of branch.csv: a point of the branch or a special point on it.
struct GaitBranchRow {
  double p = 0;                      ///< parameter value (key's unit)
  numerics::BranchPoint point;       ///< z, multipliers, stability (its p is q)
  std::string gait;
  double period = 0;                 ///< [s]
  double speed = 0;                  ///< mean hub speed along the slope [m/s]
  double dissipated = 0;             ///< energy dissipated per step [J]
  std::string event;                 ///< "start", "end: …", a special point's kind, or empty
};

struct GaitBranch {
  std::string param;
  std::vector<std::string> state_names;
  std::string mode;                  ///< the section's discrete mode along the branch
  bool exact_jacobian = false;
  numerics::Branch branch;           ///< in q
  std::vector<GaitBranchRow> rows;   ///< points and special points in the order of arclength
  std::string stop_reason;           ///< why the branch ended, in the key's unit
  std::string failure;               ///< nonempty when the start has no fixed point
};

/// The branch from the gait found at `from` (find_fixed_point from the configured initial state).
/// Throws ConfigError when param is not a real key, from = to, or either end is not a valid value.
GaitBranch continue_gait(const Config& base, const GaitContinuationSpec& spec);

/// branch.csv: parameter, the state's components, mode, period, speed, dissipated_per_step, gait,
/// abs_lambda_k and arg_lambda_k for every multiplier (largest first), stable, residual, event.
std::string gait_branch_csv(const GaitBranch& b);

}  // namespace flexgait::rimless
