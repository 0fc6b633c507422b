// The rimless outcome convention (outcome.hpp): one table of reasons with their names and
// sentences, the text made from reason, detail and stage, and physics outcomes returned, not thrown.
#include "flexgait/rimless/outcome.hpp"

#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>

#include "../support/enum_table.hpp"
#include "flexgait/numerics/hybrid_simulation.hpp"
#include "flexgait/numerics/newton.hpp"
#include "flexgait/rimless/basin.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/poincare.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

TEST(FailureReason, NamesAndSentencesAreUniqueAndRoundTrip) {
  flexgait::testing::expect_enum_table_round_trips<FailureReason>();
  std::set<std::string_view> sentences;
  for (const FailureEntry& e : kFailureTable) {
    SCOPED_TRACE(std::string(e.name));
    EXPECT_TRUE(sentences.insert(e.sentence).second) << "a sentence twice";
    EXPECT_FALSE(e.sentence.empty());
    EXPECT_EQ(failure_sentence(e.reason), e.sentence);
  }
  // Every value of the enum is in the table (the values are 0 .. size - 1, the last one named).
  for (std::size_t i = 0; i < kFailureTable.size(); ++i) EXPECT_NO_THROW(name_of(static_cast<FailureReason>(i))) << i;
  EXPECT_EQ(kFailureTable.back().reason, FailureReason::IrreducibleCrossing);
  EXPECT_EQ(static_cast<std::size_t>(FailureReason::IrreducibleCrossing) + 1, kFailureTable.size());
}

// The other outcome tables of the rimless wheel and its numerics.
TEST(FailureReason, TheOtherOutcomeTablesRoundTrip) {
  flexgait::testing::expect_enum_table_round_trips<numerics::LoopFailure>();
  flexgait::testing::expect_enum_table_round_trips<numerics::BranchEnd>();
  flexgait::testing::expect_enum_table_round_trips<numerics::NewtonFailure>();
  flexgait::testing::expect_enum_table_round_trips<BasinOutcome>();
  flexgait::testing::expect_enum_table_round_trips<GaitBranchEnd>();
  for (const auto& e : enum_names(numerics::LoopFailure{})) EXPECT_NO_THROW(loop_failure_reason(e.value)) << e.name;
}

TEST(FailureReason, TextIsStageSentenceAndDetail) {
  EXPECT_EQ((Failure{FailureReason::AtRest, {}, {}}).text(), "stopped: the wheel came to rest in double support");
  EXPECT_EQ((Failure{FailureReason::SlidAway, "xdot = 1 m/s", {}}).text(),
            "slid away: the wheel slides down the slope on its feet without turning, ever faster (xdot = 1 m/s)");
  // A sentence with "{}" takes the detail there.
  EXPECT_EQ((Failure{FailureReason::InitialFootBelowGround, "3", {}}).text(),
            "initial state: foot 3 is below the ground");
  EXPECT_EQ((Failure{FailureReason::SectionNotReached, "upright", {}}).text(), "the upright section was not reached");
  EXPECT_EQ((Failure{FailureReason::IrreducibleCrossing, "flight at the upright section", {}}).text(),
            "flight at the upright section");
  // Stages nest outermost first.
  const Failure f = Failure{FailureReason::FellBack, {}, {}}.in_stage("transient").in_stage("no initial guess");
  EXPECT_EQ(f.stage, "no initial guess: transient");
  EXPECT_EQ(f.text(), "no initial guess: transient: rolled back: the wheel fell back onto the previous leg");
  EXPECT_EQ(f.reason, FailureReason::FellBack);
  std::ostringstream out;
  out << f;
  EXPECT_EQ(out.str(), f.text());
  EXPECT_EQ(text_of(std::nullopt), "");
  EXPECT_EQ(text_of(f), f.text());
}

TEST(FailureReason, PointMassReasonsAreTheIllPosedOnes) {
  for (const FailureEntry& e : kFailureTable)
    EXPECT_EQ(ill_posed_point_mass(e.reason), e.sentence.find("I = 0") != std::string_view::npos) << e.name;
}

// A foot below the ground at the start is an outcome of that start (returned, not thrown): the
// run stops at t = 0 with the foot named, and the Poincaré map and settle_on_section say so too.
TEST(FailureReason, AFootBelowTheGroundAtTheStartIsReturned) {
  const WheelParams w = testing::measured_wheel(0.6);
  const InitialState start{1.4, 0.3};  // β = 0.3 near α = 0.314: the stance leg's compression sinks the next foot
  const RunSpec spec = default_run(w, start);
  int below = -1;
  for (int k = 0; k < w.legs; ++k)
    if (spec.contacts.find(k) < 0 && foot_height(w, k, spec.y0) < -1e-12 * w.L0) below = k;
  ASSERT_GE(below, 0) << "the case must start with a foot below the ground";

  const SimulationResult r = simulate_flexible(w, start, testing::run_options(3));
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->reason, FailureReason::InitialFootBelowGround);
  EXPECT_EQ(r.failure->detail, std::to_string(below));
  EXPECT_EQ(r.steps_completed, 0);
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(r.events.back().kind, RunEvent::Failure);
  EXPECT_EQ(r.events.back().message, r.failure->text());

  SectionState p;
  const auto settled = settle_on_section(w, testing::run_options(3), Model::Flexible, Section::Touchdown, start, 2, p);
  ASSERT_TRUE(settled.has_value());
  EXPECT_EQ(settled->reason, FailureReason::InitialFootBelowGround);
  EXPECT_EQ(settled->stage, "");                               // no stage: the transient never began
  EXPECT_EQ(failure_outcome(*settled), BasinOutcome::Failed);  // the basin names it infeasible itself
}

}  // namespace
}  // namespace flexgait::rimless
