// The paper's analyses read their parameters from the analysis.* keys (analyses.hpp): the
// defaults are the values the analyses always used, a set value reaches the analysis, and an
// inconsistent pair is refused naming its key.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/basin.hpp"
#include "flexgait/rimless/orbit_diagram.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::rimless {
namespace {

Config configured(const std::vector<std::string>& sets) {
  return resolve_config(rimless_analysis_schema(), std::nullopt, sets);
}

std::size_t rows(const std::string& csv) {
  std::istringstream in(csv);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n - 1;  // the header
}

// Exact equality: the defaults must be the literals the command line held, so that every output
// byte of `flexgait rimless analysis` stays the same.
TEST(PaperAnalysisOptions, DefaultsAreTheFormerLiterals) {
  const PaperAnalysisOptions o = paper_analysis_from_config(configured({}));
  EXPECT_EQ(o.friction_mu_from, 0.1);
  EXPECT_EQ(o.friction_mu_to, 1.5);
  EXPECT_EQ(o.friction_count, 100);
  EXPECT_EQ(o.threshold_tol, 1e-8);
  EXPECT_EQ(o.continued_bracket, 1e-4);
  EXPECT_EQ(o.split_depth, 4);
  EXPECT_EQ(o.transient_factors, (std::vector<double>{1, 3, 9}));
  EXPECT_EQ(o.continuation_steps, (std::vector<double>{1, 4, 16}));
  EXPECT_EQ(o.energy_mu, (std::vector<double>{0.6, 0.105}));
  EXPECT_EQ(o.fixed_points_mu, (std::vector<double>{0.105, 0.13, 0.2, 0.6}));
  EXPECT_EQ(o.robustness_mu, (std::vector<double>{0.105, 0.6}));
  EXPECT_EQ(o.max_steps, 300);
  EXPECT_EQ(o.return_tol, 1e-6);
  // The ε grid was 1e-3 · 10^(k/4), k = 0..12: the log-spaced (min, max, count) grid gives the same
  // doubles (log10 of 1 and 1e-3 are exact, k·3/12 rounds as k/4).
  const std::vector<double> eps = robustness_epsilons(o);
  ASSERT_EQ(eps.size(), 13u);
  for (int k = 0; k <= 12; ++k) EXPECT_EQ(eps[static_cast<std::size_t>(k)], 1e-3 * std::pow(10.0, k / 4.0)) << k;
}

// orbit-diagram's and basin's lengths, formerly the defaults of their options.
TEST(PaperAnalysisOptions, MapDefaultsAreTheFormerOptionDefaults) {
  const Config c = configured({});
  EXPECT_EQ(record_from_config<OrbitDiagramOptions>(c).transient, 100);
  EXPECT_EQ(record_from_config<OrbitDiagramOptions>(c).record, 30);
  EXPECT_EQ(record_from_config<BasinOptions>(c).steps_limit, 200);
  EXPECT_EQ(record_from_config<BasinOptions>(c).tolerance, 1e-6);
  EXPECT_EQ(record_from_config<OrbitDiagramOptions>(configured({"analysis.orbit.record=7"})).record, 7);
}

TEST(PaperAnalysisOptions, EpsilonGridEndsAndOnePoint) {
  PaperAnalysisOptions o;
  o.epsilon_min = 2e-3;
  o.epsilon_max = 2e-1;
  o.epsilon_count = 3;
  const std::vector<double> eps = robustness_epsilons(o);
  ASSERT_EQ(eps.size(), 3u);
  // Relative 1e-15: a few roundings of pow and log10.
  EXPECT_NEAR(eps[0], 2e-3, 1e-15 * 2e-3);
  EXPECT_NEAR(eps[1], 2e-2, 1e-15 * 2e-2);
  EXPECT_NEAR(eps[2], 2e-1, 1e-15 * 2e-1);
  o.epsilon_count = 1;
  EXPECT_EQ(robustness_epsilons(o), std::vector<double>{2e-3});
}

TEST(PaperAnalysisOptions, EpsilonMaxBelowMinNamesTheKey) {
  try {
    paper_analysis_from_config(configured({"analysis.robustness.epsilon_max=1e-4"}));
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "analysis.robustness.epsilon_max");
    EXPECT_NE(std::string(e.what()).find("--set: key 'analysis.robustness.epsilon_max' = '0.0001'"), std::string::npos)
        << e.what();
  }
}

// A factor or a step count is a whole number: 2.5 is refused naming its key.
TEST(PaperAnalysisOptions, FractionalCountNamesTheKey) {
  for (const std::string key : {"analysis.friction.transient_factors", "analysis.friction.continuation_steps"}) {
    try {
      paper_analysis_from_config(configured({key + "=[1, 2.5]"}));
      ADD_FAILURE() << "no ConfigError for " << key;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.key(), key);
      EXPECT_NE(std::string(e.what()).find("'2.5'"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(paper_analysis_from_config(configured({"analysis.friction.transient_factors=[2, 5]"})).transient_factors,
            (std::vector<double>{2, 5}));
}

// The energy analysis logs one periodic step: its rows end within the fixed point's period (the
// run stops at the next touchdown), and its last row is close to it (the step's single support ends
// with the touchdown or a short double support before it).
TEST(PaperAnalysisOptions, EnergyLogIsOneStep) {
  const Config c = configured({});
  const std::string csv = single_support_energy_csv(c, {0.6});
  ASSERT_GT(rows(csv), 10u) << csv;
  std::istringstream in(csv);
  std::string line, last;
  while (std::getline(in, line)) last = line;
  std::vector<std::string> cells;
  for (std::size_t from = 0, comma = 0; comma != std::string::npos; from = comma + 1) {
    comma = last.find(',', from);
    cells.push_back(last.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
  }
  ASSERT_EQ(cells.size(), 7u) << last;
  const double t_last = std::stod(cells[3]);  // mu, gait, phase, t
  const Config at = configured({"rimless.mu_s=0.6", "rimless.mu_k=0.6"});
  const FixedPointReport r =
      find_fixed_point(wheel_from_config(at), simulation_from_config(at), analysis_from_config(at), Model::Flexible,
                       Section::Touchdown, initial_from_config(at));
  ASSERT_TRUE(r.converged) << r.failure();
  EXPECT_LE(t_last, r.period);
  EXPECT_GT(t_last, 0.5 * r.period);
}

// A two-point μ list gives two rows of fixed_points.csv, at those μ.
TEST(PaperAnalysisOptions, SetMuListReachesTheAnalysis) {
  const Config c = configured({"analysis.fixed_points.mu=[0.2, 0.6]"});
  const PaperAnalysisOptions o = paper_analysis_from_config(c);
  ASSERT_EQ(o.fixed_points_mu, (std::vector<double>{0.2, 0.6}));
  const std::string csv = behaviour_fixed_points_csv(c, o.fixed_points_mu, Section::Touchdown);
  ASSERT_EQ(rows(csv), 2u) << csv;
  std::istringstream in(csv);
  std::string header, first, second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first.substr(0, first.find(',')), "0.2");
  EXPECT_EQ(second.substr(0, second.find(',')), "0.6");
}

}  // namespace
}  // namespace flexgait::rimless
