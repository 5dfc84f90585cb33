"""The scene compiler's check for free rigid motions in statics
(gen/scene/rigid_modes.py) takes a plain-Python path when the fixed
coordinates alone clearly hold all six motions (a clamp), so that a run which
changes only numbers does not import numpy.  Checked against its numpy path:

  * each coordinate's rigid velocities computed in plain Python equal the
    columns of rigid_velocities (numpy), for every coordinate of every scene of
    models/ (positions, gradients, quaternions);
  * wherever the plain path says "held", the SVD path finds no free motion,
    on every static scene of models/; and it says "held" for the clamped ones;
  * with only a clamp's fixed positions (a pin) the plain path does not say
    "held", and the SVD path finds three free motions."""
import sys

import pytest

import gen.scene.rigid_modes as R
from gen.scene import ROOT, SceneError, build

B = sys.modules["gen.scene.build"]          # (the package exports the function build under that name)

SCENES = sorted(ROOT.glob("models/*.toml"))


@pytest.fixture(scope="module")
def checked():
    """(scene, mesh, rows, analysis) of every scene's static check."""
    seen = []
    orig = B.check_static

    def spy(ctx, mesh, rows, analysis, has_contact, stat):
        seen.append((ctx, mesh, rows, analysis, has_contact))
        return orig(ctx, mesh, rows, analysis, has_contact, stat)

    B.check_static = spy
    try:
        for path in SCENES:
            try:
                build(path)
            except SceneError:
                pass
    finally:
        B.check_static = orig
    assert len(seen) >= 40, len(seen)
    return seen


def test_velocity_rows_equal_numpy_columns(checked):
    kinds = set()
    for _ctx, mesh, _rows, _a, _hc in checked:
        if len(mesh.q0) > 3000:
            continue
        modes = R.rigid_velocities(mesh)
        where, c = R._coordinates(mesh)
        kinds |= {k for k, _ in where.values()}
        scale = max(1.0, float(abs(modes).max()))
        for d in range(len(mesh.q0)):
            row = R._velocity_row(mesh.q0, where, c, d)
            assert max(abs(a - b) for a, b in zip(row, modes[:, d])) <= 1e-12 * scale, (d, row, modes[:, d])
    assert kinds == {"r", "v", "p"}, kinds


def test_plain_path_only_where_the_svd_finds_nothing_free(checked):
    held = 0
    for _ctx, mesh, rows, analysis, has_contact in checked:
        if analysis != "static":
            continue
        fast = R.fixed_hold_all(mesh, sorted(rows.fixed))
        orig = R.fixed_hold_all
        R.fixed_hold_all = lambda *a, **k: False
        try:
            ref = R.free_motions(mesh, rows.fixed, rows.lincons)
        finally:
            R.fixed_hold_all = orig
        if fast:
            held += 1
            assert ref == [], ref
    assert held >= 20, held


def test_positions_alone_do_not_hold_the_rotations(checked):
    """A clamped scene's fixed coordinates cut down to the positions they fix
    (a pin): the plain path does not say "held" (the rotations about the pin
    are free), and the SVD path finds three free motions."""
    n = 0
    for _ctx, mesh, rows, analysis, _hc in checked:
        if analysis != "static" or not R.fixed_hold_all(mesh, sorted(rows.fixed)):
            continue
        where, _c = R._coordinates(mesh)
        pos = sorted(d for d in rows.fixed if where.get(d, ("", 0))[0] == "r")
        pin = pos[:3]
        if len(pin) < 3 or pin[2] - pin[0] != 2:
            continue
        assert not R.fixed_hold_all(mesh, pin)
        free = R.free_motions(mesh, pin, [])
        assert len(free) == 3, free                # (the rotations about the pin)
        n += 1
    assert n >= 10, n
