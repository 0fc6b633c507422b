#pragma once
/// \file push_recovery.hpp
/// The largest recoverable push (issue 19): bisection on the impulse of a push of fixed duration
/// and direction, each trial a whole run of the twin from the same configuration; beside it the
/// capture-point bound of the same situation (summary.json's capture_point_bound).
#include <Eigen/Dense>

#include "flexgait/experiments/walk_experiment.hpp"

namespace flexgait::experiments {

struct PushRecovery {
  double recovered = 0;  ///< largest impulse recovered (no fall) [N s]
  double fell = 0;       ///< smallest impulse seen to fall [N s] (recovered < fell ≤ recovered + tolerance)
  double bound = 0;      ///< capture-point bound for the push's direction [N s]
  int runs = 0;
};

/// Pushes `base.push.body` at `base.push.time` for `base.push.duration` in the horizontal
/// `direction`, bisecting the impulse on [0, upper] to `tolerance` [N s]. Throws std::invalid_argument
/// if upper itself is recovered (the bracket is wrong).
PushRecovery largest_recoverable_push(WalkRunParams base, const Eigen::Vector2d& direction, double upper,
                                      double tolerance = 1.0);

}  // namespace flexgait::experiments
