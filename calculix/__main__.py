"""python3 -m calculix SCENE [--set K=V ...] [--meshes 13x4x2,26x8x4,52x16x8] ...

Prints, per mesh, the sensors' final displacements and ccx's wall time, then the
Richardson-extrapolated values with the observed order and the error estimate.
Dynamic scenes also write the sensor histories (per mesh and extrapolated) as
CSV, by default out/calculix/SCENE_SENSOR.csv.
"""
import argparse
import json
import sys

from calculix.deck import DeckError
from calculix.run import CACHE, CcxError
from calculix.scene import SceneError
from calculix.study import parse_mesh, reference


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m calculix", description=__doc__.split("\n\n")[1])
    ap.add_argument("scene", help="a scene name in models/ or a .toml path")
    ap.add_argument("--set", dest="sets", action="append", default=[], metavar="KEY=VALUE",
                    help="override a scene value, as ./build.sh run --set")
    ap.add_argument("--meshes", help="comma-separated NXxNYxNZ meshes refined by one constant factor "
                    "(default: the scene's default base mesh refined twice by 2)")
    ap.add_argument("--levels", type=int, default=3, help="number of default meshes (2 or 3)")
    ap.add_argument("--order", type=float, help="assumed convergence order with two meshes")
    ap.add_argument("--increments", type=int, help="static increments (default: static.load_steps)")
    ap.add_argument("--threads", type=int, default=1, help="ccx threads (OMP_NUM_THREADS), default 1")
    ap.add_argument("--csv", help="history CSV path (dynamic; one sensor) ")
    ap.add_argument("--json", action="store_true", help="print the study as JSON")
    a = ap.parse_args(argv)
    try:
        meshes = [parse_mesh(m) for m in a.meshes.split(",")] if a.meshes else None
        st = reference(a.scene, a.sets, meshes=meshes, levels=a.levels, order=a.order,
                       increments=a.increments, threads=a.threads,
                       log=lambda s: print(s, file=sys.stderr, flush=True))
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
              f"clamp {', '.join(f'{s} {m}' for s, m in p.clamps)})")
        t_label = "t = 1 (load factor)" if p.analysis == "static" else f"t = {p.t_end:g} s"
        for name, _ in p.sensors:
            print(f"sensor {name}: displacement at {t_label}, m")
            print(f"  {'mesh':>12} {'elements':>8} {'nodes':>7} {'ccx s':>8} {'ux':>14} {'uy':>14} {'uz':>14}")
            for r in st.runs:
                u = r.histories[name][-1][1]
                print(f"  {r.label:>12} {r.elements:>8} {r.nodes:>7} {r.wall_s:>8.1f} "
                      + " ".join(f"{x:>14.7e}" for x in u))
            ex = st.tip[name]
            print(f"  {'extrapolated':>12} {'':>8} {'':>7} {'':>8} " + " ".join(f"{e.value:>14.7e}" for e in ex))
            print(f"  {'error est.':>12} {'':>8} {'':>7} {'':>8} " + " ".join(f"{e.error:>14.2e}" for e in ex))
            print(f"  {'order':>12} {'':>8} {'':>7} {'':>8} " + " ".join(
                f"{e.order:>14.2f}" if e.order is not None else
                (f"{'assumed ' + format(e.assumed_order, 'g'):>14}" if e.assumed_order else f"{'-':>14}") for e in ex))
            notes = sorted({e.note for e in ex})
            print("  (" + "; ".join(notes) + ")")
    if p.analysis == "dynamic":
        for name, _ in p.sensors:
            path = a.csv if (a.csv and len(p.sensors) == 1) else CACHE / f"{p.name}_{name}.csv"
            st.write_history_csv(path, name)
            print(f"history of sensor {name}: {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
