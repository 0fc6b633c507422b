// The elastic gear actuator's laws (twin/elastic_actuator.hpp, spec humanoid.md "The elastic
// actuator (plant)"): the dead band, the gear torque, the encoder's quantisation, and the servo's
// steady state against a constant link torque (the sag τ/K_p without integral action, none with it).
#include "flexgait/twin/elastic_actuator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace flexgait::twin {
namespace {

TEST(ElasticActuator, DeadBandIsCentredAndOfTotalWidthB) {
  ActuatorParams p;
  p.backlash = 0.02;
  EXPECT_EQ(gear_deflection(p, 0.309, 0.30), 0.0);  // within b/2 = 0.01
  EXPECT_EQ(gear_deflection(p, 0.291, 0.30), 0.0);
  EXPECT_NEAR(gear_deflection(p, 0.35, 0.30), 0.04, 1e-15);  // beyond b/2 by 0.04
  EXPECT_NEAR(gear_deflection(p, 0.25, 0.30), -0.04, 1e-15);
  p.backlash = 0.0;
  EXPECT_EQ(gear_deflection(p, 0.35, 0.30), 0.35 - 0.30);
}

TEST(ElasticActuator, GearTorqueIsSpringOnTheDeflectionPlusDamper) {
  ActuatorParams p;
  p.backlash = 0.01;
  const ActuatorState s{0.1, 2.0, 0.0};
  EXPECT_NEAR(gear_torque(p, s, 0.05, 0.5), p.k * (0.05 - 0.005) + p.d * (2.0 - 0.5), 1e-12);
}

TEST(ElasticActuator, EncoderReadsTheNearestStep) {
  const ActuatorParams p;
  const double q = 2 * std::numbers::pi / p.encoder_steps;
  for (double theta : {0.0, 1e-7, 0.123456789, -0.7, 3.0}) {
    const double r = encoder_reading(p, theta);
    EXPECT_LE(std::abs(r - theta), 0.5 * q * (1 + 1e-12)) << theta;
    EXPECT_NEAR(r / q, std::round(r / q), 1e-6) << theta;  // a whole number of steps
  }
  EXPECT_EQ(encoder_reading(p, 0.4 * q), 0.0);
}

// A link held at θ_l = 0 with the motor commanded to 0.05: the motor settles where the servo's
// K_p e balances the gear's torque k (θ_m - θ_l): θ_m = K_p cmd / (K_p + k). With integral action
// the error goes to 0.
TEST(ElasticActuator, ServoSettlesWithItsSagAndIntegralActionRemovesIt) {
  ActuatorParams p;
  const double w = 2 * std::numbers::pi * p.bandwidth, kp = p.rotor_inertia * w * w;
  const double cmd = 0.05, dt = 1e-4;
  ActuatorState s;
  for (int i = 0; i < 50000; ++i) step_motor(p, s, cmd, 0.0, 0.0, dt);
  // 5 s at dt = 1e-4 s: the critically damped servo (poles near ω = 188 rad/s) has settled to
  // far below 1e-12 rad; semi-implicit Euler has the exact fixed point.
  EXPECT_NEAR(s.theta_m, kp * cmd / (kp + p.k), 1e-12);
  EXPECT_NEAR(s.omega_m, 0.0, 1e-10);
  p.integral_time = 0.05;
  ActuatorState si;
  for (int i = 0; i < 200000; ++i) step_motor(p, si, cmd, 0.0, 0.0, dt);
  // 20 s, 400 integral times: the sag τ/K_p ≈ 1.7e-3 rad is gone to 1e-9.
  EXPECT_NEAR(si.theta_m, cmd, 1e-9);
}

TEST(ElasticActuator, SaturatedServoDoesNotWindUp) {
  ActuatorParams p;
  p.integral_time = 0.05;
  p.torque_limit = 1.0;  // far below K_p · 1 rad
  ActuatorState s;
  step_motor(p, s, 1.0, 0.0, 0.0, 1e-3);
  EXPECT_EQ(s.integral, 0.0);
  // The motor accelerates at most by the limit: ω ≤ dt · limit / J_m.
  EXPECT_LE(s.omega_m, 1e-3 * p.torque_limit / p.rotor_inertia * (1 + 1e-12));
}

}  // namespace
}  // namespace flexgait::twin
