#pragma once
/// \file walk_scorer.hpp
/// The walk's evaluation as an observer of the closed loop (loop/closed_loop.hpp): it reads the
/// ground truth and the walking controller's status after every control period, judges falls and
/// lost support (walk_judge.hpp), records the landings, accumulates the scores of WalkMetrics
/// (docs/guide/humanoid.md, "What a walk reports") and logs WalkSample rows. It changes nothing of
/// the trajectory.
#include <functional>
#include <vector>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_judge.hpp"
#include "flexgait/loop/closed_loop.hpp"

namespace flexgait::experiments {

/// The plan's frame against the truth's: the offset between the initial feet (world = plan + offset) [m].
Eigen::Vector2d plan_offset(const twin::GroundTruth& g, const walking::WalkPlan& plan);
/// A step's landing is taken (its sole's pose read) from this long after its touchdown on, once the
/// foot has settled: half the double support [s] (landing_due).
double landing_settle(const WalkRunParams& params);
/// Whether the landing of plan.steps[n] is taken at t [s]: from its touchdown plus `settle` on,
/// once its sole is on the floor (`sole_down`). A foot still in the air then (a push can bounce an
/// early landing off the floor for a moment) is waited for until the next step lifts, the end of
/// the double support in which it takes the load (after the last step: the plan's t_settle), and
/// is taken there as it is (WalkJudge::landing: missed).
bool landing_due(const walking::WalkPlan& plan, std::size_t n, double settle, double t, bool sole_down);

class WalkScorer final : public loop::LoopObserver {
 public:
  /// \param controller the walking controller of the loop (its status and plan are read each period)
  /// \param initial the twin's truth at the start (the plan's frame is found from its feet)
  /// \param pushes the pushes applied (timed); \param record takes each logged sample (else WalkResult::log)
  WalkScorer(const WalkRunParams& params, const walking::WalkingController& controller,
             const twin::GroundTruth& initial, const std::vector<twin::Push>& pushes,
             std::function<void(const WalkSample&)> record);

  void observe(const loop::LoopStep& step) override;
  /// It scores them (summary.json's one-step and per-joint errors, joints.csv).
  bool reads_estimate_forms() const override { return true; }
  /// The walk must end: the robot fell or lost its support.
  bool fell() const { return out_.metrics.fell; }
  /// The walk's result after its last period (judges the end's support when it ran to its end).
  WalkResult finish(const loop::HumanoidLoop& loop);

 private:
  struct Accumulator {  // root mean square and maximum of |value|
    double sum2 = 0, max = 0;
    int n = 0;
    void add(double v);
    double rms() const;
  };
  /// The scores read before the period's step: deformation, estimates, attitude, the push's bound.
  void score_sensing(const loop::LoopStep& step);
  /// The scores of the state after the step: ZMP, COM, margins; the landings; the log.
  void score_motion(const loop::LoopStep& step);
  void log_sample(const loop::LoopStep& step, const Eigen::Vector2d& zmp_true, const Eigen::Vector2d& com_true,
                  double margin);
  void fall(std::optional<FallReason> reason, double t);

  const WalkRunParams& params_;
  const walking::WalkingController& controller_;
  std::function<void(const WalkSample&)> record_;
  WalkJudge judge_;
  WalkResult out_;
  Eigen::Vector2d offset_ = Eigen::Vector2d::Zero();  ///< truth → plan frame
  twin::Push first_push_;                             ///< the capture-point bound is taken for the earliest push
  bool bound_taken_ = false;
  long log_every_ = 1;
  double t_walk0_ = 0, settle_ = 0;
  Accumulator zx_, zy_, zss_, zft_, zbelief_, roll_, pitch_, com_;
  Accumulator deflection_, estimate_error_, one_step_error_, conventional_error_, newton_vs_conventional_,
      per_joint_vs_conventional_, link_error_;
  Accumulator roll_kin_encoder_, roll_kin_estimate_, attitude_error_;
  unsigned flags_since_log_ = 0;
  long newton_calls_ = 0, newton_iterations_ = 0, newton_predicted_ = 0;
  std::size_t next_landing_ = 0;
  std::vector<walking::Pose> support_;
  std::vector<const walking::SolePolygon*> support_shapes_;  ///< support_'s sole polygons
  // this period's values shared by score_sensing and score_motion
  double roll_true_ = 0, pitch_true_ = 0, roll_enc_ = 0, roll_est_ = 0;
};

}  // namespace flexgait::experiments
