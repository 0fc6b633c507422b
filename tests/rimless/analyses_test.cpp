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
