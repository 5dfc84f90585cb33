"""beamkit from Python: scenes, runs, sweeps and calibration (see docs/reference/python-api.md
and docs/howto/sweep-dask.md).  Importing this package imports no sympy.

    Scene, Run, Sensor, BeamkitError, run     beamkit.api
    sweep                                     beamkit.sweep
    fit                                       beamkit.fit
"""
from beamkit.api import BeamkitError, Run, Scene, Sensor, run  # noqa: F401


def sweep(*args, **kw):
    """beamkit.sweep.sweep (imported when first used)."""
    from beamkit.sweep import sweep as _sweep
    return _sweep(*args, **kw)


def fit(*args, **kw):
    """beamkit.fit.fit (imported when first used)."""
    from beamkit.fit import fit as _fit
    return _fit(*args, **kw)
