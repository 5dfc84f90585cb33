"""python3 -m calculix SCENE [--set K=V ...] [--meshes 13x4x2,26x8x4,52x16x8] ...

Prints, per mesh, the sensors' final displacements, ccx's wall time and Newton
iterations, then the Richardson-extrapolated values with the observed order and
the error estimate, and the checks (--check-mesh, --check-dt) with the error
they add.  Dynamic scenes also write the sensor histories (per mesh and
extrapolated) as CSV, by default out/calculix/SCENE_SENSOR.csv.  --record NAME
stores the study in references/data/calculix_silicone.json (or --data PATH,
e.g. references/data/calculix_cantilever.json; calculix.data).
"""
import argparse
import json
import os
import shlex
import sys

from calculix.deck import DeckError
from calculix.run import CACHE, CcxError
from calculix.scene import SceneError
from calculix.study import check, parse_mesh, reference


def command_line(argv):
    """The command that reproduces a run, as stored with a recorded reference."""
    return "python3 -m calculix " + " ".join(shlex.quote(x) for x in argv)


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    prog = "beamkit calculix" if os.environ.get("BK_PROG") == "beamkit" else "./build.sh calculix"
    ap = argparse.ArgumentParser(prog=prog, description=__doc__.split("\n\n")[1], allow_abbrev=False)
    ap.add_argument("scene", help="a scene name in models/ or a .toml path")
    ap.add_argument("--set", dest="sets", action="append", default=[], metavar="KEY=VALUE",
                    help="override a scene value, as ./build.sh run --set")
    ap.add_argument("--meshes", help="comma-separated NXxNYxNZ meshes refined by one constant factor, counts "
                    "not refined held (default: the scene's default base mesh refined twice by 2)")
    ap.add_argument("--grading", default="", metavar="SPEC",
                    help="mesh grading, the same for every mesh: DIR=KIND:VALUE[:ZONE] items, DIR x (toward the "
                    "clamp), y, z (toward both faces), KIND geometric (VALUE: largest/smallest element) or power "
                    "(VALUE: exponent; ZONE: fraction of the elements graded, uniform beyond), "
                    "e.g. x=power:3:0.5,z=power:2 (default uniform)")
    ap.add_argument("--levels", type=int, default=3, help="number of default meshes (2 or 3)")
    ap.add_argument("--order", type=float, help="assumed convergence order with two meshes")
    ap.add_argument("--increments", type=int,
                    help="static: first load increment 1/N (default: static.load_steps; ccx grows or cuts it)")
    ap.add_argument("--threads", type=int, default=1, help="ccx threads (OMP_NUM_THREADS), default 1")
    ap.add_argument("--check-mesh", action="append", default=[], metavar="MESH",
                    help="also run MESH and compare it with the study's mesh of the same axial count (a "
                    "cross-refinement of a held direction); adds its two-run GCI (order 2) to the error")
    ap.add_argument("--check-dt", metavar="MESH",
                    help="dynamic: also run MESH (one of the study's) with dynamic.dt halved; adds the two-run "
                    "GCI (order 2, HHT) to the error")
    ap.add_argument("--record", metavar="NAME",
                    help="store the study, its checks and this command in references/data/calculix_silicone.json")
    ap.add_argument("--note", default="", help="with --record: a remark stored with the entry")
    ap.add_argument("--data", metavar="PATH",
                    help="with --record: the data file (default references/data/calculix_silicone.json; "
                    "the seed cantilever's: references/data/calculix_cantilever.json)")
    ap.add_argument("--csv", help="history CSV path (dynamic; one sensor) ")
    ap.add_argument("--json", action="store_true", help="print the study as JSON")
    a = ap.parse_args(argv)
    log = lambda s: print(s, file=sys.stderr, flush=True)   # noqa: E731
    try:
        meshes = [parse_mesh(m) for m in a.meshes.split(",")] if a.meshes else None
        st = reference(a.scene, a.sets, meshes=meshes, levels=a.levels, order=a.order,
                       increments=a.increments, threads=a.threads, grading=a.grading, log=log)
        checks = [check(st, other_mesh=parse_mesh(m), increments=a.increments, threads=a.threads, log=log)
                  for m in a.check_mesh]
        if a.check_dt:
            if st.problem.analysis != "dynamic":
                raise ValueError("--check-dt: the scene is static")
            checks.append(check(st, base_mesh=parse_mesh(a.check_dt),
                                extra_sets=[f"dynamic.dt={st.problem.dt / 2!r}"], log=log, threads=a.threads,
                                label=f"{a.check_dt}: dt {st.problem.dt:g} -> {st.problem.dt / 2:g} s"))
    except (SceneError, DeckError) as e:
        print(str(e) if str(e).startswith("error:") else f"error: {e}", file=sys.stderr)
        return 1
    except (CcxError, ValueError, RuntimeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    p = st.problem
    if a.json:
        print(json.dumps(st.as_dict(), indent=1))
    else:
        print(f"CalculiX C3D20R reference: {p.path} ({p.analysis}, law {p.material.law}, "
              f"clamp {', '.join(f'{s} {m}' for s, m in p.clamps)}, grading {st.grading.spec() or 'uniform'}, "
              f"refined {st.refined})")
        t_label = "t = 1 (load factor)" if p.analysis == "static" else f"t = {p.t_end:g} s"
        for name, _ in p.sensors:
            print(f"sensor {name}: displacement at {t_label}, m")
            print(f"  {'mesh':>12} {'elements':>8} {'nodes':>7} {'ccx s':>8} {'iter':>6} "
                  f"{'ux':>14} {'uy':>14} {'uz':>14}")
            for r in st.runs:
                u = r.histories[name][-1][1]
                print(f"  {r.label:>12} {r.elements:>8} {r.nodes:>7} {r.wall_s:>8.1f} {r.iterations:>6} "
                      + " ".join(f"{x:>14.7e}" for x in u))
            ex = st.tip[name]
            blank = f"{'':>8} {'':>7} {'':>8} {'':>6}"
            print(f"  {'extrapolated':>12} {blank} " + " ".join(f"{e.value:>14.7e}" for e in ex))
            print(f"  {'error est.':>12} {blank} " + " ".join(f"{e.error:>14.2e}" for e in ex))
            print(f"  {'order':>12} {blank} " + " ".join(
                f"{e.order:>14.2f}" if e.order is not None else
                (f"{'assumed ' + format(e.assumed_order, 'g'):>14}" if e.assumed_order else f"{'-':>14}") for e in ex))
            notes = sorted({e.note for e in ex})
            print("  (" + "; ".join(notes) + ")")
        for c in checks:
            d, mx = c.final_diff, c.max_diff()
            print(f"check {c.label}: final difference " + " ".join(f"{x:.2e}" for x in d)
                  + ", largest over the history " + " ".join(f"{x:.2e}" for x in mx)
                  + f"; adds {c.factor:.3g} x |difference| (ccx {c.base.wall_s:.0f} s, {c.other.wall_s:.0f} s)")
    if p.analysis == "dynamic":
        for name, _ in p.sensors:
            path = a.csv if (a.csv and len(p.sensors) == 1) else CACHE / f"{p.name}_{name}.csv"
            st.write_history_csv(path, name)
            print(f"history of sensor {name}: {path}", file=sys.stderr)
    if a.record:
        from calculix.data import entry, record
        sensor = p.sensors[0][0]
        kw = {"path": a.data} if a.data else {}
        path = record(a.record, entry(st, sensor, command_line(argv), checks, note=a.note), **kw)
        print(f"recorded {a.record} in {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
