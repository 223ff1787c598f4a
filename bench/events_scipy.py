#!/usr/bin/env python3
"""Events across a shift with SciPy's solve_ivp (RK45, DOP853, Radau, BDF, LSODA): the SciPy peer of bench_events.
Same problem, stick-slip modes and long-double reference as bench/events.cpp; events located by solve_ivp.

The mode logic is this file's own statement of the rules of bench/hybrid_modes_ref.hpp (the reference's
and the CVODE peer's): within a mode dx/dt = A x + B v(t); at an event or a breakpoint the mode is
resolved and solve_ivp restarted from the projected state. States and events are measured against the
long-double reference that bench_events wrote; its columns are those of events_cpp.csv.

Usage: events_scipy.py --problem DIR --out DIR [--quick] [--check]
"""
import csv
import json
import math
import os
import sys
import time

import numpy as np
import scipy
from scipy.integrate import BDF, DOP853, LSODA, RK45, Radau, solve_ivp

from wp_scipy import Checker, fmt, max_rel_error, measure, parse_arguments

METHODS = ["RK45", "DOP853", "Radau", "BDF", "LSODA"]
SOLVERS = {"RK45": RK45, "DOP853": DOP853, "Radau": Radau, "BDF": BDF, "LSODA": LSODA}
IMPLICIT = {"Radau", "BDF", "LSODA"}  # given the Jacobian
OPEN, SLIPPING, STUCK = 0, 1, 2
PHASE_NAMES = ["open", "slipping", "stuck"]
EPS = np.finfo(float).eps
MAX_EVENTS = 10000  # a run logging more is chattering: stopped with a message


def signal_value(tab, t):
    """A piecewise-linear table [[t...], [v...]] at t, held constant outside, right-continuous at a
    repeated time (as bench::signal_value)."""
    ts, vs = tab
    if not t >= ts[0]:
        return vs[0]
    if t >= ts[-1]:
        return vs[-1]
    i = 1
    while not t < ts[i]:
        i += 1
    w = (t - ts[i - 1]) / (ts[i] - ts[i - 1])
    return vs[i - 1] + w * (vs[i] - vs[i - 1])


class Problem:
    """One problem file of bench_events: matrices, signals, elements, samples, reference."""

    def __init__(self, directory, name):
        with open(os.path.join(directory, name)) as fp:
            pb = json.load(fp)
        self.scene, self.model = pb["scene"], pb["model"]
        self.horizon, self.dt, self.count = float(pb["horizon"]), float(pb["sample"]), int(pb["count"])
        self.M = np.array(pb["M"], dtype=float)
        self.N = np.array(pb["N"], dtype=float)
        self.S = np.array(pb["S"], dtype=float).reshape(-1, self.M.shape[0])
        self.x0 = np.ravel(np.array(pb["x0"], dtype=float))  # a vector or a 1 x nx matrix
        self.inputs = [(list(map(float, s[0])), list(map(float, s[1]))) for s in pb["inputs"]]
        self.elements = pb["elements"]
        self.commands = [(list(map(float, e["command"][0])), list(map(float, e["command"][1])))
                         for e in self.elements]
        self.nx, self.ne = self.M.shape[0], self.S.shape[0]
        self.nu = self.N.shape[1] - self.ne
        # Breakpoints: every table time strictly inside (0, horizon)
        inside = {t for s in self.inputs + self.commands for t in s[0] if 0.0 < t < self.horizon}
        self.breaks = sorted(inside)
        self.times = np.arange(self.count) * self.dt  # t_k = k dt, the last exactly the horizon
        self.times[-1] = self.horizon
        self.ref = np.loadtxt(os.path.join(directory, pb["reference"]), delimiter=",", ndmin=2)
        self.ref_events = [(float(e["t"]), int(e["element"]), e["from"], e["to"]) for e in pb["reference_events"]]

    def next_break(self, t):
        for b in self.breaks:
            if b > t:
                return b
        return self.horizon

    def label(self):
        return f"{self.scene}/{self.model}"


class Singular(Exception):
    pass


class Mode:
    """The mode with stuck elements `stuck`: dx/dt = A x + B v, stuck torques Kx x + Kv v, projector P."""

    def __init__(self, pb, mask):
        self.stuck = [k for k in range(pb.ne) if mask >> k & 1]
        nu = pb.nu
        Bv = pb.N.copy()
        self.P = np.eye(pb.nx)
        self.Kx = np.zeros((len(self.stuck), pb.nx))
        self.Kv = np.zeros((len(self.stuck), pb.N.shape[1]))
        self.A, self.B = pb.M.copy(), Bv
        if self.stuck:
            cols = [nu + k for k in self.stuck]
            H = pb.S[self.stuck]
            NS = pb.N[:, cols]
            Bv[:, cols] = 0.0
            HN = H @ NS
            if np.linalg.matrix_rank(HN) < len(self.stuck):
                raise Singular("the stuck elements " + ", ".join(pb.elements[k]["name"] for k in self.stuck) +
                               " over-constrain the gear")
            self.Kx = -np.linalg.solve(HN, H @ pb.M)
            self.Kv = -np.linalg.solve(HN, H @ Bv)
            self.P = np.eye(pb.nx) - NS @ np.linalg.solve(HN, H)
            self.A = pb.M + NS @ self.Kx
            self.B = Bv + NS @ self.Kv


class Hybrid:
    """The elements' phases and slip directions, and the rules (bench::Phases): known inputs, event
    functions, the mode at an instant."""

    def __init__(self, pb):
        self.pb = pb
        self.phase = [OPEN] * pb.ne
        self.dir = [0] * pb.ne
        self.mask = 0
        self.modes = {}

    def mode(self, mask=None):
        mask = self.mask if mask is None else mask
        m = self.modes.get(mask)
        if m is None:
            m = self.modes[mask] = Mode(self.pb, mask)
        return m

    def command(self, k, t):
        return signal_value(self.pb.commands[k], t)

    def open_over(self, k, t, t_next):
        return self.command(k, t) == 0 and self.command(k, (t + t_next) / 2) == 0

    def known(self, t):
        """v(t) = [u(t); T]: slipping elements c p dir (0 for a one-way element with dir > 0), open and
        stuck ones 0."""
        pb = self.pb
        v = np.zeros(pb.nu + pb.ne)
        for i, s in enumerate(pb.inputs):
            v[i] = signal_value(s, t)
        for k, e in enumerate(pb.elements):
            if self.phase[k] == SLIPPING:
                scale = 0.0 if e["one_way"] and self.dir[k] > 0 else float(e["capacity"])
                v[pb.nu + k] = scale * self.command(k, t) * self.dir[k]
        return v

    def resolve(self, t, trigger, x, log):
        """The mode at t for state x (projected onto it in place); `trigger` the element whose event
        this is (-1: none). Appends the phase changes to `log` (None: not logged)."""
        pb = self.pb
        t_next = pb.next_break(t)
        old = list(self.phase)
        slip = pb.S @ x
        m = 0
        for k in range(pb.ne):
            if not self.open_over(k, t, t_next) and (self.phase[k] == STUCK or slip[k] == 0 or k == trigger):
                m |= 1 << k
            elif slip[k] != 0:
                self.dir[k] = 1 if slip[k] > 0 else -1
        for _ in range(pb.ne + 1):
            md = self.mode(m)
            self.phase = [STUCK if m >> k & 1 else SLIPPING for k in range(pb.ne)]
            Ts = md.Kx @ (md.P @ x) + md.Kv @ self.known(t)
            worst, worst_ratio = -1, 1.0
            for j, k in enumerate(md.stuck):
                e = pb.elements[k]
                limit = float(e["static_ratio"]) * float(e["capacity"]) * self.command(k, t)
                Tj = Ts[j]
                ratio = abs(Tj) / limit if limit > 0 else (math.inf if Tj != 0 else 0.0)
                if e["one_way"] and Tj > 0:
                    ratio = math.inf
                if ratio > worst_ratio:  # the running worst's direction, as bench::Phases
                    worst_ratio, worst = ratio, k
                    self.dir[k] = 1 if Tj > 0 else -1
            if worst < 0:
                self.mask = m
                x[:] = md.P @ x
                break
            m &= ~(1 << worst)
        for k in range(pb.ne):
            if self.phase[k] != STUCK and self.open_over(k, t, t_next):
                self.phase[k] = OPEN
            if self.phase[k] != old[k] and log is not None:
                log.append((t, k, PHASE_NAMES[old[k]], PHASE_NAMES[self.phase[k]]))

    def segment(self, t0, t_end):
        """The right-hand side and the event functions of the current mode over [t0, t_end] (no
        breakpoint inside: the inputs and commands are linear there, v(s) = v0 + (s - t0) dv).
        Returns fun, A, events, elements (the element of each event function)."""
        pb = self.pb
        md = self.mode()
        t_mid = (t0 + t_end) / 2
        v0 = self.known(t0)
        dv = (self.known(t_mid) - v0) / (t_mid - t0)
        A, bv0, bdv = md.A, md.B @ v0, md.B @ dv

        def fun(s, x):
            return A @ x + (bv0 + (s - t0) * bdv)

        events, elements = [], []

        def watch(g, k):
            # A function not above zero at the segment's start is not watched there: a just-released
            # element's slip starts at zero (up to rounding), and scipy would locate a "crossing" at t0
            # and restart into the same mode forever.
            def ev(s, x):
                v = g(s, x)
                return v if s != t0 or v > 0 else -1.0

            ev.terminal, ev.direction = True, -1
            events.append(ev)
            elements.append(k)

        for k in range(pb.ne):
            if self.phase[k] == SLIPPING:
                Sk, d = pb.S[k].copy(), float(self.dir[k])
                watch(lambda s, x, Sk=Sk, d=d: d * (Sk @ x), k)
        for j, k in enumerate(md.stuck):
            e = pb.elements[k]
            mu_c = float(e["static_ratio"]) * float(e["capacity"])
            p0 = self.command(k, t0)
            dp = (self.command(k, t_mid) - p0) / (t_mid - t0)
            kx, kv0, kvd = md.Kx[j].copy(), md.Kv[j] @ v0, md.Kv[j] @ dv

            def margin(s, x, kx=kx, kv0=kv0, kvd=kvd, mu_c=mu_c, p0=p0, dp=dp, one_way=bool(e["one_way"])):
                T = kx @ x + kv0 + (s - t0) * kvd
                g = mu_c * (p0 + (s - t0) * dp) - abs(T)
                return min(g, -T) if one_way else g

            watch(margin, k)
        return fun, A, events, elements


def counting(base):
    """The solver class `base` counting its accepted steps (solve_ivp does not report them; each
    successful _step_impl is one accepted step, its rejected tries inside it)."""

    class Counting(base):
        steps = 0

        def _step_impl(self):
            ok, message = super()._step_impl()
            if ok:
                Counting.steps += 1
            return ok, message

    return Counting


def reached(t_sample, t):
    """A sample a few ulps past (or before) t counts as at t (1150 * 1 ms against the breakpoint 1.15)."""
    return t_sample - t <= 4 * EPS * max(1.0, abs(t))


def resolve_event(hy, t, trigger, x, log):
    """The resolve at an event located by solve_ivp at (t, x); returns the time and state it took.

    solve_ivp's root (brentq to 4 ulps of t) may sit a hair before the crossing: a stuck element's
    margin still 0+ there, its ratio 1 - 1e-15, and the resolve keeps it stuck, so that the restart
    would find the same root again forever. (The reference bisects to the crossed side; CVODE returns
    it.) When the resolve changes nothing, the mode's flow is followed a few ulps on (one Euler step:
    over 1e-12 s its error is 1e-24 |A^2 x|, rounding) and the resolve tried again, the distance
    doubled up to ~1e-11 s (never onto the next breakpoint); if the element still holds, the located
    point stands."""
    before = (list(hy.phase), list(hy.dir), hy.mask)
    x_e = x.copy()
    hy.resolve(t, trigger, x, log)
    if (list(hy.phase), list(hy.dir), hy.mask) != before:
        return t, x
    md = hy.mode()
    rate = md.A @ x_e + md.B @ hy.known(t)
    t_next = hy.pb.next_break(t)
    delta = 4 * EPS * max(1.0, t)
    for _ in range(15):
        if t + delta >= t_next:
            break
        xn = x_e + delta * rate
        hy.resolve(t + delta, trigger, xn, log)
        if (list(hy.phase), list(hy.dir), hy.mask) != before:
            return t + delta, xn
        delta *= 2
    return t, x


def simulate(pb, method, rtol):
    """One run: samples (count x nx, NaN where not reached), events [(t, element, from, to)], accepted
    steps, and an error message (None: ok)."""
    solver = counting(SOLVERS[method])
    hy = Hybrid(pb)
    Y = np.full((pb.count, pb.nx), np.nan)
    events = []
    x = pb.x0.copy()
    steps, t = 0, 0.0
    try:
        hy.resolve(0.0, -1, x, None)  # the initial mode: not an event
        Y[0] = x
        k, stalled = 1, 0
        while True:
            while k < pb.count and reached(pb.times[k], t):
                Y[k] = x  # after the resolve at t
                k += 1
            if k >= pb.count:
                break
            t_end = pb.next_break(t)
            if t_end < pb.horizon:  # samples within a few ulps of the breakpoint are taken after it
                j1 = int(np.searchsorted(pb.times, t_end - 4 * EPS * max(1.0, t_end), side="right"))
                t_eval = np.append(pb.times[k:j1], t_end)
            else:
                j1 = pb.count
                t_eval = pb.times[k:]
            fun, A, evs, elements = hy.segment(t, t_end)
            kw = {}
            if method in IMPLICIT:  # SciPy 1.10's LSODA wrapper needs a callable Jacobian
                kw["jac"] = (lambda s, x: A) if method == "LSODA" else A
            solver.steps = 0
            sol = solve_ivp(fun, (t, t_end), x, method=solver, rtol=rtol, atol=1e-2 * rtol, t_eval=t_eval,
                            events=evs or None, **kw)
            steps += solver.steps
            if sol.status == -1:
                return Y, events, steps, f"solve_ivp at t = {t:.17g}: {sol.message}"
            ts = np.asarray(sol.t)
            ys = np.asarray(sol.y).reshape(pb.nx, -1)
            if sol.status == 1:  # a terminal event: the earliest
                hits = [(te[0], i) for i, te in enumerate(sol.t_events) if len(te)]
                t_e, i = min(hits)
                n = int(np.count_nonzero(ts < t_e))  # a sample at t_e is taken after the resolve
                Y[k:k + n] = ys[:, :n].T
                k += n
                stalled = stalled + 1 if t_e <= t else 0
                if stalled > 2 * pb.ne + 2:
                    return Y, events, steps, f"events without progress at t = {t:.17g}"
                t, x = t_e, np.array(sol.y_events[i][0], dtype=float)
                t, x = resolve_event(hy, t, elements[i], x, events)
                if len(events) > MAX_EVENTS:
                    return Y, events, steps, f"more than {MAX_EVENTS} events (chattering) by t = {t:.6g}"
            else:
                n = j1 - k
                Y[k:j1] = ys[:, :n].T
                k = j1
                stalled = 0
                t, x = t_end, ys[:, -1].copy()
                if t < pb.horizon:
                    hy.resolve(t, -1, x, events)
    except (Singular, np.linalg.LinAlgError) as e:
        return Y, events, steps, f"at t = {t:.17g}: {e}"
    return Y, events, steps, None


def event_error(events, pb):
    """The largest event time difference and a note; inf when the sequences differ in (element, from, to)."""
    if len(events) != len(pb.ref_events):
        return math.inf, f"{len(events)} events; the reference has {len(pb.ref_events)}"
    worst = 0.0
    for i, (e, r) in enumerate(zip(events, pb.ref_events)):
        if e[1:] != r[1:]:
            return math.inf, f"event {i} differs from the reference's"
        worst = max(worst, abs(e[0] - r[0]))
    return worst, ""


def main():
    args = parse_arguments(__doc__, ["problem", "out"])
    # quick: the first run is the timing, enough to exercise the path; the numbers are checked, not the
    # speed. A run is seconds of Python stepping (the ringing meshes bound the explicit steps to ~0.1 ms):
    # max_run is 10 s in both modes, so that --quick never skips the checked rows.
    min_batch, batches, max_run = (0.002, 1, 10.0) if args.quick else (0.05, 5, 10.0)
    # --quick runs in the test suite: one explicit method at the checked tolerance (3 s), enough to
    # exercise the mode logic and its event handling.
    tolerances = [1e-8] if args.quick else [10.0 ** -k for k in range(3, 13)]
    methods = ["DOP853"] if args.quick else METHODS
    checked = {("DOP853", 1e-8), ("Radau", 1e-8)}
    chk = Checker(args.check)

    print(f"SciPy {scipy.__version__} (NumPy {np.__version__}, Python {sys.version.split()[0]})")
    files = sorted(f for f in os.listdir(args.problem) if f.endswith(".json"))
    if not files:
        print(f"events_scipy: error: no problem (*.json) in {args.problem}", file=sys.stderr)
        return 2
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "events_scipy.csv"), "w", newline="") as out:
        w = csv.writer(out)
        w.writerow(["scene", "model", "family", "method", "knob", "value", "status", "steps", "events",
                    "max_rel_error", "max_event_error", "time_median", "time_min", "time_max", "runs_per_batch",
                    "batches", "note"])
        for f in files:
            try:
                pb = Problem(args.problem, f)
            except (OSError, ValueError, KeyError) as e:  # json.JSONDecodeError is a ValueError
                print(f"events_scipy: error: {os.path.join(args.problem, f)}: {e}", file=sys.stderr)
                return 2
            label = pb.label()
            print(f"  {label}: {pb.nx} states, {pb.ne} friction elements, {len(pb.ref_events)} reference events")
            for method in methods:
                slow = False
                for rtol in tolerances:
                    row = dict(status="ok", steps=-1, events=0, error=math.nan, event_error=math.nan,
                               t=(math.nan,) * 3, n=0, b=0, note="")
                    if slow:
                        row.update(status="skipped", note=f"a looser tolerance already took longer than {max_run:g} s")
                    else:
                        result = {}

                        def run():
                            result["r"] = simulate(pb, method, rtol)

                        t0 = time.perf_counter()
                        run()
                        one = time.perf_counter() - t0
                        Y, events, steps, message = result["r"]
                        row.update(steps=steps, events=len(events))
                        row["error"] = max_rel_error(Y, pb.ref) if message is None else math.nan
                        row["event_error"], row["note"] = event_error(events, pb)
                        if message is not None:
                            row.update(status="failed", note=message)
                        if args.quick:  # the run above is the timing: --quick runs in the test suite
                            med, lo, hi, n, b = one, one, one, 1, 1
                        else:
                            med, lo, hi, n, b = measure(run, min_batch, batches, max_run)
                        row.update(t=(med / pb.horizon, lo / pb.horizon, hi / pb.horizon), n=n, b=b)
                        slow = med > max_run
                    if (method, rtol) in checked:
                        # The harness's check (same problem, same reference), not a ranking: the
                        # reference's events, and the states near it. A skipped row fails it.
                        chk.expect(row["status"] == "ok" and math.isfinite(row["event_error"]) and row["error"] <= 1e-3,
                               f"{label}: scipy_{method} rtol {rtol:g}: status {row['status']}, event error "
                               f"{fmt(row['event_error'])} ({row['note'] or 'same events'}), "
                               f"state error {fmt(row['error'])} <= 1e-3")
                    w.writerow([pb.scene, pb.model, "scipy", "scipy_" + method, "rtol", fmt(rtol), row["status"],
                                row["steps"], row["events"], fmt(row["error"]), fmt(row["event_error"]),
                                *[fmt(v) for v in row["t"]], row["n"], row["b"], row["note"].replace(",", ";")])
                    out.flush()
                    print(f"  {label:<24} scipy_{method:<7} rtol {rtol:<8g} {row['status']:<8} "
                          f"err {fmt(row['error']):<11} event err {fmt(row['event_error']):<11} "
                          f"{fmt(row['t'][0])} s/s{'  ' + row['note'] if row['note'] else ''}", flush=True)
    if args.check:
        print(f"events_scipy: {chk.passed} checks passed, {chk.failures} failed")
    return 1 if chk.failures else 0


if __name__ == "__main__":
    sys.exit(main())
