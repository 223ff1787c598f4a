#!/usr/bin/env python3
"""Work-precision of SciPy's solve_ivp (RK45, DOP853, Radau, BDF, LSODA) on the paper scenes.

The right-hand side is built from the numbers of `pogear derive --format json` (eq. 3:
L = diag(J, 1/K), A = [[-B_J - R^T B_K R, -R^T], [R, 0]], M = L^-1 A; rigid: M = L1^-1 A1), checked
against the generated code's M and N that bench_wp_pogear wrote into the problem files, and run
vectorized as M @ x + N u, with the Jacobian M for the implicit methods. Errors are measured against
the same exact reference as pogear's, CVODE's and odeint's.

Usage: wp_scipy.py --pogear PATH --problems DIR --out DIR [--quick] [--check]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time
import tomllib

import numpy as np
import scipy
from scipy.integrate import solve_ivp

METHODS = ["RK45", "DOP853", "Radau", "BDF", "LSODA"]
IMPLICIT = {"Radau", "BDF", "LSODA"}  # given the Jacobian


def derive(pogear, model_file, keep):
    out = subprocess.run([pogear, "derive", model_file, "--keep", ",".join(keep), "--format", "json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def matrices(problem, d, effects):
    """M, N of the scene's system from the derivation's numeric values (eq. 3, or eq. 7 rigid)."""
    num = d["numeric"]
    velocities = d["velocities"]
    n = len(velocities)
    J = np.array(num["J"], dtype=float)
    b = np.array(num["b"], dtype=float) if "bearing_friction" in effects else np.zeros(n)
    tau = np.zeros((n, len(problem["inputs"])))
    for j, name in enumerate(problem["inputs"]):
        tau[velocities.index("omega_" + name.removeprefix("tau_")), j] = 1.0
    if problem["model"] == "elastic":
        K = np.array(num["K"], dtype=float)
        bK = np.array(num["b_K"], dtype=float) if "mesh_damping" in effects else np.zeros(len(K))
        R = np.array(num["R"], dtype=float)
        m = len(K)
        L = np.diag(np.concatenate([J, 1.0 / K]))
        A = np.block([[-np.diag(b) - R.T @ np.diag(bK) @ R, -R.T], [R, np.zeros((m, m))]])
        B = np.vstack([tau, np.zeros((m, tau.shape[1]))])
    else:
        Q1 = np.array(num["Q1"], dtype=float)
        L = np.array(num["L1"], dtype=float)
        # eq. 7: A1 = -Q1^T B_J Q1 is all bearing friction
        A = np.array(num["A1"], dtype=float) if "bearing_friction" in effects else np.zeros_like(L)
        B = Q1.T @ tau  # B1 = Q1^T
    return np.linalg.solve(L, A), np.linalg.solve(L, B)


def max_rel_error(y, ref):
    """Largest deviation, each component relative to its largest magnitude in the reference."""
    if y.shape != ref.shape:
        return math.nan
    scale = np.max(np.abs(ref), axis=0)
    scale[scale == 0] = 1.0
    return float(np.max(np.abs(y - ref) / scale))


def measure(run, min_batch, batches, max_run):
    """Median, min, max of per-run seconds over batches lasting >= min_batch (as bench_common.hpp)."""
    t0 = time.perf_counter()
    run()
    one = time.perf_counter() - t0
    n = max(1, math.ceil(min_batch / max(one, 1e-9)))
    if one > 1:  # slow runs: fewer repeats, the error does not need them
        batches = min(batches, 2)
    if one > max_run / 2:
        batches = 1
    per = []
    for _ in range(batches):
        t0 = time.perf_counter()
        for _ in range(n):
            run()
        per.append((time.perf_counter() - t0) / n)
    per.sort()
    m = len(per)
    median = per[m // 2] if m % 2 else 0.5 * (per[m // 2 - 1] + per[m // 2])
    return median, per[0], per[-1], n, batches


class Checker:
    """--check: counts the checks that pass and prints those that fail; without --check it does nothing."""

    def __init__(self, enabled):
        self.enabled, self.passed, self.failures = enabled, 0, 0

    def expect(self, ok, what):
        if not self.enabled:
            return
        if ok:
            self.passed += 1
        else:
            self.failures += 1
            print(f"CHECK FAILED: {what}", file=sys.stderr)


def fmt(v):
    return "nan" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.6g}"


def parse_arguments(doc, required):
    """A harness's command line: the options in `required` (each takes a value), --quick and --check."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    for name in required:
        ap.add_argument(f"--{name}", required=True)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--check", action="store_true")
    return ap.parse_args()


def main():
    args = parse_arguments(__doc__, ["pogear", "problems", "out"])
    # quick: one timed batch of one run is enough to exercise the path; the numbers are checked, not the speed
    min_batch, batches, max_run = (0.002, 1, 2.0) if args.quick else (0.05, 5, 10.0)
    tolerances = [1e-6] if args.quick else [10.0 ** -k for k in range(3, 13)]
    chk = Checker(args.check)

    print(f"SciPy {scipy.__version__} (NumPy {np.__version__}, Python {sys.version.split()[0]})")
    os.makedirs(args.out, exist_ok=True)
    files = sorted(f for f in os.listdir(args.problems) if f.endswith(".json"))
    with open(os.path.join(args.out, "wp_scipy.csv"), "w", newline="") as out:
        w = csv.writer(out)
        w.writerow(["scene", "model", "family", "method", "knob", "value", "status", "steps", "rhs_evals",
                    "max_rel_error", "time_median", "time_min", "time_max", "runs_per_batch", "batches", "note"])
        for f in files:
            with open(os.path.join(args.problems, f)) as fp:
                pb = json.load(fp)
            with open(pb["scene_file"], "rb") as fp:
                scene = tomllib.load(fp)
            model_file = os.path.join(os.path.dirname(pb["scene_file"]), scene["model"])
            keep = scene.get("keep") or None
            if pb["model"] == "rigid":  # the rigid states are the kept velocities
                keep = [s.removeprefix("omega_") for s in pb["states"]]
            d = derive(args.pogear, model_file, keep or [])
            M, N = matrices(pb, d, scene.get("effects", []))
            Mg, Ng = np.array(pb["M"]), np.array(pb["N"])
            same = np.max(np.abs(M - Mg)) <= 1e-12 * np.max(np.abs(Mg)) and \
                np.max(np.abs(N - Ng)) <= 1e-12 * np.max(np.abs(Ng))
            chk.expect(same, f"{pb['scene']}/{pb['model']}: M, N from pogear derive equal the generated code's")
            u = np.array(list(pb["inputs"].values()), dtype=float)
            Nu = (N @ u)[:, None]
            x0 = np.array(pb["x0"], dtype=float)
            ref = np.loadtxt(os.path.join(args.problems, pb["reference"]), delimiter=",", ndmin=2)
            horizon, dt = pb["horizon"], pb["sample"]
            t_eval = np.arange(ref.shape[0]) * dt
            t_eval[-1] = horizon

            def fun(t, x):  # vectorized: x has shape (n, k)
                return M @ x + Nu

            label = f"{pb['scene']}/{pb['model']}"
            for method in METHODS:
                slow = False
                for rtol in tolerances:
                    row = dict(scene=pb["scene"], model=pb["model"], family="scipy", method="scipy_" + method,
                               knob="rtol", value=rtol, status="ok", steps=-1, rhs_evals=-1, error=math.nan,
                               t=(math.nan,) * 3, n=0, b=0, note="")
                    if slow:
                        row.update(status="skipped", note=f"a looser tolerance already took longer than {max_run:g} s")
                    else:
                        result = {}

                        def run():
                            kw = {}
                            if method in IMPLICIT:  # Radau and BDF take a constant Jacobian as an
                                # array; SciPy 1.10's LSODA wrapper needs a callable
                                kw["jac"] = (lambda t, x: M) if method == "LSODA" else M
                            result["sol"] = solve_ivp(fun, (0.0, horizon), x0, method=method, t_eval=t_eval,
                                                      rtol=rtol, atol=1e-2 * rtol, vectorized=True, **kw)

                        run()
                        sol = result["sol"]
                        if not sol.success:
                            row.update(status="failed", note=sol.message)
                        row["error"] = max_rel_error(sol.y.T, ref) if sol.success else math.nan
                        row["rhs_evals"] = int(sol.nfev)
                        # solve_ivp does not report accepted steps; its dense output has one piece each
                        row["steps"] = -1
                        med, lo, hi, n, b = measure(run, min_batch, batches, max_run)
                        row.update(t=(med / horizon, lo / horizon, hi / horizon), n=n, b=b)
                        slow = med > max_run
                        # Same bound as the C++ harnesses (bench_common.hpp, adaptive_bound)
                        bound = 1e3 * max(rtol, 1e-8) + 1e-11
                        chk.expect(sol.success and row["error"] <= bound,
                               f"{label}: scipy_{method} rtol {rtol:g}: error {row['error']:.3g} <= {bound:.3g}")
                    w.writerow([row["scene"], row["model"], row["family"], row["method"], row["knob"], fmt(rtol),
                                row["status"], row["steps"], row["rhs_evals"], fmt(row["error"]),
                                *[fmt(v) for v in row["t"]], row["n"], row["b"], row["note"].replace(",", ";")])
                    out.flush()
                    print(f"  {label:<24} scipy_{method:<7} rtol {rtol:<8g} {row['status']:<8} "
                          f"err {fmt(row['error']):<11} {fmt(row['t'][0])} s/s", flush=True)
    if args.check:
        print(f"wp_scipy: {chk.passed} checks passed, {chk.failures} failed")
    return 1 if chk.failures else 0


if __name__ == "__main__":
    sys.exit(main())
