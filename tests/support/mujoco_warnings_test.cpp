// The MuJoCo warning check (mujoco_warnings.hpp) catches a real MuJoCo warning: directly (the
// check called inside EXPECT_NONFATAL_FAILURE), and end to end (this program run again as a
// sub-process, where a probe test that makes MuJoCo warn must be reported FAILED by the listener
// alone, and a probe that steps quietly must pass).
#include "mujoco_warnings.hpp"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"

namespace flexgait::test_support {
namespace {

constexpr const char* kProbeVariable = "FLEXGAIT_MUJOCO_WARNING_PROBE";

// One free body; `nan_velocity` puts a NaN in qvel, which mj_step reports as mjWARN_BADQVEL
// ("Nan, Inf or huge value in QVEL") and answers by resetting the data.
void step_mujoco(bool nan_velocity) {
  mjModel* m = twin::load_mjcf(
      R"(<mujoco><worldbody><body><freejoint/><geom size="0.1" mass="1"/></body></worldbody></mujoco>)");
  mjData* d = mj_makeData(m);
  if (nan_velocity) d->qvel[0] = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 10; ++i) mj_step(m, d);
  mj_deleteData(d);
  mj_deleteModel(m);
}

void warn_then_check() {
  step_mujoco(true);
  check_no_mujoco_warnings();
}

TEST(MujocoWarningCheck, HookRecordsTheWarningOfAStep) {
  step_mujoco(true);
  const auto messages = take_mujoco_warnings();  // taken: this test must not fail on them
  ASSERT_FALSE(messages.empty());                // MuJoCo calls the hook the first time each kind occurs in an mjData
  EXPECT_NE(messages[0].find("QVEL"), std::string::npos) << messages[0];
}

TEST(MujocoWarningCheck, CheckFailsTheTestAfterAWarning) {
  EXPECT_NONFATAL_FAILURE(warn_then_check(), "MuJoCo warning(s) raised");
  EXPECT_TRUE(take_mujoco_warnings().empty()) << "the check forgets what it reported";
}

TEST(MujocoWarningCheck, QuietSteppingRecordsNothing) {
  step_mujoco(false);
  EXPECT_TRUE(take_mujoco_warnings().empty());
}

struct ProbeRun {
  int status = -1;
  std::string output;
};

ProbeRun run_probe(const std::string& name) {
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::string command =
      std::string(kProbeVariable) + "=1 '" + exe + "' --gtest_filter=MujocoWarningProbe." + name + " 2>&1";
  ProbeRun r;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) r.output.append(buffer, n);
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

TEST(MujocoWarningCheck, ListenerFailsATestInWhichMujocoWarned) {
  const ProbeRun warns = run_probe("Warns");
  EXPECT_EQ(warns.status, 1) << warns.output;
  EXPECT_NE(warns.output.find("[  FAILED  ] MujocoWarningProbe.Warns"), std::string::npos) << warns.output;
  EXPECT_NE(warns.output.find("MuJoCo warning(s) raised"), std::string::npos) << warns.output;
  const ProbeRun quiet = run_probe("Quiet");
  EXPECT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_NE(quiet.output.find("[       OK ] MujocoWarningProbe.Quiet"), std::string::npos) << quiet.output;
}

// The probes exist only in the sub-process (the variable set): ctest never lists them.
class Probe : public ::testing::Test {
 public:
  explicit Probe(bool warn) : warn_(warn) {}
  void TestBody() override { step_mujoco(warn_); }  // no assertion: only the listener can fail it

 private:
  bool warn_;
};

[[maybe_unused]] const bool kProbesRegistered = [] {
  if (std::getenv(kProbeVariable) == nullptr) return false;
  for (const bool warn : {true, false}) {
    ::testing::RegisterTest("MujocoWarningProbe", warn ? "Warns" : "Quiet", nullptr, nullptr, __FILE__, __LINE__,
                            [warn]() -> ::testing::Test* { return new Probe(warn); });
  }
  return true;
}();

}  // namespace
}  // namespace flexgait::test_support
