#include "flexgait/humanoid/plant.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "flexgait/humanoid/model_xml.hpp"
#include "flexgait/humanoid/mujoco_messages.hpp"

namespace flexgait::humanoid {
namespace {

int require(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::logic_error("twin model has no " + name);
  return id;
}

int sensor_adr(const mjModel* m, const char* name) { return m->sensor_adr[require(m, mjOBJ_SENSOR, name)]; }

}  // namespace

JointVector standing_pose(const RobotParams& r, double pelvis_height) {
  const double leg = pelvis_height - r.hip_axes_depth - r.ankle_to_sole;  // hip axes to ankle axes
  const double reach = r.thigh + r.shank;
  if (leg <= 0.05 * reach || leg >= reach)
    throw ConfigError("walk.pelvis_height", fmt::format("key 'walk.pelvis_height' = '{}': out of the legs' reach (hip axes to ankle axes must be between 5 % and 100 % of thigh + shank)", pelvis_height));
  // Law of cosines with the hip-ankle line vertical.
  const double c_knee = (r.thigh * r.thigh + r.shank * r.shank - leg * leg) / (2 * r.thigh * r.shank);
  const double knee = std::numbers::pi - std::acos(c_knee);
  const double hip = -std::asin(r.shank * std::sin(knee) / leg);
  const double ankle = -(knee + hip);
  JointVector q{};
  for (int side = 0; side < 2; ++side) {
    const int j = leg_first_joint(side);
    q[j + 2] = hip;
    q[j + 3] = knee;
    q[j + 4] = ankle;
  }
  return q;
}

TwinModel builtin_twin(const RobotParams& robot, const PlantParams& plant) {
  TwinModel t;
  t.mjcf = humanoid_mjcf(robot, plant);
  t.sole_center = {{{0, 0, -robot.ankle_to_sole}, {0, 0, -robot.ankle_to_sole}}};
  return t;
}

HumanoidPlant::HumanoidPlant(const RobotParams& robot, const PlantParams& plant)
    : HumanoidPlant(builtin_twin(robot, plant), plant) {}

HumanoidPlant::HumanoidPlant(const TwinModel& twin, const PlantParams& plant)
    : sole_center_(twin.sole_center), params_(plant), terrain_(plant.terrain), rng_(static_cast<std::uint64_t>(plant.noise_seed)) {
  model_ = load_mjcf(twin.mjcf);
  if (params_.terrain.kind == TerrainKind::kRough) {
    // The rough floor's heights (terrain.hpp), as MuJoCo's normalised data: h = −A + 2A·data.
    const int f = require(model_, mjOBJ_HFIELD, kTerrainHfield);
    const HeightGrid& grid = terrain_.grid();
    if (model_->hfield_nrow[f] != grid.nrow || model_->hfield_ncol[f] != grid.ncol)
      throw std::logic_error("the twin's height field does not match its terrain");
    const double a = params_.terrain.rough_amplitude;
    float* data = model_->hfield_data + model_->hfield_adr[f];
    for (std::size_t i = 0; i < grid.height.size(); ++i) data[i] = static_cast<float>((grid.height[i] + a) / (2 * a));
  }
  data_ = mj_makeData(model_);
  std::vector<int> joints;
  std::vector<ActuatorParams> act;
  const JointVector stiffness = params_.gear_stiffness();
  for (int j = 0; j < kJoints; ++j) {
    joint_id_[j] = require(model_, mjOBJ_JOINT, std::string(kJointNames[j]));
    joints.push_back(joint_id_[j]);
    ActuatorParams a;
    a.k = stiffness[j];
    a.d = params_.gear_damping;
    a.backlash = params_.backlash;
    a.torque_limit = params_.torque_limit;
    a.rotor_inertia = params_.rotor_inertia;
    a.bandwidth = params_.servo_bandwidth;
    a.integral_time = params_.servo_integral_time;
    a.encoder_steps = params_.encoder_steps;
    act.push_back(a);
  }
  drives_ = std::make_unique<ElasticDrives>(model_, joints, act);
  (void)require(model_, mjOBJ_GEOM, "floor");
  push_body_ = {1, model_->jnt_bodyid[joint_id_[kWaistYaw]]};  // the root body, the waist joint's body
  sole_geom_ = {require(model_, mjOBJ_GEOM, "l_sole"), require(model_, mjOBJ_GEOM, "r_sole")};
  ft_site_ = {require(model_, mjOBJ_SITE, "l_ft"), require(model_, mjOBJ_SITE, "r_ft")};
  ft_sensor_adr_ = {sensor_adr(model_, "l_ft_force"), sensor_adr(model_, "l_ft_torque"),
                    sensor_adr(model_, "r_ft_force"), sensor_adr(model_, "r_ft_torque")};
  quat_adr_ = sensor_adr(model_, "imu_quat");
  gyro_adr_ = sensor_adr(model_, "imu_gyro");
  acc_adr_ = sensor_adr(model_, "imu_acc");
  reset(JointVector{});
}

HumanoidPlant::~HumanoidPlant() {
  if (data_ != nullptr) mj_deleteData(data_);
  if (model_ != nullptr) mj_deleteModel(model_);
}

double HumanoidPlant::time() const { return data_->time; }
double HumanoidPlant::total_mass() const { return model_->body_subtreemass[0]; }

void HumanoidPlant::reset(const JointVector& pose) {
  mj_resetData(model_, data_);
  push_force_ = push_impulse_ = floor_impulse_ = {};
  gyro_drift_ = {};
  accel_drift_ = {};
  const auto& f = params_.faults.sensor;
  const double T = params_.control_period;
  ft_fault_ = {FaultChannel<6>(f[kFtLeft], T), FaultChannel<6>(f[kFtRight], T)};
  gyro_fault_ = FaultChannel<3>(f[kGyro], T);
  accel_fault_ = FaultChannel<3>(f[kAccel], T);
  ahrs_fault_ = FaultChannel<4>(f[kAhrs], T);
  encoder_fault_ = FaultChannel<1>(f[kEncoder], T);
  for (int j = 0; j < kJoints; ++j) data_->qpos[model_->jnt_qposadr[joint_id_[j]]] = pose[j];
  // Level pelvis, then lower it until the lower sole rests on the floor.
  data_->qpos[0] = data_->qpos[1] = 0.0;
  data_->qpos[2] = 2.0;
  data_->qpos[3] = 1.0;
  data_->qpos[4] = data_->qpos[5] = data_->qpos[6] = 0.0;
  mj_kinematics(model_, data_);
  double lowest = INFINITY;
  for (int side = 0; side < 2; ++side) {
    const int g = sole_geom_[side];
    // Box bottom: centre z minus the half-extent along world z (soles are level in a level pose).
    const double* R = data_->geom_xmat + 9 * g;
    const double* h = model_->geom_size + 3 * g;
    const double* c = data_->geom_xpos + 3 * g;
    if (params_.terrain.kind == TerrainKind::kFlat) {
      const double extent = std::abs(R[6]) * h[0] + std::abs(R[7]) * h[1] + std::abs(R[8]) * h[2];
      lowest = std::min(lowest, c[2] - extent);
      continue;
    }
    // On a terrain: the sole's bottom face on a 9 × 9 grid of points, each against the floor under it.
    for (int i = -4; i <= 4; ++i)
      for (int k = -4; k <= 4; ++k) {
        const double u[3] = {0.25 * i * h[0], 0.25 * k * h[1], -h[2]};
        double p[3];
        for (int r = 0; r < 3; ++r) p[r] = c[r] + R[3 * r] * u[0] + R[3 * r + 1] * u[1] + R[3 * r + 2] * u[2];
        lowest = std::min(lowest, p[2] - terrain_.height(p[0], p[1]));
      }
  }
  data_->qpos[2] -= lowest;
  mj_forward(model_, data_);
  drives_->reset_to_links(data_);
  for (std::size_t i = 0; i < drives_->states().size(); ++i)
    model_->qpos_spring[drives_->qpos_index()[i]] = data_->qpos[drives_->qpos_index()[i]];
  read_sensors();
}

void HumanoidPlant::step(const JointVector& command) {
  const int n = params_.substeps();
  for (int k = 0; k < n; ++k) {
    apply_push();
    drives_->step(model_, data_, command.data());
    // The constraint force on the free joint's translation: the floor contacts' total (the other
    // constraints, joint limits, act within the robot and have no part there).
    for (int i = 0; i < 3; ++i) floor_impulse_[i] += model_->opt.timestep * data_->qfrc_constraint[i];
  }
  read_sensors();
}

void HumanoidPlant::set_pushes(std::vector<Push> pushes) { pushes_ = std::move(pushes); }

void HumanoidPlant::apply_push() {
  const double dt = model_->opt.timestep;
  const long n = std::lround(data_->time / dt);
  for (const int b : push_body_)
    for (int i = 0; i < 6; ++i) data_->xfrc_applied[6 * b + i] = 0.0;
  push_force_ = {};
  for (const Push& push : pushes_) {
    const bool on = push.active() && n >= std::lround(push.time / dt) && n < std::lround((push.time + push.duration) / dt);
    if (!on) continue;
    const int body = push_body_[static_cast<int>(push.body)];
    for (int i = 0; i < 3; ++i) {
      data_->xfrc_applied[6 * body + i] += push.force[i];  // force at the body's COM, world frame
      push_force_[i] += push.force[i];
    }
  }
  for (int i = 0; i < 3; ++i) push_impulse_[i] += push_force_[i] * dt;
}

void HumanoidPlant::read_sensors() {
  SensorReadings& s = sensors_;
  const double now = data_->time;
  s.t = now;
  for (int j = 0; j < kJoints; ++j) s.encoder[j] = encoder_reading(drives_->params()[j], drives_->states()[j].theta_m);
  s.encoder_stamp.fill(now);
  std::normal_distribution<double> unit(0.0, 1.0);
  auto noisy = [&](double v, double std) { return std > 0 ? v + std * unit(rng_) : v; };
  for (int side = 0; side < 2; ++side) {
    const double* f = data_->sensordata + ft_sensor_adr_[2 * side];
    const double* t = data_->sensordata + ft_sensor_adr_[2 * side + 1];
    for (int i = 0; i < 3; ++i) {
      s.ft[side].force[i] = noisy(f[i], params_.ft_force_noise);
      s.ft[side].torque[i] = noisy(t[i], params_.ft_torque_noise);
    }
    s.ft[side].stamp = now;
  }
  for (int i = 0; i < 4; ++i) s.imu.quat[i] = data_->sensordata[quat_adr_ + i];
  for (int i = 0; i < 3; ++i) {
    s.imu.gyro[i] = noisy(data_->sensordata[gyro_adr_ + i], params_.gyro_noise);
    s.imu.accel[i] = noisy(data_->sensordata[acc_adr_ + i], params_.accel_noise);
  }
  s.imu.quat_stamp = s.imu.gyro_stamp = s.imu.accel_stamp = now;
  // The IMU's bias and drift (b += σ_w √T n per period) and the AHRS output's error: draws only
  // for the terms switched on, so that the readings of earlier configurations stay the same.
  const ImuModel& imu = params_.imu;
  const double sqrt_T = std::sqrt(params_.control_period);
  for (int i = 0; i < 3; ++i) {
    gyro_drift_[i] = noisy(gyro_drift_[i], imu.gyro_bias_walk * sqrt_T);
    accel_drift_[i] = noisy(accel_drift_[i], imu.accel_bias_walk * sqrt_T);
    s.imu.gyro[i] += imu.gyro_bias + gyro_drift_[i];
    s.imu.accel[i] += imu.accel_bias + accel_drift_[i];
  }
  if (imu.ahrs_noise > 0) {
    // q ← q ⊗ [1, δ/2] (normalised), δ ~ N(0, σ²) about each body axis.
    const std::array<double, 3> d = {noisy(0, imu.ahrs_noise), noisy(0, imu.ahrs_noise), noisy(0, imu.ahrs_noise)};
    const auto q = s.imu.quat;
    const std::array<double, 4> e = {1.0, 0.5 * d[0], 0.5 * d[1], 0.5 * d[2]};
    std::array<double, 4> r = {q[0] * e[0] - q[1] * e[1] - q[2] * e[2] - q[3] * e[3],
                               q[0] * e[1] + q[1] * e[0] + q[2] * e[3] - q[3] * e[2],
                               q[0] * e[2] - q[1] * e[3] + q[2] * e[0] + q[3] * e[1],
                               q[0] * e[3] + q[1] * e[2] - q[2] * e[1] + q[3] * e[0]};
    const double n = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    for (int i = 0; i < 4; ++i) s.imu.quat[i] = r[i] / n;
  }
  if (params_.encoder_noise > 0)
    for (int j = 0; j < kJoints; ++j) s.encoder[j] = noisy(s.encoder[j], params_.encoder_noise);

  // The fault schedule.
  for (int side = 0; side < 2; ++side) {
    std::array<double, 6> v{};
    for (int i = 0; i < 3; ++i) {
      v[i] = s.ft[side].force[i];
      v[3 + i] = s.ft[side].torque[i];
    }
    ft_fault_[side].apply(now, v, s.ft[side].stamp);
    for (int i = 0; i < 3; ++i) {
      s.ft[side].force[i] = v[i];
      s.ft[side].torque[i] = v[3 + i];
    }
  }
  gyro_fault_.apply(now, s.imu.gyro, s.imu.gyro_stamp);
  accel_fault_.apply(now, s.imu.accel, s.imu.accel_stamp);
  ahrs_fault_.apply(now, s.imu.quat, s.imu.quat_stamp);
  const int j = params_.faults.encoder_joint;
  std::array<double, 1> e = {s.encoder[j]};
  encoder_fault_.apply(now, e, s.encoder_stamp[j]);
  s.encoder[j] = e[0];
}

GroundTruth HumanoidPlant::truth() const {
  GroundTruth g;
  g.t = data_->time;
  for (int j = 0; j < kJoints; ++j) {
    const double q = data_->qpos[model_->jnt_qposadr[joint_id_[j]]], v = data_->qvel[model_->jnt_dofadr[joint_id_[j]]];
    g.link_angle[j] = q;
    g.link_velocity[j] = v;
    g.motor_angle[j] = drives_->states()[j].theta_m;
    g.gear_torque[j] = gear_torque(drives_->params()[j], drives_->states()[j], q, v);
  }
  for (int i = 0; i < 3; ++i) g.pelvis_pos[i] = data_->qpos[i];
  for (int i = 0; i < 4; ++i) g.pelvis_quat[i] = data_->qpos[3 + i];
  for (int side = 0; side < 2; ++side) {
    const double* p = data_->site_xpos + 3 * ft_site_[side];
    const double* R = data_->site_xmat + 9 * ft_site_[side];
    // The sole centre c in the site frame: p + R c (the builtin's, straight below: p − R e_z d).
    const auto& c = sole_center_[side];
    for (int i = 0; i < 3; ++i) {
      g.sole_pos[side][i] = p[i] - R[3 * i + 2] * -c[2];
      if (c[0] != 0 || c[1] != 0) g.sole_pos[side][i] += R[3 * i] * c[0] + R[3 * i + 1] * c[1];
    }
    g.sole_yaw[side] = std::atan2(R[3], R[0]);
  }
  const int pelvis = 1;
  for (int i = 0; i < 3; ++i) g.com[i] = data_->subtree_com[3 * pelvis + i];
  double fz = 0, mx = 0, my = 0;
  for (int c = 0; c < data_->ncon; ++c) {
    const mjContact& con = data_->contact[c];
    if (!is_floor(con.geom1) && !is_floor(con.geom2)) continue;
    const int other = is_floor(con.geom1) ? con.geom2 : con.geom1;
    if (other != sole_geom_[0] && other != sole_geom_[1]) g.non_sole_contact = true;
    for (int side = 0; side < 2; ++side) g.sole_contact[side] = g.sole_contact[side] || other == sole_geom_[side];
    mjtNum f[6];
    mj_contactForce(model_, data_, c, f);
    // Contact frame: first row of con.frame is the normal; the normal force is f[0].
    const double n = f[0] * con.frame[2];  // world z component of the normal force
    fz += n;
    mx += n * con.pos[0];
    my += n * con.pos[1];
  }
  g.normal_force = fz;
  if (fz > 1e-9) g.zmp = {mx / fz, my / fz};
  g.warnings = mujoco_warning_count(data_);
  g.push_force = push_force_;
  g.push_impulse = push_impulse_;
  g.floor_impulse = floor_impulse_;
  // The free joint's translational rows of M q̇: ∂T/∂v_root = Σ m_i v_i, the total linear momentum.
  std::vector<mjtNum> Mv(static_cast<std::size_t>(model_->nv));
  mj_mulM(model_, data_, Mv.data(), data_->qvel);
  for (int i = 0; i < 3; ++i) g.linear_momentum[i] = Mv[static_cast<std::size_t>(i)];
  return g;
}

}  // namespace flexgait::humanoid
