#include "flexgait/twin/mujoco_messages.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

#include "flexgait/core/text.hpp"
#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::twin {
namespace {

// MuJoCo warns once per kind and mjData, but it resets an unstable mjData (and its counts) and
// warns again: a run that keeps failing would flood stderr. The first few are printed.
constexpr int kWarningsPrinted = 5;
std::atomic<int> warnings_seen{0};  // process-wide, as the hook itself is

void warning_to_stderr(const char* msg) {
  const int n = ++warnings_seen;
  if (n <= kWarningsPrinted) fmt::print(stderr, "warning: MuJoCo: {}\n", one_line(msg, 1000));
  if (n == kWarningsPrinted) fmt::print(stderr, "warning: MuJoCo: further warnings are not printed\n");
}

[[noreturn]] void error_to_stderr(const char* msg) {
  fmt::print(stderr, "error: MuJoCo: {}\n", one_line(msg, 1000));
  std::fflush(stderr);
  std::exit(1);
}

}  // namespace

void route_mujoco_messages_to_stderr() {
  mju_user_warning = warning_to_stderr;
  mju_user_error = error_to_stderr;
}

bool mujoco_messages_hooked() {
  return mju_user_warning != nullptr || mju_user_error != nullptr;
}

int mujoco_warning_count(const mjData* d) {
  int n = 0;
  for (int i = 0; i < mjNWARNING; ++i) n += d->warning[i].number;
  return n;
}

std::string mujoco_warnings_text(const mjData* d) {
  std::string text;
  for (int i = 0; i < mjNWARNING; ++i) {
    const int n = d->warning[i].number;
    if (n == 0) continue;
    text += fmt::format("{}{} ({} time{})", text.empty() ? "" : "; ", mju_warningText(i, d->warning[i].lastinfo), n,
                        n == 1 ? "" : "s");
  }
  return text;
}

}  // namespace flexgait::twin
