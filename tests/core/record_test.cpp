// One declaration per record (core/record.hpp): the schema, the configuration reader and JSON
// are derived from each record's single field list, so they cannot disagree. These tests check
// the derivation on every parameter record of the project.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <variant>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/parameters.hpp"
#include "flexgait/robot/robot_description.hpp"
#include "flexgait/robot/robot_params.hpp"
#include "flexgait/walking/walk_params.hpp"

namespace flexgait {
namespace {

using Value = std::variant<double, std::int64_t, bool, std::string>;

// Every field's value, by key (enums by name).
struct Collect {
  std::map<std::string, Value> values;
  template <class T>
  void operator()(std::string_view key, const T& v, const FieldInfo&) {
    if constexpr (NamedEnum<T>)
      values[std::string(key)] = std::string(name_of(v));
    else if constexpr (std::is_same_v<T, bool>)
      values[std::string(key)] = v;
    else if constexpr (std::is_integral_v<T>)
      values[std::string(key)] = static_cast<std::int64_t>(v);
    else if constexpr (std::is_same_v<T, std::string>)
      values[std::string(key)] = v;
    else
      values[std::string(key)] = static_cast<double>(v);
  }
};

template <class R>
std::map<std::string, Value> values_of(const R& r) {
  Collect c;
  R::visit_fields(r, c);
  return c.values;
}

// A value of the key's domain other than `current` (the perturbation must reach the member).
std::string other_value(const ParamSpec& p, const Value& current) {
  switch (p.type) {
    case ParamType::Boolean:
      return std::get<bool>(current) ? "false" : "true";
    case ParamType::Text:
      return std::get<std::string>(current) + "_2";
    case ParamType::Choice:
      for (const auto& c : p.choices)
        if (c != std::get<std::string>(current)) return c;
      return p.choices.front();
    case ParamType::Integer: {
      const auto v = std::get<std::int64_t>(current);
      return std::to_string(v + 1 <= p.max ? v + 1 : v - 1);
    }
    case ParamType::Real: {
      const double v = std::get<double>(current);
      const double up = v == 0 ? 1e-3 : v * (1 + 1e-3);
      const double down = v == 0 ? -1e-3 : v * (1 - 1e-3);
      const bool up_ok = p.max_inclusive ? up <= p.max : up < p.max;
      return format_value(up_ok ? up : down);
    }
    case ParamType::List:
      return {};  // no record checked here holds one (experiments/push_list_test.cpp)
    case ParamType::Reals:
      return {};  // (core/config_reals_test.cpp)
  }
  return {};
}

template <class R>
void check_record() {
  const Schema schema = schema_of<R>();
  const auto defaults = values_of(R{});
  ASSERT_EQ(schema.params().size(), defaults.size()) << "a key is listed twice";
  // The schema's default is the struct's default, exactly (to the last bit for reals).
  const Config config = resolve_config(schema, std::nullopt, {});
  EXPECT_EQ(values_of(record_from_config<R>(config)), defaults);
  // Each key reaches its own member and no other.
  for (const ParamSpec& p : schema.params()) {
    const std::string text = other_value(p, defaults.at(p.key));
    const Config changed = resolve_config(schema, std::nullopt, {p.key + "=" + text});
    const auto read = values_of(record_from_config<R>(changed));
    for (const auto& [key, value] : read) {
      if (key == p.key)
        EXPECT_NE(value, defaults.at(key)) << key << " = " << text << " did not reach its member";
      else
        EXPECT_EQ(value, defaults.at(key)) << "setting " << p.key << " changed " << key;
    }
  }
}

TEST(Record, RimlessParametersDeriveFromOneList) {
  check_record<rimless::WheelParams>();
  check_record<rimless::InitialState>();
  check_record<rimless::SimulationOptions>();
  check_record<rimless::AnalysisOptions>();
}

TEST(Record, HumanoidParametersDeriveFromOneList) {
  check_record<humanoid::RobotParams>();
  check_record<humanoid::RobotDescriptionParams>();
  check_record<twin::PlantParams>();
  check_record<experiments::BenchParams>();
  check_record<walking::WalkParams>();
  check_record<walking::BalanceParams>();
  check_record<compensation::CompensationParams>();
}

// The defect: the struct said 0 and the schema 1000.
TEST(Record, PlantStiffnessDefaultIsTheSchemasDefault) {
  const twin::PlantParams p;
  EXPECT_EQ(p.k_joint, 1000.0);
  for (const double k : p.gear_stiffness()) EXPECT_EQ(k, 1000.0);
  EXPECT_EQ(twin::plant_schema().find("plant.k_joint")->fallback, "1000.0");
}

TEST(Record, ChoicesComeFromTheEnumTable) {
  const Schema s = compensation::compensation_schema();
  EXPECT_EQ(s.find("control.compensation")->choices,
            (std::vector<std::string>{"off", "input", "output", "both", "robotis", "talos"}));
  EXPECT_EQ(s.find("control.weight_split")->fallback, "zmp");
  for (const auto& name : enum_name_list<compensation::CompensationMode>())
    EXPECT_EQ(name_of(*enum_from_name<compensation::CompensationMode>(name)), name);
  EXPECT_FALSE(enum_from_name<compensation::CompensationMode>("bothh").has_value());
  // A value outside the table is a bug, reported as such.
  EXPECT_THROW((void)name_of(static_cast<rimless::Model>(7)), std::logic_error);
}

TEST(Record, WalkRunSchemaIsTheUnionOfItsParts) {
  Schema parts = humanoid::robot_schema();
  parts.merge(schema_of<humanoid::RobotDescriptionParams>())
      .merge(twin::plant_schema())
      .merge(walking::walk_schema())
      .merge(walking::balance_schema());
  parts.merge(compensation::compensation_schema()).merge(schema_of<walking::EstimatorParams>());
  parts.merge(schema_of<walking::HealthParams>()).merge(schema_of<twin::Push>());
  const Schema run = experiments::walk_run_schema();
  ASSERT_EQ(run.params().size(), parts.params().size() + 2);  // + disturbance.pushes, output.log_period
  for (std::size_t i = 0; i < parts.params().size(); ++i) EXPECT_EQ(run.params()[i].key, parts.params()[i].key);
}

TEST(Record, JsonLeavesOutFieldsThatDoNotApply) {
  experiments::WalkMetrics m;
  m.compensation = compensation::CompensationMode::kInput;
  m.deflection_rms = 0.02;
  m.estimate_error_rms = 0.001;
  const auto off = record_json(m);
  EXPECT_FALSE(off.contains("estimate_error_rms"));
  EXPECT_EQ(off["compensation"], "input");
  m.compensation = compensation::CompensationMode::kBoth;
  m.pushed = true;        // push_impulse and capture_point_bound apply
  m.fell = true;          // fall_time applies
  m.joint_ranges = true;  // joint_limit_hits and desired_range_hits apply
  m.failure =
      experiments::WalkFailure{experiments::SimulationFailure::kMuJoCoWarning, "a warning"};  // failure_time applies
  const auto on = record_json(m);
  EXPECT_FALSE(off.contains("fall_time"));
  EXPECT_FALSE(off.contains("failure_time"));
  EXPECT_DOUBLE_EQ(on["estimate_error_share_of_deflection"].get<double>(), 0.05);
  // Every field the description lists appears when it applies, under the same key, in order.
  const auto fields = describe_record<experiments::WalkMetrics>();
  ASSERT_EQ(fields.size(), on.size());
  std::size_t i = 0;
  for (const auto& [key, value] : on.items()) EXPECT_EQ(key, fields[i++].key);
}

TEST(Record, FieldKeyNamesAMemberByItsDeclaredKey) {
  // field_key finds the member among the record's fields by address, so it agrees with the
  // schema's key for every field, nested records included; a member not declared is refused.
  using experiments::WalkMetrics;
  using experiments::WalkRunParams;
  EXPECT_EQ(field_key(&WalkMetrics::pelvis_roll_error_max), "pelvis_roll_error_max");
  EXPECT_EQ(field_key(&WalkMetrics::fell), "fell");
  EXPECT_EQ(field_key(&walking::BalanceParams::step_adjustment), "balance.step_adjustment");
  EXPECT_EQ(field_key(&walking::EstimatorParams::source), "estimator.source");
  EXPECT_THROW(field_key(&walking::EstimatorParams::gravity), std::logic_error);  // not a key
}

}  // namespace
}  // namespace flexgait
