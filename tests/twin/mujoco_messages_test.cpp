// MuJoCo's message hooks (twin/mujoco_messages.hpp): routing sets them (idempotently), and a
// warning then goes to stderr as one line "warning: MuJoCo: <text>". The test program's own
// warning check (tests/support/mujoco_warnings.hpp) holds the hooks: they are put back afterwards.
#include "flexgait/twin/mujoco_messages.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <string>

#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::twin {
namespace {

TEST(MujocoMessages, RoutingSetsTheHooksAndWarningsGoToStderrOnOneLine) {
  auto* const saved_warning = mju_user_warning;
  auto* const saved_error = mju_user_error;
  mju_user_warning = nullptr;
  mju_user_error = nullptr;
  EXPECT_FALSE(mujoco_messages_hooked());
  route_mujoco_messages_to_stderr();
  EXPECT_TRUE(mujoco_messages_hooked());
  auto* const routed = mju_user_warning;
  route_mujoco_messages_to_stderr();
  EXPECT_EQ(mju_user_warning, routed);  // idempotent
  ASSERT_NE(routed, nullptr);
  ::testing::internal::CaptureStderr();
  routed("Nan, Inf or huge value in QACC at DOF 3");
  const std::string err = ::testing::internal::GetCapturedStderr();
  mju_user_warning = saved_warning;
  mju_user_error = saved_error;
  EXPECT_EQ(err, "warning: MuJoCo: Nan, Inf or huge value in QACC at DOF 3\n");
}

// The per-mjData count and text the plant reports (detail/mujoco.hpp), on counts set by hand (a
// real warning would fail this test under the program's warning check).
TEST(MujocoMessages, WarningCountAndTextSumTheKinds) {
  mjModel* m =
      load_mjcf("<mujoco><worldbody><body><joint type=\"hinge\"/><geom size=\"0.1\"/></body></worldbody></mujoco>");
  mjData* d = mj_makeData(m);
  EXPECT_EQ(mujoco_warning_count(d), 0);
  EXPECT_EQ(mujoco_warnings_text(d), "");
  d->warning[mjWARN_BADQACC].number = 2;
  d->warning[mjWARN_BADQACC].lastinfo = 3;
  d->warning[mjWARN_CONTACTFULL].number = 1;
  d->warning[mjWARN_CONTACTFULL].lastinfo = 7;
  EXPECT_EQ(mujoco_warning_count(d), 3);
  // In MuJoCo's order of the kinds (contact full before bad qacc). mju_warningText returns a
  // static buffer: one call per string.
  const std::string full = mju_warningText(mjWARN_CONTACTFULL, 7);
  const std::string qacc = mju_warningText(mjWARN_BADQACC, 3);
  EXPECT_EQ(mujoco_warnings_text(d), full + " (1 time); " + qacc + " (2 times)");
  d->warning[mjWARN_BADQACC].number = 0;
  d->warning[mjWARN_CONTACTFULL].number = 0;
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace
}  // namespace flexgait::twin
