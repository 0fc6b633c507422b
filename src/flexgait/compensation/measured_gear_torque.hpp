#pragma once
/// \file measured_gear_torque.hpp
/// Each gear's torque from its servo's motor current (docs/guide/compensation.md, "Stiffness identified while
/// walking"; control.k_estimation_torque measured). The motor side of an elastic drive turns its rotor and the gear,
/// J_m θ̈_m = τ_motor − τ_gear (docs/theory/humanoid.md, "The elastic actuator"), so the gear's torque is the
/// current's torque less the rotor's inertia times its acceleration:
///     τ_gear ≈ τ̄_motor,k − J_m (θ_k − 2 θ_{k−1} + θ_{k−2}) / T²
/// with τ̄_motor,k the current's torque averaged over the period and θ the motor-side encoder: the second difference
/// is the period's mean acceleration (exact for a quadratic θ). On the twin the rotor's term is as large as the gear's
/// own torque while walking (10–20 Nm rms on the stance legs' pitch joints), so the current alone is no measure of it.
/// Until two earlier readings exist the acceleration counts as zero. Allocation-free; free of the simulator.
#include "flexgait/robot/joints.hpp"

namespace flexgait::compensation {

class MeasuredGearTorque {
 public:
  /// \param rotor_inertia J_m [kg m^2]; \param period T [s]
  MeasuredGearTorque(double rotor_inertia, double period) : rotor_inertia_(rotor_inertia), period_(period) {}

  /// One control period's readings in; the gears' torque out [Nm].
  const humanoid::JointVector& update(const humanoid::JointVector& motor_torque, const humanoid::JointVector& encoder) {
    const double scale = readings_ >= 2 ? rotor_inertia_ / (period_ * period_) : 0.0;
    for (int j = 0; j < humanoid::kJoints; ++j)
      torque_[j] = motor_torque[j] - scale * (encoder[j] - 2.0 * last_[j] + before_[j]);
    before_ = last_;
    last_ = encoder;
    if (readings_ < 2) ++readings_;
    return torque_;
  }

 private:
  double rotor_inertia_, period_;
  humanoid::JointVector last_{}, before_{}, torque_{};
  int readings_ = 0;
};

}  // namespace flexgait::compensation
