#include "flexgait/rimless/wheel_setup.hpp"

#include <utility>

#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/stagnation.hpp"

namespace flexgait::rimless {

Schema rimless_analysis_schema() {
  Schema s = rimless_schema();
  s.merge(analysis_schema()).merge(stagnation_schema());
  return s;
}

WheelSetup wheel_setup(Config config) {
  WheelSetup s{std::move(config), {}, {}, {}};
  s.wheel = wheel_from_config(s.config);
  s.initial = initial_from_config(s.config);
  check_with_origin(s.config, [&] { validate(s.wheel, s.initial); });
  s.sim = simulation_from_config(s.config);
  return s;
}

}  // namespace flexgait::rimless
