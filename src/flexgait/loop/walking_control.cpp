#include "flexgait/loop/walking_control.hpp"

#include <algorithm>

namespace flexgait::loop {

compensation::SupportPlan support_plan(const walking::WalkingController& controller, double t) {
  const walking::ControllerStatus& st = controller.status();
  compensation::SupportPlan plan{st.swinging, st.sole, st.zmp_ref, st.pelvis, -1.0, st.motion};
  const auto& steps = controller.plan().steps;
  if ((st.swinging[0] || st.swinging[1]) && st.step >= 0 && st.step < static_cast<int>(steps.size())) {
    const walking::Step& s = steps[static_cast<std::size_t>(st.step)];
    plan.single_support_phase = std::clamp((t - s.t_lift) / (s.t_land - s.t_lift), 0.0, 1.0);
  }
  return plan;
}

humanoid::JointVector WalkingControl::update(const humanoid::SensorReadings& sensors, double t) {
  const humanoid::JointVector desired = controller_.update(sensors, t);
  context_.sensors = controller_.sensors();
  context_.support = support_plan(controller_, t);
  context_.attitude = controller_.attitude();
  context_.sensors_good = controller_.status().sensor_flags == 0;
  return desired;
}

}  // namespace flexgait::loop
