#pragma once
/// \file closed_loop.hpp
/// The humanoid's closed loop (docs/guide/loop.md): the twin (plant, terrain, pushes), its sensors
/// with their faults, a controller (controller.hpp) and the deformation compensators as a stage on
/// its command (compensation_stage.hpp), advanced one control period per `step`. Observers
/// (loggers, scorers, renderers) attach from outside and read each period as a LoopStep; they
/// cannot change the trajectory.
///
/// One period: the plant's readings → the compensators' feedback → controller.update → the
/// compensators' command (and output estimate) → the joint ranges (a loaded robot) →
/// controller.sent → plant.step → the simulation's soundness → observers.
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "flexgait/loop/compensation_stage.hpp"
#include "flexgait/loop/controller.hpp"
#include "flexgait/loop/simulation_failure.hpp"
#include "flexgait/twin/plant.hpp"

namespace flexgait::loop {

/// One control period as observers see it (references valid during the observer's call).
struct LoopStep {
  long k = 0;                                ///< the period's index since reset
  double t = 0;                              ///< its start time [s]
  const humanoid::SensorReadings& readings;  ///< what the controller was given
  const humanoid::SensorReadings& sensors;   ///< as the controller used them (bad values held), encoders' own values
  const humanoid::JointVector& desired;      ///< the controller's output [rad]
  const humanoid::JointVector& command;      ///< sent to the servos [rad]
  const CompensationStage& compensation;     ///< its estimate, torques, stiffness estimates
  const twin::GroundTruth& before;           ///< the state the sensors read
  const twin::GroundTruth& after;            ///< the state at the period's end
  const twin::HumanoidPlant& plant;          ///< the twin after the period (evaluation code only)
  const std::optional<SimulationFailure>& failure;  ///< the simulation failed in this period
};

class LoopObserver {
 public:
  virtual ~LoopObserver() = default;
  virtual void observe(const LoopStep& step) = 0;
  /// Whether it reads the output estimate's one-step and per-joint forms (eq. 12, for comparison; not formed
  /// otherwise, DeformationCompensator::estimate_forms).
  virtual bool reads_estimate_forms() const { return false; }
};

/// The loop's parts that are not the controller.
struct LoopSetup {
  twin::TwinModel twin;                      ///< the twin's MJCF and sole centres
  twin::PlantParams plant;                   ///< plant.* (its true stiffness, sensors, faults, terrain)
  walking::RobotModel model;                 ///< the controller's belief of the robot (compensators, joint ranges)
  compensation::CompensationParams control;  ///< control.*
  StiffnessWindows windows;                  ///< the still stances of the stiffness identification
  bool clamp_to_ranges = false;              ///< clamp commands into the model's joint ranges (a loaded robot)
};

class HumanoidLoop {
 public:
  HumanoidLoop(const LoopSetup& setup, std::shared_ptr<Controller> controller);

  /// Puts the robot in `pose` at rest on the floor (HumanoidPlant::reset); the time restarts at 0.
  void reset(const humanoid::JointVector& pose);
  /// One control period with the controller's command. Returns the simulation's failure, if it
  /// failed in this period; a failed loop refuses further steps (std::logic_error). A non-finite
  /// command is refused before anything moves (std::invalid_argument naming the joint).
  std::optional<SimulationFailure> step();
  /// One control period with these desired angles [rad] in the controller's place (the
  /// compensators apply as configured; the controller is not updated).
  std::optional<SimulationFailure> step(const humanoid::JointVector& desired);

  void attach(LoopObserver& observer) {
    observers_.push_back(&observer);
    if (observer.reads_estimate_forms()) stage_.estimate_forms(true);
  }

  const humanoid::SensorReadings& sensors() const { return plant_.sensors(); }
  /// The twin's true state now: formed when first asked for after a period (a loop that nothing observes
  /// does not pay for it); valid until the next step or reset.
  const twin::GroundTruth& truth() const;
  double time() const { return plant_.time(); }
  long periods() const { return k_; }
  const std::optional<SimulationFailure>& failure() const { return failure_; }
  /// The last command sent [rad].
  const humanoid::JointVector& command() const { return command_; }
  /// Commanded joint angles clamped into their ranges so far (one per joint and period).
  long joint_limit_hits() const { return joint_limit_hits_; }
  /// Desired (link) joint angles outside their ranges so far (one per joint and period; a loaded
  /// robot): the plan asks for a pose the joint's stop holds the link out of.
  long desired_range_hits() const { return desired_range_hits_; }
  twin::HumanoidPlant& plant() { return plant_; }
  const twin::HumanoidPlant& plant() const { return plant_; }
  const CompensationStage& compensation() const { return stage_; }
  const walking::RobotModel& model() const { return model_; }
  Controller& controller() { return *controller_; }

 private:
  std::optional<SimulationFailure> advance(const humanoid::JointVector* desired);

  walking::RobotModel model_;
  std::shared_ptr<Controller> controller_;
  CompensationStage stage_;
  twin::HumanoidPlant plant_;
  bool clamp_ = false;
  std::vector<LoopObserver*> observers_;
  mutable twin::GroundTruth truth_;     ///< the state now, once formed (truth())
  mutable bool truth_current_ = false;  ///< truth_ is the state now
  twin::GroundTruth before_;            ///< the state at the last period's start (for observers)
  humanoid::JointVector command_{};
  long k_ = 0;
  long joint_limit_hits_ = 0;
  long desired_range_hits_ = 0;
  std::optional<SimulationFailure> failure_;
};

}  // namespace flexgait::loop
