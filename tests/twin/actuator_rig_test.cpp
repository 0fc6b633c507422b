// The stiffness bench's rig in MuJoCo (twin/actuator_rig.hpp): holding a command, the arm settles
// where the gear's spring and the servo's sag carry the load's gravity torque,
// θ_l - cmd = τ_g(θ_l) (1/k + 1/K_p) with τ_g = g (m l + m_arm l/2) cos θ_l.
#include "flexgait/twin/actuator_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace flexgait::twin {
namespace {

TEST(ActuatorRig, ArmSettlesAtTheStaticDeflectionOfGearAndServo) {
  for (double command : {0.0, 0.6}) {
    ActuatorRigParams p;
    ActuatorRig rig(p, command);
    for (int i = 0; i < 5000; ++i) rig.step(command);  // 5 s; the arm's mode (ζ ≈ 1.1, 29 rad/s) settles in < 1 s
    ASSERT_EQ(rig.warnings(), 0) << rig.warnings_text();
    const double w = 2 * std::numbers::pi * p.actuator.bandwidth, kp = p.actuator.rotor_inertia * w * w;
    const double arm_mass = 0.001;  // actuator_rig.cpp's capsule
    const double G = 9.81 * (p.load_mass * p.arm_length + arm_mass * 0.5 * p.arm_length);
    double theta = command;
    for (int k = 0; k < 100; ++k) theta = command + G * std::cos(theta) * (1 / p.actuator.k + 1 / kp);
    // Static: Euler at 1 ms has the exact equilibrium; the residual motion after 5 s is < 1e-9 rad.
    EXPECT_NEAR(rig.link_angle(), theta, 1e-8) << command;
    EXPECT_NEAR(rig.motor().theta_m, command + G * std::cos(theta) / kp, 1e-8) << command;
  }
}

}  // namespace
}  // namespace flexgait::twin
