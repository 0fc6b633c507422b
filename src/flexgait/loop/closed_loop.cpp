#include "flexgait/loop/closed_loop.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace flexgait::loop {
namespace {

bool finite_truth(const twin::GroundTruth& g) {
  auto finite = [](const auto& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
  };
  return finite(g.link_angle) && finite(g.link_velocity) && finite(g.motor_angle) && finite(g.pelvis_pos) &&
         finite(g.pelvis_quat) && finite(g.com);
}

}  // namespace

HumanoidLoop::HumanoidLoop(const LoopSetup& setup, std::shared_ptr<Controller> controller)
    : model_(setup.model),
      controller_(std::move(controller)),
      stage_(setup.model, setup.control, setup.plant.control_period, setup.windows),
      plant_(setup.twin, setup.plant),
      clamp_(setup.clamp_to_ranges) {
  if (!controller_) throw std::invalid_argument("HumanoidLoop: no controller");
  truth_ = plant_.truth();
}

void HumanoidLoop::reset(const humanoid::JointVector& pose) {
  plant_.reset(pose);
  truth_ = plant_.truth();
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
        fmt::format("the simulation failed at t = {:.6g} s ({}); reset the loop before stepping again", truth_.t,
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

  std::swap(before_, truth_);
  plant_.step(command_);
  truth_ = plant_.truth();
  const LoopStep record{k_,     t,       readings, stage_.sensors(), desired, command_,
                        stage_, before_, truth_,   plant_,           failure_};
  ++k_;
  // MuJoCo's warnings (it has already reset an unstable state or dropped contacts), or a state that
  // is no longer finite, end the loop.
  if (truth_.warnings > 0)
    failure_ = SimulationFailure::kMuJoCoWarning;
  else if (!finite_truth(truth_))
    failure_ = SimulationFailure::kDiverged;
  for (LoopObserver* observer : observers_) observer->observe(record);
  return failure_;
}

}  // namespace flexgait::loop
