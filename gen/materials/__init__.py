"""Registry of materials: every module in this folder that defines NAME and energy().

A material module holds
  NAME      scene name (law = "...")
  TITLE     one line
  PARAMS    names of the kernel parameters, in the order of mat[] in C
  INPUTS    accepted scene key sets: tuple of (keys, function(*values) -> PARAMS values)
  energy(I1, I2, J, p) -> strain energy per unit reference volume (sympy), with p a
            dict of sympy symbols named as PARAMS.
The generator derives forces and tangents from energy(); the scene reader uses
INPUTS.  Adding a material is adding one such file.
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
