#include "flexgait/twin/plant.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "flexgait/twin/detail/elastic_drives.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/sensor_faults.hpp"

namespace flexgait::twin {
namespace {

/// MuJoCo's body of the pelvis, the twin's root (the world is body 0): its subtree's centre of mass is the whole
/// robot's.
constexpr int kPelvisBody = 1;

/// How far reset() puts the lowest sole point into the floor [m]. Placed exactly on it, the sole's
/// distance is a rounding residue of ±1e-16 m and its sign decides whether MuJoCo's contact exists
/// in the first physics step (it needs distance < margin = 0): the robot would start either
/// supported or falling freely, and two descriptions of one robot could differ by it. 1 nm is far
/// above that rounding and far below the ~0.06 mm the soft contact settles to under the robot's
/// weight, so the first step starts supported.
constexpr double kResetPenetration = 1e-9;

/// The Hamilton product a ⊗ b of two quaternions (w, x, y, z).
std::array<double, 4> quat_product(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

int require(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::logic_error("twin model has no " + name);
  return id;
}

/// The twin's joint `j`: every leg joint is there; the waist may be absent (a rigid trunk,
/// ElasticDrives::kAbsentJoint).
int twin_joint(const mjModel* m, int j) {
  const std::string name(humanoid::kJointNames[j]);
  if (j == humanoid::kWaistYaw && mj_name2id(m, mjOBJ_JOINT, name.c_str()) < 0) return ElasticDrives::kAbsentJoint;
  return require(m, mjOBJ_JOINT, name);
}

int sensor_adr(const mjModel* m, const char* name) {
  return m->sensor_adr[require(m, mjOBJ_SENSOR, name)];
}

/// MuJoCo's state of one model, copied with mj_copyData.
class Data {
 public:
  explicit Data(const mjModel* m) : m_(m), d_(mj_makeData(m)) {}
  Data(const Data& o) : m_(o.m_), d_(mj_copyData(nullptr, o.m_, o.d_)) {}
  Data& operator=(const Data&) = delete;
  ~Data() { mj_deleteData(d_); }
  mjData* get() const { return d_; }

 private:
  const mjModel* m_;
  mjData* d_;
};

}  // namespace

/// Everything of the twin that changes while it runs: one value, copied whole.
struct PlantState {
  PlantState(const mjModel* m, std::uint64_t seed) : data(m), rng(seed) {}
  Data data;
  std::vector<ActuatorState> motors;  ///< one per actuated joint, in humanoid::kJointNames order
  humanoid::JointVector servo_sum{};  ///< Σ of each servo's torque over the substeps of the control period [Nm]
  std::array<double, 4> last_quat{};  ///< the IMU frame's true attitude at the last reading; 0: none yet
  std::vector<Push> pushes;
  std::array<double, 3> push_force{}, push_impulse{}, floor_impulse{};
  humanoid::SensorReadings sensors;
  std::mt19937_64 rng;
  std::array<double, 3> gyro_drift{}, accel_drift{};  ///< bias random walks [rad/s], [m/s^2]
  std::array<FaultChannel<6>, 2> ft_fault;            ///< left, right: force then torque
  FaultChannel<3> gyro_fault, accel_fault;
  FaultChannel<4> ahrs_fault;
  FaultChannel<1> encoder_fault;
};

struct HumanoidPlant::Impl {
  /// Takes ownership of `m` (as loaded; its springs are handed to the drives here).
  Impl(const TwinModel& twin, const PlantParams& plant, Terrain floor, mjModel* m);
  void read_sensors();
  void read_delta_angle();
  /// Sets xfrc_applied for the physics step starting now.
  void apply_push();
  /// A geom of the floor: any geom of the world body (the terrain's, terrain.hpp).
  bool is_floor(int geom) const { return model->geom_bodyid[geom] == 0; }

  std::array<std::array<double, 3>, 2> sole_center{};  ///< sole centres in the F/T site frames [m]
  PlantParams params;
  Terrain terrain;
  std::shared_ptr<const mjModel> model;  ///< shared by copies; never changed after construction
  /// The same model with MuJoCo's sensor stage off (mjDSBL_SENSOR), for the substeps before a control
  /// period's last: the sensors are read once per period, after its last substep, and mj_step computes
  /// them at the start of each substep, so the last substep's evaluation is the only one read (the
  /// readings, and everything else, are bit for bit those of stepping the model itself). The sensor
  /// stage (mj_rnePostConstraint for the accelerometer and the F/T sensors) is ~8 % of a MuJoCo step of
  /// the twin: skipping it in three of a period's four substeps makes the period's physics ~6 % faster.
  std::shared_ptr<const mjModel> model_unsensed;
  ElasticDrives drives;
  std::array<int, humanoid::kJoints> joint_id{};
  std::array<int, 2> push_body{};  ///< body ids of PushBody: pelvis, chest
  std::array<int, 2> sole_geom{};
  std::array<int, 2> foot_body{};  ///< the bodies of the soles: any of their geoms on the floor is support
  std::array<int, 2> ft_site{};
  std::array<int, 4> ft_sensor_adr{};  // l force, l torque, r force, r torque
  int quat_adr = 0, gyro_adr = 0, acc_adr = 0;
  PlantState state;
};

struct PlantAccess {
  static const mjModel* model(const HumanoidPlant& p) { return p.impl_->model.get(); }
  static const mjData* data(const HumanoidPlant& p) { return p.impl_->state.data.get(); }
};
const mjModel* plant_model(const HumanoidPlant& plant) {
  return PlantAccess::model(plant);
}
const mjData* plant_data(const HumanoidPlant& plant) {
  return PlantAccess::data(plant);
}

humanoid::JointVector standing_pose(const humanoid::RobotParams& r, double pelvis_height) {
  const double leg = pelvis_height - r.hip_axes_depth - r.ankle_to_sole;  // hip axes to ankle axes
  const double reach = r.thigh + r.shank;
  if (leg <= 0.05 * reach || leg >= reach)
    throw ConfigError("walk.pelvis_height",
                      fmt::format("key 'walk.pelvis_height' = '{}': out of the legs' reach (hip axes to ankle axes "
                                  "must be between 5 % and 100 % of thigh + shank)",
                                  pelvis_height));
  // Law of cosines with the hip-ankle line vertical.
  const double c_knee = (r.thigh * r.thigh + r.shank * r.shank - leg * leg) / (2 * r.thigh * r.shank);
  const double knee = std::numbers::pi - std::acos(c_knee);
  const double hip = -std::asin(r.shank * std::sin(knee) / leg);
  const double ankle = -(knee + hip);
  humanoid::JointVector q{};
  for (int side = 0; side < 2; ++side) {
    const int j = humanoid::leg_first_joint(side);
    q[j + 2] = hip;
    q[j + 3] = knee;
    q[j + 4] = ankle;
  }
  return q;
}

TwinModel builtin_twin(const humanoid::RobotParams& robot, const PlantParams& plant) {
  TwinModel t;
  t.mjcf = humanoid_mjcf(robot, plant);
  t.sole_center = {{{0, robot.sole_offset_y, -robot.ankle_to_sole}, {0, -robot.sole_offset_y, -robot.ankle_to_sole}}};
  return t;
}

HumanoidPlant::HumanoidPlant(const humanoid::RobotParams& robot, const PlantParams& plant)
    : HumanoidPlant(builtin_twin(robot, plant), plant) {}

namespace {

ElasticDrives make_drives(const mjModel* m, const PlantParams& params) {
  std::vector<int> joints;
  std::vector<ActuatorParams> act;
  const humanoid::JointVector stiffness = params.gear_stiffness();
  const humanoid::JointVector torque_limit = params.servo_torque_limits();
  for (int j = 0; j < humanoid::kJoints; ++j) {
    joints.push_back(twin_joint(m, j));
    ActuatorParams a;
    a.k = stiffness[j];
    a.d = params.gear_damping;
    a.backlash = params.backlash;
    a.torque_limit = torque_limit[j];
    a.rotor_inertia = params.rotor_inertia;
    a.bandwidth = params.servo_bandwidth;
    a.integral_time = params.servo_integral_time;
    a.encoder_steps = params.encoder_steps;
    act.push_back(a);
  }
  return ElasticDrives(m, joints, act);
}

/// Shares `m`, deleting it with the last copy.
std::shared_ptr<const mjModel> shared_model(mjModel* m) {
  return {m, [](const mjModel* p) { mj_deleteModel(const_cast<mjModel*>(p)); }};
}

/// The twin's model as compiled, the rough floor's heights written in (the plant then hands the
/// actuated joints' springs to their drives and never changes the model again).
mjModel* load_twin(const TwinModel& twin, const PlantParams& params, const Terrain& terrain) {
  mjModel* m = load_mjcf(twin.mjcf);
  if (params.terrain.kind == TerrainKind::kRough) {
    // The rough floor's heights (terrain.hpp), as MuJoCo's normalised data: h = −A + 2A·data.
    const int f = require(m, mjOBJ_HFIELD, kTerrainHfield);
    const HeightGrid& grid = terrain.grid();
    if (m->hfield_nrow[f] != grid.nrow || m->hfield_ncol[f] != grid.ncol) {
      mj_deleteModel(m);
      throw std::logic_error("the twin's height field does not match its terrain");
    }
    const double a = params.terrain.rough_amplitude;
    float* data = m->hfield_data + m->hfield_adr[f];
    for (std::size_t i = 0; i < grid.height.size(); ++i) data[i] = static_cast<float>((grid.height[i] + a) / (2 * a));
  }
  return m;
}

}  // namespace

HumanoidPlant::Impl::Impl(const TwinModel& twin, const PlantParams& plant, Terrain floor, mjModel* m)
    : sole_center(twin.sole_center),
      params(plant),
      terrain(std::move(floor)),
      model(shared_model(m)),
      drives(make_drives(m, plant)),
      state(m, static_cast<std::uint64_t>(plant.noise_seed)) {
  drives.take_springs(m);  // before anything runs; the model is const from here on
  mjModel* unsensed = mj_copyModel(nullptr, m);
  unsensed->opt.disableflags |= mjDSBL_SENSOR;
  model_unsensed = shared_model(unsensed);
  for (int j = 0; j < humanoid::kJoints; ++j) joint_id[j] = twin_joint(m, j);
  (void)require(m, mjOBJ_GEOM, "floor");
  // The root body, and the waist joint's body (the root itself for a trunk without a waist).
  push_body = {1, joint_id[humanoid::kWaistYaw] < 0 ? 1 : m->jnt_bodyid[joint_id[humanoid::kWaistYaw]]};
  sole_geom = {require(m, mjOBJ_GEOM, "l_sole"), require(m, mjOBJ_GEOM, "r_sole")};
  foot_body = {m->geom_bodyid[sole_geom[0]], m->geom_bodyid[sole_geom[1]]};
  ft_site = {require(m, mjOBJ_SITE, "l_ft"), require(m, mjOBJ_SITE, "r_ft")};
  ft_sensor_adr = {sensor_adr(m, "l_ft_force"), sensor_adr(m, "l_ft_torque"), sensor_adr(m, "r_ft_force"),
                   sensor_adr(m, "r_ft_torque")};
  quat_adr = sensor_adr(m, "imu_quat");
  gyro_adr = sensor_adr(m, "imu_gyro");
  acc_adr = sensor_adr(m, "imu_acc");
}

HumanoidPlant::HumanoidPlant(const TwinModel& twin, const PlantParams& plant) {
  Terrain terrain(plant.terrain);
  mjModel* m = load_twin(twin, plant, terrain);
  impl_ = std::make_unique<Impl>(twin, plant, std::move(terrain), m);
  reset(humanoid::JointVector{});
}

HumanoidPlant::~HumanoidPlant() = default;
HumanoidPlant::HumanoidPlant(const HumanoidPlant& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
HumanoidPlant& HumanoidPlant::operator=(const HumanoidPlant& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}

double HumanoidPlant::time() const {
  return impl_->state.data.get()->time;
}
double HumanoidPlant::total_mass() const {
  return impl_->model->body_subtreemass[0];
}
double HumanoidPlant::gravity() const {
  return -impl_->model->opt.gravity[2];
}
std::string HumanoidPlant::warnings_text() const {
  return mujoco_warnings_text(impl_->state.data.get());
}
int HumanoidPlant::warning_count() const {
  return mujoco_warning_count(impl_->state.data.get());
}
bool HumanoidPlant::state_finite() const {
  const Impl& p = *impl_;
  const mjData* d = p.state.data.get();
  const mjModel* m = p.model.get();
  const auto finite = [](const double* v, int n) {
    return std::all_of(v, v + n, [](double x) { return std::isfinite(x); });
  };
  return finite(d->qpos, m->nq) && finite(d->qvel, m->nv) && finite(d->subtree_com + 3 * kPelvisBody, 3) &&
         std::all_of(p.state.motors.begin(), p.state.motors.end(),
                     [](const ActuatorState& a) { return std::isfinite(a.theta_m); });
}
const humanoid::SensorReadings& HumanoidPlant::sensors() const {
  return impl_->state.sensors;
}
const PlantParams& HumanoidPlant::params() const {
  return impl_->params;
}
const Terrain& HumanoidPlant::terrain() const {
  return impl_->terrain;
}

void HumanoidPlant::reset(const humanoid::JointVector& pose) {
  Impl& p = *impl_;
  PlantState& st = p.state;
  mjData* d = st.data.get();
  const mjModel* m = p.model.get();
  mj_resetData(m, d);
  st.push_force = st.push_impulse = st.floor_impulse = {};
  st.gyro_drift = {};
  st.accel_drift = {};
  st.servo_sum = {};
  st.last_quat = {};
  const auto& f = p.params.faults.sensor;
  const double T = p.params.control_period;
  st.ft_fault = {FaultChannel<6>(f[humanoid::kFtLeft], T), FaultChannel<6>(f[humanoid::kFtRight], T)};
  st.gyro_fault = FaultChannel<3>(f[humanoid::kGyro], T);
  st.accel_fault = FaultChannel<3>(f[humanoid::kAccel], T);
  st.ahrs_fault = FaultChannel<4>(f[humanoid::kAhrs], T);
  st.encoder_fault = FaultChannel<1>(f[humanoid::kEncoder], T);
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (p.joint_id[j] >= 0) d->qpos[m->jnt_qposadr[p.joint_id[j]]] = pose[j];
  // Level pelvis, then lower it until the lower sole rests on the floor.
  d->qpos[0] = d->qpos[1] = 0.0;
  d->qpos[2] = 2.0;
  d->qpos[3] = 1.0;
  d->qpos[4] = d->qpos[5] = d->qpos[6] = 0.0;
  mj_kinematics(m, d);
  double lowest = INFINITY;
  for (int side = 0; side < 2; ++side) {
    const int g = p.sole_geom[side];
    // Box bottom: centre z minus the half-extent along world z (soles are level in a level pose).
    const double* R = d->geom_xmat + 9 * g;
    const double* h = m->geom_size + 3 * g;
    const double* c = d->geom_xpos + 3 * g;
    if (p.params.terrain.kind == TerrainKind::kFlat) {
      const double extent = std::abs(R[6]) * h[0] + std::abs(R[7]) * h[1] + std::abs(R[8]) * h[2];
      lowest = std::min(lowest, c[2] - extent);
      continue;
    }
    // On a terrain: the sole's bottom face on a 9 × 9 grid of points, each against the floor under it.
    for (int i = -4; i <= 4; ++i)
      for (int k = -4; k <= 4; ++k) {
        const double u[3] = {0.25 * i * h[0], 0.25 * k * h[1], -h[2]};
        double x[3];
        for (int r = 0; r < 3; ++r) x[r] = c[r] + R[3 * r] * u[0] + R[3 * r + 1] * u[1] + R[3 * r + 2] * u[2];
        lowest = std::min(lowest, x[2] - p.terrain.height(x[0], x[1]));
      }
  }
  d->qpos[2] -= lowest + kResetPenetration;
  mj_forward(m, d);
  st.motors = p.drives.at_rest(d);
  p.read_sensors();
}

void HumanoidPlant::step(const humanoid::JointVector& command) {
  Impl& p = *impl_;
  PlantState& st = p.state;
  mjData* d = st.data.get();
  const mjModel* m = p.model.get();
  const int n = p.params.substeps();
  st.servo_sum.fill(0.0);
  for (int k = 0; k < n; ++k) {
    p.apply_push();
    p.drives.step(k + 1 < n ? p.model_unsensed.get() : m, d, st.motors, command.data());
    for (int j = 0; j < humanoid::kJoints; ++j) st.servo_sum[j] += st.motors[j].servo;
    // The constraint force on the free joint's translation: the floor contacts' total (the other
    // constraints, joint limits, act within the robot and have no part there).
    for (int i = 0; i < 3; ++i) st.floor_impulse[i] += m->opt.timestep * d->qfrc_constraint[i];
  }
  p.read_sensors();
}

void HumanoidPlant::set_pushes(std::vector<Push> pushes) {
  impl_->state.pushes = std::move(pushes);
}

void HumanoidPlant::Impl::apply_push() {
  mjData* d = state.data.get();
  const double dt = model->opt.timestep;
  const long n = std::lround(d->time / dt);
  for (const int b : push_body)
    for (int i = 0; i < 6; ++i) d->xfrc_applied[6 * b + i] = 0.0;
  state.push_force = {};
  for (const Push& push : state.pushes) {
    const bool on =
        push.active() && n >= std::lround(push.time / dt) && n < std::lround((push.time + push.duration) / dt);
    if (!on) continue;
    const int body = push_body[static_cast<int>(push.body)];
    for (int i = 0; i < 3; ++i) {
      d->xfrc_applied[6 * body + i] += push.force[i];  // force at the body's COM, world frame
      state.push_force[i] += push.force[i];
    }
  }
  for (int i = 0; i < 3; ++i) state.push_impulse[i] += state.push_force[i] * dt;
}

void HumanoidPlant::Impl::read_sensors() {
  const mjData* d = state.data.get();
  humanoid::SensorReadings& s = state.sensors;
  const double now = d->time;
  s.t = now;
  for (int j = 0; j < humanoid::kJoints; ++j)
    s.encoder[j] = encoder_reading(drives.params()[j], state.motors[j].theta_m);
  s.encoder_stamp.fill(now);
  std::normal_distribution<double> unit(0.0, 1.0);
  auto noisy = [&](double v, double std) { return std > 0 ? v + std * unit(state.rng) : v; };
  for (int side = 0; side < 2; ++side) {
    const double* f = d->sensordata + ft_sensor_adr[2 * side];
    const double* t = d->sensordata + ft_sensor_adr[2 * side + 1];
    for (int i = 0; i < 3; ++i) {
      s.ft[side].force[i] = noisy(f[i], params.ft_force_noise);
      s.ft[side].torque[i] = noisy(t[i], params.ft_torque_noise);
    }
    s.ft[side].stamp = now;
  }
  for (int i = 0; i < 4; ++i) s.imu.quat[i] = d->sensordata[quat_adr + i];
  for (int i = 0; i < 3; ++i) {
    s.imu.gyro[i] = noisy(d->sensordata[gyro_adr + i], params.gyro_noise);
    s.imu.accel[i] = noisy(d->sensordata[acc_adr + i], params.accel_noise);
  }
  s.imu.quat_stamp = s.imu.gyro_stamp = s.imu.accel_stamp = now;
  // The IMU's bias and drift (b += σ_w √T n per period) and the AHRS output's error: draws only
  // for the terms switched on, so that the readings of earlier configurations stay the same.
  const ImuModel& imu = params.imu;
  const double sqrt_T = std::sqrt(params.control_period);
  for (int i = 0; i < 3; ++i) {
    state.gyro_drift[i] = noisy(state.gyro_drift[i], imu.gyro_bias_walk * sqrt_T);
    state.accel_drift[i] = noisy(state.accel_drift[i], imu.accel_bias_walk * sqrt_T);
    s.imu.gyro[i] += imu.gyro_bias + state.gyro_drift[i];
    s.imu.accel[i] += imu.accel_bias + state.accel_drift[i];
  }
  if (imu.ahrs_noise > 0) {
    // q ← q ⊗ [1, δ/2] (normalised), δ ~ N(0, σ²) about each body axis.
    const std::array<double, 3> d = {noisy(0, imu.ahrs_noise), noisy(0, imu.ahrs_noise), noisy(0, imu.ahrs_noise)};
    const auto q = s.imu.quat;
    const std::array<double, 4> e = {1.0, 0.5 * d[0], 0.5 * d[1], 0.5 * d[2]};
    const std::array<double, 4> r = quat_product(q, e);
    const double n = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    for (int i = 0; i < 4; ++i) s.imu.quat[i] = r[i] / n;
  }
  if (params.encoder_noise > 0)
    for (int j = 0; j < humanoid::kJoints; ++j) s.encoder[j] = noisy(s.encoder[j], params.encoder_noise);
  const double substeps = params.substeps();
  for (int j = 0; j < humanoid::kJoints; ++j)
    s.motor_torque[j] = noisy(state.servo_sum[j] / substeps, params.motor_torque_noise);

  // The fault schedule.
  for (int side = 0; side < 2; ++side) {
    std::array<double, 6> v{};
    for (int i = 0; i < 3; ++i) {
      v[i] = s.ft[side].force[i];
      v[3 + i] = s.ft[side].torque[i];
    }
    state.ft_fault[side].apply(now, v, s.ft[side].stamp);
    for (int i = 0; i < 3; ++i) {
      s.ft[side].force[i] = v[i];
      s.ft[side].torque[i] = v[3 + i];
    }
  }
  state.gyro_fault.apply(now, s.imu.gyro, s.imu.gyro_stamp);
  read_delta_angle();
  state.accel_fault.apply(now, s.imu.accel, s.imu.accel_stamp);
  state.ahrs_fault.apply(now, s.imu.quat, s.imu.quat_stamp);
  const int j = params.faults.encoder_joint;
  std::array<double, 1> e = {s.encoder[j]};
  state.encoder_fault.apply(now, e, s.encoder_stamp[j]);
  s.encoder[j] = e[0];
}

// The IMU's turn over the control period, integrated inside it (a strapdown IMU's delta angle, sampled at its own rate,
// free of the aliasing of one rate sample per period): the true turn between the frame's attitudes at the last two
// readings, in the frame (q_lastᶜ ⊗ q as a rotation vector), plus T times the gyro reading's error (its noise, bias,
// drift and faults), so the two channels err alike and draw nothing more from the noise generator.
void HumanoidPlant::Impl::read_delta_angle() {
  const mjData* d = state.data.get();
  humanoid::Imu& imu = state.sensors.imu;
  const double* q = d->sensordata + quat_adr;
  std::array<double, 4> last = state.last_quat;
  if (last[0] == 0 && last[1] == 0 && last[2] == 0 && last[3] == 0) last = {q[0], q[1], q[2], q[3]};
  // r = lastᶜ ⊗ q; its rotation vector 2 atan2(|v|, w) v/|v| (w ≥ 0: the shorter way).
  const std::array<double, 4> r = quat_product({last[0], -last[1], -last[2], -last[3]}, {q[0], q[1], q[2], q[3]});
  const double w = r[0];
  const std::array<double, 3> v = {r[1], r[2], r[3]};
  const double sign = w < 0 ? -1.0 : 1.0, norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const double scale = norm > 1e-300 ? 2.0 * std::atan2(norm, sign * w) / norm : 2.0;
  const double T = params.control_period;
  for (int i = 0; i < 3; ++i)
    imu.delta_angle[i] = sign * scale * v[i] + T * (imu.gyro[i] - d->sensordata[gyro_adr + i]);
  state.last_quat = {q[0], q[1], q[2], q[3]};
}

GroundTruth HumanoidPlant::truth() const {
  const Impl& p = *impl_;
  const PlantState& st = p.state;
  const mjData* d = st.data.get();
  const mjModel* m = p.model.get();
  GroundTruth g;
  g.t = d->time;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (p.joint_id[j] < 0) continue;  // absent (a rigid trunk): its truth stays 0
    const double q = d->qpos[m->jnt_qposadr[p.joint_id[j]]], v = d->qvel[m->jnt_dofadr[p.joint_id[j]]];
    g.link_angle[j] = q;
    g.link_velocity[j] = v;
    g.motor_angle[j] = st.motors[j].theta_m;
    g.gear_torque[j] = gear_torque(p.drives.params()[j], st.motors[j], q, v);
    g.servo_torque[j] = st.motors[j].servo;
  }
  for (int i = 0; i < 3; ++i) g.pelvis_pos[i] = d->qpos[i];
  for (int i = 0; i < 4; ++i) g.pelvis_quat[i] = d->qpos[3 + i];
  for (int side = 0; side < 2; ++side) {
    const double* x = d->site_xpos + 3 * p.ft_site[side];
    const double* R = d->site_xmat + 9 * p.ft_site[side];
    // The sole centre c in the site frame: p + R c (the builtin's, straight below: p − R e_z d).
    const auto& c = p.sole_center[side];
    for (int i = 0; i < 3; ++i) {
      g.sole_pos[side][i] = x[i] - R[3 * i + 2] * -c[2];
      if (c[0] != 0 || c[1] != 0) g.sole_pos[side][i] += R[3 * i] * c[0] + R[3 * i + 1] * c[1];
    }
    g.sole_yaw[side] = std::atan2(R[3], R[0]);
  }
  for (int i = 0; i < 3; ++i) g.com[i] = d->subtree_com[3 * kPelvisBody + i];
  double fz = 0, mx = 0, my = 0;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    if (!p.is_floor(con.geom1) && !p.is_floor(con.geom2)) continue;
    const int other = p.is_floor(con.geom1) ? con.geom2 : con.geom1;
    // Every contact of a foot is support (four spheres, two boxes under a foot), not a fall.
    bool foot = false;
    for (int side = 0; side < 2; ++side)
      if (other == p.sole_geom[side] || m->geom_bodyid[other] == p.foot_body[side]) foot = g.sole_contact[side] = true;
    if (!foot) g.non_sole_contact = true;
    mjtNum f[6];
    mj_contactForce(m, d, c, f);
    // Contact frame: first row of con.frame is the normal; the normal force is f[0].
    const double n = f[0] * con.frame[2];  // world z component of the normal force
    fz += n;
    mx += n * con.pos[0];
    my += n * con.pos[1];
  }
  g.normal_force = fz;
  if (fz > 1e-9) g.zmp = {mx / fz, my / fz};
  g.warnings = mujoco_warning_count(d);
  g.push_force = st.push_force;
  g.push_impulse = st.push_impulse;
  g.floor_impulse = st.floor_impulse;
  // The free joint's translational rows of M q̇: ∂T/∂v_root = Σ m_i v_i, the total linear momentum (the
  // product in MuJoCo's own scratch stack, restored at once: no allocation per period).
  mjData* scratch = st.data.get();
  const int mark = scratch->pstack;
  mjtNum* Mv = mj_stackAlloc(scratch, m->nv);
  mj_mulM(m, scratch, Mv, d->qvel);
  for (int i = 0; i < 3; ++i) g.linear_momentum[i] = Mv[i];
  scratch->pstack = mark;
  return g;
}

}  // namespace flexgait::twin
