"""Registry of materials: every module in this folder that defines NAME and energy().

A material module holds
  NAME      scene name (law = "...")
  TITLE     one line
  PARAMS    names of the kernel parameters, in the order of mat[] in C
  INPUTS    accepted scene key sets: tuple of (keys, function(*values) -> PARAMS values)
  RANGES    {scene key: (lo, hi, unit)} for every key of INPUTS: the scene reader
            refuses a value outside lo < value < hi (None: unbounded)
  energy(I1, I2, J, p) -> strain energy per unit reference volume (sympy), with p a
            dict of sympy symbols named as PARAMS.
and may hold
  small_strain(*PARAMS) -> (E, nu) at small strain: the locking warnings and
            Kelvin-Voigt damping (kelvin_voigt) need it
  GREEN_STRAIN_RANGE  (lo, hi) principal Green strains the law is meant for (the
            runtime warns beyond)
The generator derives forces and tangents from energy(); the scene reader uses
INPUTS and RANGES.  Adding a material is adding one such file (README, "Adding
a material").
"""
import importlib
import pkgutil
from pathlib import Path


def lame(E, nu):
    """(lambda, mu) from Young's modulus and Poisson's ratio."""
    return (E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu)))


def all_materials(folder=None):
    """Materials by NAME, sorted by module name: {name: (module, path)}."""
    folder = Path(folder) if folder else Path(__file__).parent
    out = {}
    for info in sorted(pkgutil.iter_modules([str(folder)]), key=lambda i: i.name):
        mod = importlib.import_module(f"{__name__}.{info.name}")
        if hasattr(mod, "NAME") and hasattr(mod, "energy"):
            out[mod.NAME] = (mod, Path(mod.__file__))
    return out
