#include "flexgait/experiments/walk_scorer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "flexgait/experiments/capture_point_bound.hpp"
#include "flexgait/experiments/compensation_study.hpp"
#include "flexgait/experiments/support_polygon.hpp"
#include "flexgait/walking/foot_wrench.hpp"

namespace flexgait::experiments {
namespace {

/// The ground truth the walk's judge reads, with the soles in the plan's frame.
SupportSample support_sample(const twin::GroundTruth& g, const twin::Terrain& terrain, const Eigen::Vector2d& offset) {
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

}  // namespace

Eigen::Vector2d plan_offset(const twin::GroundTruth& g, const walking::WalkPlan& plan) {
  return 0.5 * (Eigen::Vector2d(g.sole_pos[0][0], g.sole_pos[0][1]) +
                Eigen::Vector2d(g.sole_pos[1][0], g.sole_pos[1][1])) -
         0.5 * (Eigen::Vector2d(plan.initial[0].x, plan.initial[0].y) +
                Eigen::Vector2d(plan.initial[1].x, plan.initial[1].y));
}

double landing_settle(const WalkRunParams& params) {
  return 0.5 * params.walk.dsp_ratio * params.walk.step_time;
}

bool landing_due(const walking::WalkPlan& plan, std::size_t n, double settle, double t, bool sole_down) {
  if (n >= plan.steps.size() || t < plan.steps[n].t_land + settle) return false;
  if (sole_down) return true;
  const double deadline = n + 1 < plan.steps.size() ? plan.steps[n + 1].t_lift : plan.t_settle;
  return t >= deadline;
}

void WalkScorer::Accumulator::add(double v) {
  sum2 += v * v;
  max = std::max(max, std::abs(v));
  ++n;
}

double WalkScorer::Accumulator::rms() const {
  return n > 0 ? std::sqrt(sum2 / n) : 0.0;
}

WalkScorer::WalkScorer(const WalkRunParams& params, const walking::WalkingController& controller,
                       const twin::GroundTruth& initial, const std::vector<twin::Push>& pushes,
                       std::function<void(const WalkSample&)> record)
    : params_(params),
      controller_(controller),
      record_(std::move(record)),
      judge_(judge_limits(params, controller.model())) {
  out_.log_streamed = static_cast<bool>(record_);
  out_.plan = controller.plan();
  WalkMetrics& m = out_.metrics;
  const walking::RobotModel& model = controller.model();
  m.steps_planned = static_cast<int>(out_.plan.steps.size());
  m.joint_ranges = params.loaded && std::any_of(model.range.begin(), model.range.end(), [](const auto& r) {
                     return std::isfinite(r[0]) || std::isfinite(r[1]);
                   });
  m.riccati_residual = controller.gains().riccati_residual;
  m.compensation = params.control.mode;
  m.gravity_model = params.control.gravity;
  m.compensation_case = compensation_case_name(params);
  m.pushed = !pushes.empty();
  m.support_margin_min = INFINITY;
  first_push_ = pushes.empty() ? params.push
                               : *std::min_element(pushes.begin(), pushes.end(),
                                                   [](const auto& a, const auto& b) { return a.time < b.time; });
  offset_ = plan_offset(initial, out_.plan);
  const double T = params.plant.control_period;
  log_every_ = std::max(1L, std::lround(params.log_period / T));
  t_walk0_ = out_.plan.steps.empty() ? 0.0 : out_.plan.steps.front().t_begin;
  settle_ = landing_settle(params);
  support_.reserve(2);
  support_shapes_.reserve(2);
}

void WalkScorer::fall(std::optional<FallReason> reason, double t) {
  out_.metrics.fall_reason = reason;
  if (!reason) return;
  out_.metrics.fell = true;
  out_.metrics.fall_time = t;
}

void WalkScorer::observe(const loop::LoopStep& step) {
  score_sensing(step);
  if (step.failure) {
    WalkMetrics& m = out_.metrics;
    m.failure = WalkFailure{*step.failure,
                            *step.failure == loop::SimulationFailure::kMuJoCoWarning ? step.plant.warnings_text() : ""};
    m.failure_time = step.after.t;
    return;
  }
  score_motion(step);
}

void WalkScorer::score_sensing(const loop::LoopStep& step) {
  WalkMetrics& m = out_.metrics;
  const walking::ControllerStatus& st = controller_.status();
  const walking::RobotModel& model = controller_.model();
  const twin::GroundTruth& before = step.before;
  const humanoid::SensorReadings& sensors = step.sensors;
  const compensation::OutputEstimate* estimate = step.compensation.estimate();
  flags_since_log_ |= st.sensor_flags;
  const Eigen::Matrix3d R_before = walking::quat_to_matrix(before.pelvis_quat.data());
  roll_true_ = walking::roll_of(R_before);
  pitch_true_ = walking::pitch_of(R_before);
  const bool in_walk = before.t >= t_walk0_ && before.t <= out_.plan.t_settle;
  if (m.pushed && !bound_taken_ && before.t + 0.5 * params_.plant.physics_dt >= first_push_.time) {
    // The capture-point bound of the push's direction, where the robot stands as it begins.
    bound_taken_ = true;
    const Eigen::Vector2d direction(first_push_.force[0], first_push_.force[1]);
    std::vector<walking::Pose> soles;
    std::vector<const walking::SolePolygon*> shapes;
    for (int side = 0; side < 2; ++side)
      if (before.sole_contact[side]) {
        soles.push_back({Eigen::Vector3d(before.sole_pos[side][0], before.sole_pos[side][1], 0),
                         walking::rot_z(before.sole_yaw[side])});
        shapes.push_back(&model.sole_polygon[static_cast<std::size_t>(side)]);
      }
    const twin::HumanoidPlant& plant = step.plant;
    if (direction.norm() > 0)
      m.capture_point_bound =
          capture_point_bound(plant.total_mass(), before.com[2] - plant.terrain().height(before.com[0], before.com[1]),
                              plant.gravity(), support_polygon(soles, shapes),
                              Eigen::Vector2d(before.com[0], before.com[1]), direction)
              .impulse;
  }
  if (estimate) {
    ++newton_calls_;
    newton_iterations_ += estimate->iterations;
    m.newton_iterations_max = std::max(m.newton_iterations_max, estimate->iterations);
    m.newton_failures += !estimate->converged;
    newton_predicted_ += estimate->predicted;
  }
  // Pelvis roll by kinematics from the stance sole, assumed flat at its true heading (eq. 1).
  roll_enc_ = 0;
  roll_est_ = 0;
  const int stance = st.swinging[0] ? 1 : (st.swinging[1] ? 0 : -1);
  if (stance >= 0) {
    auto roll_through = [&](const humanoid::JointVector& q) {
      walking::LegAngles a{};
      for (int i = 0; i < humanoid::kLegJoints; ++i) a[i] = q[humanoid::leg_first_joint(stance) + i];
      const walking::Pose local = walking::leg_forward_kinematics(model.leg[stance], a);
      return walking::roll_of(walking::rot_z(before.sole_yaw[stance]) * local.R.transpose());
    };
    roll_enc_ = roll_through(sensors.encoder);
    if (estimate) roll_est_ = roll_through(estimate->newton);
  }
  if (!in_walk) return;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const int j = humanoid::leg_first_joint(side) + i;
      deflection_.add(sensors.encoder[j] - before.link_angle[j]);
      link_error_.add(before.link_angle[j] - st.desired[j]);
      if (!estimate) continue;
      estimate_error_.add(estimate->newton[j] - before.link_angle[j]);
      one_step_error_.add(estimate->one_step[j] - before.link_angle[j]);
      conventional_error_.add(estimate->conventional[j] - before.link_angle[j]);
      newton_vs_conventional_.add(estimate->newton[j] - estimate->conventional[j]);
      per_joint_vs_conventional_.add(estimate->per_joint[j] - estimate->conventional[j]);
    }
  attitude_error_.add(std::hypot(st.imu_roll - roll_true_, st.imu_pitch - pitch_true_));
  if (stance >= 0) {
    roll_kin_encoder_.add(roll_enc_ - st.imu_roll);
    if (estimate) roll_kin_estimate_.add(roll_est_ - st.imu_roll);
  }
}

void WalkScorer::score_motion(const loop::LoopStep& step) {
  WalkMetrics& m = out_.metrics;
  const walking::ControllerStatus& st = controller_.status();
  const walking::RobotModel& model = controller_.model();
  const twin::GroundTruth& g = step.after;
  const double t_now = g.t;

  // Falls and lost support (walk_judge.hpp).
  const SupportSample sample = support_sample(g, step.plant.terrain(), offset_);
  const PlannedSupport planned =
      planned_support(walking::feet_target(controller_.plan(), params_.walk.swing_height, t_now));
  fall(judge_.check(sample, planned), t_now);

  // Scores over the walk (from the first step's double support on).
  const Eigen::Vector2d zmp_true = Eigen::Vector2d(g.zmp[0], g.zmp[1]) - offset_;
  const Eigen::Vector2d com_true = Eigen::Vector2d(g.com[0], g.com[1]) - offset_;
  // The true support polygon: the soles touching the floor, where they really are.
  support_.clear();
  support_shapes_.clear();
  for (int side = 0; side < 2; ++side)
    if (g.sole_contact[side]) {
      support_.push_back({Eigen::Vector3d(g.sole_pos[side][0] - offset_.x(), g.sole_pos[side][1] - offset_.y(), 0),
                          walking::rot_z(g.sole_yaw[side])});
      support_shapes_.push_back(&model.sole_polygon[static_cast<std::size_t>(side)]);
    }
  const double margin = support_margin(support_polygon(support_, support_shapes_), zmp_true);
  if (t_now >= t_walk0_ && t_now <= out_.plan.t_settle && !m.fell) {
    zx_.add(zmp_true.x() - st.zmp_ref.x());
    zy_.add(zmp_true.y() - st.zmp_ref.y());
    // (single support of the walk as first planned)
    const walking::FeetTarget feet = walking::feet_target(out_.plan, params_.walk.swing_height, t_now);
    if (feet.swinging[0] || feet.swinging[1]) zss_.add(zmp_true.y() - st.zmp_ref.y());
    if (st.zmp_valid) zbelief_.add((st.zmp_measured - zmp_true).norm());
    // The sensors' ZMP with the soles where they really are: sensor consistency.
    double fz = 0;
    Eigen::Vector2d moment = Eigen::Vector2d::Zero();
    for (int side = 0; side < 2; ++side) {
      const Eigen::Matrix3d R = walking::rot_z(g.sole_yaw[side]);
      const walking::FootContact c =
          walking::foot_contact(step.plant.sensors().ft[side], R, model.leg[side].ankle_to_sole,
                                model.bodies[static_cast<std::size_t>(model.foot[side])].mass, model.gravity,
                                model.ft_to_sole[side].head<2>());
      if (c.normal_force <= 1.0) continue;
      moment += c.normal_force *
                (Eigen::Vector2d(g.sole_pos[side][0], g.sole_pos[side][1]) - offset_ + R.topLeftCorner<2, 2>() * c.cop);
      fz += c.normal_force;
    }
    const unsigned ft_bits = (1U << humanoid::kFtLeft) | (1U << humanoid::kFtRight);
    if (fz > params_.balance.contact_force && (st.sensor_flags & ft_bits) == 0)
      zft_.add((moment / fz - zmp_true).norm());
    roll_.add(roll_true_);
    pitch_.add(pitch_true_);
    com_.add((com_true - st.com_ref).norm());
    m.support_margin_min = std::min(m.support_margin_min, margin);
    for (int side = 0; side < 2; ++side) m.ik_clamped += st.ik[side] != walking::IkStatus::kOk;
  }
  // Landings, once the foot has settled (landing_due).
  // (steps a safe stop dropped are never landed)
  // (the controller's plan: a safe stop cuts it, step adjustment moves its landings or adds a recovery step)
  const walking::WalkPlan& plan = controller_.plan();
  const auto& steps = plan.steps;
  while (!m.fell && next_landing_ < steps.size() &&
         landing_due(plan, next_landing_, settle_, t_now, sample.sole_contact[steps[next_landing_].swing])) {
    const walking::Step& s = steps[next_landing_];
    Landing l;
    l.step = static_cast<int>(next_landing_);
    l.side = s.swing;
    l.planned_x = s.to.x;
    l.planned_y = s.to.y;
    l.planned_yaw = s.to.yaw;
    l.actual_x = g.sole_pos[s.swing][0] - offset_.x();
    l.actual_y = g.sole_pos[s.swing][1] - offset_.y();
    l.actual_yaw = g.sole_yaw[s.swing];
    l.error = std::hypot(l.actual_x - l.planned_x, l.actual_y - l.planned_y);
    out_.landings.push_back(l);
    ++next_landing_;
    fall(judge_.landing(sample, s.swing, planned), t_now);
  }
  if (step.k % log_every_ == 0 || m.fell) log_sample(step, zmp_true, com_true, margin);
}

void WalkScorer::log_sample(const loop::LoopStep& step, const Eigen::Vector2d& zmp_true,
                            const Eigen::Vector2d& com_true, double margin) {
  const walking::ControllerStatus& st = controller_.status();
  const twin::GroundTruth& g = step.after;
  const compensation::OutputEstimate* estimate = step.compensation.estimate();
  WalkSample w;
  w.t = g.t;
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
  w.pelvis_x = g.pelvis_pos[0] - offset_.x();
  w.pelvis_y = g.pelvis_pos[1] - offset_.y();
  w.imu_roll = st.imu_roll;
  w.imu_pitch = st.imu_pitch;
  w.roll_true = roll_true_;
  w.pitch_true = pitch_true_;
  w.sensor_faults = flags_since_log_;
  w.safe_stop = st.safe_stop;
  flags_since_log_ = 0;
  w.roll_correction = st.roll_correction;
  w.pitch_correction = st.pitch_correction;
  w.support_margin = margin;
  for (int side = 0; side < 2; ++side)
    w.sole[side] = {g.sole_pos[side][0] - offset_.x(), g.sole_pos[side][1] - offset_.y(), g.sole_pos[side][2]};
  w.desired = st.desired;
  w.command = step.command;
  w.encoder = step.sensors.encoder;
  w.link = step.before.link_angle;
  if (estimate) {
    w.estimate = estimate->newton;
    w.conventional = estimate->conventional;
    w.per_joint = estimate->per_joint;
    w.torque_estimate = estimate->gravity_torque;
  }
  w.torque_model = step.compensation.input_torque();
  w.torque_true = step.before.gear_torque;
  if (const auto k = step.compensation.k_estimate()) w.k_estimate = *k;
  w.roll_kin_encoder = roll_enc_;
  w.roll_kin_estimate = roll_est_;
  w.push_force = g.push_force;
  w.foot_force = st.foot_force;
  w.dcm = {st.dcm.x(), st.dcm.y()};
  w.dcm_ref = {st.dcm_ref.x(), st.dcm_ref.y()};
  if (record_)
    record_(w);
  else
    out_.log.push_back(w);
}

WalkResult WalkScorer::finish(const loop::HumanoidLoop& loop) {
  WalkMetrics& m = out_.metrics;
  const twin::GroundTruth& g = loop.truth();
  if (!m.fell && !m.failure)  // the walk ran to its end: it must end supported
    fall(judge_.at_end(support_sample(g, loop.plant().terrain(), offset_),
                       planned_support(walking::feet_target(controller_.plan(), params_.walk.swing_height, g.t))),
         g.t);
  // (a missed step's landing is logged in footsteps.csv but not completed)
  m.steps_completed = static_cast<int>(out_.landings.size()) - (m.fall_reason == FallReason::kMissedStep ? 1 : 0);
  m.support_error_max = judge_.support_error_max();
  m.steps_planned =
      std::max(m.steps_planned, static_cast<int>(controller_.plan().steps.size()));  // with a recovery step
  m.joint_limit_hits = static_cast<int>(loop.joint_limit_hits());
  m.desired_range_hits = static_cast<int>(loop.desired_range_hits());
  m.zmp_rms_x = zx_.rms();
  m.zmp_rms_y = zy_.rms();
  m.zmp_max_x = zx_.max;
  m.zmp_max_y = zy_.max;
  m.zmp_single_support_rms_y = zss_.rms();
  m.zmp_ft_rms_error = zft_.rms();
  m.zmp_controller_rms_error = zbelief_.rms();
  m.pelvis_roll_error_max = roll_.max;
  m.pelvis_roll_error_rms = roll_.rms();
  m.pelvis_pitch_error_max = pitch_.max;
  m.pelvis_pitch_error_rms = pitch_.rms();
  for (const auto& l : out_.landings) {
    m.landing_error_max = std::max(m.landing_error_max, l.error);
    m.landing_error_mean += l.error / static_cast<double>(out_.landings.size());
  }
  m.deflection_rms = deflection_.rms();
  m.deflection_max = deflection_.max;
  m.estimate_error_rms = estimate_error_.rms();
  m.estimate_error_max = estimate_error_.max;
  m.one_step_error_rms = one_step_error_.rms();
  m.conventional_error_rms = conventional_error_.rms();
  m.conventional_error_max = conventional_error_.max;
  m.newton_conventional_max = newton_vs_conventional_.max;
  m.per_joint_conventional_max = per_joint_vs_conventional_.max;
  m.link_error_rms = link_error_.rms();
  m.link_error_max = link_error_.max;
  m.pelvis_roll_kinematic_encoder_rms = roll_kin_encoder_.rms();
  m.pelvis_roll_kinematic_estimate_rms = roll_kin_estimate_.rms();
  m.newton_iterations_mean = newton_calls_ > 0 ? static_cast<double>(newton_iterations_) / newton_calls_ : 0.0;
  m.newton_predicted_share = newton_calls_ > 0 ? static_cast<double>(newton_predicted_) / newton_calls_ : 0.0;
  m.attitude_error_rms = attitude_error_.rms();
  m.attitude_error_max = attitude_error_.max;
  const walking::SensorHealth& health = controller_.health();
  for (int i = 0; i < humanoid::kSensors; ++i) {
    if (health.episodes(i) == 0) continue;
    m.sensor_fault_episodes += health.episodes(i);
    m.sensor_fault_time += health.bad_time(i);
    m.sensor_faults.push_back(
        fmt::format("{}: {} x, {:.3f} s", humanoid::kSensorNames[i], health.episodes(i), health.bad_time(i)));
  }
  const walking::SafeStop& stop = controller_.safe_stop();
  m.safe_stop = stop.active;
  if (stop.active) {
    m.safe_stop_time = stop.t;
    m.safe_stop_reason = SafeStopReason{stop.sensor, stop.fault, params_.health.hold_time, stop.steps_kept,
                                        static_cast<int>(out_.plan.steps.size())};
  }
  m.com_error_rms = com_.rms();
  m.com_error_max = com_.max;
  if (!std::isfinite(m.support_margin_min)) m.support_margin_min = 0;
  m.mujoco_warnings = g.warnings;
  m.push_impulse = std::hypot(g.push_impulse[0], g.push_impulse[1], g.push_impulse[2]);
  m.simulated_time = g.t;
  if (const auto k = loop.compensation().k_estimate()) {
    out_.k_estimation = true;
    out_.k_estimate = *k;
    out_.k_relative_std = *loop.compensation().k_relative_std();
    for (int j = 0; j < humanoid::kJoints; ++j) out_.k_identified[j] = loop.compensation().k_identified(j);
  }
  return std::move(out_);
}

}  // namespace flexgait::experiments
