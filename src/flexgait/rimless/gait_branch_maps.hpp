#pragma once
/// \file gait_branch_maps.hpp
/// The Poincaré maps a gait continuation evaluates (gait_branch.hpp), in the normalised parameter
/// q: a cache of maps by q, the map families of one section mode (and of its k-th iterate), and the
/// crossing of a change of the section's foot mode. Internal to gait_branch.cpp.
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "flexgait/core/config.hpp"
#include "flexgait/numerics/continuation.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless::detail {

/// Poincaré maps at the last few parameter values (a corrector step evaluates at p and p ± h_p).
struct MapCache {
  Config base;
  GaitContinuationSpec spec;
  SimulationOptions sim;
  AnalysisOptions opt;
  Model model;
  std::deque<std::pair<double, std::unique_ptr<PoincareMap>>> maps;
  /// The mode of the last evaluation that arrived at the section in another mode than it started.
  std::optional<SectionState> arrived;
  double arrived_q = 0;  ///< where

  double value(double q) const { return spec.from + q * (spec.to - spec.from); }
  Config config_at(double p) const;
  WheelParams wheel_at(double q) const;
  /// Whether the key's value at q is valid (its bounds, the wheel's cross-field checks).
  bool valid(double q) const;
  /// The map at q, or why the parameter value is not valid. A map of a wheel parameter (a
  /// rimless.* key) carries its ParameterDirection in q (∂P/∂q by sensitivity) when q ± h are valid.
  PoincareMap* at(double q, std::string& why);
  /// The wheel at q ± h (h = analysis.continuation.parameter_step ≈ ε^(1/3) relative in p), or nothing when the key is
  /// not a wheel parameter or either value is not valid.
  std::optional<ParameterDirection> direction_at(double q) const;
};

/// A piece of the branch in one section mode.
struct Segment {
  SectionState like;  ///< its mode (z: the start)
  numerics::Branch branch;
  std::string boundary;  ///< at its start: "section mode A -> B" (empty for the first segment)
};

/// The family of maps in q with the discrete section mode of `like` (exact: with the variational ∂P/∂z).
numerics::MapFamily family_in_mode(const std::shared_ptr<MapCache>& cache, const SectionState& like, bool exact);

/// The family of P^k (k = the spec's period) starting and ending in the mode of `like`.
numerics::MapFamily family_for(const std::shared_ptr<MapCache>& cache, const SectionState& like, bool exact);

/// Carries the branch across a change of the section's mode after `from` ended at its last point
/// (mode `to` is where the map arrived). Returns the new segment's start (the new mode's end at
/// the boundary) in `start`, or why the branch ends there.
std::optional<std::string> cross_section_mode(const std::shared_ptr<MapCache>& cache, const Segment& from,
                                              const SectionState& to, bool exact,
                                              const numerics::ContinuationOptions& o, numerics::BranchPoint& start);

}  // namespace flexgait::rimless::detail
