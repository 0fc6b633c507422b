#include "report_html.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

namespace flexgait::cli {
namespace {

namespace fs = std::filesystem;
using Row = std::map<std::string, std::string>;

std::string escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::optional<std::string> read_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::optional<nlohmann::json> read_json(const fs::path& p) {
  const auto text = read_text(p);
  if (!text) return std::nullopt;
  try {
    return nlohmann::json::parse(*text);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

/// Rows of a CSV file without quoted fields (the files flexgait writes).
std::vector<Row> read_csv(const fs::path& p) {
  std::vector<Row> rows;
  std::ifstream in(p);
  std::string line;
  std::vector<std::string> header;
  auto split = [](const std::string& l) {
    std::vector<std::string> cells;
    std::stringstream ss(l);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    if (!l.empty() && l.back() == ',') cells.emplace_back();
    return cells;
  };
  if (!std::getline(in, line)) return rows;
  header = split(line);
  while (std::getline(in, line)) {
    const auto cells = split(line);
    Row r;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) r[header[i]] = cells[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

double number(const nlohmann::json& j, const std::string& key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

struct Line {
  std::string result, ours, reference, where;
};

void rimless_lines(const fs::path& root, std::vector<Line>& t) {
  if (const auto s = read_json(root / "rimless-flexible" / "summary.json"))
    t.push_back({"Energy balance of a 20-step run (flexible legs, μ = 0.6): |E0 − E − W_damping − W_friction|",
                 fmt::format("{:.1e} J (of {:.2f} J)", number(*s, "energy_balance_error"), number(*s, "energy_initial")),
                 "— (an invariant)", "rimless-flexible"});
  const auto fixed = read_csv(root / "rimless-fixed-points" / "fixed_points.csv");
  if (!fixed.empty()) {
    std::string ours;
    int stable = 0;
    for (const auto& r : fixed) {
      ours += fmt::format("{}μ = {}: {} ({}, |λ|max {:.3f}){}", ours.empty() ? "" : "<br>", r.at("mu"), r.at("gait"),
                          r.at("converged") == "true" ? "converged" : "not converged",
                          std::stod(r.at("max_multiplier").empty() ? "nan" : r.at("max_multiplier")),
                          r.at("stable") == "true" ? ", stable" : "");
      stable += r.at("stable") == "true";
    }
    t.push_back({fmt::format("Fixed points of the behaviours by Newton-Raphson on the Poincaré map ({} of {} stable)",
                             stable, fixed.size()),
                 ours, "four behaviours, each with a stable fixed point", "rimless-fixed-points"});
  }
  if (const auto th = read_text(root / "rimless-gait-vs-friction" / "thresholds.txt")) {
    std::string html;
    for (const char c : *th) html += c == '\n' ? std::string("<br>") : escape(std::string(1, c));
    t.push_back({"Gait against friction coefficient: thresholds (bisection)", html,
                 "up to four behaviours within μ ∈ (0, 1.5); values not in the OCR", "rimless-gait-vs-friction"});
  }
  const auto energy = read_csv(root / "rimless-energy" / "energy.csv");
  if (!energy.empty()) {
    std::map<std::string, double> peak;
    for (const auto& r : energy) {
      const double e = std::stod(r.at("E_kinetic"));
      const std::string key = r.at("mu") + " (" + r.at("gait") + ")";
      peak[key] = std::max(peak.count(key) ? peak[key] : -INFINITY, e);
    }
    std::string ours;
    for (const auto& [k, v] : peak) ours += fmt::format("{}μ = {}: peak kinetic energy {:.3f} J", ours.empty() ? "" : "<br>", k, v);
    t.push_back({"Kinetic energy in single support, stick against slip", ours,
                 "slipping raises the kinetic energy in single support", "rimless-energy"});
  }
  const auto robust = read_csv(root / "rimless-robustness" / "robustness.csv");
  if (!robust.empty()) {
    std::map<std::string, std::pair<int, int>> by_mu;
    for (const auto& r : robust) {
      auto& [ok, n] = by_mu[r.at("mu")];
      ok += r.at("returned") == "true";
      ++n;
    }
    std::string ours;
    for (const auto& [mu, c] : by_mu)
      ours += fmt::format("{}μ = {}: {} of {} perturbations return to the gait", ours.empty() ? "" : "<br>", mu, c.first, c.second);
    t.push_back({"Robustness to perturbations of the fixed point", ours, "the sliding gait is robust", "rimless-robustness"});
  }
  const auto stag = read_csv(root / "rimless-stagnation" / "stagnation.csv");
  if (!stag.empty()) {
    double longest = 0, at = 0, e_min = INFINITY, e_max = -INFINITY, w_min = INFINITY, w_max = -INFINITY;
    for (const auto& r : stag) {
      if (!r.at("failure").empty()) continue;
      w_min = std::min(w_min, std::stod(r.at("omega0")));
      w_max = std::max(w_max, std::stod(r.at("omega0")));
      const double s = std::stod(r.at("slide_time_upright"));
      if (s > longest) longest = s, at = std::stod(r.at("omega0"));
      const double e = std::stod(r.at("final_energy"));
      e_min = std::min(e_min, e);
      e_max = std::max(e_max, e);
    }
    t.push_back({"Stagnation: sliding time near the upright against initial angular velocity",
                 (longest > 0 ? fmt::format("longest slide {:.3f} s at ω0 = {:.3f} rad/s", longest, at)
                              : fmt::format("no slide near the upright for ω0 in [{:.3f}, {:.3f}] rad/s", w_min, w_max)) +
                     fmt::format("; final energy {:.3f}…{:.3f} J over {} values", e_min, e_max, stag.size()),
                 "a very small interval of initial energy with a long slide near the upright (Fig. 12)",
                 "rimless-stagnation"});
  }
}

void humanoid_lines(const fs::path& root, std::vector<Line>& t) {
  if (const auto b = read_json(root / "humanoid-bench" / "summary.json")) {
    t.push_back({"Stiffness bench: fitted k_joint (true value of the twin in brackets)",
                 fmt::format("{:.1f} Nm/rad ({:.0f}), R² {:.6f}", number(*b, "k_fit"), number(*b, "k_true"),
                             number(*b, "r_squared")),
                 "≈ 1000 Nm/rad (±0.04 rad at ±40 Nm)", "humanoid-bench"});
    t.push_back({"Stiffness bench: residual error with the input compensator",
                 fmt::format("{:+.1e} … {:+.1e} rad (uncompensated max {:.4f})", number(*b, "residual_compensated_min"),
                             number(*b, "residual_compensated_max"), number(*b, "max_error_uncompensated")),
                 "−0.0037 … +0.0071 rad (Fig. 12)", "humanoid-bench"});
  }
  for (const auto& [dir, gait, thesis_off] : {std::tuple{"humanoid-quasi-static", "24 s/step", "≈ 0.04 → ≈ 0.01 rad (Fig. 13a)"},
                                              std::tuple{"humanoid-dynamic", "3 s/step", "≈ 0.04 → ≈ 0.01 rad (Fig. 13b)"}}) {
    const auto c = read_json(root / dir / "comparison.json");
    if (!c) continue;
    t.push_back({fmt::format("Peak pelvis roll error, {} ({} steps): off → compensated (cut; thesis form)", gait,
                             static_cast<int>(number(*c, "steps"))),
                 fmt::format("{:.4f} → {:.4f} rad ({:.0f} % less; thesis form {:.4f})", number(*c, "pelvis_roll_error_max_off"),
                             number(*c, "pelvis_roll_error_max_on"), 100 * number(*c, "pelvis_roll_error_max_cut"),
                             number(*c, "pelvis_roll_error_max_thesis_form")),
                 std::string(thesis_off) + "; issue target ≥ 70 % less", dir});
    t.push_back({fmt::format("Single-support ZMP tracking (rms, y), {}", gait),
                 fmt::format("{:.4f} → {:.4f} m", number(*c, "zmp_single_support_rms_y_off"),
                             number(*c, "zmp_single_support_rms_y_on")),
                 "measured ZMP closer to the desired with compensation (Fig. 14)", dir});
    t.push_back({fmt::format("Output compensator against the true link angles, {}: rms error / rms deflection", gait),
                 fmt::format("{:.5f} / {:.5f} rad = {:.1f} % (conventional {:.5f}; one-step {:.5f}); Newton ≤ {} "
                             "iterations, {} failures",
                             number(*c, "estimate_error_rms"), number(*c, "deflection_rms"),
                             100 * number(*c, "estimate_error_share_of_deflection"), number(*c, "conventional_error_rms"),
                             number(*c, "one_step_error_rms"), static_cast<int>(number(*c, "newton_iterations_max")),
                             static_cast<int>(number(*c, "newton_failures"))),
                 "not measurable on the robot; issue target ≤ 10 %", dir});
    t.push_back({fmt::format("Newton − conventional estimate, largest, {}", gait),
                 fmt::format("{:.4f} rad", number(*c, "newton_conventional_max")), "up to ≈ 0.004 rad (Fig. 15)", dir});
  }
  if (const auto m = read_json(root / "humanoid-mismatch" / "comparison.json")) {
    std::string ours;
    for (const auto& r : (*m)["rows"])
      ours += fmt::format("{}true k {:.0f} (belief {:.0f}): {:.4f}{} → {:.4f}{} rad", ours.empty() ? "" : "<br>",
                          r["k_joint_true"].get<double>(), r["k_joint_belief"].get<double>(),
                          r["pelvis_roll_error_max_off"].get<double>(), r["fell_off"].get<bool>() ? " (fell)" : "",
                          r["pelvis_roll_error_max_on"].get<double>(), r["fell_on"].get<bool>() ? " (fell)" : "");
    t.push_back({"Stiffness model wrong by ±30 %, 3 s/step: peak pelvis roll error off → compensated", ours,
                 "— (beyond the thesis)", "humanoid-mismatch"});
  }
  if (const auto w = read_json(root / "humanoid-walk-1s" / "summary.json"))
    t.push_back({"1.0 s/step with compensation (ROBOTIS's default period)",
                 fmt::format("{} of {} steps{}, peak roll error {:.4f} rad, ZMP rms y {:.4f} m",
                             w->value("steps_completed", 0), w->value("steps_planned", 0),
                             w->value("fell", false) ? " (fell)" : "", number(*w, "pelvis_roll_error_max"),
                             number(*w, "zmp_rms_y")),
                 "— (beyond the thesis)", "humanoid-walk-1s"});
}

}  // namespace

std::string reproduction_report(const fs::path& root, const std::vector<ReportSection>& sections, bool quick) {
  std::string h;
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>flexgait reproduction</title>\n";
  h += "<style>body{font-family:sans-serif;max-width:1300px;margin:2em auto;padding:0 1em;color:#222}"
       "table{border-collapse:collapse;width:100%;font-size:14px}td,th{border:1px solid #bbb;padding:5px;"
       "vertical-align:top}th{background:#eee}img{max-width:100%;border:1px solid #ddd;margin:6px 0}"
       "code{background:#f4f4f4;padding:1px 3px}.fail{color:#b00;font-weight:bold}</style>\n</head>\n<body>\n";
  h += "<h1>flexgait: reproduction of both studies</h1>\n";
  h += fmt::format("<p>Written by <code>flexgait reproduce{}</code>. Every number below is read from the run "
                   "directories next to this file; each run holds its <code>config.yaml</code>, CSV logs and "
                   "JSON summaries.{}</p>\n",
                   quick ? " --quick" : "",
                   quick ? " <b>Quick variant:</b> 3 steps of the 24 s/step walk, coarser rimless sweeps." : "");
  std::vector<Line> rimless, humanoid;
  rimless_lines(root, rimless);
  humanoid_lines(root, humanoid);
  auto table = [&](const std::string& title, const std::string& reference, const std::vector<Line>& lines) {
    h += fmt::format("<h2>{}</h2>\n<table>\n<tr><th>Result</th><th>Ours</th><th>{}</th><th>Run</th></tr>\n", title, reference);
    for (const auto& l : lines)
      h += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td><a href=\"{}/\">{}</a></td></tr>\n", escape(l.result),
                       l.ours, escape(l.reference), l.where, l.where);
    h += "</table>\n";
  };
  table("Humanoid gait control with an actuator deformation model (thesis)", "Thesis", humanoid);
  table("Flexible-leg rimless wheel with stick-slip friction (paper)", "Paper", rimless);
  h += "<h2>Runs and figures</h2>\n";
  for (const auto& s : sections) {
    h += fmt::format("<h3 id=\"{}\">{}</h3>\n<p><code>{} --out {}</code>{}</p>\n", s.dir, escape(s.title), escape(s.command),
                     s.dir, s.exit_code == 0 ? "" : fmt::format(" <span class=\"fail\">exit code {}</span>", s.exit_code));
    std::vector<std::string> pngs;
    if (fs::is_directory(root / s.dir))
      for (const auto& e : fs::directory_iterator(root / s.dir))
        if (e.path().extension() == ".png") pngs.push_back(e.path().filename().string());
    std::sort(pngs.begin(), pngs.end());
    for (const auto& p : pngs) h += fmt::format("<img src=\"{}/{}\" alt=\"{}\">\n", s.dir, p, p);
  }
  h += "</body>\n</html>\n";
  return h;
}

}  // namespace flexgait::cli
