#include "humanoid_commands.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <tuple>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/progress.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/experiments/bench_output.hpp"
#include "flexgait/experiments/compensation_study.hpp"
#include "flexgait/experiments/robot_export.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_output.hpp"
#include "flexgait/experiments/walk_pictures.hpp"
#include "flexgait/replay/scene.hpp"
#include "flexgait/twin/renderer.hpp"
#include "options.hpp"
#include "render_command.hpp"

namespace flexgait::cli {
namespace {

int bench(const RunOptions& run) {
  const Config config = resolve(experiments::bench_schema(), run);
  const experiments::BenchParams params = experiments::bench_from_config(config);
  const RunDirectory dir(run.out);  // --out before the computation
  dir.write_config(config);
  const experiments::BenchResult r = experiments::run_stiffness_bench(params);

  const std::string summary = experiments::bench_summary_json(r);
  dir.write("bench.csv", experiments::bench_csv(r));
  dir.write("summary.json", summary);
  if (run.plot) run_plot_script("plot_bench.py", {dir.path().string()});
  if (run.json) {
    fmt::print("{}", summary);
  } else {
    fmt::print("stiffness bench: k_fit = {:.6g} Nm/rad (true {:.6g}), R² = {:.5f}\n", r.k_fit, params.actuator.k,
               r.r_squared);
    fmt::print("max |link − command|: {:.5f} rad uncompensated, {:.5f} rad compensated\n", r.max_error_uncompensated,
               r.max_error_compensated);
    fmt::print("results in {}\n", dir.path().string());
  }
  if (!r.failure) return 0;
  fmt::print(stderr, "error: the stiffness bench failed: {}\n", one_line(r.failure->text(), 1000));
  return 1;
}

/// Runs the study's walks one after the other (one progress bar over all of them) and writes each
/// into its own subdirectory.
std::vector<experiments::WalkResult> run_study(const RunDirectory& dir,
                                               const std::vector<experiments::StudyCase>& cases) {
  double total = 0;
  for (const auto& c : cases) total += walking::plan_footsteps(c.params.walk).duration;
  ProgressBar bar(total, "s simulated");
  std::vector<experiments::WalkResult> results;
  double done = 0;
  for (const auto& c : cases) {
    results.push_back(experiments::run_walk(c.params, [&](double t) { bar.show(done + t); }));
    done += walking::plan_footsteps(c.params.walk).duration;
    experiments::write_walk(dir, c.name + "/", results.back());
  }
  return results;
}

/// `humanoid compensation`: thesis experiments 2-4 on one gait (off, both, both with the thesis form),
/// beside the field's baselines and the measured and dynamic loads (docs/guide/compensation.md).
int compensation_study(const RunOptions& run) {
  const Config config = resolve(experiments::walk_run_schema(), run);
  const experiments::WalkRunParams params = experiments::walk_run_from_config(config);
  const RunDirectory dir(run.out);
  dir.write_config(experiments::with_derived_values(config, params));
  const auto cases = experiments::compensation_cases(params);
  const auto results = run_study(dir, cases);
  const nlohmann::ordered_json j = experiments::compensation_comparison(cases, results);
  dir.write("comparison.json", json_file_text(j));
  if (run.plot) run_plot_script("plot_compensation.py", {dir.path().string()});
  if (run.json) {
    fmt::print("{}", json_file_text(j));
  } else {
    fmt::print(
        "{:.1f} s/step, {} steps: peak pelvis roll error {:.4f} rad off, {:.4f} rad compensated ({:.0f} % less; "
        "thesis form {:.4f})\n",
        params.walk.step_time, params.walk.steps, j["pelvis_roll_error_max_off"].get<double>(),
        j["pelvis_roll_error_max_on"].get<double>(), 100 * j["pelvis_roll_error_max_cut"].get<double>(),
        j["pelvis_roll_error_max_thesis_form"].get<double>());
    fmt::print(
        "single-support ZMP rms (y) {:.4f} m off, {:.4f} m compensated; estimated joint angles: error {:.1f} % "
        "of the deflection (rms)\n",
        j["zmp_single_support_rms_y_off"].get<double>(), j["zmp_single_support_rms_y_on"].get<double>(),
        100 * j["estimate_error_share_of_deflection"].get<double>());
    for (const auto& row : j["table"])
      fmt::print(
          "  {:<17} peak roll {:.4f} rad ({:4.0f} % less), ZMP rms y {:.4f} m, landing {:.4f} m, estimate {:5.1f} % "
          "of the deflection{}\n",
          row["case"].get<std::string>(), row["pelvis_roll_error_max"].get<double>(),
          100 * row["pelvis_roll_error_max_cut"].get<double>(), row["zmp_rms_y"].get<double>(),
          row["landing_error_mean"].get<double>(), 100 * row["estimate_error_share_of_deflection"].get<double>(),
          row["fell"].get<bool>() ? " (fell)" : "");
    fmt::print("results in {}\n", dir.path().string());
  }
  // A fall of the thesis's cases (off, both, both-thesis-form) fails the study; a comparison case
  // that falls (a baseline at a fast pace) is a result, in the table. A simulation failure always
  // fails. Either way one line on stderr says which walk and why.
  for (std::size_t i = 0; i < results.size(); ++i) {
    const auto& m = results[i].metrics;
    const bool thesis_case = i < 3;
    if (!(thesis_case && m.fell) && !m.failure) continue;
    fmt::print(stderr, "error: the {} walk {} at t = {:.2f} s: {}\n", cases[i].name, !m.failure ? "fell" : "failed",
               !m.failure ? m.fall_time : m.failure_time,
               one_line(!m.failure ? m.fall_text() : m.failure_text(), 1000));
    return 1;
  }
  return 0;
}

/// `humanoid mismatch`: the twin's stiffness scaled against the controller's belief.
int mismatch_study(const RunOptions& run, const std::vector<double>& scales) {
  const Config config = resolve(experiments::walk_run_schema(), run);
  const experiments::WalkRunParams params = experiments::walk_run_from_config(config);
  const RunDirectory dir(run.out);
  dir.write_config(experiments::with_derived_values(config, params));
  const auto cases = experiments::mismatch_cases(params, scales);
  const auto results = run_study(dir, cases);
  const nlohmann::ordered_json comparison = experiments::mismatch_comparison(cases, results);
  dir.write("comparison.json", json_file_text(comparison));
  if (run.plot) run_plot_script("plot_mismatch.py", {dir.path().string()});
  if (run.json) {
    fmt::print("{}", json_file_text(comparison));
  } else {
    for (const auto& row : comparison["rows"])
      fmt::print("true k {:6.0f} (belief {:4.0f}) Nm/rad: peak roll error {:.4f} rad off{}, {:.4f} rad compensated{}\n",
                 row["k_joint_true"].get<double>(), row["k_joint_belief"].get<double>(),
                 row["pelvis_roll_error_max_off"].get<double>(), row["fell_off"].get<bool>() ? " (fell)" : "",
                 row["pelvis_roll_error_max_on"].get<double>(), row["fell_on"].get<bool>() ? " (fell)" : "");
    fmt::print("results in {}\n", dir.path().string());
  }
  for (std::size_t i = 0; i < results.size(); ++i) {  // a fall is a result here; a failed simulation is not
    const auto& m = results[i].metrics;
    if (!m.failure) continue;
    fmt::print(stderr, "error: the {} walk failed at t = {:.2f} s: {}\n", cases[i].name, m.failure_time,
               one_line(m.failure_text(), 1000));
    return 1;
  }
  return 0;
}

struct RenderOptions {
  bool enabled = false;           ///< --render
  double fps = 25.0;              ///< --fps [1/s]
  std::string size = "1280x720";  ///< --size WIDTHxHEIGHT [pixels]
  std::string camera = "side";    ///< --camera side | follow | front
};

/// The render's view: --size and --camera checked (exit 2 naming the option), the side camera
/// framing the plan's footprints.
twin::RenderView render_view(const RenderOptions& render, const walking::WalkPlan& plan) {
  twin::RenderView view;
  std::tie(view.width, view.height) = parse_render_size(render.size, "--size", 1280, 720);
  const auto camera = twin::camera_view(render.camera);
  if (!camera)
    throw UsageError(fmt::format("--camera '{}': expected side, follow or front", one_line(render.camera, 100)));
  view.camera = *camera;
  view.walk_from = view.walk_to = plan.initial[0].x;
  auto cover = [&](const walking::Footprint& f) {
    view.walk_from = std::min(view.walk_from, f.x);
    view.walk_to = std::max(view.walk_to, f.x);
  };
  for (const auto& f : plan.initial) cover(f);
  for (const auto& f : plan.final) cover(f);
  for (const auto& step : plan.steps) cover(step.to);
  return view;
}

int walk(const RunOptions& run, const RenderOptions& render) {
  const Config config = resolve(experiments::walk_run_schema(), run);
  const experiments::WalkRunParams params = experiments::walk_run_from_config(config);
  const walking::WalkPlan plan = walking::plan_footsteps(params.walk);
  const twin::RenderView view =
      render.enabled ? render_view(render, plan) : twin::RenderView{};  // exit 2 before any file
  const RunDirectory dir(run.out);
  dir.write_config(experiments::with_derived_values(config, params));
  if (params.loaded && !run.json)
    for (int side = 0; side < 2; ++side) {
      const std::string why = walking::analytic_ik_mismatch(*params.loaded, side);
      fmt::print("{}: {} leg IK {}\n", params.description.description, side == 0 ? "left" : "right",
                 why.empty() ? "analytic" : "numeric (" + why + ")");
    }
  ProgressBar bar(plan.duration, "s simulated");
  // --render: PNG frames of the twin with the walk's markers (OSMesa, offscreen) at --fps, then
  // video.mp4 via ffmpeg; replay.html from the log's samples at 25 frames per second.
  experiments::WalkPictureOptions pictures;
  const long every = std::max(1L, std::lround(1.0 / (render.fps * params.plant.control_period)));
  if (render.enabled) {
    std::filesystem::create_directories(dir.path() / "frames");
    pictures.render = view;
    pictures.render_every = every;
  }
  pictures.replay = replay::replay_page_available();
  std::unique_ptr<experiments::WalkPictures> drawn;
  auto attach = [&](experiments::WalkLoop& w) {
    drawn = std::make_unique<experiments::WalkPictures>(
        params, w, pictures, [&](const std::vector<unsigned char>& rgb, int frame) {
          dir.write(fmt::format("frames/frame_{:05d}.png", frame), twin::encode_png(rgb, view.width, view.height));
        });
    w.loop->attach(*drawn);
  };
  // (the log streamed to disk: memory flat in the walk's length)
  experiments::WalkLogWriter log(dir, "", params.control.k_estimation != compensation::KEstimation::kOff);
  const experiments::WalkResult r = experiments::run_walk(
      params, [&](double t) { bar.show(t); }, attach,
      [&](const experiments::WalkSample& w) {
        log.add(w);
        drawn->log_sample(w);  // (the replay plots the log's columns)
      });
  log.commit();
  const int frame = drawn->frames();
  if (render.enabled) show_stage(fmt::format("encoding video.mp4 from {} frames (ffmpeg)", frame));
  if (render.enabled && !twin::encode_video(dir.path(), 1.0 / (every * params.plant.control_period)))
    fmt::print(stderr, "note: ffmpeg not found or failed; {} frames are in {}/frames\n", frame, dir.path().string());
  if (drawn->replay()) dir.write("replay.html", replay::replay_html(drawn->replay()->scene()));
  const std::string summary = json_file_text(experiments::write_walk(dir, "", r));
  if (run.plot) run_plot_script("plot_walk.py", {dir.path().string()});
  const auto& m = r.metrics;
  // A walk that did not complete (a failure, a fall, a safe stop, a step left unlanded) is exit 1
  // with one line on stderr saying why, as every command's failures are.
  std::string incomplete;
  if (m.failure)
    incomplete = fmt::format("the walk failed at t = {:.2f} s after {} of {} steps: {}", m.failure_time,
                             m.steps_completed, m.steps_planned, one_line(m.failure_text(), 1000));
  else if (m.fell)
    incomplete = fmt::format("the walk ended at t = {:.2f} s, outcome {} ({}), after {} of {} steps", m.fall_time,
                             m.outcome(), m.fall_text(), m.steps_completed, m.steps_planned);
  else if (m.safe_stop)
    incomplete = fmt::format("the walk stopped safely at t = {:.2f} s after {} of {} steps: {}", m.safe_stop_time,
                             m.steps_completed, m.steps_planned, m.safe_stop_text());
  else if (!m.completed())
    incomplete = fmt::format("the walk landed {} of {} steps", m.steps_completed, m.steps_planned);
  if (run.json) {
    fmt::print("{}", summary);
  } else {
    if (incomplete.empty())
      fmt::print("walked {} of {} steps in {:.1f} s (real-time factor {:.1f})\n", m.steps_completed, m.steps_planned,
                 m.simulated_time, m.real_time_factor);
    fmt::print("ZMP rms error x {:.4f} m, y {:.4f} m; pelvis roll error max {:.4f} rad, pitch max {:.4f} rad\n",
               m.zmp_rms_x, m.zmp_rms_y, m.pelvis_roll_error_max, m.pelvis_pitch_error_max);
    fmt::print("results in {}\n", dir.path().string());
  }
  if (incomplete.empty()) return 0;
  fmt::print(stderr, "error: {}\n", incomplete);
  return 1;
}

struct ExportOptions {
  std::string config_file;             ///< --config
  std::vector<std::string> overrides;  ///< --set
  std::string format = "mjcf";         ///< --format mjcf | urdf
  std::string out;                     ///< --out FILE
};

/// Where `humanoid export --out OUT` writes the configuration that loads OUT back: OUT with its
/// extension replaced by .yaml (OUT.config.yaml if OUT is itself a .yaml file).
std::filesystem::path reload_config_path(const std::filesystem::path& out) {
  const std::string ext = out.extension().string();
  if (ext == ".yaml" || ext == ".yml") return std::filesystem::path(out.string() + ".config.yaml");
  return std::filesystem::path(out).replace_extension(".yaml");
}

/// `humanoid export`: the twin as MJCF (elastic gears as joint springs, sensors, floor) or the
/// rigid robot as URDF, written atomically, and beside it the configuration that loads it back
/// (reload_config_path: the run's keys with robot.description naming the file and the mapping
/// of the exported names).
int export_robot(const ExportOptions& options) {
  const std::filesystem::path reload = reload_config_path(options.out);
  check_output_file(options.out, "--out");  // a device, a FIFO, a directory: refused before any work
  check_output_file(reload, "--out (its configuration beside it)");
  RunOptions run;
  run.config_file = options.config_file;
  run.overrides = options.overrides;
  const Config config = resolve(experiments::walk_run_schema(), run);
  const experiments::RobotExport exported =
      experiments::export_robot(config, options.format, std::filesystem::path(options.out).filename().string());
  write_file_atomic(options.out, exported.text);
  write_file_atomic(reload, fmt::format("# Loads {} back: flexgait humanoid walk --config {}\n{}",
                                        std::filesystem::path(options.out).filename().string(), reload.string(),
                                        exported.reload.to_yaml()));
  fmt::print("wrote {} ({}) and {} (load it back with --config {})\n", options.out, options.format, reload.string(),
             reload.string());
  return 0;
}

}  // namespace

void add_humanoid_commands(CLI::App& app, std::function<int()>& action) {
  CLI::App* humanoid = app.add_subcommand("humanoid", "THORMANG-class humanoid twin with elastic gears (MuJoCo)");
  humanoid->require_subcommand(1);
  auto run = std::make_shared<RunOptions>();
  CLI::App* b = humanoid->add_subcommand(
      "bench",
      "Stiffness bench (thesis Fig. 12): one actuator with a load arm swept through poses; fit k_joint from "
      "angle error against gravity torque, then repeat with the input compensator");
  add_run_options(*b, *run, "runs/humanoid-bench");
  b->callback([run, &action] { action = [run] { return bench(*run); }; });

  auto walk_run = std::make_shared<RunOptions>();
  auto walk_render = std::make_shared<RenderOptions>();
  CLI::App* w = humanoid->add_subcommand(
      "walk",
      "Walk the twin with the ZMP preview controller (footsteps, preview control, balance, leg IK); "
      "exit 1 if it falls");
  add_run_options(*w, *walk_run, "runs/humanoid-walk");
  w->add_flag("--render", walk_render->enabled,
              "write PNG frames of the twin to OUT/frames (offscreen, OSMesa) and OUT/video.mp4 if ffmpeg is present");
  w->add_option("--fps", walk_render->fps, "frames per second of simulated time for --render (1/s)")
      ->check(finite_number() & CLI::Range(1.0, 250.0));
  w->add_option("--size", walk_render->size, "frame size for --render, WIDTHxHEIGHT in pixels (at most 1280x720)")
      ->capture_default_str();
  w->add_option("--camera", walk_render->camera,
                "camera for --render: side (fixed, the walk passes through the frame), follow (behind the pelvis) or "
                "front (ahead of the pelvis)")
      ->capture_default_str();
  w->callback(
      [walk_run, walk_render, &action] { action = [walk_run, walk_render] { return walk(*walk_run, *walk_render); }; });

  auto exp = std::make_shared<ExportOptions>();
  CLI::App* ex = humanoid->add_subcommand(
      "export",
      "Write the robot (robot.description and its mapping; builtin by default) as MJCF (the twin: elastic "
      "gears, sensors, floor; opens in MuJoCo's simulate) or URDF (the rigid robot)");
  ex->add_option("--config", exp->config_file, "YAML configuration file (robot.*, plant.*), or a bundled one's NAME")
      ->transform(config_file_option());
  ex->add_option("--set", exp->overrides, "override one key, e.g. --set robot.description=my_robot.xml (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  ex->add_option("--format", exp->format, "mjcf or urdf")
      ->check(CLI::IsMember({"mjcf", "urdf"}))
      ->capture_default_str();
  ex->add_option("--out", exp->out, "file to write (atomically)")->required();
  ex->callback([exp, &action] { action = [exp] { return export_robot(*exp); }; });

  auto study_run = std::make_shared<RunOptions>();
  CLI::App* cs = humanoid->add_subcommand(
      "compensation",
      "Thesis experiments 2-4 on one gait (--config configs/walk-quasi-static.yaml or walk-dynamic.yaml): "
      "compensation off, both compensators (full gravity torque) and both with the thesis form, beside the field's "
      "baselines (robotis, talos) and both with the measured and dynamic loads; pelvis error "
      "(Fig. 13), ZMP (Fig. 14), estimated against true joint angles, Newton against conventional (Fig. 15); exit 1 if "
      "a walk falls");
  add_run_options(*cs, *study_run, "runs/humanoid-compensation");
  cs->callback([study_run, &action] { action = [study_run] { return compensation_study(*study_run); }; });

  auto mismatch_run = std::make_shared<RunOptions>();
  auto scales = std::make_shared<std::string>("0.7,1.0,1.3");
  CLI::App* ms = humanoid->add_subcommand(
      "mismatch",
      "The twin's true gear stiffness scaled against the controller's belief (control.k_joint): "
      "compensation off and both at each scale");
  add_run_options(*ms, *mismatch_run, "runs/humanoid-mismatch");
  ms->add_option("--scales", *scales, "true stiffness / configured plant.k_joint, comma separated")
      ->check(number_list(0.05, 20.0))
      ->capture_default_str();
  ms->callback([mismatch_run, scales, &action] {
    action = [mismatch_run, scales] {
      std::vector<double> values;
      for (const auto& text : split_list(*scales)) values.push_back(std::stod(text));  // checked by number_list
      return mismatch_study(*mismatch_run, values);
    };
  });
}

}  // namespace flexgait::cli
