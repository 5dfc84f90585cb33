"""The scene compiler (no sympy): a scene file to the model the C solver reads.

    build(path, sets)      validate and mesh a scene: the model as plain data
    write_model(model, p)  the model file for runtime/model/model.c
Errors are one line, `error: FILE: KEY: what was expected`, raised as SceneError.
"""
from gen.scene.build import ANALYSES, build  # noqa: F401
from gen.scene.files import ROOT_DIR, apply_overrides, load_index, read_toml  # noqa: F401
from gen.scene.geometry import frame_quaternion, section_axes, section_geometry  # noqa: F401
from gen.scene.materials import KEY_RANGES, law_eval, small_strain  # noqa: F401
from gen.scene.mesh import MAX_ELEMENTS  # noqa: F401
from gen.scene.model_file import write_model  # noqa: F401
from gen.scene.options import DYNAMIC_DEFAULTS, STATIC_DEFAULTS  # noqa: F401
from gen.scene.values import (NAME_RE, Ctx, SceneError, check_keys, get_array_of_tables, get_bool,  # noqa: F401
                              get_int, get_name, get_number, get_str, get_table, get_vec3)


def __getattr__(name):
    """ROOT and KERNEL_INDEX (pathlib.Path) on first use: gen/scene/files.py."""
    if name in ("ROOT", "KERNEL_INDEX"):
        from gen.scene import files
        return getattr(files, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
