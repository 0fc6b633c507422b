#include "flexgait/rimless/analyses.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

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

namespace {

// Each value of a reals key is a whole number (the key's bounds hold already).
void check_whole(const std::string& key, const std::vector<double>& values) {
  for (const double v : values)
    if (v != std::floor(v))
      throw ConfigError(key, fmt::format("key '{}' = '{}': allowed: whole numbers", key, format_number(v)));
}

}  // namespace

PaperAnalysisOptions paper_analysis_from_config(const Config& config) {
  const PaperAnalysisOptions o = record_from_config<PaperAnalysisOptions>(config);
  check_with_origin(config, [&] {
    check_whole("analysis.friction.transient_factors", o.transient_factors);
    check_whole("analysis.friction.continuation_steps", o.continuation_steps);
    if (o.epsilon_max < o.epsilon_min)
      throw ConfigError("analysis.robustness.epsilon_max",
                        fmt::format("key 'analysis.robustness.epsilon_max' = '{}': below analysis.robustness."
                                    "epsilon_min = {}; allowed: a value >= it",
                                    format_number(o.epsilon_max), format_number(o.epsilon_min)));
  });
  return o;
}

std::vector<double> robustness_epsilons(const PaperAnalysisOptions& o) {
  std::vector<double> eps;
  const int n = o.epsilon_count;
  const double decades = std::log10(o.epsilon_max) - std::log10(o.epsilon_min);
  for (int k = 0; k < n; ++k)
    eps.push_back(n == 1 ? o.epsilon_min : o.epsilon_min * std::pow(10.0, k * decades / (n - 1)));
  return eps;
}

namespace {

FrictionGait gait_of(double mu, const FixedPointReport& r, std::string source) {
  FrictionGait g;
  g.mu = mu;
  g.converged = true;
  g.stable = r.stable;
  for (const auto& m : r.multipliers) g.max_multiplier = std::max(g.max_multiplier, std::abs(m));
  g.gait = r.stable ? r.gait : r.gait + " (unstable)";
  g.source = std::move(source);
  g.point = r.point;
  return g;
}

// Natural-parameter continuation: Newton at μ_k = μ_0 + (μ - μ_0) k / n, k = 1..n, each from the
// previous fixed point, for each n of `steps` in turn.
std::optional<FrictionGait> continued(const Config& base, double mu, const FrictionGait& from,
                                      const std::vector<double>& steps) {
  for (const double steps_n : steps) {
    const int n = static_cast<int>(steps_n);
    SectionState p = from.point;
    FixedPointReport r;
    for (int k = 1; k <= n; ++k) {
      const Setup s = setup(with_mu(base, from.mu + (mu - from.mu) * k / n));
      r = find_fixed_point_from(s.w, s.sim, s.opt, p);
      if (!r.converged) break;
      p = r.point;
    }
    if (r.converged) return gait_of(mu, r, fmt::format("continued from mu = {}", format_number(from.mu)));
  }
  return std::nullopt;
}

}  // namespace

FrictionGait friction_gait(const Config& base, double mu, Section section, const PaperAnalysisOptions& options,
                           const std::vector<const FrictionGait*>& neighbours) {
  const Setup s = setup(with_mu(base, mu));
  for (const double factor_value : options.transient_factors) {
    const int factor = static_cast<int>(factor_value);
    AnalysisOptions o = s.opt;
    o.transient_steps = std::max(1, s.opt.transient_steps) * factor;
    const FixedPointReport r = find_fixed_point(s.w, s.sim, o, Model::Flexible, section, s.initial);
    if (r.converged)
      return gait_of(mu, r, factor == 1 ? "start" : fmt::format("start, {} transient steps", o.transient_steps));
    if (r.transient_failure) break;  // the start does not walk: a longer transient won't help
  }
  for (const FrictionGait* n : neighbours)
    if (n != nullptr && n->converged)
      if (auto g = continued(base, mu, *n, options.continuation_steps)) return *g;
  FrictionGait g;
  g.mu = mu;
  g.source = "start";
  SimulationOptions o = s.sim;
  o.log = false;
  o.steps = std::max(1, s.opt.transient_steps);
  const SimulationResult t = simulate_flexible(s.w, s.initial, o);
  g.gait = "none";
  for (auto it = t.steps.rbegin(); it != t.steps.rend(); ++it) {
    if (it->complete) {
      g.gait = step_gait(*it) + " (no fixed point)";
      break;
    }
  }
  return g;
}

std::vector<FrictionGait> friction_gaits(const Config& base, const std::vector<double>& mus, Section section,
                                         const PaperAnalysisOptions& options) {
  std::vector<FrictionGait> out;
  for (double mu : mus) out.push_back(friction_gait(base, mu, section, options));
  // Second pass, in order: a point with no fixed point is continued from its nearest converged
  // neighbours (nearer first; the left one on a tie).
  const int n = static_cast<int>(out.size());
  for (int i = 0; i < n; ++i) {
    if (out[static_cast<std::size_t>(i)].converged) continue;
    std::vector<const FrictionGait*> near;
    for (int d = 1; d < n && near.size() < 2; ++d) {
      for (int j : {i - d, i + d})
        if (j >= 0 && j < n && out[static_cast<std::size_t>(j)].converged)
          near.push_back(&out[static_cast<std::size_t>(j)]);
    }
    for (const FrictionGait* nb : near) {
      if (auto g = continued(base, out[static_cast<std::size_t>(i)].mu, *nb, options.continuation_steps)) {
        out[static_cast<std::size_t>(i)] = *g;
        break;
      }
    }
  }
  return out;
}

std::string friction_gaits_csv(const std::vector<FrictionGait>& gaits) {
  CsvWriter csv({"mu", "gait", "converged", "stable", "max_multiplier", "source"});
  for (const FrictionGait& g : gaits)
    csv.cell(g.mu)
        .cell(g.gait)
        .cell(g.converged ? "true" : "false")
        .cell(g.stable ? "true" : "false")
        .cell(g.max_multiplier)
        .cell(g.source)
        .end_row();
  return csv.str();
}

namespace {

// The gait at mu inside the bracket [lo, hi]. Below a bracket width of `continued_bracket` it is the
// one continued from the bracket's ends (the nearer first), the start's own (with its transients)
// only when neither continues: within it the start finds what continuation does, at a fraction of
// the cost.
FrictionGait bracket_gait(const Config& base, double mu, Section section, const FrictionGait& lo,
                          const FrictionGait& hi, const PaperAnalysisOptions& options) {
  if (hi.mu - lo.mu <= options.continued_bracket) {
    const bool lo_first = mu - lo.mu <= hi.mu - mu;
    // One Newton from each end (no intermediate steps: across a change of the section's mode the
    // far end's mode has no fixed point, and more steps would not find one).
    const Setup s = setup(with_mu(base, mu));
    for (const FrictionGait* n : {lo_first ? &lo : &hi, lo_first ? &hi : &lo}) {
      if (!n->converged) continue;
      const FixedPointReport r = find_fixed_point_from(s.w, s.sim, s.opt, n->point);
      if (r.converged) return gait_of(mu, r, fmt::format("continued from mu = {}", format_number(n->mu)));
    }
  }
  return friction_gait(base, mu, section, options, {&lo, &hi});
}

// Thresholds between lo (gait a) and hi (gait b) by bisection, each midpoint continued from the
// bracket's ends; a third gait found in between splits the bracket and both halves are refined
// (behaviour windows narrower than the sweep's spacing are found this way).
void refine_threshold(const Config& base, Section section, const PaperAnalysisOptions& o, FrictionGait lo,
                      FrictionGait hi, int depth, CsvWriter& csv) {
  while (hi.mu - lo.mu > o.threshold_tol) {
    FrictionGait mid = bracket_gait(base, 0.5 * (lo.mu + hi.mu), section, lo, hi, o);
    if (mid.gait == lo.gait) {
      lo = std::move(mid);
    } else if (mid.gait == hi.gait) {
      hi = std::move(mid);
    } else if (depth > 0) {
      refine_threshold(base, section, o, lo, mid, depth - 1, csv);
      refine_threshold(base, section, o, mid, hi, depth - 1, csv);
      return;
    } else {
      break;
    }
  }
  csv.cell(lo.mu).cell(hi.mu).cell(lo.gait).cell(hi.gait).cell(0.5 * (lo.mu + hi.mu)).end_row();
}

}  // namespace

std::string friction_thresholds_csv(const Config& base, const std::vector<FrictionGait>& gaits, Section section,
                                    const PaperAnalysisOptions& options) {
  CsvWriter csv({"mu_low", "mu_high", "gait_below", "gait_above", "threshold"});
  for (std::size_t i = 0; i + 1 < gaits.size(); ++i) {
    if (gaits[i].gait == gaits[i + 1].gait) continue;
    refine_threshold(base, section, options, gaits[i], gaits[i + 1], options.split_depth, csv);
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
    spec.stop_at = Section::Touchdown;  // one step: the run ends at the next touchdown (RunSpec::steps unused)
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
    csv.cell(mu)
        .cell(r.gait)
        .cell(r.converged ? "true" : "false")
        .cell(r.point.flight ? "flight" : mode_name(r.point.mode));
    csv.cell(state_text(r.point.z)).cell(largest).cell(m).cell(r.stable ? "true" : "false").cell(r.period);
    csv.cell(r.speed).cell(r.dissipated).cell(r.failure()).end_row();
  }
  return csv.str();
}

const std::vector<std::string>& robustness_csv_columns() {
  static const std::vector<std::string> columns{"mu", "component", "sign", "epsilon", "returned", "steps", "failure"};
  return columns;
}

std::string robustness_csv(const Config& base, double mu, const std::vector<double>& epsilons, int max_steps,
                           double return_tol, const std::function<void(double fraction)>& progress) {
  CsvWriter csv(robustness_csv_columns());
  const Setup s = setup(with_mu(base, mu));
  const FixedPointReport r = find_fixed_point(s.w, s.sim, s.opt, Model::Flexible, Section::Touchdown, s.initial);
  if (!r.converged) return csv.str();
  SimulationOptions o = s.sim;
  o.rtol = s.opt.rtol;
  o.atol = s.opt.atol;
  SectionWalk walk(s.w, o, Model::Flexible, Section::Touchdown);
  const Eigen::VectorXd scale = r.point.scale(s.w);
  const auto names = r.point.names();
  Eigen::Index trials = 0;
  for (Eigen::Index i = 0; i < r.point.z.size(); ++i) {
    for (int sign : {+1, -1}) {
      for (double eps : epsilons) {
        SectionState p = r.point;
        p.z(i) += sign * eps * scale(i);
        int steps = 0;
        bool returned = false;
        std::string failure;
        // From the perturbed point's reconstruction, then crossing to crossing in the full state; a
        // transient may change modes.
        walk.start_at(p);
        for (; steps < max_steps; ++steps) {
          const MapStep m = walk.step();
          if (m.failure) {
            failure = m.failure->text();
            break;
          }
          p = m.next;
          const bool same_mode = p.flight == r.point.flight && p.mode == r.point.mode;
          if (same_mode && ((p.z - r.point.z).cwiseQuotient(scale)).lpNorm<Eigen::Infinity>() < return_tol) {
            returned = true;
            ++steps;
            break;
          }
        }
        csv.cell(mu).cell(names[static_cast<std::size_t>(i)]).cell(static_cast<long long>(sign)).cell(eps);
        csv.cell(returned ? "true" : "false").cell(static_cast<long long>(steps)).cell(failure).end_row();
        if (progress)
          progress(static_cast<double>(++trials) / static_cast<double>(2 * r.point.z.size() * epsilons.size()));
      }
    }
  }
  return csv.str();
}

}  // namespace flexgait::rimless
