"""Registry of elements: every module in this folder that defines ELEMENT."""
import importlib
import pkgutil
from pathlib import Path


def all_elements():
    """Elements by name, in sorted order of their module names."""
    out = {}
    for info in sorted(pkgutil.iter_modules([str(Path(__file__).parent)]), key=lambda i: i.name):
        mod = importlib.import_module(f"{__name__}.{info.name}")
        elem = getattr(mod, "ELEMENT", None)
        if elem is not None:
            out[elem.name] = (elem, Path(mod.__file__))
    return out
