#include "flexgait/rimless/wheel_setup.hpp"

#include <utility>

#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/basin.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/orbit_diagram.hpp"
#include "flexgait/rimless/stagnation.hpp"

namespace flexgait::rimless {

Schema rimless_analysis_schema() {
  Schema s = rimless_schema();
  s.merge(analysis_schema()).merge(paper_analysis_schema()).merge(orbit_diagram_schema()).merge(basin_schema());
  s.merge(gait_continuation_schema());  // analysis.* together: config.yaml has one analysis: block
  s.merge(stagnation_schema());
  return s;
}

WheelSetup wheel_setup(Config config) {
  WheelSetup s{std::move(config), {}, {}, {}};
  s.wheel = wheel_from_config(s.config);
  s.initial = initial_from_config(s.config);
  check_with_origin(s.config, [&] { validate(s.wheel, s.initial); });
  s.sim = simulation_from_config(s.config);
  if (s.sim.model == Model::Flexible)
    check_with_origin(s.config, [&] {
      try {
        check_initial_state(s.wheel, s.initial);
      } catch (const ConfigError& e) {  // blame the first of the keys involved that the user set
        std::string key = e.key();
        for (const char* k :
             {"rimless.legs", "rimless.K", "rimless.m", "rimless.g", "rimless.L0", "rimless.slope", "initial.beta"})
          if (s.config.origin(k) != "default") {
            key = k;
            break;
          }
        throw ConfigError(key, e.what());
      }
    });
  return s;
}

}  // namespace flexgait::rimless
