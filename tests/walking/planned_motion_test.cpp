// The plan's joint and pelvis motion (planned_motion.hpp) against what it must be, through the
// model's own forward pass (robot_model_dynamics.hpp): a stance sole does not move, the swing
// sole moves as feet_target says (a fine difference of the plan itself, not of the IK), and the
// model's COM moves as the cart-table's state says; and it is the derivative of the plan's pose
// (central differences of the pose solved at t ± h, extrapolated).
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
  PlannedMotion at(double t, RobotModelData& data, Pose& centre, const Eigen::Matrix2d* stale = nullptr,
                   const Vector3d& off = Vector3d(0.003, -0.002, 0.0)) {
    const FeetTarget feet = feet_target(plan, walk.swing_height, t);
    const Eigen::Vector2d mid = 0.5 * (feet.sole[0].p + feet.sole[1].p).head<2>();
    in.cart = {Eigen::Vector3d(mid.x() + 0.01, 0.25, 0.6), Eigen::Vector3d(mid.y() - 0.02, -0.15, 0.9)};
    in.tilt = rot_y(0.02) * rot_x(-0.01);
    centre = Pose{Vector3d(mid.x(), mid.y(), walk.pelvis_height), rot_z(heading_of(feet.sole)) * in.tilt};
    humanoid::JointVector q{};
    std::array<IkStatus, 2> ik{};
    solve_com_pose(model, data, Eigen::Vector2d(in.cart[0](0), in.cart[1](0)), feet.sole, centre, q, ik, 30);
    Pose guess = centre;
    guess.p += off;
    Eigen::Matrix2d inverse = stale ? *stale : Eigen::Matrix2d::Identity();
    const PlannedMotion m = planned_motion(in, t, guess, data, inverse, stale == nullptr);
    last_inverse = inverse;
    // (the centre's kinematics again: planned_motion used `data`)
    forward_kinematics(model, data, centre, q);
    return m;
  }
  /// The model's COM (xy) with the pelvis at `pelvis` and the soles where the plan has them at t (the legs' IK).
  Eigen::Vector2d com_with_pelvis(const Pose& pelvis, double t, RobotModelData& data) const {
    Pose p = pelvis;
    humanoid::JointVector q{};
    std::array<IkStatus, 2> ik{};
    solve_com_pose(model, data, Eigen::Vector2d::Zero(), feet_target(plan, walk.swing_height, t).sole, p, q, ik, 1);
    return center_of_mass(model, data).head<2>();
  }
};

/// The time at phase u of step s's swing (u = 0: the middle of its double support).
double phase_time(const Step& s, double u) {
  return u == 0.0 ? 0.5 * (s.t_begin + s.t_lift) : s.t_lift + u * (s.t_land - s.t_lift);
}

TEST(PlannedMotion, StanceSoleRestsSwingSoleFollowsThePlanComFollowsTheCart) {
  Fixture f;
  const Step& s = f.plan.steps[2];
  for (double u : {0.0, 0.3, 0.55, 0.9}) {  // (u = 0: double support)
    const double t = phase_time(s, u);
    RobotModelData data;
    Pose centre;
    const PlannedMotion m = f.at(t, data, centre);
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
      // The fine difference's truncation e²/6 x⃛ (≲ 1e3 m/s³: 1e-5 m/s) and rounding 1e-16 / e² (1e-8 m/s²);
      // the IK's exact derivative otherwise, to rounding.
      EXPECT_LT((v - v_plan).norm(), 1e-5) << "side " << side << " u " << u;
      EXPECT_LT((a - a_plan).norm(), 1e-4) << "side " << side << " u " << u;
      if (u == 0 || side != s.swing) {  // (rounding: the leg's solve, its Jacobian's condition ~1e3 times ε)
        EXPECT_LT(w.norm(), 1e-10) << side;
        EXPECT_LT(alpha.norm(), 1e-9) << side;
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
    // (exact but for rounding: the COM's rates are solved for)
    EXPECT_NEAR(c_dot.x(), f.in.cart[0](1), 1e-10);
    EXPECT_NEAR(c_dot.y(), f.in.cart[1](1), 1e-10);
    EXPECT_NEAR(c_ddot.x(), f.in.cart[0](2), 1e-9);
    EXPECT_NEAR(c_ddot.y(), f.in.cart[1](2), 1e-9);
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
    f.at(t - 0.1, data, centre);
    const Eigen::Matrix2d old = f.last_inverse;
    const PlannedMotion fresh = f.at(t, data, centre);
    const Eigen::Matrix2d now = f.last_inverse;
    const PlannedMotion kept = f.at(t, data, centre, &old);
    double largest = 0, difference = 0;
    for (int j = 0; j < humanoid::kJoints; ++j) {
      largest = std::max(largest, std::abs(fresh.acceleration[j]));
      difference = std::max(difference, std::abs(kept.acceleration[j] - fresh.acceleration[j]));
    }
    EXPECT_GT((old - now).norm(), 1e-6);  // a different Jacobian
    EXPECT_LT(difference, 1e-3 * largest) << u;
  }
}

TEST(PlannedMotion, PutsTheComWithinToleranceAndLeavesThePosesExactComJacobians) {
  // The pose it found puts the model's COM over the cart's c (kPlanComTolerance), and the inverse it leaves is
  // (∂c/∂p)⁻¹ at that pose: central differences of the COM per pelvis move with the soles held (step 1e-6 m:
  // truncation ~1e-12, rounding ~1e-16/1e-6 = 1e-10 relative) times it give I to 1e-8. Its ∂c/∂φ likewise: the
  // pelvis turned by ±1e-6 rad about each world axis, its origin and the soles held (entries ~0.1 m/rad, to 1e-8).
  Fixture f;
  const Step& s = f.plan.steps[2];
  for (double u : {0.0, 0.4, 0.8}) {
    const double t = phase_time(s, u);
    RobotModelData data;
    Pose centre;
    const PlannedMotion m = f.at(t, data, centre);
    ASSERT_TRUE(m.valid);
    const FeetTarget feet = feet_target(f.plan, f.walk.swing_height, t);
    const Pose pose{m.pelvis_position, rot_z(heading_of(feet.sole)) * f.in.tilt};
    EXPECT_EQ(pose.R, m.pelvis_attitude);
    auto com_at = [&](const Pose& pelvis) { return f.com_with_pelvis(pelvis, t, data); };
    const Eigen::Vector2d target(f.in.cart[0](0), f.in.cart[1](0));
    EXPECT_LE((com_at(pose) - target).lpNorm<Eigen::Infinity>(), kPlanComTolerance) << u;
    Eigen::Matrix2d J;
    const double h = 1e-6;
    for (int axis = 0; axis < 2; ++axis) {
      Pose plus = pose, minus = pose;
      plus.p(axis) += h;
      minus.p(axis) -= h;
      J.col(axis) = (com_at(plus) - com_at(minus)) / (2 * h);
    }
    EXPECT_LT((f.last_inverse * J - Eigen::Matrix2d::Identity()).norm(), 1e-8) << u;
    Eigen::Matrix<double, 2, 3> D;
    for (int k = 0; k < 3; ++k) {
      const Pose plus{pose.p, Matrix3d(Eigen::AngleAxisd(h, Vector3d::Unit(k))) * pose.R};
      const Pose minus{pose.p, Matrix3d(Eigen::AngleAxisd(-h, Vector3d::Unit(k))) * pose.R};
      D.col(k) = (com_at(plus) - com_at(minus)) / (2 * h);
    }
    EXPECT_GT(D.norm(), 0.01) << u;
    EXPECT_LT((m.com_per_rotation - D).lpNorm<Eigen::Infinity>(), 1e-8) << u;
  }
}

TEST(PlannedMotion, IsTheDerivativeOfThePlansPose) {
  // The plan's pose at t + s (planned_motion.hpp): the soles of feet_target(t + s), the pelvis turned to their
  // heading and at its height over the floor, its xy putting the COM at c + s ċ + s²/2 c̈ (30 rounds of the IK and
  // the COM shift: converged to rounding). Central differences of step h and h/2, Richardson-extrapolated: error
  // O(h⁴) q⁽⁶⁾ (≲ 1e-10 at h = 4 ms) and rounding ~1e-15 / (h/2)² (1e-9 rad/s²); the motion agrees to 1e-7 of
  // the largest joint acceleration, on a turning walk in mid swing and in double support.
  Fixture f;
  for (const double u : {-0.5, 0.35, 0.8}) {
    const Step& s = f.plan.steps[3];
    const double t = u < 0 ? 0.5 * (s.t_begin + s.t_lift) : s.t_lift + u * (s.t_land - s.t_lift);
    RobotModelData data;
    Pose centre;
    const PlannedMotion m = f.at(t, data, centre, nullptr, Vector3d::Zero());  // (from the converged pose)
    auto pose = [&](double ds, humanoid::JointVector& q, double& heading) {
      const FeetTarget feet = feet_target(f.plan, f.walk.swing_height, t + ds);
      heading = heading_of(feet.sole);
      Pose p{centre.p, rot_z(heading) * f.in.tilt};
      p.p.z() = f.walk.pelvis_height + feet.floor_z;
      const Eigen::Vector2d c(f.in.cart[0](0) + ds * f.in.cart[0](1) + 0.5 * ds * ds * f.in.cart[0](2),
                              f.in.cart[1](0) + ds * f.in.cart[1](1) + 0.5 * ds * ds * f.in.cart[1](2));
      std::array<IkStatus, 2> ik{};
      RobotModelData scratch;
      solve_com_pose(f.model, scratch, c, feet.sole, p, q, ik, 30);
      return p;
    };
    struct Rates {
      std::array<double, humanoid::kJoints + 4> d1, d2;  // the joints, then the pelvis's x, y, z and heading
    };
    auto differences = [&](double h) {
      std::array<humanoid::JointVector, 3> q{};
      std::array<Pose, 3> p;
      std::array<double, 3> heading{};
      for (int i = 0; i < 3; ++i) p[i] = pose((i - 1) * h, q[i], heading[i]);
      Rates r{};
      for (int j = 0; j < humanoid::kJoints + 4; ++j) {
        auto x = [&](int i) {
          if (j < humanoid::kJoints) return q[i][j];
          if (j < humanoid::kJoints + 3) return p[i].p(j - humanoid::kJoints);
          return heading[i];  // (no wrap near this walk's headings)
        };
        r.d1[j] = (x(2) - x(0)) / (2 * h);
        r.d2[j] = (x(2) - 2 * x(1) + x(0)) / (h * h);
      }
      return r;
    };
    const double h = 4e-3;
    const Rates coarse = differences(h), fine = differences(h / 2);
    double largest = 0;
    for (int j = 0; j < humanoid::kJoints; ++j) largest = std::max(largest, std::abs(m.acceleration[j]));
    EXPECT_GT(largest, 0.1) << u;
    for (int j = 0; j < humanoid::kJoints + 4; ++j) {
      const double v = (4 * fine.d1[j] - coarse.d1[j]) / 3, a = (4 * fine.d2[j] - coarse.d2[j]) / 3;
      const double mv = j < humanoid::kJoints       ? m.velocity[j]
                        : j < humanoid::kJoints + 3 ? m.pelvis.velocity(j - humanoid::kJoints)
                                                    : m.pelvis.angular_velocity.z();
      const double ma = j < humanoid::kJoints       ? m.acceleration[j]
                        : j < humanoid::kJoints + 3 ? m.pelvis.acceleration(j - humanoid::kJoints)
                                                    : m.pelvis.angular_acceleration.z();
      EXPECT_NEAR(mv, v, 1e-7 * largest) << "u " << u << " coordinate " << j;
      EXPECT_NEAR(ma, a, 1e-7 * largest) << "u " << u << " coordinate " << j;
    }
  }
}

TEST(PlannedMotion, CarriedPelvisMissesBySecondOrderInWhatTheMotionDoesNotHold) {
  // One control period (8 ms) after a plan pose the cart is where its state said (c + ċT + c̈T²/2), and the balance
  // has shifted the COM by 1e-5 m and tilted the pelvis by 1e-4 rad in roll and pitch, which the motion does not
  // hold: its carry alone misses the pose's exact pelvis (30 rounds of the IK and the COM shift) by about the tilt
  // times the COM's lever, ~1e-5 m. carried_pelvis's first-order step leaves the second order: the changes' squares
  // (1e-8 rad² times ~0.1 m) and the motion's third (T³/6 times the pelvis's jerk: with no change at all the carry
  // misses by 1.1e-7 m in this turning walk's mid swing, 6e-9 m in double support).
  Fixture f;
  const Step& s = f.plan.steps[2];
  const double T = 0.008;
  for (double u : {0.0, 0.4, 0.8}) {
    const double t = phase_time(s, u);
    RobotModelData data;
    Pose centre;
    Eigen::Matrix2d inverse = Eigen::Matrix2d::Identity();
    f.at(t, data, centre);  // (the Jacobian's inverse for the exact start below)
    inverse = f.last_inverse;
    const PlannedMotion m = planned_motion(f.in, t, centre, data, inverse, false);
    ASSERT_TRUE(m.valid);
    const Eigen::Vector2d shift(1e-5, -1e-5);
    const Matrix3d tilt = rot_y(0.02 + 1e-4) * rot_x(-0.01 - 1e-4);
    const FeetTarget feet = feet_target(f.plan, f.walk.swing_height, t + T);
    const Matrix3d attitude = rot_z(heading_of(feet.sole)) * tilt;
    Eigen::Vector2d target;
    for (int axis = 0; axis < 2; ++axis)
      target(axis) = f.in.cart[axis](0) + T * f.in.cart[axis](1) + 0.5 * T * T * f.in.cart[axis](2) + shift(axis);
    Pose exact{m.pelvis_position, attitude};
    exact.p.z() = f.walk.pelvis_height + feet.floor_z;
    humanoid::JointVector q{};
    std::array<IkStatus, 2> ik{};
    solve_com_pose(f.model, data, target, feet.sole, exact, q, ik, 30);
    const Vector3d carried = carried_pelvis(m, T, target, attitude, inverse);
    const Vector3d motion_alone = m.pelvis_position + T * m.pelvis.velocity + 0.5 * T * T * m.pelvis.acceleration;
    const double miss = (carried - exact.p).head<2>().lpNorm<Eigen::Infinity>();
    const double alone = (motion_alone - exact.p).head<2>().lpNorm<Eigen::Infinity>();
    EXPECT_GT(alone, 5e-6) << u;
    EXPECT_LT(miss, 2e-7) << u;
    EXPECT_LT(miss, 1e-2 * alone) << u;
    RecordProperty("miss_" + std::to_string(static_cast<int>(10 * u)), std::to_string(miss));
  }
}

}  // namespace
}  // namespace flexgait::walking
