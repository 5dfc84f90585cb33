"""Binaries run under valgrind are built for an instruction set valgrind decodes.

valgrind 3.19 cannot decode AVX-512, which gcc emits for -march=native on CPUs
that have it (Intel Xeon with avx512f ... avx512_fp16): the suite was red there
and green on an AMD EPYC.  The `memcheck` build (gen/solver_build.py) is limited
to x86-64-v3; every valgrind run goes through `./build.sh run --memcheck`."""
import re
import subprocess
from pathlib import Path

from util import ROOT


def test_memcheck_variant_flags_are_not_native():
    from gen.solver_build import KERNEL_FLAGS, MEMCHECK_ARCH, VARIANTS
    assert MEMCHECK_ARCH == "-march=x86-64-v3"
    for table in (VARIANTS, KERNEL_FLAGS):
        flags = table["memcheck"]
        assert MEMCHECK_ARCH in flags, flags
        assert not any(f.startswith(("-march=native", "-mtune=native", "-mavx512")) for f in flags), flags


def test_valgrind_is_only_started_through_the_memcheck_build():
    """No test, report or tool starts valgrind on its own (it would pick the release
    build, -march=native): the only valgrind command line is gen/pipeline.py's."""
    offenders = []
    for path in list((ROOT / "tests").glob("*.py")) + list((ROOT / "report").glob("*.py")) + \
            list((ROOT / "gen").rglob("*.py")) + [ROOT / "build.sh"]:
        if path.name == Path(__file__).name:
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            if re.search(r"""["']valgrind["']\s*,""", line) or re.search(r"^\s*(exec\s+)?valgrind\s+-", line):
                if path != ROOT / "gen" / "pipeline.py":
                    offenders.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not offenders, "valgrind started outside run --memcheck:\n" + "\n".join(offenders)


def test_memcheck_solver_has_no_avx512_instructions():
    """The linked memcheck solver and every object in it: built with x86-64-v3 (flag
    stamps) and free of AVX-512 registers (zmm, opmask k0-k7) in the disassembly."""
    from gen.cache import solver
    from gen.scene import build
    model = build(ROOT / "models" / "cantilever_bend_10N.toml")
    exe = solver(model["pairs"], "memcheck")
    stamps = list((ROOT / "out" / "build" / "memcheck").rglob("*.o.flags"))
    assert stamps
    for st in stamps:
        text = st.read_text()
        assert "-march=x86-64-v3" in text and "native" not in text, (st, text)
    dis = subprocess.run(["objdump", "-d", "--no-show-raw-insn", str(exe)], capture_output=True, text=True,
                         check=True).stdout
    bad = [l for l in dis.splitlines() if re.search(r"%zmm\d|%k[0-7]\b|\{%k[0-7]\}", l)]
    assert not bad, f"{len(bad)} AVX-512 instructions in {exe}, e.g.\n" + "\n".join(bad[:5])
    assert re.search(r"%ymm\d", dis), "expected AVX2 code (x86-64-v3) in the memcheck build"
