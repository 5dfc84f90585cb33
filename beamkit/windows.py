"""Sweep outputs over a time window: a statistic of one result column of a run
over its output steps (numpy only, no sympy).

    NAME.FIELD:STAT            over the whole run
    NAME.FIELD:STAT@T0:T1      over the output steps with T0 <= time <= T1

NAME.FIELD is a sensor's x, y, z, ux, uy, uz (sensors.csv), or a joint's
(constraint name) or an actuator's value, rate, effort, power (joints.csv,
actuators.csv); STAT is peak (largest |v|), max, min, amplitude ((max - min)/2),
rms (root mean square of the values) or mean.  In statics the time is the load
factor.  A window that holds no output step gives no value.
"""
import csv
import math
import re
from pathlib import Path

STATS = ("peak", "max", "min", "amplitude", "rms", "mean")
SENSOR_FIELDS = ("x", "y", "z", "ux", "uy", "uz")
JOINT_FIELDS = ("value", "rate", "effort", "power")
_NAME = re.compile(r"[A-Za-z0-9_.\-]+")


def is_window(o):
    return ":" in o


def parse(o):
    """(name, field, stat, t0, t1) of a window output, or a message why not."""
    head, _, tail = o.partition(":")
    name, dot, field = head.rpartition(".")
    stat, at, win = tail.partition("@")
    if not dot or not _NAME.fullmatch(name) or field not in SENSOR_FIELDS + JOINT_FIELDS:
        return f"expected NAME.FIELD:STAT with FIELD one of {', '.join(SENSOR_FIELDS + JOINT_FIELDS)}"
    if stat not in STATS:
        return f"unknown statistic {stat!r}; expected one of {', '.join(STATS)}"
    t0, t1 = -math.inf, math.inf
    if at:
        try:
            t0, t1 = (float(x) for x in win.split(":"))
        except ValueError:
            return f"expected the window as @T0:T1 (two numbers), found @{win}"
        if not t1 > t0:
            return f"expected T1 > T0 in @{win}"
    return name, field, stat, t0, t1


def names(doc):
    """(sensor names, joint and actuator names) of a scene's TOML."""
    def named(table):
        return {t.get("name") for t in doc.get(table, []) if isinstance(t, dict) and isinstance(t.get("name"), str)}
    joints = named("constraint") | named("actuator")
    joints |= {f"constraint{i}" for i, t in enumerate(doc.get("constraint", [])) if isinstance(t, dict)
               and "name" not in t}
    joints |= {f"actuator{i}" for i, t in enumerate(doc.get("actuator", [])) if isinstance(t, dict) and "name" not in t}
    return named("sensor"), joints


def check(doc, path, o):
    """None when the window output o can be read from a run of the scene doc, else
    the error line."""
    p = parse(o)
    if isinstance(p, str):
        return f"error: --output {o}: {p}"
    name, field = p[0], p[1]
    sensors, joints = names(doc)
    if field in SENSOR_FIELDS and name not in sensors:
        return f"error: --output {o}: no sensor {name!r} in {path} (sensors: {', '.join(sorted(sensors)) or 'none'})"
    if field in JOINT_FIELDS and name not in joints:
        return (f"error: --output {o}: no joint or actuator {name!r} in {path} (named: "
                f"{', '.join(sorted(joints)) or 'none'})")
    return None


def _series(run_dir, name, field):
    """(times, values) of the column in the run's table."""
    run_dir = Path(run_dir)
    if field in SENSOR_FIELDS:
        files = [("sensors.csv", "sensor")]
    else:
        files = [("actuators.csv", "actuator"), ("joints.csv", "name")]
    for fname, key in files:
        try:
            with open(run_dir / fname, newline="", encoding="utf-8") as fh:
                rows = [r for r in csv.DictReader(fh) if r.get(key) == name]
        except OSError:
            continue
        if rows:
            return [float(r["time"]) for r in rows], [float(r[field]) for r in rows]
    return [], []


def value(run_dir, o):
    """The statistic of window output o over run_dir's results (None: no step in it)."""
    name, field, stat, t0, t1 = parse(o)
    t, v = _series(run_dir, name, field)
    w = [x for ti, x in zip(t, v) if t0 <= ti <= t1 and math.isfinite(x)]
    if not w:
        return None
    if stat == "peak":
        return max(abs(x) for x in w)
    if stat == "max":
        return max(w)
    if stat == "min":
        return min(w)
    if stat == "amplitude":
        return (max(w) - min(w)) / 2
    if stat == "rms":
        return math.sqrt(sum(x * x for x in w) / len(w))
    return sum(w) / len(w)
