#!/usr/bin/env python3
"""Shift metrics of a pogear run computed from its files alone, for the tests: an independent
reading of docs/friction-elements.md's "Shift metrics", sharing no code with pogear.

    shift_metrics_reference.py SCENE.toml RUN_DIR [SUFFIX]

reads the scene (its [engagement] commands: constants and tables), RUN_DIR/<name><SUFFIX>.csv and
RUN_DIR/<name><SUFFIX>.events.csv (SUFFIX "" or ".rigid"), and prints the metrics as JSON on
standard output.
"""
import bisect
import csv
import json
import math
import os
import sys
import tomllib


def command_points(value, scene_dir):
    """A command as the points of a piecewise-linear function of time (held outside them)."""
    if isinstance(value, (int, float)) or isinstance(value, str):
        return [(0.0, float(value))]
    if "table" in value and isinstance(value["table"], str):
        with open(os.path.join(scene_dir, value["table"]), newline="") as f:
            rows = list(csv.reader(f))[1:]
        return [(float(t), float(v)) for t, v in rows]
    raise SystemExit("this reference reads constant and table commands only: %r" % (value,))


def command_at(points, t, left=False):
    """The command at t; with left, its limit from below (a repeated time is a jump)."""
    times = [p[0] for p in points]
    i = bisect.bisect_left(times, t) if left else bisect.bisect_right(times, t)
    if i == 0:
        return points[0][1]
    if i == len(points):
        return points[-1][1]
    (t0, v0), (t1, v1) = points[i - 1], points[i]
    return v0 + (t - t0) / (t1 - t0) * (v1 - v0)


def windows(commands, horizon):
    pieces = []
    for points in commands.values():
        for (t0, v0), (t1, v1) in zip(points, points[1:]):
            a, b = max(t0, 0.0), min(t1, horizon)
            if a > b:
                continue
            if t0 == t1 and v0 != v1:
                pieces.append((a, a))
            elif v0 != v1:
                pieces.append((a, b))
    pieces.sort()
    merged = []
    for a, b in pieces:
        if merged and a <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], b)
        else:
            merged.append([a, b])
    return merged


def interpolate(times, values, t):
    i = bisect.bisect_right(times, t)
    if i == 0:
        return values[0]
    if i == len(times):
        return values[-1]
    return values[i - 1] + (t - times[i - 1]) / (times[i] - times[i - 1]) * (values[i] - values[i - 1])


def main():
    scene_path, run_dir = sys.argv[1], sys.argv[2]
    suffix = sys.argv[3] if len(sys.argv) > 3 else ""
    with open(scene_path, "rb") as f:
        scene = tomllib.load(f)
    name = scene.get("name", os.path.splitext(os.path.basename(scene_path))[0])
    with open(os.path.join(run_dir, name + suffix + ".csv"), newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    header = [h.split(" [")[0] for h in rows[0]]
    units = [h.split(" [")[1].rstrip("]") if " [" in h else "" for h in rows[0]]
    data = [[float(x) for x in r] for r in rows[1:]]
    col = {h: i for i, h in enumerate(header)}
    times = [r[0] for r in data]
    # The engaged elements in the CSV's order (T_ columns), their commands from the scene.
    elements = [h[2:] for h in header if h.startswith("T_") and "slip_" + h[2:] in col]
    scene_dir = os.path.dirname(scene_path)
    commands = {e: command_points(scene["engagement"][e], scene_dir) for e in elements}
    with open(os.path.join(run_dir, name + suffix + ".events.csv"), newline="") as f:
        events = [(float(r[0]), r[1], r[2], r[3]) for r in list(csv.reader(f))[1:] if r and not r[0].startswith("#")]
    horizon = times[-1]

    def state_before(e, k, t):
        mine = [ev for ev in events if ev[1] == e]
        if not mine:
            if (int(data[0][col["mode"]]) >> k) & 1:
                return "stuck"
            return "slipping" if data[0][col["T_" + e]] != 0 else "open"
        s = mine[0][2]
        for ev in mine:
            if ev[0] < t:
                s = ev[3]
        return s

    ws = windows(commands, horizon)
    shifts = []
    for i, (start, cmd_end) in enumerate(ws):
        nxt = ws[i + 1][0] if i + 1 < len(ws) else math.inf
        off = [e for e in elements if command_at(commands[e], cmd_end) < command_at(commands[e], start, left=True)]
        on = [e for e in elements if command_at(commands[e], cmd_end) > command_at(commands[e], start, left=True)]
        end = cmd_end
        for ev in events:
            if ev[1] in off + on and start <= ev[0] < nxt:
                end = max(end, ev[0])
        end = min(end, horizon)
        shift = {"start_s": start, "end_s": end, "offgoing": off, "oncoming": on}
        releases = [max([ev[0] for ev in events if ev[1] == e and start <= ev[0] <= end and ev[2] == "stuck"], default=None)
                    for e in off]
        locks = [max([ev[0] for ev in events if ev[1] == e and start <= ev[0] <= end and ev[3] == "stuck"], default=None)
                 for e in on]
        release = max(releases) if off and None not in releases else None
        lock = max(locks) if on and None not in locks else None
        shift["torque_phase_end_s"] = release
        shift["lockup_s"] = lock
        shift["time_to_lockup_s"] = None if lock is None else lock - start
        shift["inertia_phase_s"] = None if release is None or lock is None else lock - release
        per = {}
        for k, e in enumerate(elements):
            # Slip time: the intervals in the state `slipping`, clipped to [start, end].
            state, since, slip_time = state_before(e, k, start), start, 0.0
            for ev in events:
                if ev[1] == e and start <= ev[0] <= end:
                    if state == "slipping":
                        slip_time += ev[0] - since
                    state, since = ev[3], ev[0]
            if state == "slipping":
                slip_time += end - since
            energy = [r[col["E_" + e]] for r in data]
            scale = math.pi / 30 if units[col["slip_" + e]] == "rpm" else 1.0
            inside = [r for r in data if start <= r[0] <= end]
            # A sample in which the element is stuck (its bit of `mode`) has no slip power.
            power = max(0.0 if (int(r[col["mode"]]) >> k) & 1 else abs(r[col["T_" + e]] * r[col["slip_" + e]] * scale)
                        for r in inside)
            if slip_time > 0 and power == 0:
                power = None  # it slipped between samples only: no sampled peak
            per[e] = {"slip_time_s": slip_time, "heat_J": interpolate(times, energy, end) - interpolate(times, energy, start),
                      "peak_slip_power_W": power}
        shift["elements"] = per
        inside = [r for r in data if start <= r[0] <= end]
        before = [r for r in data if r[0] < start]
        if "T_half_shafts" in col and before:
            c = col["T_half_shafts"]
            b = before[-1][c]
            lo, hi = min(r[c] for r in inside), max(r[c] for r in inside)
            shift["output_torque"] = {"before_Nm": b, "min_Nm": lo, "max_Nm": hi, "min_ratio": lo / b, "max_ratio": hi / b}
        if "vehicle_jerk" in col:
            shift["peak_jerk_m_per_s3"] = max((r[col["vehicle_jerk"]] for r in inside), key=abs)
        shifts.append(shift)
    json.dump({"scene": name, "shifts": shifts}, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
