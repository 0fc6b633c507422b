// The compensators as a stage: off passes the command unchanged; compensated feedback adds the
// last deflection estimate θ̂ − θ_enc to the encoders the controller reads, and the stage hands
// back the encoders' own values; the standing context puts both soles where the encoders do.
#include "flexgait/loop/compensation_stage.hpp"

#include <gtest/gtest.h>

#include "flexgait/twin/plant.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::loop {
namespace {

struct Fixture {
  humanoid::RobotParams robot;
  walking::RobotModel model = walking::make_robot_model(robot);
  humanoid::JointVector pose = twin::standing_pose(robot, 0.72);
  humanoid::SensorReadings readings() const {
    humanoid::SensorReadings r;
    r.encoder = pose;
    // the weight on both feet, split evenly (the F/T's force on the foot from the leg: down)
    for (auto& ft : r.ft) ft.force = {0, 0, -0.5 * 9.81 * 40};
    return r;
  }
};

TEST(CompensationStage, OffPassesTheCommandUnchanged) {
  Fixture f;
  compensation::CompensationParams p;
  p.mode = compensation::CompensationMode::kOff;
  CompensationStage stage(f.model, p, 0.004);
  const ControlContext c = CompensationStage::standing_context(f.model, f.readings());
  humanoid::JointVector desired = f.pose;
  desired[4] += 0.01;
  EXPECT_EQ(stage.command(desired, c, 0.0), desired);
  EXPECT_EQ(stage.estimate(), nullptr);
  EXPECT_FALSE(stage.k_estimate().has_value());
}

TEST(CompensationStage, CompensatedFeedbackAddsTheLastDeflectionEstimate) {
  Fixture f;
  compensation::CompensationParams p;
  p.mode = compensation::CompensationMode::kBoth;
  p.compensated_feedback = true;
  CompensationStage stage(f.model, p, 0.004);
  const humanoid::SensorReadings raw = f.readings();
  // Before any estimate the controller reads the encoders themselves.
  EXPECT_EQ(stage.feedback(raw).encoder, raw.encoder);
  ControlContext c = CompensationStage::standing_context(f.model, stage.feedback(raw));
  stage.command(f.pose, c, 0.0);
  ASSERT_NE(stage.estimate(), nullptr);
  EXPECT_EQ(stage.sensors().encoder, raw.encoder);  // the encoders' own values handed back
  const humanoid::SensorReadings fed = stage.feedback(raw);
  double largest = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    // exact up to one rounding of the sum and the difference
    EXPECT_NEAR(fed.encoder[j] - raw.encoder[j], stage.estimate()->newton[j] - raw.encoder[j], 1e-15) << j;
    largest = std::max(largest, std::abs(fed.encoder[j] - raw.encoder[j]));
  }
  EXPECT_GT(largest, 1e-4);  // the standing robot's gears deflect (k = 1000 Nm/rad: milliradians)
}

TEST(CompensationStage, TheStandingContextPutsBothSolesWhereTheEncodersDo) {
  Fixture f;
  humanoid::SensorReadings r = f.readings();
  const double roll = 0.05;
  r.imu.quat = {std::cos(roll / 2), std::sin(roll / 2), 0, 0};
  const ControlContext c = CompensationStage::standing_context(f.model, r);
  EXPECT_FALSE(c.support.swinging[0] || c.support.swinging[1]);
  EXPECT_NEAR(walking::roll_of(c.attitude), roll, 1e-12);
  // The symmetric pose: soles mirror each other about the pelvis's sagittal plane (in the pelvis
  // frame), and the reference ZMP is their midpoint.
  const Eigen::Vector3d l = c.attitude.transpose() * c.support.soles[0].p,
                        rr = c.attitude.transpose() * c.support.soles[1].p;
  EXPECT_NEAR(l.x(), rr.x(), 1e-12);
  EXPECT_NEAR(l.y(), -rr.y(), 1e-12);
  EXPECT_NEAR(l.z(), rr.z(), 1e-12);
  EXPECT_LT(l.z(), -0.5);  // below the pelvis
  EXPECT_NEAR((c.support.zmp_ref - 0.5 * (c.support.soles[0].p + c.support.soles[1].p).head<2>()).norm(), 0, 1e-15);
}

}  // namespace
}  // namespace flexgait::loop
