#pragma once
/// \file robot_description.hpp
/// A robot from its description file (docs/guide/robot.md): the keys that name the file and map its joints,
/// feet and IMU onto flexgait's (robot.description, robot.joints.*, robot.feet.*, robot.imu_body,
/// robot.exclude_contacts), and what the loader reads from the file, as plain data free of any
/// simulator (LoadedRobot). The loader (robot_loader.hpp) fills it through MuJoCo's compiler; the
/// twin (twin_mjcf.hpp) and the controller's model (walking/robot_model.hpp) are made from it.
///
/// Frames: each body's pose relative to its parent as the file's compiler gives it (MuJoCo's
/// body_pos, body_quat), inertial frames relative to the body; all joint angles zero (qpos0).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/robot/joints.hpp"
#include "flexgait/robot/robot_params.hpp"

namespace flexgait::humanoid {

/// One foot: the body that carries the sole and the sole rectangle.
struct FootMapping {
  std::string body;                   ///< body below the ankle-roll joint that carries the sole
  std::string sole_geom = "none";     ///< a box geom of that body whose bottom face is the sole, or none
  std::string sole_size = "none";     ///< "length width" [m] of the sole rectangle (when sole_geom is none)
  std::string sole_center = "0 0 0";  ///< centre of the sole rectangle in the foot body's frame "x y z" [m]
};

/// The keys robot.description and the mapping of a description file onto flexgait's names.
/// Defaults: the builtin robot's own names (the mapping an exported builtin loads back with).
struct RobotDescriptionParams {
  std::string description = "builtin";  ///< builtin, or a path to an MJCF (.xml) or URDF (.urdf) file
  std::array<std::string, kJoints> joints = [] {
    std::array<std::string, kJoints> names;
    for (int j = 0; j < kJoints; ++j) names[j] = std::string(kJointNames[j]);
    return names;
  }();
  std::array<FootMapping, 2> feet = {FootMapping{"l_foot", "l_sole"}, FootMapping{"r_foot", "r_sole"}};
  std::string imu_body = "root";          ///< body carrying the IMU; root: the root body
  std::string exclude_contacts = "none";  ///< "a:b,c:d": body pairs whose contacts are excluded

  bool builtin() const { return description == "builtin"; }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("robot.description", s.description,
      {.doc = "builtin (the generated THORMANG-class robot) or a path to an MJCF (.xml) or URDF (.urdf) file"});
    for (int j = 0; j < kJoints; ++j)
      v("robot.joints." + std::string(kJointNames[j]), s.joints[j],
        {.doc = j == kWaistYaw ? "name in the description file of this hinge joint, or none (a trunk without a waist)"
                               : "name in the description file of this hinge joint"});
    for (int side = 0; side < 2; ++side) {
      const std::string f = std::string("robot.feet.") + (side == 0 ? "left" : "right");
      v(f + ".body", s.feet[side].body,
        {.doc = "foot body (below the ankle-roll joint; the F/T sensor sits at its joint to its parent)"});
      v(f + ".sole_geom", s.feet[side].sole_geom,
        {.doc = "box geom of the foot whose bottom face is the sole, or none"});
      v(f + ".sole_size", s.feet[side].sole_size,
        {.unit = "m", .doc = "'length width' of the sole when sole_geom is none, or none"});
      v(f + ".sole_center", s.feet[side].sole_center,
        {.unit = "m", .doc = "'x y z' centre of the sole in the foot body's frame (with sole_size)"});
    }
    v("robot.imu_body", s.imu_body, {.doc = "body carrying the IMU (root: the root body)"});
    v("robot.exclude_contacts", s.exclude_contacts,
      {.doc = "'a:b,c:d' body pairs whose contacts are ignored, or none"});
  }
};

/// What the loader read of a description file (MuJoCo's compiled numbers, full precision).
struct LoadedJoint {
  std::string name;
  int mapped = -1;                      ///< flexgait joint (humanoid::Joint), −1: held rigid in the twin
  std::array<double, 3> pos{};          ///< anchor in the body frame [m]
  std::array<double, 3> axis{0, 0, 1};  ///< unit axis in the body frame
  bool limited = false;
  std::array<double, 2> range{};          ///< [rad]
  double armature = 0, frictionloss = 0;  ///< [kg m^2], [Nm]
  double damping = 0;                     ///< the file's joint damping [Nm s/rad] (the twin's gears set their own)
  /// The inertia the joint turns at the file's zero angles: the composite inertia of the bodies below it about
  /// its axis, the joint-space mass matrix's diagonal without the armature [kg m^2] (the link side of its gear).
  double link_inertia = 0;
  /// The largest torque the file's actuators on this joint can apply [Nm]: gear × force range, or
  /// gear × gain × control range for a motor without a force range; 0: the file sets none.
  double force_limit = 0;
};

struct LoadedGeom {
  std::string name;
  std::string type;              ///< MJCF type: plane, sphere, capsule, ellipsoid, cylinder, box
  std::array<double, 3> size{};  ///< MuJoCo's size [m]
  std::array<double, 3> pos{};
  std::array<double, 4> quat{1, 0, 0, 0};
  int contype = 1, conaffinity = 1, condim = 3;
  std::array<double, 3> friction{1, 0.005, 0.0001};
  std::array<double, 2> solref{0.02, 1};
  std::array<double, 5> solimp{0.9, 0.95, 0.001, 0.5, 2};
  double margin = 0, gap = 0;
  std::array<float, 4> rgba{0.5f, 0.5f, 0.5f, 1};
};

struct LoadedBody {
  std::string name;
  int parent = -1;              ///< index in LoadedRobot::bodies; −1: the root
  std::array<double, 3> pos{};  ///< in the parent frame [m]
  std::array<double, 4> quat{1, 0, 0, 0};
  double mass = 0;                          ///< [kg]
  std::array<double, 3> ipos{};             ///< centre of mass in the body frame [m]
  std::array<double, 4> iquat{1, 0, 0, 0};  ///< principal axes of inertia in the body frame
  std::array<double, 3> inertia{};          ///< principal moments [kg m^2]
  std::vector<LoadedJoint> joints;          ///< hinges and slides of this body (a free joint is dropped)
  std::vector<LoadedGeom> geoms;
};

/// The sole of one foot, in the foot body's frame: a rectangle (the controller's), and when the
/// file's contact geoms make it, their convex hull on the sole plane.
/// A foot body whose frame is turned from the root's at zero joint angles by less than this is a
/// level foot printed with few digits (6 digits of a quaternion: ~1e-6 rad): its sole's frame is the
/// body's own [rad].
inline constexpr double kLevelFootTilt = 1e-3;

struct Sole {
  int geom = -1;                   ///< index in the foot body's geoms, −1: added by the twin
  std::array<double, 3> center{};  ///< centre of the rectangle, in the foot body's frame [m]
  double length = 0, width = 0;    ///< along the sole frame's x and y [m]
  /// The sole's frame (x forward, z out of the sole) in the foot body's frame, w x y z: identity when
  /// the body's axes are the sole's. A foot body turned at zero joint angles (kLevelFootTilt or more;
  /// frames that follow the joint axes) has its sole's frame from its contact geoms: the box of the
  /// lowest point, its face that looks most down and its axis that looks most forward; without a box,
  /// or with a sole_size, the root's axes at zero joint angles. A sole_geom box's own axes.
  std::array<double, 4> quat{1, 0, 0, 0};
  /// Whether the sole has a frame of its own (`quat` is not the identity).
  bool has_own_frame() const { return quat != std::array<double, 4>{1, 0, 0, 0}; }
  /// From the foot's contact geoms (no sole_geom, no sole_size): the convex hull (counter-clockwise,
  /// x y in the sole frame [m]) of their points on the sole plane z = center[2], the lowest of them;
  /// the rectangle is its bounding rectangle. Empty for a sole named or sized by the mapping.
  std::vector<std::array<double, 2>> hull;
  /// The foot body's geoms (indices in its geoms) whose points make the hull: the twin gives them
  /// the sole's contact; false `hull_in_twin`: one of them is a mesh (not carried into the twin),
  /// and the twin's sole plate on the rectangle touches the floor instead.
  std::vector<int> hull_geoms;
  bool hull_in_twin = false;
};

struct LoadedRobot {
  std::string source;              ///< the file
  std::vector<LoadedBody> bodies;  ///< the robot's tree, parents before children; bodies[0] is the root
  std::array<std::array<int, 2>, kJoints>
      joint{};                ///< each flexgait joint: (body, joint in that body); body −1: absent
  std::array<int, 2> foot{};  ///< foot body of each side
  /// Each leg's joints from the root to the foot, as roles (0 hip yaw, 1 hip roll, 2 hip pitch,
  /// 3 knee, 4 ankle pitch, 5 ankle roll): the hips' three in any order, the knee, the ankle's two.
  std::array<std::array<int, kLegJoints>, 2> leg_order{{{0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5}}};
  std::array<Sole, 2> sole{};
  int imu_body = 0;
  std::vector<std::array<int, 2>>
      exclude;                        ///< body pairs whose contacts are ignored (the file's and robot.exclude_contacts)
  std::vector<std::string> warnings;  ///< what the loader translated or dropped, one line each
  double gravity = kDefaultGravity;   ///< the file's gravity (`<option gravity>`), along −z [m/s^2]

  bool has_joint(int j) const { return joint[j][0] >= 0; }
};

}  // namespace flexgait::humanoid
