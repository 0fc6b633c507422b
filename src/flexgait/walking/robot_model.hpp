#pragma once
/// \file robot_model.hpp
/// The controller's own rigid-body model of the robot (no simulator inside): the kinematic tree
/// of the pelvis, the waist and the two legs with the links' masses at their centres — from
/// RobotParams (the builtin robot, THORMANG3's inertials: builtin_inertials.hpp) or from a loaded description
/// (docs/guide/robot.md: each
/// link the file's bodies it moves, lumped with their inertias; the rest lumped into the trunk). It gives the
/// whole-body centre of mass, each leg's sole Jacobian and the leg links' own gravity torque — what the COM planner and
/// the deformation model (spec eqs. 4-6 and the full form) need. Model (immutable) and Data (frames, scratch) apart; no
/// allocation after construction.
#include <array>
#include <string>

#include "flexgait/robot/joints.hpp"
#include "flexgait/robot/robot_description.hpp"
#include "flexgait/robot/robot_params.hpp"
#include "flexgait/walking/leg_kinematics.hpp"
#include "flexgait/walking/sole_polygon.hpp"

namespace flexgait::walking {

inline constexpr int kBodies =
    16;  ///< pelvis, chest, 2 × (hip yaw, hip roll, thigh, shank, ankle pitch, ankle roll, foot)
inline constexpr int kFirstLegBody = 2;  ///< the left hip yaw body; the legs' bodies follow

/// Every body frame is parallel to the pelvis frame at zero joint angles; a body's origin is its
/// joint's anchor (a point of the joint axis).
struct RobotModel {
  struct Body {
    int parent = -1;                      ///< index of the parent body (−1: the pelvis)
    int joint = -1;                       ///< actuated joint (humanoid::Joint) between parent and body, −1: rigid
    Vector3d axis = Vector3d::Zero();     ///< unit joint axis in the body frame
    Vector3d offset = Vector3d::Zero();   ///< body origin in the parent frame at zero angle [m]
    double mass = 0;                      ///< [kg]
    Vector3d com = Vector3d::Zero();      ///< centre of mass in the body frame [m]
    Matrix3d inertia = Matrix3d::Zero();  ///< about the centre of mass, body frame [kg m^2]
    /// k where `axis` is e_k exactly (the builtin's joints, most loaded legs'; index_joint_axes), −1 otherwise: the
    /// joint then turns two of the frame's columns only and its world axis is the frame's column k.
    int axis_index = -1;
  };
  std::array<Body, kBodies> bodies;            ///< parents before children
  std::array<int, 2> foot{};                   ///< foot body of each leg
  std::array<LegGeometry, 2> leg;              ///< per side
  double total_mass = 0;                       ///< [kg]
  double gravity = humanoid::kDefaultGravity;  ///< along −z, the description's [m/s^2]
  double sole_length = 0, sole_width = 0;      ///< the sole's bounding rectangle [m]
  /// Each sole's polygon in its sole frame (about sole_offset): the convex hull of a loaded foot's
  /// contact geoms, else (the builtin, a sole named or sized by the mapping) the rectangle.
  std::array<SolePolygon, 2> sole_polygon;
  std::array<Vector3d, 2> sole_offset{};  ///< sole centre in the foot frame [m]
  /// The sole's orientation in the foot link's frame: a loaded foot body turned from the root at
  /// zero angles (its printed tilt below kMaxFootTilt, or a frame of its own, humanoid::Sole::quat);
  /// identity unless sole_tilted.
  std::array<Matrix3d, 2> sole_rotation{Matrix3d::Identity(), Matrix3d::Identity()};
  std::array<bool, 2> sole_tilted{false, false};
  /// The sole centre from the F/T sensor, in the sole's frame [m] (the F/T wrench's lever arm): the
  /// sole_offset unless the sole has a frame of its own.
  std::array<Vector3d, 2> ft_to_sole{};
  /// Each joint's range [rad] (a loaded description's limited joints; ±∞ otherwise, and for the builtin).
  std::array<std::array<double, 2>, humanoid::kJoints> range = [] {
    std::array<std::array<double, 2>, humanoid::kJoints> r;
    r.fill({-LegGeometry::kNoLimit, LegGeometry::kNoLimit});
    return r;
  }();
};

/// The largest tilt of a loaded foot's frame from the root's at zero angles that is taken as a
/// printed level foot and modelled (6 printed digits of a quaternion: ~1e-6 rad) [rad].
inline constexpr double kMaxFootTilt = humanoid::kLevelFootTilt;

/// Clamps each angle of `q` into its joint's range; returns how many were outside.
int clamp_to_ranges(const RobotModel& model, humanoid::JointVector& q);
/// How many angles of `q` lie outside their joints' ranges.
int outside_ranges(const RobotModel& model, const humanoid::JointVector& q);

RobotModel make_robot_model(const humanoid::RobotParams& robot);
/// The model of a loaded description. Each leg's IK is analytic when the leg has its layout
/// (leg_kinematics.hpp: hip yaw (z), roll (x), pitch (y) axes meeting in a point, knee (y)
/// straight below, ankle pitch (y) and roll (x) meeting straight below the knee, the sole centre
/// below the ankle (a horizontal shift allowed, LegGeometry::sole_shift); checked to 1e-9 m), numeric otherwise
/// (leg[side].analytic, and analytic_ik_mismatch says why). A sole turned at zero angles (sole_rotation) is levelled
/// by the numeric IK.
RobotModel make_robot_model(const humanoid::LoadedRobot& robot);
/// Why the analytic IK does not apply to leg `side` of a loaded description ("" when it does).
std::string analytic_ik_mismatch(const humanoid::LoadedRobot& robot, int side);
/// Fills leg[side]'s general chain (axes, anchors, sole) from the model's bodies.
void fill_leg_chain(RobotModel& model, int side);
/// Sets each body's axis_index from its axis (the model's factories call it once the bodies are set).
void index_joint_axes(RobotModel& model);

struct RobotModelData {
  std::array<Pose, kBodies> frame;          ///< world pose of each body
  std::array<Vector3d, kBodies> com_world;  ///< world position of each body's centre of mass [m]
  std::array<Vector3d, kBodies> axis;       ///< each jointed body's joint axis in the world, R a (0 for a rigid one)
};

/// World frames of every body for this pelvis pose and these joint angles. With `first` > 0 only the bodies from
/// `first` on (e.g. kFirstLegBody: the legs after a change of their angles alone); those before are kept from the
/// last call, the same numbers as a whole pass.
void forward_kinematics(const RobotModel& model, RobotModelData& data, const Pose& pelvis,
                        const humanoid::JointVector& q, int first = 0);
/// Whole-body centre of mass after forward_kinematics [m].
Vector3d center_of_mass(const RobotModel& model, const RobotModelData& data);
/// World pose of the sole centre of `side` after forward_kinematics.
Pose sole_pose(const RobotModel& model, const RobotModelData& data, int side);

using LegJacobian = Eigen::Matrix<double, 6, 6>;  ///< rows: linear (3), angular (3); columns: leg joints
using LegTorque = Eigen::Matrix<double, 6, 1>;    ///< leg joints, kinematic order [Nm]

/// Geometric Jacobian of the point `point` (world) rigidly attached to the foot of `side`, with
/// respect to that leg's six joints (columns in role order: hip yaw, roll, pitch, knee, ankle
/// pitch, roll, whatever their order in the chain), world frame, after forward_kinematics.
LegJacobian leg_jacobian(const RobotModel& model, const RobotModelData& data, int side, const Vector3d& point);
/// The torque each joint of leg `side` must supply to hold that leg's own links below it against
/// gravity, the leg hanging from the pelvis (g_leg of the spec's full form) [Nm]. Sign: the gear
/// torque the joint applies to its child, positive about the joint axis.
LegTorque leg_gravity_torque(const RobotModel& model, const RobotModelData& data, int side);

}  // namespace flexgait::walking
