#!/usr/bin/python3
"""An independent reference of the flexible-leg rimless wheel with stick-slip friction, in SciPy.

The model of docs/theory/rimless.md (Bao, Zhang and Zhou 2024: a rimless wheel whose spokes are
massless spring-damper legs, each foot on the ground sticking or slipping under Coulomb friction),
written again from its equations with numpy and scipy.integrate.solve_ivp (DOP853, its own event
location) and nothing of flexgait's C++ engine. It is the yardstick of two things:

- correctness: two implementations that share only the equations must give the same touchdown
  times and states (tests/rimless/scipy_reference_test.py holds the engine to it);
- speed: the engine's cost per wheel step against this script's (bench/rimless_bench.cpp times
  the engine on the same wheel and the same 20 steps; `--time` here).

Usage:
    rimless_scipy_reference.py [--config FILE] [--set KEY=VALUE ...] [--steps N]
                               [--events FILE] [--touchdowns FILE] [--compare RUN_DIR] [--time R]
--config/--set take flexgait's keys (rimless.*, initial.omega, initial.beta, sim.steps,
solver.rtol, solver.atol); --compare RUN_DIR holds the run to a `flexgait rimless simulate` run
directory (events.csv, log.csv) and prints the largest differences; --time R runs the simulation
R times and prints the CPU and wall time per wheel step, median and best (Python's start-up and
imports excluded).
Example (the engine's side: build/release/bench/rimless_bench --benchmark_filter=FlexibleWheelStepDop853):
    bench/rimless_scipy_reference.py --config configs/rimless.yaml --set rimless.mu_s=0.13 \
        --set rimless.mu_k=0.13 --time 5

The model, as implemented here (slope frame: x down the slope, y along its normal; gravity
g (sin φ, -cos φ); q = (x, y, θ) the hub and the wheel's angle; leg k at β_k = θ + 2αk, α = π/N):
- a foot on the ground: L_k = y / cos β_k, δ_k = L0 - L_k, axial force f_k = K δ_k + C δ̇_k;
  foot position c_k = x - y tan β_k, A_k = ∂c_k/∂q = (1, -tan β_k, -y / cos² β_k);
  generalised force f_k ∂L_k/∂q + A_k^T T_k with ∂L_k/∂q = (0, 1/cos β_k, L_k tan β_k);
  diag(m, m, I) q̈ = m g (sin φ, -cos φ, 0) + Σ_k (f_k ∂L_k/∂q + A_k^T T_k);
- stick: A_k q̈ = -Ȧ_k q̇ with T_k the multiplier (index-reduced, no stabilisation: c_k drifts
  by the integration error only); slip: T_k = -μ_k s f_k / (cos β_k - μ_k s sin β_k), s = sign ċ_k;
  N_k = (f_k - T_k sin β_k) / cos β_k;
- a free leg relaxes, K δ + C δ̇ = 0, in closed form: δ(t) = δ(t_off) exp(-K (t - t_off) / C);
- events (located by solve_ivp on DOP853's dense output): touchdown (y - (L0 - δ_k) cos β_k
  crosses 0 downward), lift-off (N_k crosses 0 downward), stick→slip (|T_k|/N_k - μ_s crosses 0
  upward, as atan2(|T_k|, N_k) - atan μ_s), slip→stick (ċ_k crosses 0), a slip's denominator
  cos β - μ_k s sin β reaching 0 (jam), a stance leg reaching |β| = π/2 (failure); only at the
  ends of DOP853's steps, as solve_ivp does: a crossing and its return inside one step is not seen;
- between events the touchdown guards of the free legs that could reach cos β > 0 are watched,
  chosen again after every rotation of the wheel by 2α;
- a landing foot slips in the direction it moves; if that slip's denominator is ≤ 0 (a
  Painlevé jam) a tangential impulse perpendicular to its leg stops it (M Δq̇ = A^T Π, no
  impulse along the spring leg); a foot on the ground that this would set slipping with a
  non-positive denominator (a sticking trailing foot at a landing, at large μ) is stopped by the
  same impulse problem; a foot with a positive one carries no impulse (a perpendicular impulse
  lies outside its friction cone). The lost kinetic energy is booked as friction work;
- modes at an event: the foot whose guard fired is decided by its event (stick→slip: slip with
  s = -sign T_stick; lift-off: leaves; slip→stick: stick, else slip either way; touchdown: slip
  with s = sign ċ); every other foot keeps its mode if the combination is consistent, else the
  combinations are enumerated (each foot: its previous mode, then stick, then slip, then leave)
  and the first consistent one is taken: stick needs |ċ| ≈ 0, N ≥ 0 and |T| ≤ μ_s N; slip needs
  N ≥ 0, a positive denominator and, from |ċ| ≈ 0, an acceleration c̈ in its direction; leave
  needs f ≤ 0 (a free leg's foot then rises: dh/dt = -cos β f / C).
A touchdown of a leg ahead of the stance leg ends a wheel step (flexgait's sim.steps).
The wheel needs I > 0 (the θ row of the mass matrix is inverted).
"""
import argparse
import csv
import itertools
import math
import os
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

# The keys read from a flexgait configuration and their defaults (configs/rimless.yaml).
DEFAULTS = {
    "rimless.m": 1.0,
    "rimless.I": 0.3,
    "rimless.legs": 10,
    "rimless.slope": 0.1,
    "rimless.L0": 1.0,
    "rimless.K": 1000.0,
    "rimless.C": 30.0,
    "rimless.mu_s": 0.6,
    "rimless.mu_k": 0.6,
    "rimless.g": 9.81,
    "initial.omega": 1.4,
    "initial.beta": 0.0,
    "sim.steps": 20,
    "sim.max_time": 120.0,
    "solver.rtol": 1e-10,
    "solver.atol": 1e-12,
}

STICK, SLIP = "stick", "slip"


class ReferenceError(RuntimeError):
    """The run cannot go on (a failure of the wheel or no consistent contact mode)."""


class Wheel:
    def __init__(self, p):
        self.m = float(p["rimless.m"])
        self.I = float(p["rimless.I"])
        self.legs = int(p["rimless.legs"])
        self.slope = float(p["rimless.slope"])
        self.L0 = float(p["rimless.L0"])
        self.K = float(p["rimless.K"])
        self.C = float(p["rimless.C"])
        self.mu_s = float(p["rimless.mu_s"])
        self.mu_k = float(p["rimless.mu_k"])
        self.g = float(p["rimless.g"])
        if not self.I > 0:
            raise ReferenceError("rimless.I must be > 0 for the reference (the mass matrix is inverted)")
        self.alpha = math.pi / self.legs
        self.gx = self.m * self.g * math.sin(self.slope)
        self.gy = -self.m * self.g * math.cos(self.slope)
        self.minv = (1.0 / self.m, 1.0 / self.m, 1.0 / self.I)

    def beta(self, k, theta):
        return theta + 2.0 * self.alpha * k

    def free_delta(self, free, k, t):
        """A free leg's compression at t: K δ + C δ̇ = 0 from its value at lift-off."""
        d0, t0 = free[k]
        if d0 == 0.0:
            return 0.0
        if self.C == 0.0:
            return 0.0
        return d0 * math.exp(-self.K / self.C * (t - t0))


def wrap(a):
    """a in (-π, π]."""
    return a - 2.0 * math.pi * math.floor((a + math.pi) / (2.0 * math.pi))


class Foot:
    """One foot on the ground at one state: kinematics, axial force, and (after solve) T, N, c̈."""

    __slots__ = ("leg", "mode", "s", "cb", "sb", "L", "Lq", "A", "Adq", "delta", "ddelta", "f", "cdot", "T", "N", "cdd",
                 "den")

    def __init__(self, w, leg, mode, s, z):
        y, yd, thd = z[1], z[4], z[5]
        b = z[2] + 2.0 * w.alpha * leg
        cb, sb = math.cos(b), math.sin(b)
        tb = sb / cb
        L = y / cb
        self.leg, self.mode, self.s = leg, mode, s
        self.cb, self.sb, self.L = cb, sb, L
        self.Lq = (0.0, 1.0 / cb, L * tb)
        self.A = (1.0, -tb, -y / (cb * cb))
        # dA/dt q̇ with β̇ = θ̇
        self.Adq = -2.0 * yd * thd / (cb * cb) - 2.0 * y * sb * thd * thd / (cb * cb * cb)
        self.delta = w.L0 - L
        self.ddelta = -(yd / cb + L * tb * thd)
        self.f = w.K * self.delta + w.C * self.ddelta
        self.cdot = z[3] - tb * yd + self.A[2] * thd
        self.den = cb - w.mu_k * s * sb if mode == SLIP else 1.0
        self.T = self.N = self.cdd = 0.0


def solve_contacts(w, contacts, z):
    """The accelerations q̈ and the feet (with T, N and c̈) for the feet `contacts` [(leg, mode, s)]
    at state z. A slip with a non-positive denominator (a jam) gets T = N = nan."""
    feet = [Foot(w, leg, mode, s, z) for leg, mode, s in contacts]
    F = [w.gx, w.gy, 0.0]
    sticks = []
    for ft in feet:
        F[1] += ft.f * ft.Lq[1]
        F[2] += ft.f * ft.Lq[2]
        if ft.mode == SLIP:
            ft.T = -w.mu_k * ft.s * ft.f / ft.den if ft.den > 0.0 else math.nan
            F[0] += ft.A[0] * ft.T
            F[1] += ft.A[1] * ft.T
            F[2] += ft.A[2] * ft.T
        else:
            sticks.append(ft)
    mi = w.minv
    if sticks:
        # (A_i M⁻¹ A_j^T) T_j = -Ȧ_i q̇ - A_i M⁻¹ F
        n = len(sticks)
        m0, m1, m2 = mi
        G = [[a.A[0] * m0 * b.A[0] + a.A[1] * m1 * b.A[1] + a.A[2] * m2 * b.A[2] for b in sticks] for a in sticks]
        r = [-a.Adq - (a.A[0] * m0 * F[0] + a.A[1] * m1 * F[1] + a.A[2] * m2 * F[2]) for a in sticks]
        if n == 1:
            Ts = [r[0] / G[0][0]]
        elif n == 2:
            det = G[0][0] * G[1][1] - G[0][1] * G[1][0]
            Ts = [(r[0] * G[1][1] - G[0][1] * r[1]) / det, (G[0][0] * r[1] - G[1][0] * r[0]) / det]
        else:
            Ts = list(np.linalg.solve(np.array(G), np.array(r)))
        for ft, T in zip(sticks, Ts):
            ft.T = T
            F[0] += ft.A[0] * T
            F[1] += ft.A[1] * T
            F[2] += ft.A[2] * T
    qdd = (F[0] * mi[0], F[1] * mi[1], F[2] * mi[2])
    for ft in feet:
        ft.N = (ft.f - ft.T * ft.sb) / ft.cb
        ft.cdd = ft.A[0] * qdd[0] + ft.A[1] * qdd[1] + ft.A[2] * qdd[2] + ft.Adq
    return qdd, feet


def energy(w, z, contacts, free, t):
    """Mechanical energy [J]: kinetic + gravity + every leg's spring (free legs included)."""
    E = 0.5 * w.m * (z[3] ** 2 + z[4] ** 2) + 0.5 * w.I * z[5] ** 2
    E += -w.gx * z[0] - w.gy * z[1]
    on = {leg for leg, _, _ in contacts}
    for k in range(w.legs):
        if k in on:
            d = w.L0 - z[1] / math.cos(w.beta(k, z[2]))
        else:
            d = w.free_delta(free, k, t)
        E += 0.5 * w.K * d * d
    return E


class Segment:
    """One smooth segment: the right-hand side and the guards of fixed contact modes."""

    def __init__(self, w, contacts, free, z0):
        self.w, self.contacts, self.free = w, contacts, free
        self.key = None
        self.val = None
        self.events = []
        self.kinds = []  # (kind, leg) per event function
        theta0 = z0[2]
        on = {leg for leg, _, _ in contacts}
        # Touchdown candidates: free legs that can reach cos β > 0 within a rotation of 2α (the
        # segment ends at such a rotation and the candidates are chosen again).
        for k in range(w.legs):
            if k in on:
                continue
            if math.cos(w.beta(k, theta0)) > -math.sin(2.0 * w.alpha):
                self._add(self._touchdown(k), -1, ("touchdown", k))
        for i, (leg, mode, s) in enumerate(contacts):
            self._add(self._normal(i), -1, ("liftoff", leg))
            self._add(self._cosb(leg), -1, ("fall", leg))
            if mode == STICK:
                self._add(self._ratio(i), 1, ("stick_to_slip", leg))
            else:
                self._add(self._cdot(i), -s, ("slip_to_stick", leg))
                self._add(self._den(i), -1, ("slip_jam", leg))
        rot = 2.0 * w.alpha
        self._add(lambda t, z: (z[2] - theta0) ** 2 - rot * rot, 1, ("refresh", -1))

    def _add(self, fn, direction, kind):
        fn.terminal = True
        fn.direction = direction
        self.events.append(fn)
        self.kinds.append(kind)

    def evaluate(self, t, z):
        key = (t, z[0], z[1], z[2], z[3], z[4], z[5])
        if key != self.key:
            self.val = solve_contacts(self.w, self.contacts, z)
            self.key = key
        return self.val

    def rhs(self, t, z):
        qdd, feet = self.evaluate(t, z)
        C = self.w.C
        wd = 0.0
        wf = 0.0
        for ft in feet:
            wd += C * ft.ddelta * ft.ddelta
            if ft.mode == SLIP:
                wf -= ft.T * ft.cdot
        return [z[3], z[4], z[5], qdd[0], qdd[1], qdd[2], wd, wf]

    def _touchdown(self, k):
        w, free = self.w, self.free

        def g(t, z):
            return z[1] - (w.L0 - w.free_delta(free, k, t)) * math.cos(z[2] + 2.0 * w.alpha * k)

        return g

    def _normal(self, i):
        return lambda t, z: self.evaluate(t, z)[1][i].N

    def _ratio(self, i):
        # |T|/N - μ_s as the reaction's angle from the normal, atan2(|T|, N) - atan μ_s: the same
        # zero, and continuous where N passes 0 with T ≠ 0 (the foot leaves the cone before it
        # leaves the ground). It jumps only where T and N vanish together, at a lift-off inside the
        # cone, where the lift-off guard has the same root (Simulation.run tells them apart).
        edge = math.atan(self.w.mu_s)

        def g(t, z):
            ft = self.evaluate(t, z)[1][i]
            return math.atan2(abs(ft.T), ft.N) - edge

        return g

    def _cdot(self, i):
        return lambda t, z: self.evaluate(t, z)[1][i].cdot

    def _den(self, i):
        return lambda t, z: self.evaluate(t, z)[1][i].den

    def _cosb(self, leg):
        w = self.w
        return lambda t, z: math.cos(z[2] + 2.0 * w.alpha * leg)


class Simulation:
    def __init__(self, params):
        self.p = dict(params)
        self.w = Wheel(self.p)
        self.rtol = float(self.p["solver.rtol"])
        self.atol = float(self.p["solver.atol"])
        self.v_scale = math.sqrt(self.w.g * self.w.L0)
        # |ċ| below this is "at rest" when modes are chosen: far above the drift of a sticking
        # foot's ċ (the integration error, ~rtol √(g L0)) and far below any landing or slip speed.
        self.v_tol = 1e-7 * self.v_scale
        self.n_tol = 1e-9 * self.w.m * self.w.g  # N ≥ -n_tol
        self.events = []  # (t, kind, leg, modes)
        # every touchdown: t, leg, the state (x, y, θ, ẋ, ẏ, θ̇) before and after the reset, whether
        # it starts a wheel step (a leg ahead of the stance leg; else a bounce)
        self.touchdowns = []
        self.rhs_evals = 0
        self.jams = 0

    # -- modes ------------------------------------------------------------------------------
    def modes_text(self, contacts):
        text = " ".join(f"{leg}:{mode if mode == STICK else ('slip+' if s > 0 else 'slip-')}"
                        for leg, mode, s in contacts if mode != "leave")
        return text or "flight"

    def consistent(self, z, combo, exempt=()):
        """combo: [(leg, mode, s)] with mode stick, slip or leave; True if every foot's mode holds."""
        staying = [c for c in combo if c[1] != "leave"]
        _, feet = solve_contacts(self.w, staying, z)
        feet_by_leg = {ft.leg: ft for ft in feet}
        for leg, mode, s in combo:
            if mode == "leave":
                f = Foot(self.w, leg, STICK, 0, z).f
                if f > self.n_tol:
                    return False
                continue
            ft = feet_by_leg[leg]
            if not ft.N >= -self.n_tol:
                return False
            if mode == STICK:
                if abs(ft.cdot) > self.v_tol or abs(ft.T) > self.w.mu_s * ft.N + self.n_tol:
                    return False
            else:
                if not ft.den > 0.0:
                    return False
                if abs(ft.cdot) > self.v_tol:
                    if ft.cdot * s < 0:
                        return False
                elif leg not in exempt and ft.cdd * s < 0:
                    return False
        return True

    def choose(self, z, contacts, decided, exempt=()):
        """New contacts: `decided` {leg: [candidates in order]} for the feet whose event fired,
        the others keep their mode if consistent, else the first consistent combination."""
        options = []
        for leg, mode, s in contacts:
            if leg in decided:
                options.append([(leg, m, ss) for m, ss in decided[leg]])
                continue
            cdot = Foot(self.w, leg, STICK, 0, z).cdot
            opts = [(leg, mode, s)]
            if abs(cdot) <= self.v_tol:
                opts += [(leg, STICK, 0), (leg, SLIP, 1), (leg, SLIP, -1)]
            else:
                opts += [(leg, SLIP, 1 if cdot > 0 else -1)]
            opts.append((leg, "leave", 0))
            seen = []
            for o in opts:
                if o not in seen:
                    seen.append(o)
            options.append(seen)
        for combo in itertools.product(*options):
            if self.consistent(z, combo, exempt):
                return list(combo)
        raise ReferenceError(f"no consistent contact mode for feet {[c[0] for c in contacts]} at state {list(z[:6])}")

    # -- the run ----------------------------------------------------------------------------
    def initial(self):
        """Single support on leg 0 at β = initial.beta, foot at c = 0, the leg compressed
        statically by m g cos φ / K, rolling about the foot at θ̇ = initial.omega (ċ = 0, δ̇ = 0)."""
        w = self.w
        omega, beta = float(self.p["initial.omega"]), float(self.p["initial.beta"])
        L = w.L0 - w.m * w.g * math.cos(w.slope) / w.K
        y = L * math.cos(beta)
        return np.array([y * math.tan(beta), y, beta, L * omega * math.cos(beta), -L * omega * math.sin(beta), omega,
                         0.0, 0.0])

    def jam(self, z, contacts, leg):
        """Stops foot `leg` by a tangential impulse perpendicular to its leg (its spring carries no
        impulse): M Δq̇ = Σ_j A_j^T Π_j with A_j q̇⁺ = 0 for every stopped foot j. A foot on the ground
        that the impulse would set slipping with a non-positive denominator is jammed as well and
        joins the stopped feet (a foot with a positive one cannot take a perpendicular impulse
        inside its friction cone, so it carries none). Each stopped foot's normal impulse
        -Π_j tan β_j must be ≥ 0. Returns the kinetic energy taken (friction work)."""
        w = self.w
        mi = w.minv
        v0 = z[3:6].copy()
        stopped = [leg]
        while True:
            z[3:6] = v0
            feet = [Foot(w, j, STICK, 0, z) for j in stopped]
            G = np.array([[sum(a.A[d] * mi[d] * b.A[d] for d in range(3)) for b in feet] for a in feet])
            P = np.linalg.solve(G, np.array([-a.cdot for a in feet]))
            for ft, Pj in zip(feet, P):
                for d in range(3):
                    z[3 + d] += mi[d] * ft.A[d] * Pj
            more = []
            for c in contacts:
                if c[0] in stopped:
                    continue
                cdot = Foot(w, c[0], STICK, 0, z).cdot
                if abs(cdot) > self.v_tol and Foot(w, c[0], SLIP, 1 if cdot > 0 else -1, z).den <= 0.0:
                    more.append(c[0])
            if not more:
                break
            stopped += more
        for ft, Pj in zip(feet, P):
            if -Pj * ft.sb / ft.cb < -self.n_tol * 1e-3:
                raise ReferenceError(f"jam of foot {leg}: foot {ft.leg} would need a pulling impulse")
        self.jams += 1
        ke = lambda v: 0.5 * w.m * (v[0] ** 2 + v[1] ** 2) + 0.5 * w.I * v[2] ** 2  # noqa: E731
        return ke(v0) - ke(z[3:6]), stopped

    def run(self, steps=None):
        w = self.w
        steps = int(self.p["sim.steps"]) if steps is None else steps
        t_max = float(self.p["sim.max_time"])
        t = 0.0
        z = self.initial()
        free = {k: (0.0, 0.0) for k in range(w.legs)}
        contacts = self.choose(z, [(0, STICK, 0)], {0: [(STICK, 0), (SLIP, 1), (SLIP, -1)]})
        self.events.append((t, "start", 0, self.modes_text(contacts)))
        self.E0 = energy(w, z, contacts, free, t)
        self.w_free_done = 0.0  # work of the free legs' dampers up to their touchdowns (closed form)
        stance = 0
        done = 0
        while done < steps:
            seg = Segment(w, contacts, free, z)
            count = [0]

            def fun(tt, zz, seg=seg, count=count):
                count[0] += 1
                return seg.rhs(tt, zz)

            sol = solve_ivp(fun, (t, t_max), z, method="DOP853", rtol=self.rtol, atol=self.atol, events=seg.events)
            self.rhs_evals += count[0]
            if sol.status != 1:
                raise ReferenceError(f"no event before t = {t_max} s (sim.max_time) or solver failure: {sol.message}")
            t_new = sol.t[-1]
            z = sol.y[:, -1].copy()
            # the event that ended the segment: the earliest root (solve_ivp stops at it)
            fired = [i for i, te in enumerate(sol.t_events) if len(te) and te[-1] == t_new]
            kind, leg = seg.kinds[fired[0]]
            t = t_new
            if kind == "refresh":
                continue
            if kind == "fall":
                raise ReferenceError(f"leg {leg} passed |beta| = pi/2 at t = {t}")
            if kind == "touchdown":
                b = wrap(w.beta(leg, z[2]))
                if b > 0 and z[5] < 0 and z[3] < 0:
                    raise ReferenceError(f"the wheel rolled back onto leg {leg} at t = {t}")
                new_step = wrap(b - wrap(w.beta(stance, z[2]))) < 0
                self.touchdowns.append([t, leg, z[:6].copy(), None, new_step])
                if new_step:
                    stance = leg
                    done += 1
                s = 1 if Foot(w, leg, STICK, 0, z).cdot > 0 else -1
                jammed = Foot(w, leg, SLIP, s, z).den <= 0.0
                d0, d1 = free[leg][0], w.free_delta(free, leg, t)
                self.w_free_done += 0.5 * w.K * (d0 * d0 - d1 * d1)
                del free[leg]
                contacts = contacts + [(leg, SLIP, s)]
                if jammed:
                    work, stopped = self.jam(z, contacts, leg)
                    z[7] += work
                    decided = {j: [(STICK, 0), (SLIP, 1), (SLIP, -1), ("leave", 0)] for j in stopped if j != leg}
                    decided[leg] = [(STICK, 0), (SLIP, 1), (SLIP, -1)]
                else:
                    decided = {leg: [(SLIP, s)]}
                contacts = self.choose(z, contacts, decided)
                if jammed:
                    self.events.append((t, "jam", leg, self.modes_text(contacts)))
                self.events.append((t, "touchdown", leg, self.modes_text(contacts)))
                self.touchdowns[-1][3] = z[:6].copy()  # after the reset (a jam's impulse)
            if kind == "stick_to_slip":
                _, feet = solve_contacts(w, contacts, z)
                ft = next(ft for ft in feet if ft.leg == leg)
                if not (ft.N > 0 and abs(ft.T) >= w.mu_s * ft.N * (1 - 1e-6)):
                    kind = "liftoff"  # the guard's jump where T and N vanish together
            if kind == "liftoff":
                contacts = self.choose(z, contacts, {leg: [("leave", 0)]})
                self.events.append((t, "liftoff", leg, self.modes_text(contacts)))
            elif kind == "stick_to_slip":
                T = ft.T
                # its incipient acceleration is 0 here (|T| = μ_s N): the direction is -sign T
                contacts = self.choose(z, contacts, {leg: [(SLIP, -1 if T > 0 else 1)]}, exempt=(leg,))
                self.events.append((t, "stick_to_slip", leg, self.modes_text(contacts)))
            elif kind == "slip_to_stick":
                s_prev = next(c[2] for c in contacts if c[0] == leg)
                contacts = self.choose(z, contacts, {leg: [(STICK, 0), (SLIP, -s_prev), (SLIP, s_prev)]})
                self.events.append((t, "slip_to_stick", leg, self.modes_text(contacts)))
            elif kind == "slip_jam":
                work, stopped = self.jam(z, contacts, leg)
                z[7] += work
                contacts = self.choose(z, contacts, {j: [(STICK, 0), (SLIP, 1), (SLIP, -1), ("leave", 0)]
                                                     for j in stopped})
                self.events.append((t, "jam", leg, self.modes_text(contacts)))
            # the feet that left relax freely from their compression now
            for c in contacts:
                if c[1] == "leave":
                    free[c[0]] = (Foot(w, c[0], STICK, 0, z).delta, t)
            contacts = [c for c in contacts if c[1] != "leave"]
        self.steps = done
        self.t_end = t
        self.z_end = z
        self.contacts_end = contacts
        self.free_end = free
        return self

    def energy_error(self):
        """E(t) + W_damp + W_fric - E(0) at the end [J] (the free legs' damper work in closed form:
        what their springs lost since lift-off)."""
        w, t = self.w, self.t_end
        E = energy(w, self.z_end, self.contacts_end, self.free_end, t)
        w_free = 0.0
        # every lift-off's leftover spring energy that has decayed since is damper work; free legs
        # still relaxing hold the rest in E. The runs' free legs start at δ = 0 or at a lift-off.
        for k, (d0, t0) in self.free_end.items():
            w_free += 0.5 * w.K * (d0 * d0 - w.free_delta(self.free_end, k, t) ** 2)
        return E + self.z_end[6] + self.z_end[7] + w_free + self.w_free_done - self.E0


def parse_params(config, sets):
    p = dict(DEFAULTS)
    if config:
        import yaml
        with open(config) as fh:
            doc = yaml.safe_load(fh) or {}
        for section, values in doc.items():
            if isinstance(values, dict):
                for k, v in values.items():
                    key = f"{section}.{k}"
                    if key in p:
                        p[key] = v
    for item in sets:
        key, _, value = item.partition("=")
        if key not in p:
            raise SystemExit(f"rimless_scipy_reference.py: --set {item}: unknown key {key!r} "
                             f"(allowed: {', '.join(sorted(p))})")
        p[key] = float(value)
    return p


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--config")
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--steps", type=int)
    ap.add_argument("--events", help="write the events as CSV (t,kind,leg,modes)")
    ap.add_argument("--touchdowns", help="write the touchdowns as CSV (t,leg,new_step,x,y,theta,xd,yd,thetad)")
    ap.add_argument("--compare", metavar="RUN_DIR", help="compare with a flexgait rimless simulate run")
    ap.add_argument("--time", type=int, metavar="R", help="time R runs, print the best wall time per step")
    a = ap.parse_args(argv)
    p = parse_params(a.config, a.set)
    if a.steps is not None:
        p["sim.steps"] = a.steps
    sim = Simulation(p).run()
    print(f"reference: {sim.steps} steps in {sim.t_end:.6f} s, {len(sim.events)} events, "
          f"{sim.rhs_evals} right-hand sides ({sim.rhs_evals / sim.steps:.0f} per step), {sim.jams} jams")
    if a.events:
        with open(a.events, "w", newline="") as fh:
            out = csv.writer(fh)
            out.writerow(["t", "kind", "leg", "modes"])
            for t, kind, leg, modes in sim.events:
                out.writerow([repr(t), kind, leg, modes])
    if a.touchdowns:
        with open(a.touchdowns, "w", newline="") as fh:
            out = csv.writer(fh)
            out.writerow(["t", "leg", "new_step", "x", "y", "theta", "xd", "yd", "thetad"])
            for t, leg, q, _, new_step in sim.touchdowns:
                out.writerow([repr(t), leg, int(new_step)] + [repr(float(v)) for v in q])
    if a.compare:
        report = compare(sim, a.compare)
        for line in report["lines"]:
            print(line)
    if a.time:
        # CPU and wall time of the simulation alone (imports and Python's start-up excluded), per
        # wheel step; the CPU time is the figure to hold against Google Benchmark's us/step (a rate
        # over CPU time). Median and best of R runs.
        cpu, wall = [], []
        for _ in range(a.time):
            w0, c0 = time.perf_counter(), time.process_time()
            s = Simulation(p).run()
            cpu.append((time.process_time() - c0) / s.steps)
            wall.append((time.perf_counter() - w0) / s.steps)
        print(f"time per step over {a.time} runs of {s.steps} steps: CPU median {np.median(cpu) * 1e6:.0f} us, "
              f"best {min(cpu) * 1e6:.0f} us; wall median {np.median(wall) * 1e6:.0f} us, "
              f"best {min(wall) * 1e6:.0f} us")
    return 0


def read_engine_run(run_dir):
    """The engine's events (t, kind, leg, modes) and the states before and after every event
    (log.csv's first and last rows at an event's time)."""
    with open(os.path.join(run_dir, "events.csv")) as fh:
        events = [(float(r["t"]), r["kind"], int(r["leg"]), r["modes"]) for r in csv.DictReader(fh)]
    rows = {}
    with open(os.path.join(run_dir, "log.csv")) as fh:
        for r in csv.DictReader(fh):
            t = float(r["t"])
            q = [float(r[k]) for k in ("x", "y", "theta", "xd", "yd", "thetad")]
            rows.setdefault(t, [q, q])[1] = q
    return events, rows


def compare(sim, run_dir):
    """Event by event: the same kinds, legs and modes; the largest time difference; at every
    touchdown of a new leg the largest difference of the state before the reset."""
    events, rows = read_engine_run(run_dir)
    ref = [e for e in sim.events if e[1] != "failure"]
    eng = [e for e in events if e[1] not in ("failure", "section")]
    n = min(len(ref), len(eng))
    lines = []
    mismatch = None
    dt = 0.0
    for i in range(n):
        a, b = ref[i], eng[i]
        if (a[1], a[2], a[3]) != (b[1], b[2], b[3]):
            mismatch = (i, a, b)
            break
        dt = max(dt, abs(a[0] - b[0]))
    eng_td = [e for e in eng if e[1] == "touchdown"]
    dq = [0.0, 0.0]
    dtd = 0.0
    pairs = 0
    for (t, leg, pre, post, _), e in zip(sim.touchdowns, [e for e in eng_td if e[0] > 0]):
        if leg != e[2]:
            break
        dtd = max(dtd, abs(t - e[0]))
        for side, q in enumerate((pre, post)):
            dq[side] = max(dq[side], max(abs(float(q[j]) - rows[e[0]][side][j]) for j in range(6)))
        pairs += 1
    lines.append(f"events: reference {len(ref)}, engine {len(eng)}, equal kinds/legs/modes for the first "
                 f"{mismatch[0] if mismatch else n}")
    if mismatch:
        lines.append(f"first difference: event {mismatch[0]}: reference {mismatch[1]}, engine {mismatch[2]}")
    lines.append(f"largest event-time difference (matching events): {dt:.3e} s")
    n_eng = len([e for e in eng_td if e[0] > 0])
    lines.append(f"touchdowns compared: {pairs} of {n_eng}, largest time difference {dtd:.3e} s, largest state "
                 f"difference (x, y, θ, ẋ, ẏ, θ̇) before the reset {dq[0]:.3e}, after it {dq[1]:.3e}")
    return {"lines": lines, "mismatch": mismatch, "dt": dt, "touchdown_dt": dtd, "touchdown_dq": dq,
            "touchdowns": pairs, "touchdowns_eng": n_eng, "events_ref": len(ref), "events_eng": len(eng)}


if __name__ == "__main__":
    sys.exit(main())
