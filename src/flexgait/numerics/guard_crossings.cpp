#include "flexgait/numerics/guard_crossings.hpp"

#include <boost/math/tools/toms748_solve.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace flexgait::numerics {
namespace {

constexpr double kUround = std::numeric_limits<double>::epsilon();

// A crossing of a guard from g_lo to g that its direction lets through (CVODE: rootdir·g_lo <= 0).
bool crosses(int direction, double g_lo, double g) {
  return direction * g_lo <= 0 && (g == 0.0 || (g_lo < 0) != (g < 0));
}

}  // namespace

void GuardCrossings::start(double t, std::span<const int> directions, std::span<const double> g) {
  if (g.size() != directions.size()) throw std::invalid_argument("GuardCrossings::start: sizes differ");
  directions_.assign(directions.begin(), directions.end());
  g_lo_.resize(g.size());
  t_lo_.resize(g.size());
  active_.resize(g.size());
  scratch_.resize(g.size());
  fired_.assign(g.size(), 0);
  rearm(t, g);
}

void GuardCrossings::rearm(double t, std::span<const double> g) {
  t_ = t;
  first_step_ = true;
  inactive_ = 0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    g_lo_[i] = g[i];
    t_lo_[i] = t;
    active_[i] = g[i] != 0.0;
    inactive_ += g[i] == 0.0;
  }
}

void GuardCrossings::probe_unarmed(double t1, std::span<const double> g1, const Values& g_at) {
  const double tol = 100.0 * kUround * (std::abs(t1) + std::abs(t1 - t_));
  for (std::size_t i = 0; i < directions_.size(); ++i) {
    const int d = directions_[i];
    if (active_[i] == 0 || d == 0 || !(d * g_lo_[i] > 0) || !(d * g1[i] > 0)) continue;
    for (int k = 1; k <= kProbeLevels; ++k) {
      const double s = t_ + std::ldexp(t1 - t_, -k);
      if (s - t_ <= tol) break;
      g_at(s, scratch_);
      if (d * scratch_[i] < 0) {  // on the side before the crossing: the bracket starts here
        g_lo_[i] = scratch_[i];
        t_lo_[i] = s;
        break;
      }
    }
  }
}

std::optional<double> GuardCrossings::check(double t1, std::span<const double> g1, const Values& g_at,
                                            const Value& g_i_at) {
  const std::size_t n = directions_.size();
  const double tol = 100.0 * kUround * (std::abs(t1) + std::abs(t1 - t_));
  // Guards that were 0 where watching started: activated where they have moved away from 0.
  if (inactive_ > 0) {
    const double t_plus = t_ + std::max(tol, 0.1 * (t1 - t_));
    if (t_plus < t1) {
      g_at(t_plus, scratch_);
      for (std::size_t i = 0; i < n; ++i) {
        if (active_[i] == 0 && scratch_[i] != 0.0) {
          active_[i] = 1;
          --inactive_;
          g_lo_[i] = scratch_[i];
          t_lo_[i] = t_plus;
        }
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (active_[i] == 0 && g1[i] != 0.0) {  // moved away only by the step's end: no crossing yet
        active_[i] = 1;
        --inactive_;
        g_lo_[i] = g1[i];
        t_lo_[i] = t1;
      }
    }
  }
  if (first_step_) probe_unarmed(t1, g1, g_at);
  first_step_ = false;
  // The earliest root among the guards that crossed.
  double first = t1;
  int first_guard = -1;
  for (std::size_t i = 0; i < n; ++i) {
    if (active_[i] == 0 || t_lo_[i] >= t1 || !crosses(directions_[i], g_lo_[i], g1[i])) continue;
    double root = t1;
    if (g1[i] != 0.0) {
      auto g_i = [&](double t) { return g_i_at(t, static_cast<int>(i)); };
      auto close_enough = [tol](double a, double b) { return b - a <= tol; };
      std::uintmax_t iterations = 100;
      root = boost::math::tools::toms748_solve(g_i, t_lo_[i], t1, g_lo_[i], g1[i], close_enough, iterations).second;
    }
    if (first_guard < 0 || root < first) {
      first = root;
      first_guard = static_cast<int>(i);
    }
  }
  if (first_guard < 0) {
    if (inactive_ == 0) {
      std::copy(g1.begin(), g1.end(), g_lo_.begin());
      std::fill(t_lo_.begin(), t_lo_.end(), t1);
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        if (active_[i] == 0) continue;
        g_lo_[i] = g1[i];
        t_lo_[i] = t1;
      }
    }
    t_ = t1;
    return std::nullopt;
  }
  // Every guard that has crossed by the first root fires; watching restarts there.
  std::vector<double>& g = scratch_;
  if (first < t1)
    g_at(first, g);
  else
    std::copy(g1.begin(), g1.end(), g.begin());
  for (std::size_t i = 0; i < n; ++i) {
    const bool fired = active_[i] != 0 && crosses(directions_[i], g_lo_[i], g[i]);
    fired_[i] = fired || static_cast<int>(i) == first_guard ? (g_lo_[i] > 0 ? -1 : 1) : 0;
  }
  rearm(first, g);
  return first;
}

}  // namespace flexgait::numerics
