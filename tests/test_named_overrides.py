"""Names on loads and `--set` of named items, arrays and inline tables (issue 37):
a named load's value changed by name gives the run of the scene edited by hand."""
from util import BUILD, ROOT, ensure_dir, run_scene, tip

TENDON = (ROOT / "models" / "tendon_ancf.toml").read_text()


def test_set_a_named_load_and_an_array():
    """load.pull.tension=75 (by the load's name) equals the scene with tension = 75.0
    written in it (tip identical), and halves the tip deflection (linear range, the
    curvature T d / EI); load.pull.offset=[0.0, -0.004] (a TOML array) reverses it."""
    d = ensure_dir(BUILD / "named")
    named = d / "named.toml"
    named.write_text(TENDON.replace('type = "tendon"', 'type = "tendon"\nname = "pull"'))
    edited = d / "edited.toml"
    edited.write_text(TENDON.replace("tension = 150.0", "tension = 75.0"))
    full = tip(run_scene(named)[0])
    half = tip(run_scene(named, ["load.pull.tension=75"])[0])
    assert half == tip(run_scene(edited)[0])
    assert abs(half[2] / full[2] - 0.5) < 1e-3, (half, full)
    flipped = tip(run_scene(named, ["load.pull.offset=[0.0, -0.004]"])[0])
    assert abs(flipped[2] + full[2]) < 1e-9 * abs(full[2]), (flipped, full)


def test_duplicate_load_name_and_bad_array_set():
    from test_bad_input import check_error, run_text
    text = TENDON.replace('type = "tendon"', 'type = "tendon"\nname = "pull"')
    text += '[[load]]\nname = "pull"\ntype = "gravity"\nvalue = [0.0, 0.0, -9.81]\n'
    check_error(text, "load[1].name", "used twice")
    r, p, _ = run_text(TENDON, "arr", extra=["--set", "load.0.tension=[1, 2]"])
    assert r.returncode == 1 and r.stderr.strip().count("\n") == 0, r.stderr
    assert "load.0.tension" in r.stderr and "not an array" in r.stderr, r.stderr
