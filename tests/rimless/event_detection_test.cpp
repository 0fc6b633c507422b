// Events that start and end within one integrator step (numerics/guard_crossings.hpp, the interior
// samples): a foot that leaves the friction cone and comes back within a long DOP853 step slips,
// at every tolerance; and over a seeded random sample of wheels the event sequence at the default
// tolerance is the one at rtol 1e-12, with every contact's invariants held on the dense output of
// an independent integration of each segment (sticking feet inside the friction cone, loaded feet
// pressing, free feet above the ground).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "flexgait/numerics/ode_integrator.hpp"
#include "flexgait/rimless/dynamics.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/flow.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

// The events of a run and the start of every smooth segment.
struct Record final : RunSink {
  void on_event(const EventRecord& e) override {
    if (e.kind != RunEvent::Start) events.push_back(e);
  }
  void on_restart(double t, std::span<const double> state, const ContactSet& contacts) override {
    restarts.push_back({t, std::vector<double>(state.begin(), state.end()), contacts});
  }
  std::vector<EventRecord> events;
  std::vector<Restart> restarts;
};

SimulationOptions events_only(int steps, double rtol = 1e-10) {
  SimulationOptions o = testing::run_options(steps, rtol);
  o.log = false;
  o.sample_dt = 10.0;
  o.max_step_time = 60.0;
  return o;
}

std::string time_text(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9f", t);
  return buf;
}

// How two event lists compare: the same (kind and leg) throughout, whatever their times; else
// different after their times had drifted apart by more than kDrift (the trajectories diverged: a
// sensitive run, the two tolerances' global errors grown past the event-detection question; on
// the seeded sample such runs also differ between rtol 1e-12, 1e-13 and 1e-14); else different
// but for a tie (the first difference is an event of the same kind at the same instant, to kTie,
// on another leg); else different (`text` shows where).
enum class Comparison { Same, Diverged, Tie, Different };
constexpr double kDrift = 1e-6, kTie = 1e-8;
Comparison compare(const std::vector<EventRecord>& a, const std::vector<EventRecord>& b, std::string& text) {
  std::size_t i = 0;
  bool diverged = false;
  // A run's failure record (at rest, slid away, ...) is dated where a decaying or growing quantity
  // passes a threshold, not at a guard's root: its time is not compared (a wheel coming to rest
  // whose 114 events agree to 4e-11 s between rtol 1e-10 and 1e-12 is declared at rest 0.28 s apart).
  const auto drifted = [&](std::size_t j) {
    return a[j].kind != RunEvent::Failure && std::abs(a[j].t - b[j].t) > kDrift;
  };
  while (i < a.size() && i < b.size() && a[i].kind == b[i].kind && a[i].leg == b[i].leg) {
    diverged = diverged || drifted(i);
    ++i;
  }
  if (i == a.size() && i == b.size()) return Comparison::Same;
  const auto show = [i](const std::vector<EventRecord>& v) {
    std::string s;
    for (std::size_t j = i > 0 ? i - 1 : 0; j < v.size() && j < i + 3; ++j)
      s += std::to_string(static_cast<int>(v[j].kind)) + ":" + std::to_string(v[j].leg) + "@" + time_text(v[j].t) +
           (v[j].message.empty() ? "" : " (" + v[j].message + ")") + " ";
    return s;
  };
  text = "event " + std::to_string(i) + ": " + show(a) + "| " + show(b);
  if (diverged) return Comparison::Diverged;
  if (i < a.size() && i < b.size() && a[i].kind == b[i].kind && std::abs(a[i].t - b[i].t) <= kTie)
    return Comparison::Tie;
  return Comparison::Different;
}

std::string sequence(const std::vector<EventRecord>& events) {
  std::string s;
  for (const EventRecord& e : events) s += std::to_string(static_cast<int>(e.kind)) + ":" + std::to_string(e.leg) + " ";
  return s;
}

using testing::Segment;

struct Violation {
  double cone = 0;     // worst (|T| - μ_s N) / (μ_s N) of a sticking foot
  double tension = 0;  // worst -N / (m g) of a foot on the ground
  double depth = 0;    // worst -h of a free foot [m]
};

// Every segment integrated again from its restart state to the next restart, the contacts' and free
// feet's invariants checked on kPerStep points of each step's dense output.
Violation invariants_on_dense_output(const WheelParams& w, const SimulationOptions& o,
                                     const std::vector<Restart>& restarts, double t_end) {
  constexpr int kPerStep = 32;
  // The two integrations differ by their global errors, so a guard's root on this one differs from
  // the run's by that over the guard's rate; at a lift-off N falls at up to ~1e9 N/s, and the
  // event location test holds the two roots to 1e-9 s: samples within 1e-8 s of the segment's
  // end are at its event.
  constexpr double kAtTheEvent = 1e-8;
  Violation v;
  for (std::size_t s = 0; s < restarts.size(); ++s) {
    const Restart& r = restarts[s];
    const double t1 = s + 1 < restarts.size() ? restarts[s + 1].t : t_end;
    if (!(t1 > r.t)) continue;
    Segment seg(w, r.contacts);
    numerics::OdeIntegrator integ(seg, state_size(w), integrator_options(w, o));
    integ.restart(r.t, r.state, std::vector<int>{});
    std::vector<double> y(r.state.size());
    double t0 = r.t;
    while (t0 < t1) {
      integ.step(t1);
      const double te = integ.time();
      for (int j = 1; j <= kPerStep; ++j) {
        const double ts = t0 + (te - t0) * j / kPerStep;
        if (ts > t1 - kAtTheEvent) break;
        integ.interpolate(ts, y);
        const Dynamics d = contact_dynamics(w, r.contacts, y);
        for (int i = 0; i < r.contacts.count; ++i) {
          const ContactForce& f = d.force[i];
          v.tension = std::max(v.tension, -f.N / (w.m * w.g));
          if (r.contacts.mode[i] == FootMode::Stick && f.N > 0)
            v.cone = std::max(v.cone, (std::abs(f.T) - w.mu_s * f.N) / (w.mu_s * f.N));
        }
        for (int k = 0; k < w.legs; ++k)
          if (r.contacts.find(k) < 0) v.depth = std::max(v.depth, -foot_height(w, k, y));
      }
      t0 = te;
    }
  }
  return v;
}

// The deepest a free foot may go: 1e-9 m (a foot that lifts off and never rises above the ground
// lands where its guard h + 1e-9 L0 reaches 0, L0 = 1 m), plus the round-off of h (~1e-16 m).
constexpr double kDepth = 1e-9 + 1e-15;

// The wheel of the reproducer: μ_s = μ_k = 1.0141, I = 0.4273, C = 22.928, K = 2642.4, N = 10,
// φ = 0.1577, ω0 = 2.3735 (m = L0 = 1).
WheelParams reproducer_wheel() {
  WheelParams w;
  w.mu_s = w.mu_k = 1.0141;
  w.I = 0.4273;
  w.C = 22.928;
  w.K = 2642.4;
  w.legs = 10;
  w.slope = 0.1577;
  return w;
}

TEST(EventDetection, AFootThatLeavesTheConeWithinOneStepSlips) {
  const WheelParams w = reproducer_wheel();
  Record fine, run;
  const SimulationResult ref = simulate_flexible(w, InitialState{2.3735}, events_only(20, 1e-12), fine);
  const SimulationResult r = simulate_flexible(w, InitialState{2.3735}, events_only(20), run);
  ASSERT_FALSE(r.failure.has_value()) << *r.failure;
  EXPECT_EQ(r.steps_completed, 20);
  EXPECT_EQ(sequence(run.events), sequence(fine.events));
  // Leg 1 slips from 6.060336 to 6.068974 s (an independent implementation's times, given to
  // 1e-6 s): the stick→slip and slip→stick events there, each within 1e-6 s.
  double slip_start = -1, slip_end = -1;
  for (const EventRecord& e : run.events) {
    if (e.leg != 1 || e.t < 6.0 || e.t > 6.1) continue;
    if (e.kind == RunEvent::StickToSlip && slip_start < 0) slip_start = e.t;
    if (e.kind == RunEvent::SlipToStick && slip_start >= 0 && slip_end < 0) slip_end = e.t;
  }
  EXPECT_NEAR(slip_start, 6.060336, 1e-6);
  EXPECT_NEAR(slip_end, 6.068974, 1e-6);
  const Violation v = invariants_on_dense_output(w, events_only(20), run.restarts, r.t_final);
  EXPECT_LE(v.cone, 1e-6);
  EXPECT_LE(v.depth, kDepth);
  EXPECT_LE(v.tension, 1e-6);
}

// The seeded random sample of tests/rimless/parameter_space_test.cpp (the same generator, seed
// and ranges: μ 0.05–5 log-uniform, I 0.02–1, C 5–60, K 300–1e4 log-uniform, N 6–14, φ 0.03–0.2,
// ω0 1–3; 20 steps; test_support.hpp), its first FLEXGAIT_RANDOM_WHEELS sets (10 here: ~1 s; all 200 by setting it).

TEST(EventDetection, RandomWheelsHaveTheEventsOfRtol1e12AndHoldTheirInvariants) {
  const char* env = std::getenv("FLEXGAIT_RANDOM_WHEELS");
  const int sets = env != nullptr ? std::atoi(env) : 10;
  testing::SplitMix64 rng{20261123};
  std::array<int, 4> counts{};
  Violation worst;
  for (int i = 0; i < sets; ++i) {
    const testing::RandomWheel s = testing::RandomWheel::draw(rng);
    const WheelParams w = s.params();
    const double omega0 = s.omega0;
    SCOPED_TRACE(::testing::Message() << "set " << i << ": mu " << w.mu_s << " I " << w.I << " C " << w.C << " K "
                                      << w.K << " N " << w.legs << " slope " << w.slope << " omega0 " << omega0);
    Record fine, run;
    simulate_flexible(w, InitialState{omega0}, events_only(20, 1e-12), fine);
    const SimulationResult r = simulate_flexible(w, InitialState{omega0}, events_only(20), run);
    std::string where;
    const Comparison c = compare(run.events, fine.events, where);
    ++counts[static_cast<std::size_t>(c)];
    EXPECT_NE(c, Comparison::Different) << where << " (rtol 1e-10 | rtol 1e-12)";
    if (c == Comparison::Diverged || c == Comparison::Tie)
      std::printf("set %d: %s %s\n", i, c == Comparison::Tie ? "tie" : "diverged", where.c_str());
    const Violation v = invariants_on_dense_output(w, events_only(20), run.restarts, r.t_final);
    // The targets: no sticking foot outside the cone by more than 1e-6 relative, no free foot below
    // -1e-9 m; a loaded foot pulls by no more than 1e-6 m g (the consistency check's tolerance).
    EXPECT_LE(v.cone, 1e-6);
    EXPECT_LE(v.depth, kDepth);
    EXPECT_LE(v.tension, 1e-6);
    worst.cone = std::max(worst.cone, v.cone);
    worst.depth = std::max(worst.depth, v.depth);
    worst.tension = std::max(worst.tension, v.tension);
  }
  RecordProperty("same_sequence", counts[0]);
  std::printf(
      "%d sets: %d the same event sequence, %d different after their times drifted apart by > 1e-6 s, %d "
      "different at a tie, %d different; worst cone excess %.3g, depth %.3g m, tension %.3g m g\n",
      sets, counts[0], counts[1], counts[2], counts[3], worst.cone, worst.depth, worst.tension);
}

// Landings of feet that left the ground: a foot that rose above it lands at h = 0 (to 1e-12 m),
// however little it rose, also one whose touchdown guard was never armed (it had not been 1e-9 m
// above the ground at a step's end). Returns the landings checked (all, and the micro-bounces
// among them: rose less than 1 µm); how high each foot rose is read off an independent
// integration of its flight segment.
struct Landings {
  int checked = 0, micro = 0;
  double worst = 0;  // the largest |h| at a checked landing [m]
};
Landings landings_at_zero(const WheelParams& w, const SimulationOptions& o, const Record& run) {
  Landings out;
  for (std::size_t s = 0; s + 1 < run.restarts.size(); ++s) {
    const Restart &r = run.restarts[s], &next = run.restarts[s + 1];
    Segment seg(w, r.contacts);
    numerics::OdeIntegrator integ(seg, state_size(w), integrator_options(w, o));
    integ.restart(r.t, r.state, std::vector<int>{});
    std::vector<double> y(r.state.size());
    std::vector<double> highest(static_cast<std::size_t>(w.legs), -INFINITY);
    for (double t0 = r.t; t0 < next.t;) {
      integ.step(next.t);
      const double te = integ.time();
      for (int j = 1; j <= 32; ++j) {
        integ.interpolate(t0 + (te - t0) * j / 32, y);
        for (int k = 0; k < w.legs; ++k)
          if (r.contacts.find(k) < 0)
            highest[static_cast<std::size_t>(k)] = std::max(highest[static_cast<std::size_t>(k)], foot_height(w, k, y));
      }
      t0 = te;
    }
    for (const EventRecord& e : run.events) {
      if (e.t != next.t || e.kind != RunEvent::Touchdown || r.contacts.find(e.leg) >= 0) continue;
      const double rose = highest[static_cast<std::size_t>(e.leg)];
      if (!(rose > 1e-14)) continue;  // it never rose: it left with the ground pushing it back
      const double h = foot_height(w, e.leg, next.state);
      ++out.checked;
      out.micro += rose < 1e-6;
      out.worst = std::max(out.worst, std::abs(h));
    }
  }
  return out;
}

TEST(EventDetection, MicroBouncesLandAtZeroHeight) {
  const char* env = std::getenv("FLEXGAIT_RANDOM_WHEELS");
  const int sets = env != nullptr ? std::atoi(env) : 10;
  testing::SplitMix64 rng{20261123};
  Landings all;
  for (int i = 0; i < sets; ++i) {
    const testing::RandomWheel s = testing::RandomWheel::draw(rng);
    const WheelParams w = s.params();
    Record run;
    simulate_flexible(w, InitialState{s.omega0}, events_only(20), run);
    const Landings l = landings_at_zero(w, events_only(20), run);
    if (l.micro > 0)
      std::printf("set %d: %d landings, %d micro-bounces, worst |h| %.3g m\n", i, l.checked, l.micro, l.worst);
    all.checked += l.checked;
    all.micro += l.micro;
    all.worst = std::max(all.worst, l.worst);
  }
  EXPECT_LE(all.worst, 1e-12);
  EXPECT_GT(all.micro, 0);  // the sample has micro-bounces (1 in the first 10 sets, 78 in all 200)
  std::printf("%d landings, %d micro-bounces, worst |h| %.3g m\n", all.checked, all.micro, all.worst);
}

}  // namespace
}  // namespace flexgait::rimless
