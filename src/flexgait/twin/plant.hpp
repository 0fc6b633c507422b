#pragma once
/// \file plant.hpp
/// The digital twin as a plant (docs/theory/humanoid.md): joint commands in, sensor readings out, at the
/// control period over a finer physics step. Ground truth (link angles, pelvis pose, COM, true
/// ZMP from the contact forces) is on a separate path, for evaluation code only: a controller is
/// handed SensorReadings and nothing else.
///
/// Sensor model: encoders quantised (plus optional noise), F/T and IMU with white noise, the IMU
/// with bias and bias drift and an AHRS orientation output with its own error (ImuModel), and a
/// fault schedule per sensor (SensorFaults: dropout, stuck, NaN, latency). All noise comes from
/// one generator seeded by plant.noise.seed: the same configuration gives the same readings.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "flexgait/robot/joints.hpp"
#include "flexgait/robot/robot_params.hpp"
#include "flexgait/robot/sensors.hpp"
#include "flexgait/twin/disturbance.hpp"
#include "flexgait/twin/plant_params.hpp"
#include "flexgait/twin/terrain.hpp"

namespace flexgait::twin {

/// What only evaluation code may read.
struct GroundTruth {
  double t = 0;
  humanoid::JointVector link_angle{}, link_velocity{};  ///< true joint (link-side) angles [rad], [rad/s]
  humanoid::JointVector motor_angle{};                  ///< unquantised motor side [rad]
  humanoid::JointVector gear_torque{};                  ///< [Nm]
  humanoid::JointVector servo_torque{};                 ///< the motors' servo torque, last physics step [Nm]
  std::array<double, 3> pelvis_pos{};                   ///< [m]
  std::array<double, 4> pelvis_quat{1, 0, 0, 0};
  std::array<double, 3> com{};                      ///< whole-body centre of mass [m]
  std::array<double, 2> zmp{};                      ///< centre of pressure of the floor contacts (x, y) [m]
  std::array<std::array<double, 3>, 2> sole_pos{};  ///< left, right: sole centre (TwinModel::sole_center) [m]
  std::array<double, 2> sole_yaw{};                 ///< heading of each sole [rad]
  std::array<bool, 2> sole_contact{};               ///< the sole touches the floor
  double normal_force = 0;                          ///< total floor normal force [N]
  bool non_sole_contact = false;                    ///< a body other than a sole touches the floor
  int warnings = 0;                                 ///< MuJoCo warnings raised so far
  std::array<double, 3> push_force{};               ///< push force of the last physics step (world) [N]
  std::array<double, 3> push_impulse{};             ///< push impulse applied so far (world) [N s]
  std::array<double, 3> floor_impulse{};            ///< impulse of the floor's contact forces so far (world) [N s]
  std::array<double, 3> linear_momentum{};          ///< total linear momentum of the robot (world) [kg m/s]
};

/// The twin's model: its MJCF (model_xml.hpp's names: joints by kJointNames, sole geoms l_sole /
/// r_sole, sites imu, l_ft, r_ft, the floor) and each sole's centre in its F/T site's frame.
struct TwinModel {
  std::string mjcf;
  std::array<std::array<double, 3>, 2> sole_center{};  ///< [m]
};

/// The builtin robot's twin (humanoid_mjcf), sole centres ankle_to_sole below the ankles and
/// robot.sole_offset_y outward.
TwinModel builtin_twin(const humanoid::RobotParams& robot, const PlantParams& plant);

/// The twin (MuJoCo behind a pimpl: twin/detail/ for its model and state). The model is compiled
/// once and shared, const, by copies; everything that changes while the twin runs (MuJoCo's
/// state, the motors, the sensors' noise generator, drifts and faults, the pushes' bookkeeping)
/// is one plant state, so a copy of the plant continues exactly as the original would.
class HumanoidPlant {
 public:
  HumanoidPlant(const humanoid::RobotParams& robot, const PlantParams& plant);
  /// The twin of any robot (twin_mjcf.hpp for a loaded description).
  HumanoidPlant(const TwinModel& twin, const PlantParams& plant);
  ~HumanoidPlant();
  /// A copy shares the const model and copies the state.
  HumanoidPlant(const HumanoidPlant& other);
  HumanoidPlant& operator=(const HumanoidPlant& other);

  /// Puts the robot in `pose` (link and motor angles), pelvis level, at rest, lowered until a sole
  /// touches the floor (on a terrain: its lowest point over the soles, terrain.hpp's heights), 1 nm
  /// into it, so that the contact exists from the first physics step whatever the rounding.
  void reset(const humanoid::JointVector& pose);
  /// Advances one control period with these motor-side position commands [rad].
  void step(const humanoid::JointVector& command);
  /// The pushes to apply from now on (replace any earlier ones; disturbance.hpp for their timing);
  /// forces on the same body at the same time add up.
  void set_pushes(std::vector<Push> pushes);
  /// One push (set_pushes with one).
  void set_push(const Push& push) { set_pushes({push}); }
  const humanoid::SensorReadings& sensors() const;
  GroundTruth truth() const;
  double time() const;
  double total_mass() const;
  /// The magnitude of the twin's gravity [m/s^2] (for evaluation).
  double gravity() const;
  /// MuJoCo's warnings so far as one line ("" if none; GroundTruth::warnings counts them).
  std::string warnings_text() const;
  /// MuJoCo's warnings raised so far (GroundTruth::warnings, without forming the rest of the truth).
  int warning_count() const;
  /// Whether the state is finite: MuJoCo's positions and velocities, the motors' angles and the whole body's
  /// centre of mass (a diverged simulation; without forming the truth).
  bool state_finite() const;

  const PlantParams& params() const;
  /// The floor (plant.terrain's geometry; for evaluation only: the controller is not told).
  const Terrain& terrain() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend struct PlantAccess;
};

/// Standing pose: feet under the hips, pelvis at `pelvis_height` above the floor, knee bent so
/// that hip and ankle pitch are −knee/2 (legs vertical on average). Throws if out of reach.
humanoid::JointVector standing_pose(const humanoid::RobotParams& robot, double pelvis_height);

}  // namespace flexgait::twin
