#include "flexgait/loop/closed_loop.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace flexgait::loop {

HumanoidLoop::HumanoidLoop(const LoopSetup& setup, std::shared_ptr<Controller> controller)
    : model_(setup.model),
      controller_(std::move(controller)),
      stage_(setup.model, setup.control, setup.plant.control_period, setup.windows),
      plant_(setup.twin, setup.plant),
      clamp_(setup.clamp_to_ranges) {
  if (!controller_) throw std::invalid_argument("HumanoidLoop: no controller");
}

void HumanoidLoop::reset(const humanoid::JointVector& pose) {
  plant_.reset(pose);
  truth_current_ = false;
  command_ = pose;
  k_ = 0;
  failure_.reset();
}

std::optional<SimulationFailure> HumanoidLoop::step() {
  return advance(nullptr);
}

std::optional<SimulationFailure> HumanoidLoop::step(const humanoid::JointVector& desired) {
  return advance(&desired);
}

std::optional<SimulationFailure> HumanoidLoop::advance(const humanoid::JointVector* given) {
  if (failure_)
    throw std::logic_error(
        fmt::format("the simulation failed at t = {:.6g} s ({}); reset the loop before stepping again", time(),
                    name_of(*failure_)));
  const double t = static_cast<double>(k_) * plant_.params().control_period;
  const humanoid::SensorReadings readings = stage_.feedback(plant_.sensors());
  humanoid::JointVector desired;
  const ControlContext* context = nullptr;
  if (given) {
    desired = *given;
  } else {
    desired = controller_->update(readings, t);
    context = controller_->context();
  }
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (!std::isfinite(desired[j]))
      throw std::invalid_argument(fmt::format("{} for joint {} ({}) is {}; allowed: a finite angle [rad]",
                                              given ? "the given command" : "the controller's command", j,
                                              humanoid::kJointNames[static_cast<std::size_t>(j)], desired[j]));
  ControlContext standing;
  if (!context) {
    standing = CompensationStage::standing_context(model_, readings);
    context = &standing;
  }
  command_ = stage_.command(desired, *context, t);
  if (clamp_) {  // never silent
    desired_range_hits_ += walking::outside_ranges(model_, desired);
    joint_limit_hits_ += walking::clamp_to_ranges(model_, command_);
  }
  if (!given) controller_->sent(command_);

  // The ground truth is formed for the observers (and whoever asks for truth()), not for the loop itself.
  const bool observed = !observers_.empty();
  if (observed) before_ = truth();
  plant_.step(command_);
  truth_current_ = false;
  const long k = k_++;
  // MuJoCo's warnings (it has already reset an unstable state or dropped contacts), or a state that
  // is no longer finite, end the loop.
  if (plant_.warning_count() > 0)
    failure_ = SimulationFailure::kMuJoCoWarning;
  else if (!plant_.state_finite())
    failure_ = SimulationFailure::kDiverged;
  if (observed) {
    const LoopStep record{k,      t,       readings, stage_.sensors(), desired, command_,
                          stage_, before_, truth(),  plant_,           failure_};
    for (LoopObserver* observer : observers_) observer->observe(record);
  }
  return failure_;
}

const twin::GroundTruth& HumanoidLoop::truth() const {
  if (!truth_current_) {
    truth_ = plant_.truth();
    truth_current_ = true;
  }
  return truth_;
}

}  // namespace flexgait::loop
