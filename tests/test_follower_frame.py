"""The generated section frame of follower loads (bk_element.section_frame) and
its Jacobian against central differences of the generated frame and against the
Gram-Schmidt frame of frame() (tests/frame_check.c), for every element."""
import subprocess

from util import BUILD, ROOT, ensure_dir


def element_files(index):
    """{element: generated C files its descriptor needs} from index.json."""
    out = {}
    for p in index["pairs"]:
        out.setdefault(p["element"], [f for f in p["files"] if f != f"{p['element']}_{p['material']}.c"])
    body = index["body"]
    out[body["element"]] = list(body["files"])
    return out


def build_frame_check(variant="release"):
    from gen.scene import load_index
    from gen.solver_build import BUILD as SOLVER_BUILD
    from gen.solver_build import (CC, KERNEL_FLAGS, KERNELS, LIBS, RUNTIME, VARIANTS, _compile_many,
                                  _kernel_headers, build_lock, compile_object)
    index = load_index()
    files = element_files(index)
    names = sorted(files)
    d = ensure_dir(BUILD / variant)
    table = d / "frame_check_table.c"
    text = ('#include "bk_kernel.h"\n' + "".join(f"extern const bk_element bk_element_{n};\n" for n in names) +
            "const bk_element *const frame_check_elements[] = {" + ", ".join(f"&bk_element_{n}" for n in names) +
            "};\n" + f"const int frame_check_nelements = {len(names)};\n")
    if not table.exists() or table.read_text() != text:
        table.write_text(text)
    srcs = sorted({f for fs in files.values() for f in fs})
    with build_lock():
        # the kernel objects where the solvers' builds keep them (the same flags): compiled once for both
        jobs = [(KERNELS / f, SOLVER_BUILD / variant / "kernels" / (f[:-2] + ".o"), KERNEL_FLAGS[variant],
                 _kernel_headers(KERNELS / f)) for f in srcs]
        _compile_many(jobs, None)
        hdrs = [RUNTIME / "bk_kernel.h"]
        objs = [j[1] for j in jobs]
        for src in (ROOT / "tests" / "frame_check.c", table):
            obj = d / (src.stem + ".o")
            compile_object(src, obj, VARIANTS[variant], hdrs)
            objs.append(obj)
        exe = d / "frame_check"
        if not exe.exists() or exe.stat().st_mtime < max(o.stat().st_mtime for o in objs):
            r = subprocess.run([CC] + VARIANTS[variant] + [str(o) for o in objs] + ["-o", str(exe)] + LIBS,
                               capture_output=True, text=True)
            assert r.returncode == 0, r.stderr[-3000:]
    return exe, index


def test_section_frame_jacobian_against_central_differences():
    """20 states per element: dR/dq vs 4th-order central differences of R, R
    orthonormal, equal to the Gram-Schmidt frame of frame() and the same with
    and without the Jacobian; only the cable has no section frame.  The rods'
    section_line() (LINE_TOL); only the rods have one."""
    exe, index = build_frame_check()
    r = subprocess.run([str(exe), "20"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    rows = [dict(kv.split("=", 1) for kv in line.split()) for line in r.stdout.splitlines()]
    seen = {d["element"] for d in rows}
    assert seen == set(index["elements"]) | {index["body"]["element"]}, seen
    bad = []
    for d in rows:
        kind = index["elements"].get(d["element"], {}).get("kind")
        if kind == "cable":
            assert d.get("section_frame") == "none", d
            continue
        assert "section_frame" not in d, d
        for k, tol in (("fd", 1e-9), ("consist", 1e-14), ("orth", 1e-13), ("gs", 1e-12)):
            if not float(d[k]) <= tol:
                bad.append(f"{d['element']}: {k} = {d[k]} > {tol:.0e}")
        if kind != "rod":
            assert d.get("section_line") == "none", d
            continue
        for k, tol in LINE_TOL:
            if not float(d[k]) <= tol:
                bad.append(f"{d['element']}: {k} = {d[k]} > {tol:.0e}")
    assert not bad, "\n".join(bad) + "\n" + r.stdout


# section_line() (tendons and chambers on rods): its tangent against the xi-derivative
# of the line built from frame() and section_frame(), its Jacobian and contracted
# Hessian against 4th-order central differences (tests/frame_check.c).
LINE_TOL = (("line_xi", 1e-10), ("line_fd", 1e-10), ("line_h", 1e-9), ("line_c", 1e-14))


def test_solver_refuses_a_follower_load_on_an_element_without_section_frame():
    """The scene compiler refuses follower loads on the cable (tests/test_loads_outputs.py);
    a model file that has one anyway stops the solver with one line naming the load."""
    import re
    import tempfile
    from pathlib import Path
    from util import run_cli
    out = Path(tempfile.mkdtemp(prefix="bk-ff-", dir=ensure_dir(BUILD / "runs")))
    text = (ROOT / "models" / "cantilever_follower.toml").read_text()
    scene = out / "follower_cable_refused.toml"          # its own solver name: no other test relinks it
    scene.write_text(text.replace('element = "gef"', 'element = "ancf_cable"').replace("follower = true",
                                                                                       "follower = false"))
    r = run_cli(["run", str(scene), "--quiet", "--out", str(out / "run")])
    assert r.returncode == 0, r.stderr
    model = (out / "run" / "model.dat").read_text()
    for rec in ("force", "moment"):
        bad = re.sub(rf"^({rec} .*) 0$", r"\1 1", model, count=1, flags=re.M)
        assert bad != model
        (out / "bad.dat").write_text(bad)
        r = subprocess.run([str(ROOT / "out" / "bin" / "follower_cable_refused"), str(out / "bad.dat"),
                            str(out / "w"), "--quiet"], capture_output=True, text=True)
        assert r.returncode == 1, (r.returncode, r.stderr)
        assert (f"{rec} 0: follower load on element 9 (ancf_cable): expected an element with a section frame"
                in r.stderr), r.stderr
        assert len(r.stderr.strip().splitlines()) == 1, r.stderr
