// Orbit diagram: on the rigid wheel every recorded crossing after the transient is the
// closed-form fixed point ω*(φ); the long-form CSV repeats the per-value record faithfully.
#include "flexgait/rimless/orbit_diagram.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>
#include <span>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::rimless {
namespace {

// After 60 steps the distance to ω* has shrunk by r^120 = 0.728^60 ≈ 5e-9 from O(1): below the
// integration error. Each step integrates to solver.rtol = 1e-10 (ω ~ 1.5 rad/s), the error
// contracting by r² per step, so the recorded ω⁺ is within 1e-8 rad/s of ω*.
TEST(OrbitDiagram, RigidWheelRecordsTheFixedPointAtEverySlope) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  OrbitDiagramSpec spec{{"rimless.slope", 0.05, 0.2, 4}, 60, 5};
  check_orbit_diagram(base, spec);
  std::string points = "index," + orbit_points_header() + "\n";
  for (int i = 0; i < spec.sweep.count; ++i) points += std::to_string(i) + "," + orbit_points_row(base, spec, i) + "\n";
  const std::string csv = orbit_csv(points);
  const std::vector<CsvRecord> rows = parse_csv(csv);
  ASSERT_EQ(rows.size(), 1u + 4 * 5);
  EXPECT_EQ(rows[0].text, "parameter,step,mode,gait,thetad,state,failure");
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const auto& f = rows[r].fields;
    const double slope = std::stod(f[0]);
    const WheelParams w = wheel_from_config(sweep_point_config(base, SweepSpec{"rimless.slope", slope, slope, 1}, 0));
    EXPECT_NEAR(std::stod(f[4]), rigid_step_map(w).fixed_point(), 1e-8) << rows[r].text;
    EXPECT_EQ(f[4], f[5]);  // the rigid state is θ̇ alone
    EXPECT_EQ(f[6], "");
    EXPECT_EQ(f[1], std::to_string((r - 1) % 5 + 1));
  }
}

// The flexible wheel (measured parameters, μ = 0.6) at two slopes where its gait is a stable fixed
// point (|λ|max 0.75 at φ = 0.1): after 150 steps the distance to it has shrunk by 0.75^150 ≈ 1e-19,
// so every recorded crossing is Newton's fixed point up to the integration error (solver.rtol 1e-10
// per step, contracted): within 1e-7 in every component. Period 1: one distinct value.
TEST(OrbitDiagram, FlexibleWheelRecordsNewtonsFixedPoint) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  OrbitDiagramSpec spec{{"rimless.slope", 0.08, 0.12, 2}, 150, 4};
  std::string points = "index," + orbit_points_header() + "\n";
  for (int i = 0; i < spec.sweep.count; ++i) points += std::to_string(i) + "," + orbit_points_row(base, spec, i) + "\n";
  const std::vector<CsvRecord> rows = parse_csv(orbit_csv(points));
  ASSERT_EQ(rows.size(), 1u + 2 * 4);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const auto& f = rows[r].fields;
    const Config c = sweep_point_config(base, SweepSpec{"rimless.slope", std::stod(f[0]), 0, 1}, 0);
    const SimulationOptions sim = simulation_from_config(c);
    const FixedPointReport fp = find_fixed_point(wheel_from_config(c), sim, analysis_from_config(c), sim.model,
                                                 Section::Touchdown, initial_from_config(c));
    ASSERT_TRUE(fp.converged) << fp.failure();
    ASSERT_TRUE(fp.stable);
    const std::vector<std::string> z = split_text(f[5], ';');
    ASSERT_EQ(z.size(), static_cast<std::size_t>(fp.point.z.size())) << rows[r].text;
    for (std::size_t k = 0; k < z.size(); ++k)
      EXPECT_NEAR(std::stod(z[k]), fp.point.z(static_cast<Eigen::Index>(k)), 1e-7) << rows[r].text;
    EXPECT_EQ(f[3], fp.gait);
  }
  const auto summary = nlohmann::json::parse(orbit_summary_json(points));
  for (const auto& v : summary["values"]) EXPECT_EQ(v["distinct"], 1);
  EXPECT_DOUBLE_EQ(summary["period_one_until"].get<double>(), 0.12);
  EXPECT_TRUE(summary["first_multiple"].is_null());
}

TEST(OrbitDiagram, AValueThatFallsRecordsWhy) {
  // ω0 = -1 rad/s from β0 = -0.2 rad behind the top rolls back at once.
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt,
                                     {"sim.model=rigid", "initial.omega=-1", "initial.beta=-0.2"});
  OrbitDiagramSpec spec{{"rimless.slope", 0.05, 0.1, 2}, 5, 3};
  const std::string row = orbit_points_row(base, spec, 0);
  const std::string csv = orbit_csv("index," + orbit_points_header() + "\n0," + row + "\n");
  const std::vector<CsvRecord> rows = parse_csv(csv);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].fields[1], "");
  // The failure cell is the reason's text: the rigid wheel fell back onto the previous leg.
  EXPECT_EQ(rows[1].fields[6], (Failure{FailureReason::FellBack, {}, {}}).text()) << csv;
}

// Past the Neimark–Sacker point (φ = 0.226277 with the measured parameters) the orbit is
// quasi-periodic and at some crossings a free leg is still compressed or a second foot is down:
// restarting each cycle from the reduced section state left the orbit there ("infeasible section
// point: foot 0 is below the ground" after 16–42 crossings at φ = 0.2272 .. 0.2303). The diagram
// follows the full hybrid state, so its crossings are those of one uninterrupted simulation: the
// state just before every landing of a new leg after the transient. Both runs restart the
// integrator at every touchdown from the same state, so they agree to round-off; 1e-9 (rad, m/s,
// rad/s) allows the round-off's growth over 166 steps of a neutrally stable orbit.
TEST(OrbitDiagram, PastTheNeimarkSackerPointFollowsTheSimulatedOrbit) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  constexpr int kTransient = 100, kRecord = 64;
  OrbitDiagramSpec spec{{"rimless.slope", 0.2272, 0.2300, 2}, kTransient, kRecord};
  for (int i = 0; i < spec.sweep.count; ++i) {
    const std::vector<CsvRecord> rows =
        parse_csv("index," + orbit_points_header() + "\n0," + orbit_points_row(base, spec, i) + "\n");
    ASSERT_EQ(rows.size(), 2u);
    const auto& f = rows[1].fields;
    EXPECT_EQ(f[2], std::to_string(kRecord)) << rows[1].text;
    EXPECT_EQ(f[7], "") << rows[1].text;
    const std::vector<std::string> states = split_text(f[6], ';'), modes = split_text(f[3], ';');
    ASSERT_EQ(states.size(), static_cast<std::size_t>(kRecord));

    // The same wheel simulated without a stop: the state at each new leg's landing.
    const Config c = sweep_point_config(base, spec.sweep, i);
    const WheelParams w = wheel_from_config(c);
    SimulationOptions sim = simulation_from_config(c);
    sim.log = false;
    sim.max_time = std::numeric_limits<double>::infinity();
    sim.steps = kTransient + 2 + kRecord;
    struct Landings final : RunSink {
      std::vector<Restart> restarts;
      std::vector<StepRecord> steps;
      void on_step(const StepRecord& s) override { steps.push_back(s); }
      void on_restart(double t, std::span<const double> y, const ContactSet& contacts) override {
        restarts.push_back({t, {y.begin(), y.end()}, contacts});
      }
    } run;
    const SimulationResult r = simulate_flexible(w, initial_from_config(c), sim, run);
    ASSERT_FALSE(r.failure) << r.failure->text();
    ASSERT_EQ(run.steps.size(), static_cast<std::size_t>(sim.steps + 1));
    using S = StateIndex;
    for (int k = 0; k < kRecord; ++k) {
      // The transient ends at touchdown kTransient, the settled point is touchdown kTransient + 1,
      // crossing k + 1 is touchdown kTransient + 2 + k: step kTransient + 3 + k (1-based) starts there.
      const StepRecord& step = run.steps[static_cast<std::size_t>(kTransient + 2 + k)];
      const auto at =
          std::find_if(run.restarts.begin(), run.restarts.end(), [&](const Restart& x) { return x.t == step.t_start; });
      ASSERT_NE(at, run.restarts.end()) << "no restart at t = " << step.t_start;
      const std::vector<double>& y = at->state;
      std::vector<double> expected{leg_angle(w, step.stance_leg, y[S::theta])};
      if (modes[static_cast<std::size_t>(k)] != "stick") expected.push_back(y[S::xd]);
      expected.push_back(y[S::yd]);
      expected.push_back(y[S::thetad]);
      const std::vector<std::string> z = split_text(states[static_cast<std::size_t>(k)], ' ');
      ASSERT_EQ(z.size(), expected.size()) << "crossing " << k + 1;
      for (std::size_t j = 0; j < z.size(); ++j)
        EXPECT_NEAR(std::stod(z[j]), expected[j], 1e-9) << "phi " << spec.sweep.value(i) << " crossing " << k + 1;
    }
  }
}

TEST(OrbitDiagram, RefusesBadInput) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  EXPECT_THROW(check_orbit_diagram(base, {{"rimless.slope", 0.05, 0.1, 3}, 0, 5}), ConfigError);
  EXPECT_THROW(check_orbit_diagram(base, {{"rimless.slope", 0.05, 0.1, 3}, 5, 0}), ConfigError);
  EXPECT_THROW(check_orbit_diagram(base, {{"rimless.slope", 0.05, 2.0, 3}, 5, 5}), ConfigError);
}

}  // namespace
}  // namespace flexgait::rimless
