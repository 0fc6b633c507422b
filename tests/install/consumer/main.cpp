// A user's program built against the installed flexgait: the rigid wheel's fixed point.
#include <flexgait/rimless/rigid_wheel.hpp>
#include <flexgait/version.hpp>

#include <cmath>
#include <cstdio>

int main() {
  flexgait::rimless::WheelParams w;
  w.I = 0.0;
  w.legs = 8;
  const auto map = flexgait::rimless::rigid_step_map(w);
  const double multiplier = map.derivative(map.fixed_point());
  std::printf("flexgait %s: rigid wheel multiplier %.15f\n", flexgait::kVersion, multiplier);
  return std::abs(multiplier - 0.5) < 1e-14 ? 0 : 1;
}
