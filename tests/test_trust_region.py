"""static.globalization = "trust_region" (runtime/analysis/static_trust.c): a
slack cable (models/slack_cable.toml, EI / (EA L^2) = 7e-12) that plain Newton
cannot start hangs as the catenary (closed form, not our elements); the trust
region leaves a problem Newton solves at Newton's answer; loads without a
potential are refused."""
import json
import math

from scipy.optimize import brentq

from util import run_cli, run_scene

W = 1000.0 * math.pi * 0.005**2 * 9.81       # weight per length of the rope (N/m)
A = brentq(lambda a: 2 * a * math.sinh(5.0 / a) - 12.0, 0.5, 100.0)   # catenary parameter, 12 m over 10 m


def test_slack_cable_hangs_as_the_catenary():
    s, _ = run_scene("slack_cable")
    assert s["converged"] and s["steps"] == 1, s
    z = s["sensors"]["middle"]["position"][2]
    sag = A * (math.cosh(5.0 / A) - 1.0)                      # 2.92344 m below the supports
    assert abs(-z / sag - 1) < 2e-3, (z, sag)
    by_type = {r["type"]: r["force"] for r in s["reactions"]}
    for f in by_type.values():                                 # horizontal tension w a at both ends
        assert abs(abs(f[0]) / (W * A) - 1) < 5e-3, (f, W * A)
    vertical = sum(f[2] for f in by_type.values())
    assert abs(vertical / (12.0 * W) - 1) < 2e-3, (vertical, 12.0 * W)


def test_plain_newton_fails_on_the_slack_cable_and_names_the_trust_region():
    r = run_cli(["run", "slack_cable", "--quiet", "--set", "static.globalization=none",
                 "--set", "static.max_iterations=25", "--set", "static.max_cutbacks=6"])
    assert r.returncode == 2, r.stderr[-2000:]
    assert 'globalization = "trust_region"' in r.stderr


def test_trust_region_on_a_problem_newton_solves_gives_newtons_answer():
    newton, _ = run_scene("cantilever_bend_100N")
    trust, _ = run_scene("cantilever_bend_100N", ["static.globalization=trust_region",
                                                   "static.max_iterations=200"])
    a, b = newton["sensors"]["tip"]["position"], trust["sensors"]["tip"]["position"]
    assert max(abs(x - y) for x, y in zip(a, b)) < 1e-9, (a, b)


def test_loads_without_a_potential_are_refused():
    r = run_cli(["run", "cantilever_follower", "--quiet", "--set", "static.globalization=trust_region"])
    assert r.returncode != 0
    assert "needs loads with a potential" in r.stderr, r.stderr[-2000:]
