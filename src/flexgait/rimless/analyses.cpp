#include "flexgait/rimless/analyses.hpp"

#include <fmt/format.h>

#include <cmath>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/sweep.hpp"

namespace flexgait::rimless {
namespace {

Config with_mu(const Config& base, double mu) {
  SweepSpec spec{"rimless.mu", mu, mu, 1};
  return sweep_point_config(base, spec, 0);
}

struct Setup {
  WheelParams w;
  InitialState initial;
  SimulationOptions sim;
  AnalysisOptions opt;
};

Setup setup(const Config& c) {
  Setup s{wheel_from_config(c), initial_from_config(c), simulation_from_config(c), analysis_from_config(c)};
  validate(s.w, s.initial);
  return s;
}

std::string multipliers_text(const FixedPointReport& r, double& largest) {
  std::string m;
  largest = 0;
  for (std::size_t k = 0; k < r.multipliers.size(); ++k) {
    m += fmt::format("{}{}:{}", k ? ";" : "", format_number(r.multipliers[k].real()),
                     format_number(r.multipliers[k].imag()));
    largest = std::max(largest, std::abs(r.multipliers[k]));
  }
  return m;
}

std::string state_text(const Eigen::VectorXd& z) {
  std::string s;
  for (Eigen::Index k = 0; k < z.size(); ++k) s += (k ? ";" : "") + format_number(z(k));
  return s;
}

}  // namespace

std::string gait_at_friction(const Config& base, double mu, Section section) {
  const Setup s = setup(with_mu(base, mu));
  const FixedPointReport r = find_fixed_point(s.w, s.sim, s.opt, Model::Flexible, section, s.initial);
  if (r.converged) return r.gait;
  SimulationOptions o = s.sim;
  o.log = false;
  o.steps = std::max(1, s.opt.transient_steps);
  const SimulationResult t = simulate_flexible(s.w, s.initial, o);
  for (auto it = t.steps.rbegin(); it != t.steps.rend(); ++it)
    if (it->complete) return gait_label(it->single_support) + " (no fixed point)";
  return "none";
}

namespace {

// Thresholds between lo (gait a) and hi (gait b) by bisection; a third gait found in between
// splits the bracket and both halves are refined (behaviour windows narrower than the sweep's
// spacing are found this way).
void refine_threshold(const Config& base, Section section, double tolerance, double lo, const std::string& a,
                      double hi, const std::string& b, int depth, CsvWriter& csv) {
  while (hi - lo > tolerance) {
    const double mid = 0.5 * (lo + hi);
    const std::string g = gait_at_friction(base, mid, section);
    if (g == a) {
      lo = mid;
    } else if (g == b) {
      hi = mid;
    } else if (depth > 0) {
      refine_threshold(base, section, tolerance, lo, a, mid, g, depth - 1, csv);
      refine_threshold(base, section, tolerance, mid, g, hi, b, depth - 1, csv);
      return;
    } else {
      break;
    }
  }
  csv.cell(lo).cell(hi).cell(a).cell(b).cell(0.5 * (lo + hi)).end_row();
}

}  // namespace

std::string friction_thresholds_csv(const Config& base, const std::vector<std::pair<double, std::string>>& points,
                                    Section section, double tolerance) {
  CsvWriter csv({"mu_low", "mu_high", "gait_below", "gait_above", "threshold"});
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (points[i].second == points[i + 1].second) continue;
    refine_threshold(base, section, tolerance, points[i].first, points[i].second, points[i + 1].first,
                     points[i + 1].second, 4, csv);
  }
  return csv.str();
}

std::string single_support_energy_csv(const Config& base, const std::vector<double>& mus) {
  CsvWriter csv({"mu", "gait", "phase", "t", "beta", "E_kinetic", "E_total_minus_start"});
  for (double mu : mus) {
    const Setup s = setup(with_mu(base, mu));
    const FixedPointReport r = find_fixed_point(s.w, s.sim, s.opt, Model::Flexible, Section::Touchdown, s.initial);
    if (!r.converged) continue;
    SimulationOptions o = s.sim;
    o.log = true;
    o.rtol = s.opt.rtol;
    o.atol = s.opt.atol;
    FlexibleWheelSimulator sim(s.w, o);
    RunSpec spec = section_run(s.w, r.point);
    spec.stop_at = Section::Touchdown;
    spec.steps = 3;
    const SimulationResult run = sim.run(spec);
    if (run.samples.empty()) continue;
    const int stance = s.w.legs - 1;  // the leg landing at the section
    const double e0 = run.samples.front().energy.total();
    for (const LogSample& smp : run.samples) {
      const ContactSample& c = smp.contact[0];
      if (c.leg != stance || smp.contact[1].leg >= 0) continue;  // single support on the stance leg only
      const double beta = leg_angle(s.w, stance, smp.q[2]);
      csv.cell(mu).cell(r.gait).cell(c.mode == FootMode::Stick ? "stick" : "slip").cell(smp.t).cell(beta);
      csv.cell(smp.energy.kinetic).cell(smp.energy.total() - e0).end_row();
    }
  }
  return csv.str();
}

std::string behaviour_fixed_points_csv(const Config& base, const std::vector<double>& mus, Section section) {
  CsvWriter csv({"mu", "gait", "converged", "mode", "state", "max_multiplier", "multipliers", "stable", "period",
                 "speed", "dissipated_per_cycle", "failure"});
  for (double mu : mus) {
    const Setup s = setup(with_mu(base, mu));
    const FixedPointReport r = find_fixed_point(s.w, s.sim, s.opt, Model::Flexible, section, s.initial);
    double largest = 0;
    const std::string m = multipliers_text(r, largest);
    csv.cell(mu).cell(r.gait).cell(r.converged ? "true" : "false").cell(r.point.flight ? "flight" : mode_name(r.point.mode));
    csv.cell(state_text(r.point.z)).cell(largest).cell(m).cell(r.stable ? "true" : "false").cell(r.period);
    csv.cell(r.speed).cell(r.dissipated).cell(r.failure).end_row();
  }
  return csv.str();
}

std::string robustness_csv(const Config& base, double mu, const std::vector<double>& epsilons, int max_steps) {
  CsvWriter csv({"mu", "component", "sign", "epsilon", "returned", "steps", "failure"});
  const Setup s = setup(with_mu(base, mu));
  const FixedPointReport r = find_fixed_point(s.w, s.sim, s.opt, Model::Flexible, Section::Touchdown, s.initial);
  if (!r.converged) return csv.str();
  SimulationOptions o = s.sim;
  o.rtol = s.opt.rtol;
  o.atol = s.opt.atol;
  PoincareMap map(s.w, o, Model::Flexible, Section::Touchdown);
  const Eigen::VectorXd scale = r.point.scale(s.w);
  const auto names = r.point.names();
  for (Eigen::Index i = 0; i < r.point.z.size(); ++i) {
    for (int sign : {+1, -1}) {
      for (double eps : epsilons) {
        SectionState p = r.point;
        p.z(i) += sign * eps * scale(i);
        int steps = 0;
        bool returned = false;
        std::string failure;
        for (; steps < max_steps; ++steps) {
          const MapStep m = map.apply(p, /*keep_mode=*/false);  // a transient may change modes
          if (m.failure) {
            failure = *m.failure;
            break;
          }
          p = m.next;
          const bool same_mode = p.flight == r.point.flight && p.mode == r.point.mode;
          if (same_mode && ((p.z - r.point.z).cwiseQuotient(scale)).lpNorm<Eigen::Infinity>() < 1e-6) {
            returned = true;
            ++steps;
            break;
          }
        }
        csv.cell(mu).cell(names[static_cast<std::size_t>(i)]).cell(static_cast<long long>(sign)).cell(eps);
        csv.cell(returned ? "true" : "false").cell(static_cast<long long>(steps)).cell(failure).end_row();
      }
    }
  }
  return csv.str();
}

}  // namespace flexgait::rimless
