// The largest recoverable standing sagittal push (issue 19) for balance.mode pd and dcm, as a
// fraction of the capture-point bound: bisection to 1 N s, forward and backward, a 0.1 s push on
// the pelvis at 4 s (the DCM mode's COM bias has settled), compensation off and both. Not a benchmark of speed: a measurement
// program, run by hand (about a minute per line).
//   push_recovery [pelvis|chest] [step]
// `step`: balance.mode dcm with step adjustment (balance.step_adjustment) instead of pd and dcm.
#include <fmt/format.h>

#include <cstring>
#include <vector>

#include "flexgait/experiments/push_recovery.hpp"

int main(int argc, char** argv) {
  using namespace flexgait;
  bool chest = false, step = false;
  for (int i = 1; i < argc; ++i) {
    chest = chest || std::strcmp(argv[i], "chest") == 0;
    step = step || std::strcmp(argv[i], "step") == 0;
  }
  fmt::print("body {}, standing, 0.1 s push at t = 4 s\n", chest ? "chest" : "pelvis");
  fmt::print("{:>12} {:>5} {:>9} {:>14} {:>12} {:>10} {:>8}\n", "compensation", "mode", "direction", "recovered[Ns]", "fell at[Ns]",
             "bound[Ns]", "fraction");
  for (const auto comp : {compensation::CompensationMode::kOff, compensation::CompensationMode::kBoth})
  for (const auto mode : step ? std::vector{walking::BalanceMode::kDcm} : std::vector{walking::BalanceMode::kPd, walking::BalanceMode::kDcm}) {
    for (const double sign : {1.0, -1.0}) {
      experiments::WalkRunParams p;
      p.control.mode = comp;
      p.walk.steps = 0;
      p.walk.end_time = 5.5;  // push at 4 s, 3 s to fall
      p.balance.mode = mode;
      p.balance.step_adjustment = step;
      p.push = humanoid::Push{4.0, chest ? humanoid::PushBody::kChest : humanoid::PushBody::kPelvis, {}, 0.1};
      const auto r = experiments::largest_recoverable_push(p, Eigen::Vector2d(sign, 0), 100.0, 1.0);
      fmt::print("{:>12} {:>5}{} {:>9} {:>14.2f} {:>12.2f} {:>10.2f} {:>8.2f}\n", name_of(comp), name_of(mode), step ? "+step" : "", sign > 0 ? "forward" : "backward",
                 r.recovered, r.fell, r.bound, r.recovered / r.bound);
    }
  }
  return 0;
}
