"""Kernel timings for ./build.sh bench: every element x material x integration
pair, generated kernel against the plain quadrature loop of bench/plain.c.

Builds bench/kernels.c with the release flags of the solvers, linked with every
generated pair (gen/solver_build.py), writes the spec it reads (geometry,
material parameters, shape-function gradients at the quadrature points of the
single-rule continuum variants) and parses its CSV.  Operation counts are read
from the kernel headers in out/kernels/.
"""
import csv
import io
import math
import re
import subprocess
from functools import lru_cache
from pathlib import Path

from gen.scene import ROOT, load_index

BENCH = ROOT / "bench"
KERNELS = ROOT / "out" / "kernels"
GEOM = (0.1, 0.01, 0.01)          # element length, section b, h (m): a 10-element, 1 m beam

# Material parameters used for the timings (values matter little: no branches).
MATERIALS = {
    "svk": (5.769230769230769e9, 3.846153846153846e9),           # lambda, mu (E = 1e10, nu = 0.3)
    "neo_hookean": (5.769230769230769e9, 3.846153846153846e9),
    "mooney_rivlin": (2.0e5, 5.0e4, 2.5e8),                     # c10, c01, kappa
    "arruda_boyce": (3.0e5, 3.0, 3.0e8),                        # mu, lambda_m, kappa
}


def section_geom(l, b, h):
    """geom[] of a rectangle in the slot order of runtime/bk_kernel.h."""
    from gen import contract
    A = b * h
    I1, I2 = b * h**3 / 12, h * b**3 / 12
    return contract.geom_vector(L=l, B=b, H=h, A=A, I1=I1, I2=I2, IP=I1 + I2,
                                SHAPE=contract.section_shapes()["rectangle"])


def resultant_params(geom, E=1e10, nu=0.3):
    l, b, h, A, I1, I2 = geom[:6]
    G = E / (2 * (1 + nu))
    k = 10 * (1 + nu) / (12 + 11 * nu)
    a, c = max(b, h), min(b, h)
    J = 0.1406 * c**4 if a == c else a * c**3 / 3 * (1 - 0.63 * c / a)
    return (E * A, k * G * A, k * G * A, G * J, E * I1, E * I2)


HDR_RE = re.compile(r'integration "(\w+)": (\d+) pts[^\n]*\n'
                    r'[\s*]+energy\s+per point ([\d /]+); per element (\d+)[^\n]*\n'
                    r'[\s*]+force\s+per point ([\d /]+); per element (\d+)[^\n]*\n'
                    r'[\s*]+force \+ upper tangent\s+per point ([\d /]+); per element (\d+)')


@lru_cache(maxsize=None)
def header_ops(element, material):
    """{integration: dict(points, force_pt, ft_pt, force, ft)} parsed from out/kernels/<pair>.h."""
    text = (KERNELS / f"{element}_{material}.h").read_text()
    out = {}
    for m in HDR_RE.finditer(text):
        out[m.group(1)] = {"points": int(m.group(2)), "energy_pt": m.group(3).strip(),
                           "force_pt": m.group(5).strip(), "ft_pt": m.group(7).strip(),
                           "force": int(m.group(6)), "ft": int(m.group(8))}
    if not out:   # resultant beams: one line "Operations per element call (N Gauss points): ..."
        m = re.search(r"Operations per element call \((\d+) Gauss points\):.*?force (\d+) .*?"
                      r"force \+ upper tangent (\d+)", text, re.S)
        if m:
            out["full"] = {"points": int(m.group(1)), "energy_pt": "", "force_pt": "", "ft_pt": "",
                           "force": int(m.group(2)), "ft": int(m.group(3))}
    return out


def plain_rule(element, integration, geom):
    """Rows (w, grad N_a ...) at the points of a single-part rule, or None."""
    import sympy as sp

    from gen.continuum import qp_coords
    from gen.element import B, H, L, XI, Y, Z, shape_gradients
    from gen.elements import all_elements
    from gen.quadrature import box_rule
    elem = all_elements()[element][0]
    if elem.kind != "continuum":
        return None
    parts = elem.rule(integration)
    if len(parts) != 1 or parts[0].energy != "all":
        return None
    l, b, h = geom[:3]
    grads = shape_gradients(elem)
    fn = sp.lambdify((XI, Y, Z, L, B, H), [g for gs in grads for g in gs], "math")
    rows = []
    for s, w in box_rule(parts[0].points):
        c = qp_coords(s)
        xi, y, z = (float(sp.sympify(c[v]).subs({B: b, H: h})) for v in (XI, Y, Z))
        rows.append([float(w) * l * b * h] + [float(v) for v in fn(xi, y, z, l, b, h)])
    return rows


def build_driver(log=None):
    from gen.solver_build import BUILD, VARIANTS, compile_object, build_solver
    index = load_index()
    pairs = [f"{p['element']}_{p['material']}_{p['integration']}" for p in index["pairs"]]
    flags = VARIANTS["release"] + ["-I" + str(BENCH)]
    objs = []
    for name in ("kernels.c", "plain.c"):
        obj = BUILD / "release" / "bench" / (Path(name).stem + ".o")
        compile_object(BENCH / name, obj, flags, [BENCH / "plain.h", ROOT / "runtime" / "bk_kernel.h"], log)
        objs.append(obj)
    exe = build_solver(pairs, BUILD / "release" / "bench" / "bench_kernels", index, "release", log, main_objs=objs)
    return exe, index


def spec_text(index, repeats, target, only=None):
    geom = section_geom(*GEOM)
    lines = ["geom " + " ".join(repr(g) for g in geom), f"timing {repeats} {target}"]
    for p in index["pairs"]:
        name = f"{p['element']}_{p['material']}_{p['integration']}"
        if only and name not in only:
            continue
        mat = resultant_params(geom) if p["material"] == "resultant" else MATERIALS[p["material"]]
        rows = None if p["material"] == "resultant" else plain_rule(p["element"], p["integration"], geom)
        law = p["material"] if rows else "-"
        nshape = (len(rows[0]) - 1) // 3 if rows else 0
        lines.append(f"pair {name} {len(mat)} " + " ".join(repr(float(x)) for x in mat) +
                     f" {law} {len(rows) if rows else 0} {nshape}")
        for r in rows or []:
            lines.append(" ".join(repr(x) for x in r))
    return "\n".join(lines) + "\n"


TIMES = ("t_force_s", "t_force_tangent_s", "t_lanes_force_s", "t_lanes_force_tangent_s", "t_plain_force_s",
         "t_plain_force_tangent_s")


def run(workdir, repeats=7, target=0.004, only=None, log=None, passes=1):
    """List of dicts, one per pair, with times (s), op counts and derived rates.
    passes > 1: the driver runs that many times one after the other and each
    time is the shortest over the passes (each pass times every pair once, so a
    pair's samples lie seconds apart: a slow spell of a shared machine reaches
    one of them, not all)."""
    exe, index = build_driver(log)
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    spec = workdir / "kernels_spec.txt"
    spec.write_text(spec_text(index, repeats, target, only))
    merged = {}
    for _ in range(passes):
        r = subprocess.run([str(exe), str(spec)], capture_output=True, text=True, env=_single_thread_env())
        if r.returncode != 0:
            raise RuntimeError(f"bench_kernels failed:\n{r.stderr[-2000:]}")
        for d in csv.DictReader(io.StringIO(r.stdout)):
            if d["pair"] not in merged:
                merged[d["pair"]] = d
                continue
            for k in TIMES:
                a, b = float(merged[d["pair"]][k]), float(d[k])
                if b < a:                               # (NaN stays NaN: no kernel of that kind)
                    merged[d["pair"]][k] = d[k]
    rows = []
    for d in merged.values():
        el, rest = next((e, d["pair"][len(e) + 1:]) for e in sorted(index["elements"], key=len, reverse=True)
                        if d["pair"].startswith(e + "_"))
        mat, integ = rest.rsplit("_", 1)
        h = header_ops(el, mat).get(integ, {})
        row = {"pair": d["pair"], "element": el, "material": mat, "integration": integ,
               "ndof": int(d["ndof"]), "nqp": int(d["nqp"]),
               "ops_force": int(d["ops_force"]), "ops_force_tangent": int(d["ops_force_tangent"]),
               "hdr_force": h.get("force"), "hdr_force_tangent": h.get("ft"),
               "hdr_force_per_point": h.get("force_pt", ""), "hdr_force_tangent_per_point": h.get("ft_pt", "")}
        for k in ("t_force_s", "t_force_tangent_s", "t_lanes_force_s", "t_lanes_force_tangent_s",
                  "t_plain_force_s", "t_plain_force_tangent_s", "plain_rel_diff_f", "plain_rel_diff_K",
                  "lanes_rel_diff"):
            row[k] = float(d[k])
        # t_force_s, t_force_tangent_s: per element as the solvers call the kernels (the lane
        # kernels where the pair has them); t_scalar_*: one element per call.
        row["lanes"] = math.isfinite(row["t_lanes_force_tangent_s"])
        row["t_scalar_force_s"], row["t_scalar_force_tangent_s"] = row["t_force_s"], row["t_force_tangent_s"]
        if row["lanes"]:
            row["t_force_s"], row["t_force_tangent_s"] = row["t_lanes_force_s"], row["t_lanes_force_tangent_s"]
        row["gflops_force"] = row["ops_force"] / row["t_force_s"] / 1e9
        row["gflops_force_tangent"] = row["ops_force_tangent"] / row["t_force_tangent_s"] / 1e9
        row["speedup_force"] = row["t_plain_force_s"] / row["t_force_s"]
        row["speedup_force_tangent"] = row["t_plain_force_tangent_s"] / row["t_force_tangent_s"]
        rows.append(row)
    return rows


def measured_peak(log=None):
    """One core's peak double-precision GFLOP/s, measured by bench/peak.c (FMA
    chains on 64-byte vectors) built with the kernels' release flags."""
    from gen.solver_build import BUILD, CC, KERNEL_FLAGS, WARN
    exe = BUILD / "release" / "bench" / "bench_peak"
    exe.parent.mkdir(parents=True, exist_ok=True)
    src = BENCH / "peak.c"
    if not exe.exists() or exe.stat().st_mtime < src.stat().st_mtime:
        flags = [f for f in KERNEL_FLAGS["release"] if f != "-fPIC"]
        subprocess.run([CC] + WARN + flags + [str(src), "-o", str(exe)], check=True, capture_output=True, text=True)
    r = subprocess.run([str(exe)], capture_output=True, text=True, env=_single_thread_env(), check=True)
    return float(r.stdout.strip().split(",")[1])


def _single_thread_env():
    import os
    env = dict(os.environ)
    env["OMP_NUM_THREADS"] = "1"
    return env


def cpu_peak():
    """(model, MHz, flags summary, double-precision flop/cycle/core, peak GFLOP/s per core)."""
    model, mhz, flags = "unknown", None, set()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            k, _, v = line.partition(":")
            k = k.strip()
            if k == "model name" and model == "unknown":
                model = v.strip()
            elif k == "cpu MHz" and mhz is None:
                mhz = float(v)
            elif k == "flags" and not flags:
                flags = set(v.split())
    except OSError:
        pass
    if "avx512f" in flags:
        fpc, isa = 32, "AVX-512 + FMA (2 x 8 doubles x 2)"
    elif "avx2" in flags and "fma" in flags:
        fpc, isa = 16, "AVX2 + FMA (2 units x 4 doubles x 2)"
    elif "avx" in flags:
        fpc, isa = 8, "AVX (4-wide add + 4-wide mul)"
    else:
        fpc, isa = 4, "SSE2 (2-wide add + 2-wide mul)"
    peak = fpc * (mhz or 0) / 1e3
    return {"model": model, "mhz": mhz, "isa": isa, "flops_per_cycle": fpc, "peak_gflops": peak}


if __name__ == "__main__":
    import sys
    rows = run(ROOT / "out" / "report" / "bench", repeats=3, target=0.002,
               only=set(sys.argv[1:]) or None, log=print)
    for r in rows:
        print(r["pair"], r["ops_force_tangent"], r["hdr_force_tangent"], f"{r['t_force_tangent_s']*1e6:.1f} us",
              f"plain {r['t_plain_force_tangent_s']*1e6:.1f} us", f"x{r['speedup_force_tangent']:.2f}",
              f"{r['gflops_force_tangent']:.2f} GF/s", r["plain_rel_diff_f"], r["plain_rel_diff_K"])
