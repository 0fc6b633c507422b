#include "mujoco_warnings.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <mutex>

namespace flexgait::test_support {
namespace {

// The one piece of global state: what the hook recorded since the last check.
struct Records {
  std::mutex mutex;
  std::vector<std::string> messages;
};
Records& records() {
  static Records r;
  return r;
}

void record_warning(const char* message) {
  Records& r = records();
  const std::lock_guard lock(r.mutex);
  r.messages.emplace_back(message != nullptr ? message : "(no message)");
}

class WarningListener : public ::testing::EmptyTestEventListener {
 public:
  void OnTestEnd(const ::testing::TestInfo& /*info*/) override { check_no_mujoco_warnings(); }
};

class WarningEnvironment : public ::testing::Environment {
 public:
  void TearDown() override { check_no_mujoco_warnings(); }  // warnings outside any test
};

}  // namespace

void install_mujoco_warning_check() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  mju_user_warning = &record_warning;
  ::testing::AddGlobalTestEnvironment(new WarningEnvironment);  // owned by GoogleTest
  // Appended last: GoogleTest calls OnTestEnd in reverse order, so the failure is in the test's
  // result before the result printer reports it.
  ::testing::UnitTest::GetInstance()->listeners().Append(new WarningListener);  // owned by GoogleTest
}

std::vector<std::string> take_mujoco_warnings() {
  Records& r = records();
  const std::lock_guard lock(r.mutex);
  std::vector<std::string> out;
  out.swap(r.messages);
  return out;
}

void check_no_mujoco_warnings() {
  if (mju_user_warning != &record_warning)
    ADD_FAILURE() << "MuJoCo warning check: mju_user_warning was replaced; warnings are no longer seen";
  const std::vector<std::string> messages = take_mujoco_warnings();
  if (messages.empty()) return;
  std::string text;
  for (const auto& m : messages) text += "\n  " + m;
  ADD_FAILURE() << "MuJoCo warning(s) raised (" << messages.size() << "):" << text;
}

}  // namespace flexgait::test_support
