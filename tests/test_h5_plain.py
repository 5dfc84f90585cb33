"""runtime/output/h5_plain.c, the HDF5 file format written without the HDF5
library (a short run's results.h5: runtime/output/h5_whole.c), against the
library itself: tests/h5_plain_check.c (AddressSanitizer + UBSan) writes the same
attributes, datasets (int32, int64, float64 with inf, nan and -0, null-padded and
null-terminated strings, a compound, a 2-d array, an empty one; two of them
large enough to be written from in place, not copied) and groups (one
of more than 8 links, an empty one) with each; h5py (libhdf5 reading, which
checks every checksum) reads them alike, and as the values written.  A run's
results.h5 made in one piece equals the CSVs and the states in
tests/test_results_h5.py."""
import math
import subprocess
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")

from util import BUILD, build_runtime_program, ensure_dir


@lru_cache(maxsize=None)
def files():
    exe = build_runtime_program(["h5_plain_check.c"], "h5_plain_check", "sanitize")
    d = Path(tempfile.mkdtemp(prefix="bk-h5plain-", dir=ensure_dir(BUILD / "runs")))
    r = subprocess.run([str(exe), str(d / "plain.h5"), str(d / "lib.h5")], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, f"h5_plain_check failed ({r.returncode}):\n{r.stdout}\n{r.stderr[-4000:]}"
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    return r.stdout, d / "plain.h5", d / "lib.h5"


def content(path):
    """{name: (kind, dtype, shape, value bytes, attributes)} of every object, as h5py reads them."""
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, o):
            attrs = {k: (o.attrs[k], o.attrs[k].dtype) for k in o.attrs}
            if isinstance(o, h5py.Dataset):
                a = o[()]
                out[name] = ("dataset", o.dtype, o.shape, a.tobytes(), attrs)
            else:
                out[name] = ("group", None, None, None, attrs)
        visit("/", f)
        f.visititems(visit)
    return out


def test_checksum_is_hdf5s():
    assert "checksums equal" in files()[0]


def test_plain_file_reads_as_the_librarys():
    _, plain, lib = files()
    a, b = content(plain), content(lib)
    assert sorted(a) == sorted(b)
    for name in a:
        assert a[name][:4] == b[name][:4], name
        assert a[name][4].keys() == b[name][4].keys(), name
        for k, (v, t) in a[name][4].items():
            assert t == b[name][4][k][1] and v == b[name][4][k][0], (name, k)


def test_plain_file_holds_the_values_written():
    _, plain, _ = files()
    with h5py.File(plain, "r") as f:
        assert f.attrs["name"] == b"beam" and f.attrs["empty"] == b"" and f.attrs["count"] == -5
        assert f.attrs["count"].dtype == np.int64
        assert f["ints32"].dtype == np.int32 and list(f["ints32"][()]) == [1, -2, 2147483647]
        assert list(f["ints64"][()]) == [-9223372036854775807, 42]
        d = f["doubles"][()]
        assert d.shape == (2, 3) and d.dtype == np.float64
        assert d[0, 0] == 1.5 and d[0, 1] == 0 and math.copysign(1, d[0, 1]) < 0 and d[0, 2] == 1e-300
        assert d[1, 0] == math.inf and math.isnan(d[1, 1]) and d[1, 2] == -2.25e17
        assert list(f["pad64"][()]) == [b"arm", b"a longer name"] and f["pad64"].dtype == "S64"
        assert list(f["term8"][()]) == [b"r_x", b"lambda"] and f["term8"].dtype == "S8"
        r = f["rows"][()]
        assert r.dtype.names == ("step", "time", "name", "x")
        assert list(r["step"]) == [0, 1, 2] and list(r["time"]) == [0, 0.25, 0.5]
        assert list(r["name"]) == [b"pt0", b"pt1", b"pt2"] and list(r["x"]) == [0, -1, -2]
        assert sorted(f["many"]) == [f"d{k}" for k in range(10)]
        assert [int(f["many"][f"d{k}"][0]) for k in range(10)] == list(range(10))
        assert len(f["none"]) == 0 and f["zero"].shape == (0,)
        i, j = np.mgrid[0:3000, 0:4]
        assert f["big"].shape == (3000, 4) and np.array_equal(f["big"][()], i / 2 - j)
        r = f["bigrows"][()]
        assert list(r["step"]) == list(range(400)) and list(r["x"]) == [-k for k in range(400)]
        assert list(r["name"]) == [f"pt{k}".encode() for k in range(400)]
