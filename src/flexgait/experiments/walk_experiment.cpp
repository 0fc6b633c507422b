#include "flexgait/experiments/walk_experiment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "flexgait/core/text.hpp"
#include "flexgait/experiments/push_timing.hpp"
#include "flexgait/experiments/walk_scorer.hpp"
#include "flexgait/twin/plant.hpp"
#include "flexgait/twin/robot_loader.hpp"
#include "flexgait/twin/twin_mjcf.hpp"

namespace flexgait::experiments {
namespace {

/// x rounded up to the millimetre [m].
double to_millimetre_up(double x) {
  return std::ceil(x * 1000.0 - 1e-9) / 1000.0;
}

/// The robot's own defaults where the configuration leaves them to it (the keys left `auto`; docs/guide/robot.md):
/// the walking height and step width (stance_defaults.hpp) for every robot, and for a loaded description the
/// keys of walking::kScaledDefaults scaled from the builtin's values by the robot's size, the torque limits
/// from the file's actuators where it has them (each joint its own while plant.torque_limit is derived), and
/// a step width scaled as the legs.
/// The builtin robot keeps the builtin's values (the rules' reference). Each value derived is also put in
/// p.derived, for config.yaml.
void apply_robot_defaults(const Config& c, const walking::RobotModel& model, WalkRunParams& p) {
  const walking::StanceDefaults d = walking::stance_defaults(model);
  Config resolved = c;
  const auto derive = [&](const std::string& key, double value) {
    if (!c.derived(key)) return;
    p.derived.emplace_back(key, value);
    resolved.set(key, format_number(value), "auto (from the robot)");
  };
  derive("walk.pelvis_height", d.pelvis_height);
  if (p.loaded) {
    const walking::RobotModel reference = walking::make_robot_model(humanoid::RobotParams{});
    const double pelvis = c.derived("walk.pelvis_height") ? d.pelvis_height : c.real("walk.pelvis_height");
    const walking::RobotScale scale =
        walking::robot_scale(model, pelvis, reference, walking::stance_defaults(reference).pelvis_height);
    const double actuators = walking::leg_actuator_torque(*p.loaded);
    for (const walking::ScaledDefault& rule : walking::kScaledDefaults) {
      const std::string key(rule.key);
      if (key == "plant.physics_dt") continue;                                  // from the gears, below
      if (key == "control.k_joint" || key == "balance.capture_torque_limit") {  // the plant's, set or derived
        derive(key, resolved.real(key == "control.k_joint" ? "plant.k_joint" : "plant.torque_limit"));
        continue;
      }
      derive(key, key == "plant.torque_limit" && actuators > 0 ? actuators
                                                               : walking::scaled_default(rule, c.real(key), scale));
    }
    // The physics step: 1 ms, halved while the fastest gear mode (each gear's stiffness against the inertia its
    // joint turns) turns more than walking::kMaxGearPhasePerStep per step (MuJoCo takes the gear springs explicitly).
    derive("plant.physics_dt",
           walking::gear_physics_step(
               walking::fastest_gear_mode(*p.loaded, twin::plant_from_config(resolved).gear_stiffness()),
               c.real("plant.physics_dt")));
    p.plant = twin::plant_from_config(resolved);
    // Each joint's servo at the file's own limit where the file has one, the rest at plant.torque_limit as
    // derived; plant.torque_limit set by the user holds every joint (docs/guide/robot.md, "Torque limits").
    if (c.derived("plant.torque_limit")) p.plant.joint_torque_limit = walking::joint_actuator_torques(*p.loaded);
    p.walk = record_from_config<walking::WalkParams>(resolved);
    p.balance = record_from_config<walking::BalanceParams>(resolved);
    // The capture step's torque check holds each joint to its servo's own limit (derived with plant.torque_limit).
    if (c.derived("balance.capture_torque_limit")) p.balance.capture_joint_torque_limit = p.plant.joint_torque_limit;
    p.control = compensation::compensation_from_config(resolved);
    // The hip spacing, at most the builtin's width scaled with the leg (the sideways sway, and with it the
    // legs' roll, scales so), at least the soles' width + 2 cm.
    derive(
        "walk.step_width",
        std::max(std::min(d.step_width, walking::scaled_default({"", 0, 1, 0, ""}, c.real("walk.step_width"), scale)),
                 to_millimetre_up(model.sole_width + 0.02)));
  } else {
    for (const walking::ScaledDefault& rule : walking::kScaledDefaults)
      derive(std::string(rule.key), c.real(std::string(rule.key)));
    derive("walk.step_width", d.step_width);
  }
  if (c.derived("walk.pelvis_height")) p.walk.pelvis_height = d.pelvis_height;
  if (c.derived("walk.step_width")) p.walk.step_width = resolved.real("walk.step_width");
}

/// The default compensation case of `humanoid walk`, both-dynamic-horizontal-lag (docs/guide/compensation.md, "The
/// default case"): when the compensators of ours run (control.compensation input, output, both), their keys left
/// unset take the physics the 1 s walk needs — the dynamic loads, the plan's whole ground wrench
/// (control.plan_horizontal_force 1, with the dynamic loads only), the gears' damping believed at the plant's, the F/T
/// low-pass short (kLagLoadFilterTime) when that damping is believed — and, with the output compensator, the
/// controller's kinematic estimators read the link angles it estimates (control.compensated_feedback; spec eq. 1):
/// the encoders carry the deflection the compensator adds, so a COM or tilt estimate from the encoders alone is off
/// by it, and the dcm stabiliser read that offset as a DCM error and pushed the robot back by the compensation.
/// Off and the field's baselines keep the schema's defaults (the thesis's static model): they run none of it.
void resolve_compensation_defaults(const Config& c, WalkRunParams& p) {
  compensation::CompensationParams& k = p.control;
  if (!k.input() && !k.output()) return;
  const auto resolve = [&](const std::string& key, auto& field, auto value, const std::string& text) {
    if (c.origin(key) != "default") return;
    field = value;
    p.case_defaults.emplace_back(key, text);
  };
  if (k.output()) resolve("control.compensated_feedback", k.compensated_feedback, true, "true");
  resolve("control.load_model", k.load_model, compensation::LoadModel::kDynamic, "dynamic");
  if (k.load_model == compensation::LoadModel::kDynamic)
    resolve("control.plan_horizontal_force", k.plan_horizontal_force, 1.0, "1");
  resolve("control.gear_damping", k.gear_damping, p.plant.gear_damping, format_number(p.plant.gear_damping));
  if (k.gear_damping > 0)
    resolve("control.load_filter_time", k.load_filter_time, compensation::kLagLoadFilterTime,
            format_number(compensation::kLagLoadFilterTime));
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
    throw ConfigError(
        "walk.pelvis_height",
        fmt::format("key 'walk.pelvis_height' = '{}': this robot's legs ({:.4f} m thigh + shank, {:.4f} m "
                    "stretched) stand with the pelvis from {:.4f} to {:.4f} m (hip to ankle 45-97.5 % of "
                    "the leg)",
                    p.walk.pelvis_height, L, reach.stretched_height, lowest, highest));
  if (p.walk.step_width <= model.sole_width)
    throw ConfigError("walk.step_width", fmt::format("key 'walk.step_width' = '{}': the soles ({:.4f} m wide) would "
                                                     "overlap; allowed: more than {:.4f} m",
                                                     p.walk.step_width, model.sole_width, model.sole_width));
  const twin::TerrainParams& t = p.plant.terrain;
  if (t.kind != twin::TerrainKind::kStep) return;
  const double up = leg - 0.05 * L, down = L - leg;
  if (t.step_height > up || -t.step_height > down)
    throw ConfigError("terrain.step.height",
                      fmt::format("key 'terrain.step.height' = '{}': beyond the legs' reach at walk.pelvis_height = {} "
                                  "(from {:.4f} to {:.4f} m)",
                                  t.step_height, p.walk.pelvis_height, -down, up));
}

}  // namespace

WalkRunParams walk_run_from_config(const Config& c) {
  WalkRunParams p = record_from_config<WalkRunParams>(c);
  check_with_origin(c, [&] { p.plant = twin::plant_from_config(c); });  // with its cross-key check
  p.controller_robot = p.robot;
  if (!p.description.builtin()) {
    // A relative path given in a configuration file is relative to that file.
    const std::string& origin = c.origin("robot.description");
    const auto colon = origin.rfind(':');
    const std::filesystem::path path(p.description.description);
    if (path.is_relative() && colon != std::string::npos && std::filesystem::is_regular_file(origin.substr(0, colon)))
      p.description.description = (std::filesystem::path(origin.substr(0, colon)).parent_path() / path).string();
    check_with_origin(
        c, [&] { p.loaded = std::make_shared<const humanoid::LoadedRobot>(twin::load_robot(p.description)); });
  }
  check_with_origin(c, [&] {
    const walking::RobotModel model = walk_controller_model(p);  // refuses a foot the controller cannot handle
    apply_robot_defaults(c, model, p);
    check_reach(p, model);
    walking::check_standing_pose(model, p.walk.pelvis_height, p.walk.step_width);
  });
  resolve_compensation_defaults(c, p);
  if (p.control.compensated_feedback && !p.control.output())
    throw ConfigError("control.compensated_feedback",
                      "key 'control.compensated_feedback' = 'true' needs the output compensator's estimate; allowed "
                      "with control.compensation output or both");
  if (p.control.plan_horizontal_force > 0 && p.control.load_model != compensation::LoadModel::kDynamic)
    throw ConfigError("control.plan_horizontal_force",
                      fmt::format("key 'control.plan_horizontal_force' = '{}' needs the plan's motion; allowed with "
                                  "control.load_model dynamic (else 0)",
                                  p.control.plan_horizontal_force));
  if (p.control.k_estimation_per_joint && p.control.k_estimation_torque != compensation::KTorque::kMeasured)
    throw ConfigError("control.k_estimation_per_joint",
                      "key 'control.k_estimation_per_joint' = 'true' needs each joint's torque measured: the parallel "
                      "joints' modelled torques move together while walking and their few-percent errors leave the "
                      "joints apart ill-determined; allowed with control.k_estimation_torque measured");
  // The controller believes its servos' datasheet: the rotors' inertia the plant has.
  if (c.origin("control.rotor_inertia") == "default") p.control.rotor_inertia = p.plant.rotor_inertia;
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
    throw ConfigError(
        "control.k_estimation_gyro_rest",
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
  // (a loaded robot's config.yaml says which values were derived, kDerivedOrigin; the builtin's keeps its bytes)
  // (plant.torque_limit and balance.capture_torque_limit stay auto where the file limits joints of its own: set,
  // one value would hold every joint)
  const humanoid::JointVector& own = params.plant.joint_torque_limit;
  const bool own_limits = std::any_of(own.begin(), own.end(), [](double x) { return x > 0; });
  for (const auto& [key, value] : params.derived)
    if (out.derived(key) && !(own_limits && (key == "plant.torque_limit" || key == "balance.capture_torque_limit")))
      out.set(key, format_number(value), params.loaded ? kDerivedOrigin : "auto (from the robot)");
  for (const auto& [key, value] : params.case_defaults) out.set(key, value, "default (the compensation case)");
  return out;
}

Schema walk_run_schema() {
  const Schema keys = schema_of<WalkRunParams>();
  Schema out;
  for (ParamSpec spec : keys.params()) {
    for (const walking::ScaledDefault& rule : walking::kScaledDefaults)
      if (spec.key == rule.key) spec.derived = std::string(rule.rule) + "; the builtin robot keeps the builtin's";
    out.add(std::move(spec));
  }
  for (const ParamAlias& a : keys.aliases()) out.alias(a.key, a.parts, a.doc);
  return out;
}

twin::TwinModel walk_twin(const WalkRunParams& params) {
  if (!params.loaded) return twin::builtin_twin(params.robot, params.plant);
  twin::TwinModel t;
  t.mjcf = twin::twin_mjcf(*params.loaded, params.robot, params.plant);
  for (int side = 0; side < 2; ++side) t.sole_center[side] = twin::sole_center_in_site(params.loaded->sole[side]);
  return t;
}

walking::RobotModel walk_controller_model(const WalkRunParams& params) {
  return params.loaded ? walking::make_robot_model(*params.loaded) : walking::make_robot_model(params.controller_robot);
}

loop::LoopSetup walk_loop_setup(const WalkRunParams& params, const walking::RobotModel& model,
                                const walking::WalkPlan& plan) {
  loop::LoopSetup setup{walk_twin(params), params.plant, model, params.control, {}, static_cast<bool>(params.loaded)};
  // (the start stance is still until the preview sees the first step: the end of the gyro's calibration at rest)
  setup.windows.rest_end = plan.steps.empty() ? plan.duration : plan.steps.front().t_begin - params.walk.preview_time;
  setup.windows.calibration_begin = params.walk.calibration.start;
  setup.windows.calibration_end = params.walk.calibration.end();
  return setup;
}

WalkLoop make_walk_loop(const WalkRunParams& params, std::shared_ptr<loop::Controller> controller_in_its_place) {
  walking::WalkingController controller(walk_controller_model(params), params.walk, params.balance,
                                        params.plant.control_period, params.estimator, params.health);
  controller.set_plan_motion(params.control.load_model == compensation::LoadModel::kDynamic);
  const loop::LoopSetup setup = walk_loop_setup(params, controller.model(), controller.plan());
  WalkLoop w;
  w.control = std::make_shared<loop::WalkingControl>(std::move(controller));
  w.loop = std::make_unique<loop::HumanoidLoop>(setup, controller_in_its_place
                                                           ? std::move(controller_in_its_place)
                                                           : std::shared_ptr<loop::Controller>(w.control));
  walking::WalkingController& c = w.control->controller();
  // (the plan's frame taken as the world's: the twin's initial feet sit within millimetres of the plan's)
  const twin::Terrain& terrain = w.loop->plant().terrain();
  if (params.plant.terrain.known_heights) c.know_floor([&](double x, double y) { return terrain.height(x, y); });
  w.loop->reset(c.initial_pose());
  w.pushes = timed_pushes(twin::all_pushes(params.pushes, params.push), c.plan());
  w.loop->plant().set_pushes(w.pushes);
  return w;
}

WalkResult run_walk(const WalkRunParams& params, const std::function<void(double)>& progress,
                    const std::function<void(WalkLoop&)>& attach,
                    const std::function<void(const WalkSample&)>& record) {
  const auto wall0 = std::chrono::steady_clock::now();
  WalkLoop w = make_walk_loop(params);
  const walking::WalkingController& controller = w.control->controller();
  WalkScorer scorer(params, controller, w.loop->truth(), w.pushes, record);
  w.loop->attach(scorer);
  if (attach) attach(w);

  const long ticks = std::lround(controller.plan().duration / params.plant.control_period);
  const double duration = controller.plan().duration;
  for (long k = 0; k < ticks; ++k) {
    if (w.loop->step()) break;
    if (progress && k % 250 == 0) progress(w.loop->time());
    if (scorer.fell()) break;
  }
  if (progress) progress(duration);
  WalkResult out = scorer.finish(*w.loop);
  WalkMetrics& m = out.metrics;
  m.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  m.real_time_factor = m.wall_time > 0 ? m.simulated_time / m.wall_time : 0.0;
  return out;
}

}  // namespace flexgait::experiments
