"""The scene fuzzer (tests/fuzz_scenes.py): 300 mutants of the models/ scenes per run,
validated in process and, when accepted, solved by the AddressSanitizer + UBSan
solver.  No crash (Python exception, signal, sanitizer report, multi-line error),
no hang; every rejection is one line naming the file and the key."""
import pytest
from fuzz_scenes import fuzz
from util import BUILD, ensure_dir


@pytest.mark.slow
def test_fuzzed_scenes_never_crash():
    work = ensure_dir(BUILD / "fuzz")
    lines = []
    counts, problems = fuzz(300, seed=20261123, workdir=work, log=lines.append)
    print(f"fuzzer: tried 300: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    assert not problems, "\n\n".join(f"{o}: {p}\n{d}" for p, o, d in problems[:5])
    assert counts.get("rejected", 0) > 100 and counts.get("solved", 0) > 10, counts
