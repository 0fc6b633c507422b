#include "flexgait/experiments/compensation_study.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "flexgait/experiments/walk_output.hpp"

namespace flexgait::experiments {
namespace {

using compensation::CompensationMode;
using compensation::GravityForm;

/// A case: the compensation keys that name it, the rest the base's. `lag`: the gears' Kelvin–Voigt lag believed as
/// the twin's damping (control.gear_damping = plant.gear_damping) with the short F/T low-pass.
WalkRunParams with(const WalkRunParams& base, CompensationMode mode, GravityForm form,
                   compensation::LoadModel load = compensation::LoadModel::kGravity, double horizontal_force = 0.0,
                   bool lag = false) {
  WalkRunParams p = base;
  p.control.mode = mode;
  p.control.gravity = form;
  p.control.load_model = load;
  p.control.plan_horizontal_force = horizontal_force;
  p.control.gear_damping = lag ? p.plant.gear_damping : 0.0;
  p.control.load_filter_time = lag ? compensation::kLagLoadFilterTime : compensation::kStaticLoadFilterTime;
  return p;
}

const WalkResult& result_of(const std::vector<StudyCase>& cases, const std::vector<WalkResult>& results,
                            const std::string& name) {
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (cases[i].name == name) return results.at(i);
  throw std::invalid_argument("no case named " + name);
}

/// 1 − on/off: the share of an error that compensation removes.
double cut(double off, double on) {
  return off > 0 ? 1.0 - on / off : 0.0;
}

/// The same member of off and on as KEY_off, KEY_on, KEY the member's own key in WalkMetrics
/// (declared once there).
template <class T>
void add_off_on(nlohmann::ordered_json& j, T WalkMetrics::*metric, const WalkMetrics& off, const WalkMetrics& on) {
  const std::string key = field_key(metric);
  j[key + "_off"] = off.*metric;
  j[key + "_on"] = on.*metric;
}

/// A metric compared between cases: KEY_off, KEY_on, then KEY_cut and KEY_thesis_form when asked.
struct Compared {
  double WalkMetrics::*metric;
  bool with_cut = false;
  bool with_thesis_form = false;
};

void add_compared(nlohmann::ordered_json& j, const Compared& c, const WalkMetrics& off, const WalkMetrics& on,
                  const WalkMetrics* thesis = nullptr) {
  add_off_on(j, c.metric, off, on);
  const std::string key = field_key(c.metric);
  if (c.with_cut) j[key + "_cut"] = cut(off.*c.metric, on.*c.metric);
  if (c.with_thesis_form && thesis != nullptr) j[key + "_thesis_form"] = thesis->*c.metric;
}

}  // namespace

std::string compensation_case_name(const WalkRunParams& params) {
  const compensation::CompensationParams& c = params.control;
  if (!c.input() && !c.output()) return std::string(name_of(c.mode));
  std::string name(name_of(c.mode));
  if (c.gravity == GravityForm::kThesis) name += "-thesis-form";
  if (c.load_model != compensation::LoadModel::kGravity) name += "-" + std::string(name_of(c.load_model));
  if (c.load_model == compensation::LoadModel::kDynamic && c.plan_horizontal_force > 0)
    name += c.plan_horizontal_force == 1.0 ? "-horizontal" : fmt::format("-horizontal-{:g}", c.plan_horizontal_force);
  if (c.gear_damping > 0)
    name += c.gear_damping == params.plant.gear_damping ? "-lag" : fmt::format("-lag-{:g}", c.gear_damping);
  return name;
}

std::vector<StudyCase> compensation_cases(const WalkRunParams& base) {
  using compensation::LoadModel;
  const std::vector<WalkRunParams> runs = {
      with(base, CompensationMode::kOff, base.control.gravity),
      with(base, CompensationMode::kBoth, GravityForm::kFull),
      with(base, CompensationMode::kBoth, GravityForm::kThesis),
      with(base, CompensationMode::kRobotis, GravityForm::kFull),
      with(base, CompensationMode::kTalos, GravityForm::kFull),
      with(base, CompensationMode::kBoth, GravityForm::kFull, LoadModel::kMeasured),
      with(base, CompensationMode::kBoth, GravityForm::kFull, LoadModel::kDynamic),
      with(base, CompensationMode::kBoth, GravityForm::kFull, LoadModel::kDynamic, 1.0),
      with(base, CompensationMode::kBoth, GravityForm::kFull, LoadModel::kDynamic, 1.0, true)};
  std::vector<StudyCase> cases;
  for (const WalkRunParams& p : runs) cases.push_back({compensation_case_name(p), p});
  return cases;
}

std::vector<StudyCase> mismatch_cases(const WalkRunParams& base, const std::vector<double>& scales) {
  std::vector<StudyCase> cases;
  for (const double s : scales) {
    for (const CompensationMode mode : {CompensationMode::kOff, CompensationMode::kBoth}) {
      WalkRunParams p = with(base, mode, base.control.gravity);
      p.plant.k_joint *= s;
      cases.push_back({fmt::format("k{:03.0f}-{}", 100 * s, name_of(mode)), p});
    }
  }
  return cases;
}

nlohmann::ordered_json compensation_comparison(const std::vector<StudyCase>& cases,
                                               const std::vector<WalkResult>& results) {
  const WalkMetrics& off = result_of(cases, results, "off").metrics;
  const WalkMetrics& on = result_of(cases, results, "both").metrics;
  const WalkMetrics& thesis = result_of(cases, results, "both-thesis-form").metrics;
  nlohmann::ordered_json j;
  j["step_time"] = cases.front().params.walk.step_time;
  j["steps"] = cases.front().params.walk.steps;
  j["k_joint_true"] = cases.front().params.plant.gear_stiffness()[humanoid::kLeftHipRoll];
  j["k_joint_belief"] = cases.front().params.control.stiffness()[humanoid::kLeftHipRoll];
  j["weight_split"] = std::string(name_of(cases.front().params.control.split));
  for (const Compared& c :
       {Compared{&WalkMetrics::pelvis_roll_error_max, true, true}, Compared{&WalkMetrics::pelvis_pitch_error_max},
        Compared{&WalkMetrics::zmp_single_support_rms_y, true}, Compared{&WalkMetrics::zmp_rms_x},
        Compared{&WalkMetrics::landing_error_mean}, Compared{&WalkMetrics::link_error_rms, false, true}})
    add_compared(j, c, off, on, &thesis);
  j["deflection_rms"] = on.deflection_rms;
  j["estimate_error_rms"] = on.estimate_error_rms;
  j["estimate_error_share_of_deflection"] = on.deflection_rms > 0 ? on.estimate_error_rms / on.deflection_rms : 0.0;
  j["one_step_error_rms"] = on.one_step_error_rms;
  j["conventional_error_rms"] = on.conventional_error_rms;
  j["newton_conventional_max"] = on.newton_conventional_max;
  j["per_joint_conventional_max"] = on.per_joint_conventional_max;
  j["newton_iterations_max"] = on.newton_iterations_max;
  j["newton_failures"] = on.newton_failures;
  nlohmann::ordered_json fell, table = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const WalkMetrics& m = results[i].metrics;
    fell[cases[i].name] = m.fell;
    // Without an output compensator the controller's joint angles are the encoders': their error
    // is the whole deflection (share 1).
    const bool output = cases[i].params.control.output();
    nlohmann::ordered_json row;
    row["case"] = cases[i].name;
    row["compensation"] = std::string(name_of(cases[i].params.control.mode));
    row["load_model"] = std::string(name_of(cases[i].params.control.load_model));
    row["fell"] = m.fell;
    row["pelvis_roll_error_max"] = m.pelvis_roll_error_max;
    row["pelvis_roll_error_max_cut"] = cut(off.pelvis_roll_error_max, m.pelvis_roll_error_max);
    row["zmp_rms_x"] = m.zmp_rms_x;
    row["zmp_rms_y"] = m.zmp_rms_y;
    row["landing_error_mean"] = m.landing_error_mean;
    row["estimate_error_share_of_deflection"] =
        !output ? 1.0 : (m.deflection_rms > 0 ? m.estimate_error_rms / m.deflection_rms : 0.0);
    table.push_back(row);
  }
  j["fell"] = fell;
  j["table"] = table;
  nlohmann::ordered_json all;
  for (std::size_t i = 0; i < cases.size(); ++i) all[cases[i].name] = walk_summary(results[i]);
  j["cases"] = all;
  return j;
}

nlohmann::ordered_json mismatch_comparison(const std::vector<StudyCase>& cases,
                                           const std::vector<WalkResult>& results) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i + 1 < cases.size(); i += 2) {
    const WalkRunParams& p = cases[i].params;
    const WalkMetrics& off = results[i].metrics;
    const WalkMetrics& on = results[i + 1].metrics;
    nlohmann::ordered_json r;
    r["k_joint_true"] = p.plant.gear_stiffness()[humanoid::kLeftHipRoll];
    r["k_joint_belief"] = p.control.stiffness()[humanoid::kLeftHipRoll];
    add_off_on(r, &WalkMetrics::fell, off, on);
    r["steps_off"] = off.steps_completed;  // (the key predates WalkMetrics' steps_completed)
    r["steps_on"] = on.steps_completed;
    for (const Compared& c : {Compared{&WalkMetrics::pelvis_roll_error_max, true},
                              Compared{&WalkMetrics::zmp_single_support_rms_y}, Compared{&WalkMetrics::link_error_rms}})
      add_compared(r, c, off, on);
    rows.push_back(r);
  }
  nlohmann::ordered_json j;
  j["step_time"] = cases.front().params.walk.step_time;
  j["steps"] = cases.front().params.walk.steps;
  j["balance_enabled"] = cases.front().params.balance.enabled;
  j["rows"] = rows;
  return j;
}

}  // namespace flexgait::experiments
