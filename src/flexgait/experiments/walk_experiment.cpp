#include "flexgait/experiments/walk_experiment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cmath>

#include "flexgait/compensation/chain_stiffness_calibration.hpp"
#include "flexgait/compensation/stiffness_estimator.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/experiments/capture_point_bound.hpp"
#include "flexgait/experiments/push_timing.hpp"
#include "flexgait/experiments/support_polygon.hpp"
#include "flexgait/experiments/walk_judge.hpp"
#include "flexgait/walking/foot_wrench.hpp"
#include "flexgait/twin/plant.hpp"
#include "flexgait/twin/robot_loader.hpp"
#include "flexgait/twin/twin_mjcf.hpp"

namespace flexgait::experiments {
namespace {

struct Accumulator {  // root mean square and maximum of |value|
  double sum2 = 0, max = 0;
  int n = 0;
  void add(double v) {
    sum2 += v * v;
    max = std::max(max, std::abs(v));
    ++n;
  }
  double rms() const { return n > 0 ? std::sqrt(sum2 / n) : 0.0; }
};

bool finite_truth(const humanoid::GroundTruth& g) {
  auto finite = [](const auto& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
  };
  return finite(g.link_angle) && finite(g.link_velocity) && finite(g.motor_angle) && finite(g.pelvis_pos) &&
         finite(g.pelvis_quat) && finite(g.com);
}

/// The ground truth the walk's judge reads, with the soles in the plan's frame.
SupportSample support_sample(const humanoid::GroundTruth& g, const humanoid::Terrain& terrain, const Eigen::Vector2d& offset) {
  SupportSample s;
  s.t = g.t;
  s.sole_contact = g.sole_contact;
  s.other_contact = g.non_sole_contact;
  // (the pelvis's height above the floor under it: terrain.hpp)
  s.pelvis_height = g.pelvis_pos[2] - terrain.height(g.pelvis_pos[0], g.pelvis_pos[1]);
  s.pelvis_R = walking::quat_to_matrix(g.pelvis_quat.data());
  for (int side = 0; side < 2; ++side) {
    s.sole[side] = Eigen::Vector2d(g.sole_pos[side][0], g.sole_pos[side][1]) - offset;
    s.sole_height[side] = g.sole_pos[side][2] - terrain.height(g.sole_pos[side][0], g.sole_pos[side][1]);
  }
  return s;
}

PlannedSupport planned_support(const walking::FeetTarget& feet) {
  PlannedSupport p;
  for (int side = 0; side < 2; ++side) {
    p.sole[side] = feet.sole[side].p.head<2>();
    p.swinging[side] = feet.swinging[side];
  }
  return p;
}

/// The judge's limits for this robot and walk (walk_judge.hpp states why each is what it is).
JudgeLimits judge_limits(const WalkRunParams& p, const walking::RobotModel& model) {
  JudgeLimits L;
  L.pelvis_height = p.walk.pelvis_height;
  L.fall_height = p.fall_height;
  L.fall_tilt = p.fall_tilt;
  L.position_tolerance = 0.5 * std::min(model.sole_length, model.sole_width);
  L.sole_lift_tolerance = 0.1 * model.sole_length;
  return L;
}

/// The robot's own walking height and step width where the configuration leaves them to it
/// (walk.pelvis_height, walk.step_width: auto, the defaults; docs/guide/robot.md).
void apply_stance_defaults(const Config& c, const walking::RobotModel& model, walking::WalkParams& walk) {
  const walking::StanceDefaults d = walking::stance_defaults(model);
  if (c.derived("walk.pelvis_height")) walk.pelvis_height = d.pelvis_height;
  if (c.derived("walk.step_width")) walk.step_width = d.step_width;
}

/// A stance the legs cannot take: hip to ankle between 45 % and 97.5 % of thigh + shank (the
/// builtin: pelvis 0.478–0.793 m), soles apart. And a step the legs cannot take: the controller
/// walks at walk.pelvis_height above z = 0 (it is not told of the step), so a foot landing on a
/// step up must fold its leg by h (hip to ankle at least 5 % of thigh + shank, as standing_pose)
/// and one reaching down a step must stretch by |h|.
void check_reach(const WalkRunParams& p, const walking::RobotModel& model) {
  const walking::LegReach reach = walking::leg_reach(model);
  const double L = reach.length, leg = walking::hip_to_ankle(reach, p.walk.pelvis_height);
  const double lowest = reach.stretched_height - 0.55 * L, highest = reach.stretched_height - 0.025 * L;
  if (leg < 0.45 * L || leg > 0.975 * L)
    throw ConfigError("walk.pelvis_height",
                      fmt::format("key 'walk.pelvis_height' = '{}': this robot's legs ({:.4f} m thigh + shank, {:.4f} m "
                                  "stretched) stand with the pelvis from {:.4f} to {:.4f} m (hip to ankle 45-97.5 % of "
                                  "the leg)", p.walk.pelvis_height, L, reach.stretched_height, lowest, highest));
  if (p.walk.step_width <= model.sole_width)
    throw ConfigError("walk.step_width", fmt::format("key 'walk.step_width' = '{}': the soles ({:.4f} m wide) would "
                                                     "overlap; allowed: more than {:.4f} m",
                                                     p.walk.step_width, model.sole_width, model.sole_width));
  const humanoid::TerrainParams& t = p.plant.terrain;
  if (t.kind != humanoid::TerrainKind::kStep) return;
  const double up = leg - 0.05 * L, down = L - leg;
  if (t.step_height > up || -t.step_height > down)
    throw ConfigError("terrain.step.height",
                      fmt::format("key 'terrain.step.height' = '{}': beyond the legs' reach at walk.pelvis_height = {} "
                                  "(from {:.4f} to {:.4f} m)", t.step_height, p.walk.pelvis_height, -down, up));
}

}  // namespace

WalkRunParams walk_run_from_config(const Config& c) {
  WalkRunParams p = record_from_config<WalkRunParams>(c);
  check_with_origin(c, [&] { p.plant = humanoid::plant_from_config(c); });  // with its cross-key check
  p.controller_robot = p.robot;
  if (!p.description.builtin()) {
    // A relative path given in a configuration file is relative to that file.
    const std::string& origin = c.origin("robot.description");
    const auto colon = origin.rfind(':');
    const std::filesystem::path path(p.description.description);
    if (path.is_relative() && colon != std::string::npos && std::filesystem::is_regular_file(origin.substr(0, colon)))
      p.description.description = (std::filesystem::path(origin.substr(0, colon)).parent_path() / path).string();
    check_with_origin(c, [&] {
      p.loaded = std::make_shared<const humanoid::LoadedRobot>(humanoid::load_robot(p.description));
    });
  }
  check_with_origin(c, [&] {
    const walking::RobotModel model = walk_controller_model(p);  // refuses a foot the controller cannot handle
    apply_stance_defaults(c, model, p.walk);
    check_reach(p, model);
    walking::check_standing_pose(model, p.walk.pelvis_height, p.walk.step_width);
  });
  if (p.control.compensated_feedback && !p.control.output())
    throw ConfigError("control.compensated_feedback",
                      "key 'control.compensated_feedback' = 'true' needs the output compensator's estimate; allowed "
                      "with control.compensation output or both");
  if (p.control.plan_horizontal_force > 0 && p.control.load_model != compensation::LoadModel::kDynamic)
    throw ConfigError("control.plan_horizontal_force",
                      fmt::format("key 'control.plan_horizontal_force' = '{}' needs the plan's motion; allowed with "
                                  "control.load_model dynamic (else 0)",
                                  p.control.plan_horizontal_force));
  const walking::CalibrationMotion& calibration = p.walk.calibration;
  if (calibration.time > 0 && calibration.end() > p.walk.start_time - p.walk.preview_time)
    throw ConfigError("calibration.time",
                      fmt::format("key 'calibration.time' = '{}' does not end before the COM moves to the first step "
                                  "(walk.preview_time before it); allowed: 0 to walk.start_time - walk.preview_time - "
                                  "calibration.start = {:.6g} s (lengthen walk.start_time)",
                                  calibration.time, p.walk.start_time - p.walk.preview_time - calibration.start));
  if (p.control.k_estimation == compensation::KEstimation::kCalibrate &&
      p.control.load_model == compensation::LoadModel::kGravity)
    throw ConfigError("control.k_estimation",
                      "key 'control.k_estimation' = 'calibrate' needs each foot's measured load (the weight split "
                      "misplaces the ankles' torques by tens of percent); allowed with control.load_model measured or "
                      "dynamic");
  if (p.control.k_estimation == compensation::KEstimation::kCalibrate && !(calibration.time > 0))
    throw ConfigError("control.k_estimation",
                      "key 'control.k_estimation' = 'calibrate' needs the calibration in the start stance; allowed "
                      "with calibration.time > 0 (configs/calibrate-stiffness.yaml)");
  // (the gyro's rest: the still start stance, after the calibration's motion)
  const double still = p.walk.start_time - p.walk.preview_time - calibration.end();
  if (p.control.k_estimation_gyro_rest > 0 && p.control.k_estimation_gyro_rest > still)
    throw ConfigError("control.k_estimation_gyro_rest",
                      fmt::format("key 'control.k_estimation_gyro_rest' = '{}' is longer than the still start stance (the "
                                  "COM moves from walk.preview_time before the first step, and the calibration's motion "
                                  "ends at calibration.start + calibration.time); allowed: 0 to {:.6g} s (lengthen "
                                  "walk.start_time)",
                                  p.control.k_estimation_gyro_rest, still));
  check_with_origin(c, [&] {
    const walking::WalkPlan plan = walking::plan_footsteps(p.walk);
    for (std::size_t i = 0; i < p.pushes.size(); ++i)
      check_push_timing(p.pushes[i], plan, fmt::format("disturbance.pushes[{}].", i));
    check_push_timing(p.push, plan, "disturbance.push.");
  });
  return p;
}

Config with_derived_values(const Config& config, const WalkRunParams& params) {
  Config out = config;
  for (const auto& [key, value] : {std::pair{"walk.pelvis_height", params.walk.pelvis_height},
                                   std::pair{"walk.step_width", params.walk.step_width}})
    if (out.derived(key)) out.set(key, format_number(value), "auto (from the robot)");
  return out;
}

humanoid::TwinModel walk_twin(const WalkRunParams& params) {
  if (!params.loaded) return humanoid::builtin_twin(params.robot, params.plant);
  humanoid::TwinModel t;
  t.mjcf = humanoid::twin_mjcf(*params.loaded, params.robot, params.plant);
  for (int side = 0; side < 2; ++side) t.sole_center[side] = params.loaded->sole[side].center;
  return t;
}

walking::RobotModel walk_controller_model(const WalkRunParams& params) {
  return params.loaded ? walking::make_robot_model(*params.loaded) : walking::make_robot_model(params.controller_robot);
}

WalkResult run_walk(const WalkRunParams& params, const std::function<void(double)>& progress,
                    const std::function<void(const humanoid::HumanoidPlant&)>& observe,
                    const std::function<void(const WalkSample&)>& record) {
  const auto wall0 = std::chrono::steady_clock::now();
  const double T = params.plant.control_period;
  walking::WalkingController controller(walk_controller_model(params), params.walk, params.balance, T, params.estimator,
                                        params.health);
  compensation::DeformationCompensator compensator(controller.model(), params.control, T);
  controller.set_plan_motion(params.control.load_model == compensation::LoadModel::kDynamic);
  const bool k_estimation = params.control.k_estimation == compensation::KEstimation::kOn;
  const bool k_calibration = params.control.k_estimation == compensation::KEstimation::kCalibrate;
  compensation::ChainStiffnessCalibration chain_calibration(controller.model(), params.control, T, params.walk.calibration.start,
                                                            params.walk.calibration.end());
  // (the start stance is still until the preview sees the first step: the end of the gyro's calibration at rest)
  compensation::StiffnessEstimator stiffness_estimator(
      controller.model(), params.control, T,
      controller.plan().steps.empty() ? controller.plan().duration
                                      : controller.plan().steps.front().t_begin - params.walk.preview_time);
  humanoid::HumanoidPlant plant(walk_twin(params), params.plant);
  // (the plan's frame taken as the world's: the twin's initial feet sit within millimetres of the plan's)
  if (params.plant.terrain.known_heights) controller.know_floor([&](double x, double y) { return plant.terrain().height(x, y); });
  plant.reset(controller.initial_pose());
  const std::vector<humanoid::Push> pushes =
      timed_pushes(humanoid::all_pushes(params.pushes, params.push), controller.plan());
  plant.set_pushes(pushes);
  // The capture-point bound is taken for the earliest push (summary.json).
  const humanoid::Push first_push =
      pushes.empty() ? params.push
                     : *std::min_element(pushes.begin(), pushes.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  const walking::RobotModel& model = controller.model();

  WalkResult out;
  out.log_streamed = static_cast<bool>(record);
  out.plan = controller.plan();
  WalkMetrics& m = out.metrics;
  m.steps_planned = static_cast<int>(out.plan.steps.size());
  m.joint_ranges = params.loaded && std::any_of(model.range.begin(), model.range.end(), [](const auto& r) {
    return std::isfinite(r[0]) || std::isfinite(r[1]);
  });
  m.riccati_residual = controller.gains().riccati_residual;
  m.compensation = params.control.mode;
  m.gravity_model = params.control.gravity;
  m.pushed = !pushes.empty();
  bool bound_taken = false;

  // Truth → plan frame: the offset between the initial feet.
  humanoid::GroundTruth g = plant.truth();
  const Eigen::Vector2d offset =
      0.5 * (Eigen::Vector2d(g.sole_pos[0][0], g.sole_pos[0][1]) + Eigen::Vector2d(g.sole_pos[1][0], g.sole_pos[1][1])) -
      0.5 * (Eigen::Vector2d(out.plan.initial[0].x, out.plan.initial[0].y) +
             Eigen::Vector2d(out.plan.initial[1].x, out.plan.initial[1].y));

  const long ticks = std::lround(out.plan.duration / T);
  const long log_every = std::max(1L, std::lround(params.log_period / T));
  const double t_walk0 = out.plan.steps.empty() ? 0.0 : out.plan.steps.front().t_begin;
  Accumulator zx, zy, zss, zft, zbelief, roll, pitch, com;
  Accumulator deflection, estimate_error, one_step_error, conventional_error, newton_vs_conventional,
      per_joint_vs_conventional, link_error;
  Accumulator roll_kin_encoder, roll_kin_estimate, attitude_error;
  unsigned flags_since_log = 0;
  long newton_calls = 0, newton_iterations = 0;
  m.support_margin_min = INFINITY;
  std::size_t next_landing = 0;
  const double settle = 0.5 * params.walk.dsp_ratio * params.walk.step_time;  // after touchdown
  const double length = model.sole_length, width = model.sole_width;
  std::vector<walking::Pose> support;
  support.reserve(2);
  WalkJudge judge(judge_limits(params, model));

  // control.compensated_feedback: the output compensator's last deflection estimate θ̂ − θ_enc,
  // added to the encoders the controller reads (the gears move little in one period).
  humanoid::JointVector deflection_estimate{};
  humanoid::SensorReadings readings;
  for (long k = 0; k < ticks; ++k) {
    const double t = k * T;
    readings = plant.sensors();
    if (params.control.compensated_feedback)
      for (int j = 0; j < humanoid::kJoints; ++j) readings.encoder[j] += deflection_estimate[j];
    const humanoid::JointVector& desired = controller.update(readings, t);
    const walking::ControllerStatus& st = controller.status();
    // The readings as the controller used them (bad values held by its health check), with the
    // encoders' own values.
    humanoid::SensorReadings sensors = controller.sensors();
    if (params.control.compensated_feedback)
      for (int j = 0; j < humanoid::kJoints; ++j) sensors.encoder[j] -= deflection_estimate[j];
    flags_since_log |= st.sensor_flags;
    // The thesis's Fig. 2: input compensator → robot → encoders → output compensator.
    compensation::SupportPlan plan_now{st.swinging, st.sole, st.zmp_ref, st.pelvis, -1.0, st.motion};
    if ((st.swinging[0] || st.swinging[1]) && st.step >= 0 && st.step < static_cast<int>(controller.plan().steps.size())) {
      const walking::Step& s = controller.plan().steps[static_cast<std::size_t>(st.step)];
      plan_now.single_support_phase = std::clamp((t - s.t_lift) / (s.t_land - s.t_lift), 0.0, 1.0);
    }
    if (params.control.load_model != compensation::LoadModel::kGravity) compensator.sense(sensors.ft);
    humanoid::JointVector command = compensator.input(desired, st.pelvis.R, plan_now);
    if (params.loaded) m.joint_limit_hits += walking::clamp_to_ranges(model, command);  // never silent
    controller.sent(command);
    const compensation::OutputEstimate* estimate =
        params.control.output() ? &compensator.output(sensors.encoder, controller.attitude(), plan_now) : nullptr;
    if (estimate && params.control.compensated_feedback)
      for (int j = 0; j < humanoid::kJoints; ++j) deflection_estimate[j] = estimate->newton[j] - sensors.encoder[j];
    if (k_estimation || k_calibration) {
      // Stiffness identification (docs/guide/compensation.md): the torque the output compensator solved with.
      const humanoid::JointVector& tau =
          estimate ? estimate->gravity_torque : compensator.torque(sensors.encoder, controller.attitude(), plan_now);
      if (k_estimation) {
        stiffness_estimator.update(t, sensors.encoder, controller.attitude(), sensors.imu, tau, sensors.ft, plan_now,
                                   st.sensor_flags == 0);
        compensator.set_stiffness(stiffness_estimator.stiffness());
      } else {
        chain_calibration.update(t, sensors.encoder, tau, sensors.ft, plan_now, st.sensor_flags == 0);
        compensator.set_stiffness(chain_calibration.stiffness());
      }
    }
    const humanoid::GroundTruth before = plant.truth();  // the state the sensors read
    const Eigen::Matrix3d R_before = walking::quat_to_matrix(before.pelvis_quat.data());
    const double roll_true = walking::roll_of(R_before), pitch_true = walking::pitch_of(R_before);
    const humanoid::JointVector encoder = sensors.encoder;  // (the plant's sensors change on step)
    const bool in_walk = before.t >= t_walk0 && before.t <= out.plan.t_settle;
    if (m.pushed && !bound_taken && before.t + 0.5 * params.plant.physics_dt >= first_push.time) {
      // The capture-point bound of the push's direction, where the robot stands as it begins.
      bound_taken = true;
      const Eigen::Vector2d direction(first_push.force[0], first_push.force[1]);
      std::vector<walking::Pose> soles;
      for (int side = 0; side < 2; ++side)
        if (before.sole_contact[side])
          soles.push_back({Eigen::Vector3d(before.sole_pos[side][0], before.sole_pos[side][1], 0), walking::rot_z(before.sole_yaw[side])});
      if (direction.norm() > 0)
        m.capture_point_bound = capture_point_bound(plant.total_mass(), before.com[2] - plant.terrain().height(before.com[0], before.com[1]),
                                                    plant.gravity(),
                                                    support_polygon(soles, length, width),
                                                    Eigen::Vector2d(before.com[0], before.com[1]), direction)
                                    .impulse;
    }
    if (estimate) {
      ++newton_calls;
      newton_iterations += estimate->iterations;
      m.newton_iterations_max = std::max(m.newton_iterations_max, estimate->iterations);
      m.newton_failures += !estimate->converged;
    }
    // Pelvis roll by kinematics from the stance sole, assumed flat at its true heading (eq. 1).
    double roll_enc = 0, roll_est = 0;
    const int stance = st.swinging[0] ? 1 : (st.swinging[1] ? 0 : -1);
    if (stance >= 0) {
      auto roll_through = [&](const humanoid::JointVector& q) {
        walking::LegAngles a{};
        for (int i = 0; i < humanoid::kLegJoints; ++i) a[i] = q[humanoid::leg_first_joint(stance) + i];
        const walking::Pose local = walking::leg_forward_kinematics(model.leg[stance], a);
        return walking::roll_of(walking::rot_z(before.sole_yaw[stance]) * local.R.transpose());
      };
      roll_enc = roll_through(sensors.encoder);
      if (estimate) roll_est = roll_through(estimate->newton);
    }
    if (in_walk) {
      for (int side = 0; side < 2; ++side)
        for (int i = 0; i < humanoid::kLegJoints; ++i) {
          const int j = humanoid::leg_first_joint(side) + i;
          deflection.add(sensors.encoder[j] - before.link_angle[j]);
          link_error.add(before.link_angle[j] - st.desired[j]);
          if (!estimate) continue;
          estimate_error.add(estimate->newton[j] - before.link_angle[j]);
          one_step_error.add(estimate->one_step[j] - before.link_angle[j]);
          conventional_error.add(estimate->conventional[j] - before.link_angle[j]);
          newton_vs_conventional.add(estimate->newton[j] - estimate->conventional[j]);
          per_joint_vs_conventional.add(estimate->per_joint[j] - estimate->conventional[j]);
        }
      attitude_error.add(std::hypot(st.imu_roll - roll_true, st.imu_pitch - pitch_true));
      if (stance >= 0) {
        roll_kin_encoder.add(roll_enc - st.imu_roll);
        if (estimate) roll_kin_estimate.add(roll_est - st.imu_roll);
      }
    }
    plant.step(command);
    if (observe) observe(plant);
    g = plant.truth();
    const double t_now = g.t;

    // The simulation's own failures end the walk: MuJoCo's warnings (it has already reset an
    // unstable state or dropped contacts), or a state that is no longer finite.
    if (g.warnings > 0)
      m.failure = WalkFailure{SimulationFailure::kMuJoCoWarning, plant.warnings_text()};
    else if (!finite_truth(g))
      m.failure = WalkFailure{SimulationFailure::kDiverged, {}};
    if (m.failure) {
      m.failure_time = t_now;
      break;
    }

    // Falls and lost support (walk_judge.hpp).
    const SupportSample sample = support_sample(g, plant.terrain(), offset);
    const walking::FeetTarget planned_feet = walking::feet_target(controller.plan(), params.walk.swing_height, t_now);
    m.fall_reason = judge.check(sample, planned_support(planned_feet));
    if (m.fall_reason) {
      m.fell = true;
      m.fall_time = t_now;
    }

    // Scores over the walk (from the first step's double support on).
    const Eigen::Vector2d zmp_true = Eigen::Vector2d(g.zmp[0], g.zmp[1]) - offset;
    const Eigen::Vector2d com_true = Eigen::Vector2d(g.com[0], g.com[1]) - offset;
    // The true support polygon: the soles touching the floor, where they really are.
    support.clear();
    for (int side = 0; side < 2; ++side)
      if (g.sole_contact[side])
        support.push_back({Eigen::Vector3d(g.sole_pos[side][0] - offset.x(), g.sole_pos[side][1] - offset.y(), 0),
                           walking::rot_z(g.sole_yaw[side])});
    const double margin = support_margin(support_polygon(support, length, width), zmp_true);
    const walking::FeetTarget feet = walking::feet_target(out.plan, params.walk.swing_height, t_now);
    if (t_now >= t_walk0 && t_now <= out.plan.t_settle && !m.fell) {
      zx.add(zmp_true.x() - st.zmp_ref.x());
      zy.add(zmp_true.y() - st.zmp_ref.y());
      if (feet.swinging[0] || feet.swinging[1]) zss.add(zmp_true.y() - st.zmp_ref.y());
      if (st.zmp_valid) zbelief.add((st.zmp_measured - zmp_true).norm());
      // The sensors' ZMP with the soles where they really are: sensor consistency.
      double fz = 0;
      Eigen::Vector2d moment = Eigen::Vector2d::Zero();
      for (int side = 0; side < 2; ++side) {
        const Eigen::Matrix3d R = walking::rot_z(g.sole_yaw[side]);
        const walking::FootContact c = walking::foot_contact(plant.sensors().ft[side], R, model.leg[side].ankle_to_sole,
                                                             model.bodies[static_cast<std::size_t>(model.foot[side])].mass,
                                                             model.sole_offset[side].head<2>());
        if (c.normal_force <= 1.0) continue;
        moment += c.normal_force * (Eigen::Vector2d(g.sole_pos[side][0], g.sole_pos[side][1]) - offset +
                                    R.topLeftCorner<2, 2>() * c.cop);
        fz += c.normal_force;
      }
      const unsigned ft_bits = (1U << humanoid::kFtLeft) | (1U << humanoid::kFtRight);
      if (fz > params.balance.contact_force && (st.sensor_flags & ft_bits) == 0) zft.add((moment / fz - zmp_true).norm());
      roll.add(roll_true);
      pitch.add(pitch_true);
      com.add((com_true - st.com_ref).norm());
      m.support_margin_min = std::min(m.support_margin_min, margin);
      for (int side = 0; side < 2; ++side) m.ik_clamped += st.ik[side] != walking::IkStatus::kOk;
    }
    // Landings, once the foot has settled.
    // (steps a safe stop dropped are never landed)
    // (the controller's plan: a safe stop cuts it, step adjustment moves its landings or adds a recovery step)
    while (next_landing < controller.plan().steps.size() && t_now >= controller.plan().steps[next_landing].t_land + settle &&
           !m.fell) {
      const walking::Step& s = controller.plan().steps[next_landing];
      Landing l;
      l.step = static_cast<int>(next_landing);
      l.side = s.swing;
      l.planned_x = s.to.x;
      l.planned_y = s.to.y;
      l.planned_yaw = s.to.yaw;
      l.actual_x = g.sole_pos[s.swing][0] - offset.x();
      l.actual_y = g.sole_pos[s.swing][1] - offset.y();
      l.actual_yaw = g.sole_yaw[s.swing];
      l.error = std::hypot(l.actual_x - l.planned_x, l.actual_y - l.planned_y);
      out.landings.push_back(l);
      ++next_landing;
      m.fall_reason = judge.landing(sample, s.swing, planned_support(planned_feet));
      if (m.fall_reason) {
        m.fell = true;
        m.fall_time = t_now;
      }
    }

    if (k % log_every == 0 || m.fell) {
      WalkSample w;
      w.t = t_now;
      w.step = st.step;
      w.zmp_ref_x = st.zmp_ref.x();
      w.zmp_ref_y = st.zmp_ref.y();
      w.zmp_ft_x = st.zmp_measured.x();
      w.zmp_ft_y = st.zmp_measured.y();
      w.zmp_true_x = zmp_true.x();
      w.zmp_true_y = zmp_true.y();
      w.com_ref_x = st.com_ref.x();
      w.com_ref_y = st.com_ref.y();
      w.com_x = com_true.x();
      w.com_y = com_true.y();
      w.com_z = g.com[2];
      w.pelvis_z = g.pelvis_pos[2];
      w.imu_roll = st.imu_roll;
      w.imu_pitch = st.imu_pitch;
      w.roll_true = roll_true;
      w.pitch_true = pitch_true;
      w.sensor_faults = flags_since_log;
      w.safe_stop = st.safe_stop;
      flags_since_log = 0;
      w.roll_correction = st.roll_correction;
      w.pitch_correction = st.pitch_correction;
      w.support_margin = margin;
      for (int side = 0; side < 2; ++side)
        w.sole[side] = {g.sole_pos[side][0] - offset.x(), g.sole_pos[side][1] - offset.y(), g.sole_pos[side][2]};
      w.desired = st.desired;
      w.command = command;
      w.encoder = encoder;
      w.link = before.link_angle;
      if (estimate) {
        w.estimate = estimate->newton;
        w.conventional = estimate->conventional;
        w.per_joint = estimate->per_joint;
        w.torque_estimate = estimate->gravity_torque;
      }
      w.torque_model = compensator.input_torque();
      w.torque_true = before.gear_torque;
      if (k_estimation) w.k_estimate = stiffness_estimator.estimate();
      if (k_calibration) w.k_estimate = chain_calibration.estimate();
      w.roll_kin_encoder = roll_enc;
      w.roll_kin_estimate = roll_est;
      w.push_force = g.push_force;
      w.dcm = {st.dcm.x(), st.dcm.y()};
      w.dcm_ref = {st.dcm_ref.x(), st.dcm_ref.y()};
      if (record)
        record(w);
      else
        out.log.push_back(w);
    }
    if (progress && k % 250 == 0) progress(t_now);
    if (m.fell) break;
  }
  if (progress) progress(out.plan.duration);
  if (!m.fell && !m.failure) {  // the walk ran to its end: it must end supported
    m.fall_reason = judge.at_end(support_sample(g, plant.terrain(), offset),
                                 planned_support(walking::feet_target(controller.plan(), params.walk.swing_height, g.t)));
    if (m.fall_reason) {
      m.fell = true;
      m.fall_time = g.t;
    }
  }

  // (a missed step's landing is logged in footsteps.csv but not completed)
  m.steps_completed = static_cast<int>(out.landings.size()) - (m.fall_reason == FallReason::kMissedStep ? 1 : 0);
  m.support_error_max = judge.support_error_max();
  m.steps_planned = std::max(m.steps_planned, static_cast<int>(controller.plan().steps.size()));  // with a recovery step
  m.zmp_rms_x = zx.rms();
  m.zmp_rms_y = zy.rms();
  m.zmp_max_x = zx.max;
  m.zmp_max_y = zy.max;
  m.zmp_single_support_rms_y = zss.rms();
  m.zmp_ft_rms_error = zft.rms();
  m.zmp_controller_rms_error = zbelief.rms();
  m.pelvis_roll_error_max = roll.max;
  m.pelvis_roll_error_rms = roll.rms();
  m.pelvis_pitch_error_max = pitch.max;
  m.pelvis_pitch_error_rms = pitch.rms();
  for (const auto& l : out.landings) {
    m.landing_error_max = std::max(m.landing_error_max, l.error);
    m.landing_error_mean += l.error / static_cast<double>(out.landings.size());
  }
  m.deflection_rms = deflection.rms();
  m.deflection_max = deflection.max;
  m.estimate_error_rms = estimate_error.rms();
  m.estimate_error_max = estimate_error.max;
  m.one_step_error_rms = one_step_error.rms();
  m.conventional_error_rms = conventional_error.rms();
  m.conventional_error_max = conventional_error.max;
  m.newton_conventional_max = newton_vs_conventional.max;
  m.per_joint_conventional_max = per_joint_vs_conventional.max;
  m.link_error_rms = link_error.rms();
  m.link_error_max = link_error.max;
  m.pelvis_roll_kinematic_encoder_rms = roll_kin_encoder.rms();
  m.pelvis_roll_kinematic_estimate_rms = roll_kin_estimate.rms();
  m.newton_iterations_mean = newton_calls > 0 ? static_cast<double>(newton_iterations) / newton_calls : 0.0;
  m.attitude_error_rms = attitude_error.rms();
  m.attitude_error_max = attitude_error.max;
  const walking::SensorHealth& health = controller.health();
  for (int i = 0; i < humanoid::kSensors; ++i) {
    if (health.episodes(i) == 0) continue;
    m.sensor_fault_episodes += health.episodes(i);
    m.sensor_fault_time += health.bad_time(i);
    m.sensor_faults.push_back(fmt::format("{}: {} x, {:.3f} s", humanoid::kSensorNames[i], health.episodes(i), health.bad_time(i)));
  }
  const walking::SafeStop& stop = controller.safe_stop();
  m.safe_stop = stop.active;
  if (stop.active) {
    m.safe_stop_time = stop.t;
    m.safe_stop_reason = SafeStopReason{stop.sensor, stop.fault, params.health.hold_time, stop.steps_kept,
                                        static_cast<int>(out.plan.steps.size())};
  }
  m.com_error_rms = com.rms();
  m.com_error_max = com.max;
  if (!std::isfinite(m.support_margin_min)) m.support_margin_min = 0;
  m.mujoco_warnings = g.warnings;
  m.push_impulse = std::hypot(g.push_impulse[0], g.push_impulse[1], g.push_impulse[2]);
  m.simulated_time = g.t;
  m.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  m.real_time_factor = m.wall_time > 0 ? m.simulated_time / m.wall_time : 0.0;
  if (k_estimation) {
    out.k_estimation = true;
    out.k_estimate = stiffness_estimator.estimate();
    for (int j = 0; j < humanoid::kJoints; ++j)
      out.k_identified[j] = stiffness_estimator.group(j) != compensation::StiffnessEstimator::kNone;
  }
  if (k_calibration) {
    out.k_estimation = true;
    out.k_estimate = chain_calibration.estimate();
    for (int j = 0; j < humanoid::kJoints; ++j) out.k_identified[j] = chain_calibration.identified(j);
  }
  return out;
}

}  // namespace flexgait::experiments
