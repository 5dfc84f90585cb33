"""The benchmark's plain quadrature loop (bench/plain.c) computes the same
internal force and tangent as the generated kernels, for every single-rule
continuum element x material pair: the kernel ratio in ./build.sh bench
compares like with like.  Also: op counts parsed from the kernel headers agree
with the pair descriptors, and the lane kernels it times agree with the
one-element kernels.  The driver runs with timing off (no timings in tests)."""
import pytest
import csv
import io
import subprocess
import sys

from util import BUILD, ROOT, ensure_dir

sys.path.insert(0, str(ROOT))


@pytest.mark.slow
def test_plain_loop_matches_generated_kernels():
    from report import bench_kernels
    exe, index = bench_kernels.build_driver()
    spec = ensure_dir(BUILD / "bench") / "plain_spec.txt"
    spec.write_text(bench_kernels.spec_text(index, 1, 0.0))
    r = subprocess.run([str(exe), str(spec)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    assert len(rows) == len(index["pairs"])
    checked = 0
    for d in rows:
        # the lane kernels the benchmark times (8 elements per call) against the one-element kernel
        if "resultant" not in d["pair"]:
            assert float(d["lanes_rel_diff"]) < 1e-11, f"{d['pair']}: lane kernel differs {d['lanes_rel_diff']}"
        if d["plain_rel_diff_K"] == "nan":
            assert "resultant" in d["pair"] or d["pair"].endswith("_sri"), f"{d['pair']}: no plain loop"
            continue
        checked += 1
        assert float(d["plain_rel_diff_f"]) < 1e-11, f"{d['pair']}: force differs {d['plain_rel_diff_f']}"
        assert float(d["plain_rel_diff_K"]) < 1e-11, f"{d['pair']}: tangent differs {d['plain_rel_diff_K']}"
    assert checked >= 20, checked


def test_header_op_counts_match_descriptors():
    from report import bench_kernels
    from gen.scene import load_index
    index = load_index()
    for p in index["pairs"]:
        h = bench_kernels.header_ops(p["element"], p["material"])
        assert p["integration"] in h, f"{p}: no operation counts in the header"
    # the operation-count target, per quadrature point
    h = bench_kernels.header_ops("ancf3243", "svk")["full"]
    assert int(h["ft_pt"]) <= 3000, h
