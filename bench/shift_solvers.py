#!/usr/bin/env python3
"""Which solver for a shift (docs/accuracy-vs-time.md, "Which solver for a shift"): every shipped
scene with brakes or clutches, and one held back (bench/scenes/zf6hp26_2_3_upshift.toml), run by
`pogear simulate --interpreted` with exact stepping and with dopri5 and implicit (TR-BDF2) across
tolerances, each measured against a reference run of its own scene:

- the exact run where the scene is linear (exact to rounding), else dopri5 at rtol 1e-12;
- state error: the largest difference of a speed (the omega_ and slip_ columns) over the samples,
  relative to the largest speed of the reference;
- event error: the largest difference of the event times [s] when the sequence of events is the
  reference's, "differs" otherwise;
- heat error: the largest difference of an element's heat at the horizon, relative to the largest;
- time: the run's own wall time, the median of --repeat runs, per simulated second.

    bench/shift_solvers.py POGEAR [OUT.md]

prints (and writes) a Markdown table per scene and model (elastic, rigid).
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCENES = [
    "models/scenes/simpson_1_2_upshift.toml",
    "models/scenes/simpson_vehicle_upshift.toml",
    "models/scenes/zf6hp26_1_2_upshift.toml",
    "models/scenes/gearshift_planetary.toml",
    "models/scenes/zf6hp26_launch.toml",
    "models/scenes/power_split_ev_launch.toml",
    "bench/scenes/zf6hp26_2_3_upshift.toml",
]
TOLERANCES = [1e-4, 1e-6, 1e-8, 1e-10]
REPEAT = 3


def run(pogear, scene, solver, tolerance, out):
    cmd = [pogear, "simulate", os.path.join(ROOT, scene), "--interpreted", "--solver", solver, "-o", out,
           "--repeat", str(REPEAT)]
    if tolerance is not None:
        cmd += ["--tolerance", repr(tolerance)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    if p.returncode != 0:
        return None, p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "failed"
    walls = {}
    for line in p.stdout.splitlines():
        m = re.match(r"^(\S+?)(\.rigid)?: \w+, (\d+) steps, .* ([0-9.e+-]+) s wall", line)
        if m:
            walls[m.group(2) or ""] = (float(m.group(4)), int(m.group(3)))
    return walls, None


def read_run(out, name, suffix):
    with open(os.path.join(out, name + suffix + ".csv"), newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    header = [h.split(" [")[0] for h in rows[0]]
    data = [[float(x) for x in r] for r in rows[1:]]
    with open(os.path.join(out, name + suffix + ".events.csv"), newline="") as f:
        events = [(float(r[0]), tuple(r[1:])) for r in list(csv.reader(f))[1:] if r and not r[0].startswith("#")]
    return header, data, events


def errors(ref, got):
    header, a, ev_a = ref
    _, b, ev_b = got
    speeds = [j for j, h in enumerate(header) if h.startswith("omega_") or h.startswith("slip_")]
    scale = max(abs(r[j]) for r in a for j in speeds) or 1.0
    state = max(abs(x[j] - y[j]) for x, y in zip(a, b) for j in speeds) / scale
    if [e[1] for e in ev_a] == [e[1] for e in ev_b]:
        event = max((abs(x[0] - y[0]) for x, y in zip(ev_a, ev_b)), default=0.0)
    else:
        event = None
    heats = [j for j, h in enumerate(header) if h.startswith("E_") and h != "E_converter"]
    big = max([abs(a[-1][j]) for j in heats] + [1.0])
    heat = max((abs(a[-1][j] - b[-1][j]) for j in heats), default=0.0) / big
    return state, event, heat


def main():
    pogear = sys.argv[1]
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            name = os.path.splitext(os.path.basename(scene))[0]
            with open(os.path.join(ROOT, scene)) as f:
                text = f.read()
            horizon = float(re.search(r'horizon = "([0-9.e+-]+)\*s"', text).group(1))
            rigid = "compare_rigid = true" in text
            ref_dir = os.path.join(tmp, name, "ref")
            reference = "exact"
            walls, why = run(pogear, scene, "exact", None, ref_dir)
            if walls is None:  # nonlinear: exact stepping refused
                reference = "dopri5 rtol 1e-12"
                walls, why = run(pogear, scene, "dopri5", 1e-12, ref_dir)
            configs = ([("exact", None)] if reference == "exact" else []) + \
                      [(s, r) for s in ("dopri5", "implicit") for r in TOLERANCES]
            runs = {}
            for solver, tol in configs:
                out = ref_dir if (solver, tol) == ("exact", None) else os.path.join(tmp, name, f"{solver}_{tol}")
                runs[(solver, tol)] = (out,) + ((walls, None) if out == ref_dir else run(pogear, scene, solver, tol, out))
            for suffix in [""] + ([".rigid"] if rigid else []):
                ref = read_run(ref_dir, name, suffix)
                block = [f"\n{name}{suffix} (reference: {reference}, horizon {horizon:g} s)\n",
                         "| solver | rtol | state error | event error [s] | heat error | steps | s per simulated s |",
                         "|---|---|---|---|---|---|---|"]
                for (solver, tol), (out, w, why) in runs.items():
                    if w is None:
                        block.append(f"| {solver} | {tol if tol else '-'} | {why} | | | | |")
                        continue
                    state, event, heat = errors(ref, read_run(out, name, suffix))
                    wall, steps = w.get(suffix, (float("nan"), 0))
                    block.append(f"| {solver} | {tol if tol else '-'} | {state:.2g} | "
                                 f"{'differs' if event is None else f'{event:.2g}'} | {heat:.2g} | {steps} | "
                                 f"{wall / horizon:.3g} |")
                print("\n".join(block), flush=True)
                lines += block
    if len(sys.argv) > 2:
        with open(sys.argv[2], "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
