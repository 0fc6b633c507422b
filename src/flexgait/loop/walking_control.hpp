#pragma once
/// \file walking_control.hpp
/// The builtin walking controller (walking/walking_controller.hpp: footsteps, preview control,
/// balance, leg IK) in the loop's controller slot, reporting its plan to the compensators.
#include "flexgait/loop/controller.hpp"
#include "flexgait/walking/walking_controller.hpp"

namespace flexgait::loop {

class WalkingControl final : public Controller {
 public:
  explicit WalkingControl(walking::WalkingController controller) : controller_(std::move(controller)) {}

  humanoid::JointVector update(const humanoid::SensorReadings& sensors, double t) override;
  void sent(const humanoid::JointVector& command) override { controller_.sent(command); }
  const ControlContext* context() const override { return &context_; }

  walking::WalkingController& controller() { return controller_; }
  const walking::WalkingController& controller() const { return controller_; }

 private:
  walking::WalkingController controller_;
  ControlContext context_;
};

/// The support the compensators read from the walking controller's last update: its swinging
/// feet, planned soles, reference ZMP, pelvis command, plan's motion, and the single-support
/// phase s ∈ [0, 1] of its current step at t (−1 outside single support).
compensation::SupportPlan support_plan(const walking::WalkingController& controller, double t);

}  // namespace flexgait::loop
