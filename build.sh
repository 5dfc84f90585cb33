#!/bin/sh
# build.sh -- the one entry point of the project.  ./build.sh --help lists the commands.
# Its first lines are POSIX sh, so that a repeated `run` starts out/bin/run-cached
# from /bin/sh (Debian's dash starts in 0.75 ms, bash in 1.6 ms: a quarter of the
# whole command); everything else is bash, started below on this same file.
set -eu

# Paths on the command line (scene files, --out, plot RUN_DIR) are the caller's:
# gen/cli.py resolves them against this directory.
export BK_CALLER_CWD="${BK_CALLER_CWD:-$PWD}"
# The repository: this script's directory, found without a subshell or dirname
# (a process each: 10 ms of a 50 ms `run` on a virtual machine where a fork is slow).
case "$0" in
    */*) cd "${0%/*}" ;;
esac
ROOT="$PWD"
# `run` first: a repeated run is started by out/bin/run-cached (frontend/,
# built on the first `run` below, and again when this script is newer) before
# the rest of this script is read.  It checks that it is newer than its sources
# itself (in C: the same 19 tests here took 0.4 ms) and, when it is not, comes
# back with BK_RUN_CACHED_STALE=1 to be rebuilt below.
if [ "${1:-}" = run ] && [ $# -gt 1 ] && [ -z "${BK_NO_FAST_RUN:-}${BK_RUN_CACHED_STALE:-}" ] && \
    [ out/bin/run-cached -nt build.sh ] && [ -x out/bin/run-cached ]; then
    shift
    BK_ROOT="$ROOT" exec out/bin/run-cached "$@"
fi
# The rest in bash.
if [ -z "${BASH_VERSION:-}" ]; then
    exec /bin/bash "$ROOT/build.sh" "$@"
fi
set -o pipefail
PY=/usr/bin/python3
export PYTHONPATH="$ROOT${PYTHONPATH:+:$PYTHONPATH}"
# Bytecode of gen/, calculix/, report/ (and of the standard library modules they
# import) is cached under out/pycache, outside the source tree: a run of a built
# scene imports the scene compiler in ~40 ms instead of compiling it each time.
unset PYTHONDONTWRITEBYTECODE
export PYTHONPYCACHEPREFIX="$ROOT/out/pycache"
DEFAULT_SCENE=cantilever_bend_100N

# Debian packages the project needs (build, generator, tests, plots).
PACKAGES=(gcc libc6-dev binutils python3 python3-sympy python3-numpy python3-scipy python3-matplotlib
          python3-pytest python3-pytest-xdist libsuitesparse-dev libgsl-dev valgrind paraview calculix-ccx
          python3-dask python3-distributed liblapack-dev libhdf5-dev python3-h5py)
EX_USAGE=64

usage() {
    # (the same text as `beamkit --help`, bin/beamkit, with its own name)
    if [ "${BK_PROG:-}" = beamkit ]; then
        usage_text | sed -e 's|^usage: \./build\.sh \[COMMAND\]|usage: beamkit COMMAND|' \
                         -e 's|^From any directory: bin/beamkit COMMAND \.\.\. is \./build\.sh COMMAND \.\.\.|beamkit COMMAND ... runs the repository'"'"'s build.sh COMMAND ...|' \
                         -e 's|^  (none)   |  setup    |' -e 's|\./build\.sh|beamkit|g'
    else
        usage_text
    fi
}

usage_text() {
    cat <<'EOF'
usage: ./build.sh [COMMAND] [ARGS...]

Commands:
  (none)                 install missing Debian packages, regenerate the kernels,
                         build and run the default scene and print its summary
  test [PYTEST ARGS]     run every test with pytest on both cores; the last line is
                         pytest's summary ("N passed, N failed in ...").  Options go
                         to pytest: -k EXPR (tests whose name matches, e.g.
                         -k "cantilever and not full"), -m "not slow" (skip the slow
                         tests), -x (stop at the first failure), -n 1 (one worker);
                         a test file or node id (tests/test_weld.py,
                         tests/test_weld.py::test_x) runs just those
  run SCENE [options]    build the per-scene solver if stale and run it; SCENE is a
                         name in models/ or a path to a .toml file
      --set KEY=VALUE      override a scene value: a number, true/false, a string
                           where the scene has one, a TOML [array] or {table}
                           (repeatable), e.g. --set material.alu.E=3e7
                           --set beam.arm.elements=20 --set beam.arm.element=gef
      --out DIR            results directory (default out/runs/SCENE)
      --threads N          OpenMP threads of the element evaluation (default:
                           every core; models below 256 elements run on one;
                           the results are the same bits for any N)
      --verbose            log every load step;  --quiet  print only errors
      --sanitize           build and run with AddressSanitizer + UBSan
      --memcheck           build for valgrind (-march=x86-64-v3) and run under
                           valgrind memcheck
  sweep SCENE [options]  every combination of scene values, each run its own solver
                         process on a Dask cluster: OUT/sweep.csv (one row per run:
                         the values, converged, wall_s, outputs, error), OUT/runs/,
                         OUT/sweep_KEY.png; OUT defaults to out/sweeps/SCENE; a
                         sweep run again skips the runs already done
      --grid KEY=v1,v2,...   values of a key (repeatable: every combination)
      --random KEY=lo:hi     uniform draws (with --samples N [--seed S])
      --set KEY=VALUE        in every run;  --out DIR;  --quiet
      --output OUT           a column: SENSOR.ux (.uy .uz .x .y .z), steps,
                             newton_iterations, strain_energy, frequency.N, ...;
                             over time: NAME.FIELD:STAT[@T0:T1], STAT peak max
                             min amplitude rms mean (e.g. joint.effort:peak)
      --plot OUT             the output drawn against each key (default the first)
      --scheduler tcp://HOST:PORT  an existing Dask cluster (or its
                             --scheduler-file, or DASK_SCHEDULER_ADDRESS);
                             default a local cluster
      --workers N            local workers (default: the cores);  --threads N
                             OpenMP threads per solver (default 1);  --vtk
  fit SCENE --data MEASURED.csv --param KEY=lo:hi[:start] ... [options]
                         least squares of a sensor history against measured points
                         (CSV: t or load_factor, and x,y,z or ux,uy,uz; empty cells
                         missing): fitted values, standard errors, residual and
                         OUT/fit.png (default OUT out/fit/SCENE); refuses a
                         parameter the data cannot identify.  --sensor NAME,
                         --diff-step H, --max-runs N, and --set, --out,
                         --scheduler, --workers, --threads, --quiet as for sweep
  gen [--check] [--force]  regenerate out/kernels/ (incremental by input hash);
                         --check fails if the committed kernels are stale
  plot RUN_DIR           PNG plots of a run: sensors.png, energy.png (dynamic),
                         modes.png (modal: a panel per mode shape), beam.png
                         (the last ParaView frame drawn in 3-D), joints.png and
                         reactions.png (joint angles, efforts, reactions) and path.png
                         (arc-length runs: load factor against displacement,
                         critical points marked)
  animate RUN_DIR [options]  the run's ParaView frames as a video drawn offscreen:
                         RUN_DIR/animation.mp4 (ffmpeg, installed when missing),
                         coloured by a field, the sensors' paths, a scale bar,
                         scene name and time.  --field NAME (default
                         displacement; e.g. strain_energy_density), --gif,
                         --fps N (default 10), --out FILE
  scenes                 list the scenes in models/ with their descriptions
  report [--quick]       the seed cantilever tables beside the paper's, the
                         verification matrix (continuum elements x laws x
                         compressibility vs beam theory and CalculiX) and the
                         pendulums / falling silicone:
                         out/report/{seed_tables,verification,pendulum}.md
  hard [--quick]         numerical stability on hard cases (buckling, two-turn
                         roll-up, torsion, stiff pendulums, incompressibility,
                         slenderness, long runs) per element: out/report/hard.md
                         (+ hard_*.csv, hard_rollup_newton.png)
  calculix SCENE [options]  the CalculiX reference of a straight-beam scene: the
                         scene as a C3D20R solid (calculix-ccx) on 2-3 meshes,
                         the sensors' displacements Richardson-extrapolated with
                         an error estimate; --meshes NXxNYxNZ,..., --json, --set
                         (calculix --help lists them; docs/howto/verify-calculix.md)
  deps                   only install missing Debian packages
  bench [--quick]        the speed-against-error report: work-precision diagrams,
                         kernel timings, scaling, toolchain times, in
                         out/report/bench.md (+ bench_*.csv, bench_*.png);
                         about 6 minutes on 2 cores, --quick about 1 minute
  --help                 this text

Results of a run: out/runs/SCENE/summary.json and sensors.csv (see docs/reference/outputs.md).
From any directory: bin/beamkit COMMAND ... is ./build.sh COMMAND ... (put the
repository's bin/ on PATH to type `beamkit`; it runs /usr/bin/python3 whatever
python3 comes first on PATH).
Relative paths (SCENE files, --out DIR, RUN_DIR) are taken from the directory
you call build.sh from.

Exit status:
  0    success
  1    bad input (scene file, key, value; output directory): one "error:" line
  2    the solve did not converge (results of the converged steps are kept);
       sweep: sweep.csv is written but some runs failed; fit: a run failed or
       the optimizer stopped before converging
  3    run with BK_RUN_CACHED_ONLY=1: the run needs Python (the reason on stderr)
  64   usage error (unknown command or option, missing argument)
  99   run --memcheck: valgrind found an error or a leak
  130  interrupted by Ctrl-C (SIGINT), 143 by SIGTERM: results so far are kept,
       summary.json has "interrupted": true (sweep: the finished runs are kept)
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

# install_deps once: the commands that need the Debian packages but run often
# (run, gen, scenes, ...) check a stamp (out/.deps-installed: the package
# list it was made for) instead of asking dpkg each time; a fresh clone or a
# changed list installs what is missing first.
DEPS_STAMP="$ROOT/out/.deps-installed"
ensure_deps() {      # (--always: ask dpkg whatever the stamp says)
    local want="${PACKAGES[*]}" have=
    [ -f "$DEPS_STAMP" ] && read -r have < "$DEPS_STAMP"
    if [ "$have" = "$want" ] && [ "${1:-}" != --always ]; then
        # (renewed when build.sh is newer: out/bin/run-cached starts Python
        # itself only with a stamp no older than build.sh)
        [ "$DEPS_STAMP" -nt "$ROOT/build.sh" ] || touch "$DEPS_STAMP"
        return 0
    fi
    install_deps
    mkdir -p "${DEPS_STAMP%/*}"
    printf '%s\n' "$want" > "$DEPS_STAMP"
}

# The launcher of repeated runs (frontend/run_cached.c), built on first use;
# when it cannot be built, runs take the Python front end (same results).
build_run_cached() {
    local exe="$1" tmp="$1.$$.tmp" f stale=
    for f in "$ROOT"/frontend/*.[ch] "$ROOT/build.sh"; do
        [ "$exe" -nt "$f" ] || stale=1
    done
    [ -z "$stale" ] && return 0
    mkdir -p "${exe%/*}"
    # (static: no dynamic loader at start, ~1 ms of a repeated run)
    if gcc -O2 -std=c11 -Wall -Wextra -static "$ROOT"/frontend/*.c -o "$tmp" 2>/dev/null \
        || gcc -O2 -std=c11 -Wall -Wextra "$ROOT"/frontend/*.c -o "$tmp" 2>/dev/null; then
        mv -f "$tmp" "$exe"
    else
        rm -f "$tmp"
        return 1
    fi
}

cmd="${1:-}"
case "$cmd" in
    "")
        ensure_deps --always
        "$PY" -m gen.cli gen
        "$PY" -m gen.cli run "$DEFAULT_SCENE"
        case ":$PATH:" in
            *":$ROOT/bin:"*) ;;
            *) echo "tip: export PATH=\"$ROOT/bin:\$PATH\" to run 'beamkit COMMAND' from anywhere" >&2 ;;
        esac
        ;;
    -h|--help|help)
        usage
        ;;
    deps)
        ensure_deps --always
        echo "deps: the ${#PACKAGES[@]} Debian packages of build.sh are installed"
        ;;
    test)
        shift
        ensure_deps --always
        # pytest (Debian's python3-pytest) with python3-pytest-xdist on both
        # cores; tests/pytest.ini holds the options and markers.
        # A test file or node id (tests/test_weld.py, ...::test_x; from the
        # caller's directory) runs just those; otherwise the whole tests/ folder.
        workers=(-n "${BK_TEST_WORKERS:-2}")
        args=() where=("$ROOT/tests") value=0
        for a in "$@"; do
            case "$a" in -n|-n*|--numprocesses*) workers=() ;; esac
            if [ "$value" = 0 ] && [ "${a#-}" = "$a" ]; then
                f="${a%%::*}"
                case "$f" in /*) ;; *) [ -e "$BK_CALLER_CWD/$f" ] && a="$BK_CALLER_CWD/$a" ;; esac
                [ -e "${a%%::*}" ] && where=()
            fi
            case "$a" in -k|-m|-n|-p|-o|-c|-W|--durations|--maxfail|--deselect|--ignore|--rootdir) value=1 ;; *) value=0 ;; esac
            args+=("$a")
        done
        set +e
        "$PY" -m pytest -c "$ROOT/tests/pytest.ini" --rootdir "$ROOT/tests" "${workers[@]}" "${args[@]}" "${where[@]}"
        rc=$?
        set -e
        if [ "$rc" -eq 5 ]; then
            echo "error: no test was collected or selected (check -k / -m)" >&2
            exit 1
        fi
        exit "$rc"
        ;;
    run)
        shift
        if [ $# -eq 0 ]; then
            echo "error: run needs a SCENE (./build.sh scenes lists them)" >&2
            exit $EX_USAGE
        fi
        # An identical earlier run (same scene bytes, --set values, generator,
        # runtime and kernels) is run by out/bin/run-cached (frontend/) without
        # starting Python (see the top of this script); anything else it hands
        # back here with BK_NO_FAST_RUN=1.  Built here when missing or stale.
        unset BK_RUN_CACHED_STALE        # (set until here: bash reads the lines above too)
        if [ -z "${BK_NO_FAST_RUN:-}" ] && build_run_cached "$ROOT/out/bin/run-cached"; then
            # (checked just now: it need not check again, nor, with a source
            # dated in the future, come back here for ever)
            BK_ROOT="$ROOT" BK_RUN_CACHED_CHECKED=1 exec "$ROOT/out/bin/run-cached" "$@"
        fi
        ensure_deps
        # gen/cli.py (an identical earlier run is reused without the scene
        # compiler); -S: no site packages (the run path needs none), frozen
        # modules: the interpreter's own start-up modules from its binary (1.5 ms
        # of a 10 ms start here); gen.cli imported, not run as a script, so that
        # its bytecode comes from out/pycache (a script is compiled at every start: 2-7 ms).
        # frontend/python_start.c starts the same command itself once
        # the package stamp is current: keep the two in step
        exec "$PY" -S -X frozen_modules=on -c 'import sys; from gen.cli import run_command; run_command(sys.argv[1:])' \
            run "$@"
        ;;
    gen)
        shift
        ensure_deps
        exec "$PY" -m gen.cli gen "$@"
        ;;
    sweep|fit)
        ensure_deps
        exec "$PY" -m beamkit.cli "$@"
        ;;
    scenes)
        ensure_deps
        exec "$PY" -m gen.cli scenes
        ;;
    plot)
        shift
        ensure_deps
        exec "$PY" -m report.plot "$@"
        ;;
    animate)
        shift
        case " $* " in
            *" --gif "*|*" -h "*|*" --help "*) ;;
            *) PACKAGES=(ffmpeg); install_deps ;;      # (MP4: only this command needs it)
        esac
        exec "$PY" -m report.animate "$@"
        ;;
    hard)
        shift
        ensure_deps
        exec "$PY" -m report.hard "$@"
        ;;
    calculix)
        # (paths on its command line are the caller's: run from there)
        shift
        ensure_deps
        cd "$BK_CALLER_CWD"
        exec "$PY" -m calculix "$@"
        ;;
    report)
        shift
        ensure_deps
        "$PY" -m report.seed_tables "$@"
        "$PY" -m report.verification "$@"
        exec "$PY" -m report.dynamics "$@"
        ;;
    bench)
        shift
        ensure_deps --always
        "$PY" -m gen.cli gen
        exec "$PY" -m report.bench "$@"
        ;;
    *)
        echo "error: unknown command '$cmd' (${BK_PROG:-./build.sh} --help lists the commands)" >&2
        exit $EX_USAGE
        ;;
esac
