// The plan's joint and pelvis motion (planned_motion.hpp) against what it must be, through the
// model's own forward pass (robot_model_dynamics.hpp): a stance sole does not move, the swing
// sole moves as feet_target says (a fine difference of the plan itself, not of the IK), and the
// model's COM moves as the cart-table's state says; and the central difference converges as h².
#include "flexgait/walking/planned_motion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "flexgait/walking/rotation.hpp"
#include "flexgait/walking/walk_params.hpp"

namespace flexgait::walking {
namespace {

struct Fixture {
  RobotModel model = make_robot_model(humanoid::RobotParams{});
  WalkParams walk;
  WalkPlan plan;
  PlanPoseInputs in;
  Eigen::Matrix2d last_inverse = Eigen::Matrix2d::Identity();  ///< the Jacobian the last `at` used
  Fixture() {
    walk.step_time = 1.0;
    walk.turn = 0.1;  // the heading turns too
    plan = plan_footsteps(walk);
    in.model = &model;
    in.plan = &plan;
    in.swing_height = walk.swing_height;
    in.pelvis_height = walk.pelvis_height;
  }
  /// The plan's motion at t with the COM over the stance sole's inner edge, moving and accelerating,
  /// from a guess 3 mm off the converged pose `centre` (as the controller's commanded pelvis is
  /// off the plan's by the balance's foot lifts and rotations).
  PlannedMotion at(double t, double h, RobotModelData& data, Pose& centre, const Eigen::Matrix2d* stale = nullptr) {
    const FeetTarget feet = feet_target(plan, walk.swing_height, t);
    const Eigen::Vector2d mid = 0.5 * (feet.sole[0].p + feet.sole[1].p).head<2>();
    in.cart = {Eigen::Vector3d(mid.x() + 0.01, 0.25, 0.6), Eigen::Vector3d(mid.y() - 0.02, -0.15, 0.9)};
    in.tilt = rot_y(0.02) * rot_x(-0.01);
    centre = Pose{Vector3d(mid.x(), mid.y(), walk.pelvis_height), rot_z(heading_of(feet.sole)) * in.tilt};
    humanoid::JointVector q{};
    std::array<IkStatus, 2> ik{};
    solve_com_pose(model, data, Eigen::Vector2d(in.cart[0](0), in.cart[1](0)), feet.sole, centre, q, ik, 30);
    Pose guess = centre;
    guess.p += Vector3d(0.003, -0.002, 0.0);
    Eigen::Matrix2d inverse = stale ? *stale : Eigen::Matrix2d::Identity();
    const PlannedMotion m = planned_motion(in, t, h, guess, data, inverse, stale == nullptr);
    last_inverse = inverse;
    // (the centre's kinematics again: planned_motion used `data`)
    forward_kinematics(model, data, centre, q);
    return m;
  }
};

TEST(PlannedMotion, StanceSoleRestsSwingSoleFollowsThePlanComFollowsTheCart) {
  Fixture f;
  const Step& s = f.plan.steps[2];
  for (double u : {0.0, 0.3, 0.55, 0.9}) {  // (u = 0: double support)
    const double t = u == 0.0 ? 0.5 * (s.t_begin + s.t_lift) : s.t_lift + u * (s.t_land - s.t_lift);
    RobotModelData data;
    Pose centre;
    const PlannedMotion m = f.at(t, 0.01, data, centre);
    ASSERT_TRUE(m.valid);
    RobotDynamicsData dyn;
    inverse_dynamics(f.model, data, m.pelvis, m.velocity, m.acceleration, dyn, {}, 0.0);
    for (int side = 0; side < 2; ++side) {
      const int foot = f.model.foot[side];
      const Vector3d sole = f.model.sole_offset[side];
      const Vector3d r = data.frame[foot].R * sole;
      const Vector3d& w = dyn.angular_velocity[foot];
      const Vector3d& alpha = dyn.angular_acceleration[foot];
      const Vector3d v = dyn.velocity[foot] + w.cross(r);
      const Vector3d a = dyn.acceleration[foot] + alpha.cross(r) + w.cross(w.cross(r));
      Vector3d v_plan = Vector3d::Zero(), a_plan = Vector3d::Zero();
      if (u > 0 && side == s.swing) {
        // A fine central difference of feet_target itself (step 1e-4 s).
        const double e = 1e-4;
        const Vector3d p0 = feet_target(f.plan, f.walk.swing_height, t - e).sole[side].p;
        const Vector3d p1 = feet_target(f.plan, f.walk.swing_height, t).sole[side].p;
        const Vector3d p2 = feet_target(f.plan, f.walk.swing_height, t + e).sole[side].p;
        v_plan = (p2 - p0) / (2 * e);
        a_plan = (p2 - 2 * p1 + p0) / (e * e);
        EXPECT_GT(v_plan.norm() + a_plan.norm(), 0.05);
      }
      // Truncation h²/6 x⃛ of the 0.01 s difference: < 1e-3 of the swing's velocity and
      // acceleration (~0.5 m/s, ~5 m/s²); the fine difference's own rounding ~1e-16/1e-8 m/s².
      EXPECT_LT((v - v_plan).norm(), 5e-4) << "side " << side << " u " << u;
      EXPECT_LT((a - a_plan).norm(), 2e-2) << "side " << side << " u " << u;
      if (u == 0 || side != s.swing) {
        EXPECT_LT(w.norm(), 2e-4) << side;
        EXPECT_LT(alpha.norm(), 2e-2) << side;
      }
    }
    // The model's COM: its velocity and acceleration are the cart's (horizontal), since
    // Σ m_i a_ci = M c̈ is the pelvis's net force with gravity out and no feet given.
    Vector3d momentum = Vector3d::Zero();
    for (int i = 0; i < kBodies; ++i) {
      const Vector3d c = data.frame[i].R * f.model.bodies[i].com;
      momentum += f.model.bodies[i].mass * (dyn.velocity[i] + dyn.angular_velocity[i].cross(c));
    }
    const Vector3d c_dot = momentum / f.model.total_mass;
    const Vector3d c_ddot = dyn.joint_wrench[0].force / f.model.total_mass;
    EXPECT_NEAR(c_dot.x(), f.in.cart[0](1), 2e-4);
    EXPECT_NEAR(c_dot.y(), f.in.cart[1](1), 2e-4);
    EXPECT_NEAR(c_ddot.x(), f.in.cart[0](2), 2e-2);
    EXPECT_NEAR(c_ddot.y(), f.in.cart[1](2), 2e-2);
  }
}

TEST(PlannedMotion, AJacobianFromATenthOfASecondBeforeServesAsWell) {
  // (the controller takes it again every 0.1 s)
  Fixture f;
  const Step& s = f.plan.steps[2];
  for (double u : {0.2, 0.5, 0.8}) {
    const double t = s.t_lift + u * (s.t_land - s.t_lift);
    RobotModelData data;
    Pose centre;
    f.at(t - 0.1, 0.01, data, centre);
    const Eigen::Matrix2d old = f.last_inverse;
    const PlannedMotion fresh = f.at(t, 0.01, data, centre);
    const Eigen::Matrix2d now = f.last_inverse;
    const PlannedMotion kept = f.at(t, 0.01, data, centre, &old);
    double largest = 0, difference = 0;
    for (int j = 0; j < humanoid::kJoints; ++j) {
      largest = std::max(largest, std::abs(fresh.acceleration[j]));
      difference = std::max(difference, std::abs(kept.acceleration[j] - fresh.acceleration[j]));
    }
    EXPECT_GT((old - now).norm(), 1e-6);  // a different Jacobian
    EXPECT_LT(difference, 1e-3 * largest) << u;
  }
}

TEST(PlannedMotion, CentralDifferenceConvergesAsHSquared) {
  Fixture f;
  const Step& s = f.plan.steps[3];
  const double t = s.t_lift + 0.4 * (s.t_land - s.t_lift);
  RobotModelData data;
  Pose centre;
  const PlannedMotion coarse = f.at(t, 0.02, data, centre), fine = f.at(t, 0.01, data, centre),
                      finest = f.at(t, 0.005, data, centre);
  double e_coarse = 0, e_fine = 0, largest = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    e_coarse = std::max(e_coarse, std::abs(coarse.acceleration[j] - finest.acceleration[j]));
    e_fine = std::max(e_fine, std::abs(fine.acceleration[j] - finest.acceleration[j]));
    largest = std::max(largest, std::abs(finest.acceleration[j]));
  }
  EXPECT_GT(largest, 1.0);            // a swing: accelerations of rad/s²
  EXPECT_LT(e_fine, 1e-3 * largest);  // h = 0.01 s (the controller's): within 0.1 %
  // h² convergence: (0.02² − 0.005²) / (0.01² − 0.005²) = 5; allow 3.5-6.5 (fixed-point round-off)
  EXPECT_GT(e_coarse / e_fine, 3.5);
  EXPECT_LT(e_coarse / e_fine, 6.5);
}

}  // namespace
}  // namespace flexgait::walking
