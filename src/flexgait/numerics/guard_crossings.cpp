#include "flexgait/numerics/guard_crossings.hpp"

#include <boost/math/tools/toms748_solve.hpp>

#include <algorithm>
#include <array>
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

// A guard that holds one finite nonzero value v at every point of a step has no root there and
// passes every curvature bound (its differences are 0): a slot the mode leaves unused.
bool finite_nonzero(double v) {
  return v != 0.0 && std::abs(v) <= std::numeric_limits<double>::max();
}

}  // namespace

double locate_root(const std::function<double(double)>& g, double a, double b, double ga, double gb, double tol) {
  if (gb == 0.0) return b;
  auto close_enough = [tol](double lo, double hi) { return hi - lo <= tol; };
  std::uintmax_t iterations = 100;
  return boost::math::tools::toms748_solve(g, a, b, ga, gb, close_enough, iterations).second;
}

void GuardCrossings::start(double t, std::span<const int> directions, std::span<const double> g) {
  if (g.size() != directions.size()) throw std::invalid_argument("GuardCrossings::start: sizes differ");
  directions_.assign(directions.begin(), directions.end());
  watched_.clear();
  for (std::size_t i = 0; i < directions_.size(); ++i)
    if (directions_[i] != kNoGuard) watched_.push_back(i);
  g_lo_.resize(g.size());
  t_lo_.resize(g.size());
  active_.resize(g.size());
  scratch_.resize(g.size());
  samples_.resize(g.size() * (kSamples - 1));
  for (auto* v : {&lo_t_, &lo_g_, &hi_t_, &hi_g_, &curvature_, &roots_, &prev_g_}) v->resize(g.size());
  fired_.assign(g.size(), 0);
  rearm(t, g);
}

void GuardCrossings::rearm(double t, std::span<const double> g) {
  t_ = t;
  first_step_ = true;
  has_prev_ = false;
  inactive_ = 0;
  for (const std::size_t i : watched_) {
    g_lo_[i] = g[i];
    t_lo_[i] = t;
    active_[i] = g[i] != 0.0;
    inactive_ += g[i] == 0.0;
  }
  lo_at_start_ = inactive_ == 0;
}

void GuardCrossings::probe_unarmed(double t1, std::span<const double> g1, const Values& g_at) {
  const double tol = 100.0 * kUround * (std::abs(t1) + std::abs(t1 - t_));
  for (const std::size_t i : watched_) {
    const int d = directions_[i];
    if (active_[i] == 0 || d == 0 || !(d * g_lo_[i] > 0) || !(d * g1[i] > 0)) continue;
    for (int k = 1; k <= kProbeLevels; ++k) {
      const double s = t_ + std::ldexp(t1 - t_, -k);
      if (s - t_ <= tol) break;
      g_at(s, scratch_);
      if (d * scratch_[i] < 0) {  // on the side before the crossing: the bracket starts here
        g_lo_[i] = scratch_[i];
        t_lo_[i] = s;
        lo_at_start_ = false;
        break;
      }
    }
  }
}

bool GuardCrossings::refine(std::size_t i, Point a, Point b, int depth, const Values& g_at, Point& lo, Point& hi) {
  if (depth == 0 || budget_ == 0 || (a.g < 0) != (b.g < 0) || a.g == 0.0) return false;
  const double dt = b.t - a.t;
  if (std::min(std::abs(a.g), std::abs(b.g)) > curvature_[i] * dt * dt / 8) return false;  // no root possible
  const Point m{a.t + 0.5 * dt, 0.0};
  if (!(m.t > a.t && m.t < b.t)) return false;
  --budget_;
  ++interior_evaluations_;
  g_at(m.t, scratch_);
  const Point mid{m.t, scratch_[i]};
  // The new triple's curvature: twice the second divided difference, doubled for safety (above).
  curvature_[i] = std::max(curvature_[i], 8.0 * std::abs(a.g - 2.0 * mid.g + b.g) / (dt * dt));
  const int d = directions_[i];
  if (crosses(d, a.g, mid.g)) {
    lo = a, hi = mid;
    return true;
  }
  if (refine(i, a, mid, depth - 1, g_at, lo, hi)) return true;
  if (crosses(d, mid.g, b.g)) {
    lo = mid, hi = b;
    return true;
  }
  return refine(i, mid, b, depth - 1, g_at, lo, hi);
}

bool GuardCrossings::coarse_excludes(double t1, std::span<const double> g1, double t_mid, std::size_t mid) const {
  const std::size_t n = directions_.size();
  const double half = 0.5 * (t1 - t_);
  for (const std::size_t i : watched_) {
    if (active_[i] == 0 || t_lo_[i] >= t1) continue;
    // A guard activated after the midpoint has no second difference here: the full samples.
    if (!(t_lo_[i] < t_mid)) return false;
    const Point a{t_lo_[i], g_lo_[i]}, b{t_mid, samples_[mid * n + i]}, c{t1, g1[i]};
    if (a.g == b.g && b.g == c.g && finite_nonzero(a.g)) continue;  // an unused slot (above): reach 0
    if (a.g == 0.0 || b.g == 0.0 || c.g == 0.0 || (a.g < 0) != (b.g < 0) || (b.g < 0) != (c.g < 0)) return false;
    // M (h/2)²/8 with M = 4 |g[a, b, c]| (twice |g''|, above); with a at the step's start the
    // points are equally spaced and it is |g(a) - 2 g(b) + g(c)| / 4.
    const double reach =
        a.t == t_ ? 0.25 * std::abs(a.g - 2.0 * b.g + c.g)
                  : 0.5 * std::abs((c.g - b.g) / (c.t - b.t) - (b.g - a.g) / (b.t - a.t)) / (c.t - a.t) * half * half;
    const double least = std::min({std::abs(a.g), std::abs(b.g), std::abs(c.g)});
    if (!(least > kCoarseMargin * reach)) return false;
  }
  return true;
}

bool GuardCrossings::previous_step_excludes(double t1, std::span<const double> g1) const {
  const double h = t1 - t_, h_prev = t_ - prev_t_;
  if (!(h_prev > 0.0 && h_prev <= kPreviousStepRatio * h)) return false;
  // kCoarseMargin M h²/8 with M = 4 |g[a, b, c]| (twice the |g''| it shows, above):
  // reach · |(g(c) - g(b))/h - (g(b) - g(a))/h_prev|.
  const double reach = kCoarseMargin * 0.5 * h * h / (h + h_prev), w = 1.0 / h, w_prev = 1.0 / h_prev;
  bool excluded = true;
  for (const std::size_t i : watched_) {
    const double a = prev_g_[i], b = g_lo_[i], c = g1[i];
    // An unused slot (above) passes the test below, |v| > reach · 0: its arithmetic is skipped.
    if (a == b && b == c && finite_nonzero(a)) continue;
    const bool one_side = ((a > 0) & (b > 0) & (c > 0)) | ((a < 0) & (b < 0) & (c < 0));  // branch-free
    excluded =
        excluded & one_side & (std::min(std::abs(b), std::abs(c)) > reach * std::abs((c - b) * w - (b - a) * w_prev));
  }
  return excluded;
}

bool GuardCrossings::sample_interior(double t1, std::span<const double> g1, const Values& g_at) {
  const std::size_t n = directions_.size();
  const std::size_t inner = kSamples - 1;
  const double h = t1 - t_;
  const auto whole_step = [&] {  // each guard's bracket: the step (its part from t_lo_)
    for (const std::size_t i : watched_) {
      lo_t_[i] = t_lo_[i], lo_g_[i] = g_lo_[i];
      hi_t_[i] = t1, hi_g_[i] = g1[i];
    }
  };
  const double tol = 100.0 * kUround * (std::abs(t1) + std::abs(h));
  if (!(h > kSamples * tol)) {
    whole_step();
    return true;
  }
  // The previous step's end and this step's ends first (no evaluation): where they show every
  // guard far from 0 for its curvature, no sample (above).
  if (has_prev_ && lo_at_start_ && previous_step_excludes(t1, g1)) return false;
  std::array<double, kSamples - 1> times{};
  for (std::size_t j = 0; j < inner; ++j) times[j] = t_ + h * static_cast<double>(j + 1) / kSamples;
  const auto sample = [&](std::size_t j) {
    g_at(times[j], std::span<double>(samples_).subspan(j * n, n));
    ++interior_evaluations_;
  };
  // The midpoint first: where it shows every guard far from 0 for its curvature (the coarse
  // bound, above), the step is done with one sample.
  constexpr std::size_t mid = inner / 2;
  sample(mid);
  if (coarse_excludes(t1, g1, times[mid], mid)) return false;
  whole_step();
  for (std::size_t j = 0; j < inner; ++j)
    if (j != mid) sample(j);
  budget_ = kRefineBudget;
  std::array<Point, kSamples + 1> points{};
  for (const std::size_t i : watched_) {
    if (active_[i] == 0 || t_lo_[i] >= t1) continue;
    const int d = directions_[i];
    std::size_t count = 0;
    points[count++] = {t_lo_[i], g_lo_[i]};
    for (std::size_t j = 0; j < inner; ++j)
      if (times[j] > t_lo_[i]) points[count++] = {times[j], samples_[j * n + i]};
    points[count++] = {t1, g1[i]};
    // An unused slot (above): no crossing, every second difference 0 and the bound below
    // excludes a root; its arithmetic is skipped.
    bool constant = finite_nonzero(points[0].g);
    for (std::size_t j = 1; j < count; ++j) constant = constant && points[j].g == points[0].g;
    if (constant) continue;
    // A crossing at the samples: the first one brackets the root.
    bool crossed = false;
    for (std::size_t j = 1; j < count && !crossed; ++j) {
      if (!crosses(d, points[j - 1].g, points[j].g)) continue;
      lo_t_[i] = points[j - 1].t, lo_g_[i] = points[j - 1].g;
      hi_t_[i] = points[j].t, hi_g_[i] = points[j].g;
      crossed = true;
    }
    if (crossed) continue;
    // M: twice the largest |g''| the second divided differences show, g'' = 2 g[a, b, c]; with all
    // samples on one side of 0 and the bound (above) excluding 0 on the widest part, no root.
    double M = 0.0, least = std::abs(points[0].g);
    bool one_side = true;
    for (std::size_t j = 1; j < count; ++j) {
      least = std::min(least, std::abs(points[j].g));
      one_side = one_side && (points[j].g < 0) == (points[0].g < 0);
      if (j + 1 == count) break;
      const Point &a = points[j - 1], &b = points[j], &c = points[j + 1];
      const double dd = ((c.g - b.g) / (c.t - b.t) - (b.g - a.g) / (b.t - a.t)) / (c.t - a.t);
      M = std::max(M, 4.0 * std::abs(dd));
    }
    const double widest = h / kSamples;  // no part is wider (the first may be shorter)
    if (one_side && least > M * widest * widest / 8) continue;
    curvature_[i] = M;
    for (std::size_t j = 1; j < count; ++j) {
      Point lo{}, hi{};
      if (!refine(i, points[j - 1], points[j], kRefineDepth, g_at, lo, hi)) continue;
      lo_t_[i] = lo.t, lo_g_[i] = lo.g;
      hi_t_[i] = hi.t, hi_g_[i] = hi.g;
      break;
    }
  }
  return true;
}

std::optional<double> GuardCrossings::check(double t1, std::span<const double> g1, const Values& g_at,
                                            const Value& g_i_at) {
  const double tol = 100.0 * kUround * (std::abs(t1) + std::abs(t1 - t_));
  // Guards that were 0 where watching started: activated where they have moved away from 0.
  if (inactive_ > 0) {
    const double t_plus = t_ + std::max(tol, 0.1 * (t1 - t_));
    if (t_plus < t1) {
      g_at(t_plus, scratch_);
      for (const std::size_t i : watched_) {
        if (active_[i] == 0 && scratch_[i] != 0.0) {
          active_[i] = 1;
          --inactive_;
          g_lo_[i] = scratch_[i];
          t_lo_[i] = t_plus;
        }
      }
    }
    for (const std::size_t i : watched_) {
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
  const bool may_cross = sample_interior(t1, g1, g_at);
  // The earliest root among the guards that crossed.
  double first = t1;
  int first_guard = -1;
  if (may_cross) std::fill(roots_.begin(), roots_.end(), std::numeric_limits<double>::infinity());
  for (std::size_t j = 0; j < watched_.size() && may_cross; ++j) {
    const std::size_t i = watched_[j];
    if (active_[i] == 0 || lo_t_[i] >= hi_t_[i] || !crosses(directions_[i], lo_g_[i], hi_g_[i])) continue;
    const double root = locate_root([&](double t) { return g_i_at(t, static_cast<int>(i)); }, lo_t_[i], hi_t_[i],
                                    lo_g_[i], hi_g_[i], tol);
    roots_[i] = root;
    if (first_guard < 0 || root < first) {
      first = root;
      first_guard = static_cast<int>(i);
    }
  }
  if (first_guard < 0) {
    // This step's start, for the next step's bound (above), where every guard was watched from there.
    has_prev_ = lo_at_start_;
    prev_t_ = t_;
    if (has_prev_) prev_g_.swap(g_lo_);
    lo_at_start_ = inactive_ == 0;
    if (inactive_ == 0) {
      std::copy(g1.begin(), g1.end(), g_lo_.begin());
      std::fill(t_lo_.begin(), t_lo_.end(), t1);
    } else {
      for (const std::size_t i : watched_) {
        if (active_[i] == 0) continue;
        g_lo_[i] = g1[i];
        t_lo_[i] = t1;
      }
    }
    t_ = t1;
    return std::nullopt;
  }
  // Every guard that has crossed by the first root fires, and every guard whose own root lies
  // within the root tolerance of it (a tie: two roots that coincide but for round-off, e.g. two
  // feet slipping as one that reach stick together, fire together whatever the round-off, as
  // CVODE's guards crossing within its final bracket do); watching restarts there.
  std::vector<double>& g = scratch_;
  if (first < t1)
    g_at(first, g);
  else
    std::copy(g1.begin(), g1.end(), g.begin());
  for (const std::size_t i : watched_) {  // (a slot without a guard keeps fired_ 0 from start())
    // From the start of the guard's bracket in this step where that lies before the crossing.
    const double g_from = lo_t_[i] <= first ? lo_g_[i] : g_lo_[i];
    const bool fired = active_[i] != 0 && (crosses(directions_[i], g_from, g[i]) || roots_[i] <= first + tol);
    fired_[i] = fired || static_cast<int>(i) == first_guard ? (g_from > 0 ? -1 : 1) : 0;
  }
  rearm(first, g);
  return first;
}

}  // namespace flexgait::numerics
