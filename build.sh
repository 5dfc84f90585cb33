#!/usr/bin/env bash
# build.sh -- the one entry point of the project.  ./build.sh --help lists the commands.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$ROOT"
PY=/usr/bin/python3
export PYTHONPATH="$ROOT${PYTHONPATH:+:$PYTHONPATH}"
export PYTHONDONTWRITEBYTECODE=1
DEFAULT_SCENE=cantilever_bend_100N

# Debian packages the project needs (build, generator, tests, plots).
PACKAGES=(gcc libc6-dev python3 python3-sympy python3-numpy python3-matplotlib
          libsuitesparse-dev libgsl-dev valgrind calculix-ccx)

usage() {
    cat <<'EOF'
usage: ./build.sh [COMMAND] [ARGS...]

Commands:
  (none)                 install missing Debian packages, regenerate the kernels,
                         build and run the default scene and print its summary
  test                   run every test; the last line is "N passed, N failed"
  run SCENE [options]    build the per-scene solver if stale and run it; SCENE is a
                         name in models/ or a path to a .toml file
      --set KEY=VALUE      override a numeric scene value (repeatable), e.g.
                           --set material.alu.E=3e7 --set beam.arm.elements=20
      --out DIR            results directory (default out/runs/SCENE)
      --verbose            log every load step;  --quiet  print only errors
      --sanitize           build and run with AddressSanitizer + UBSan
  gen [--check] [--force]  regenerate out/kernels/ (incremental by input hash);
                         --check fails if the committed kernels are stale
  plot RUN_DIR           PNG plots of a run: sensors.png, energy.png (dynamic) and
                         beam.png (the last ParaView frame drawn in 3-D)
  scenes                 list the scenes in models/
  report [--quick]       the seed cantilever tables beside the paper's, the nearly
                         incompressible cantilever and the pendulums / falling
                         silicone: out/report/{seed_tables,incompressible,pendulum}.md
  hard [--quick]         numerical stability on hard cases (buckling, two-turn
                         roll-up, torsion, stiff pendulums, incompressibility,
                         slenderness, long runs) per element: out/report/hard.md
                         (+ hard_*.csv, hard_rollup_newton.png)
  deps                   only install missing Debian packages
  bench [--quick]        the speed-against-error report: work-precision diagrams,
                         kernel timings, scaling, toolchain times, in
                         out/report/bench.md (+ bench_*.csv, bench_*.png);
                         about 10 minutes on 2 cores, --quick about 1 minute
  --help                 this text

Results of a run: out/runs/SCENE/summary.json and sensors.csv (see README.md).
EOF
}

install_deps() {
    local missing=()
    for p in "${PACKAGES[@]}"; do
        if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
            missing+=("$p")
        fi
    done
    if [ ${#missing[@]} -eq 0 ]; then
        return 0
    fi
    echo "installing Debian packages: ${missing[*]}" >&2
    if [ "$(id -u)" -ne 0 ]; then
        echo "error: packages missing (${missing[*]}) and not running as root: install them with apt-get" >&2
        exit 1
    fi
    export DEBIAN_FRONTEND=noninteractive
    if ! apt-get install -y -q "${missing[@]}" >&2; then
        apt-get update -q >&2
        apt-get install -y -q "${missing[@]}" >&2
    fi
}

cmd="${1:-}"
case "$cmd" in
    "")
        install_deps
        "$PY" -m gen.cli gen
        "$PY" -m gen.cli run "$DEFAULT_SCENE"
        ;;
    -h|--help|help)
        usage
        ;;
    deps)
        install_deps
        ;;
    test)
        shift
        install_deps
        exec "$PY" "$ROOT/tests/run.py" "$@"
        ;;
    run)
        shift
        if [ $# -eq 0 ]; then
            echo "error: run needs a SCENE (./build.sh scenes lists them)" >&2
            exit 1
        fi
        exec "$PY" -m gen.cli run "$@"
        ;;
    gen)
        shift
        exec "$PY" -m gen.cli gen "$@"
        ;;
    scenes)
        exec "$PY" -m gen.cli scenes
        ;;
    plot)
        shift
        exec "$PY" -m report.plot "$@"
        ;;
    hard)
        shift
        exec "$PY" -m report.hard "$@"
        ;;
    report)
        shift
        "$PY" -m report.seed_tables "$@"
        "$PY" -m report.incompressible "$@"
        exec "$PY" -m report.dynamics "$@"
        ;;
    bench)
        shift
        install_deps
        "$PY" -m gen.cli gen
        exec "$PY" -m report.bench "$@"
        ;;
    *)
        echo "error: unknown command '$cmd' (./build.sh --help lists the commands)" >&2
        exit 1
        ;;
esac
