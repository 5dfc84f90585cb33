#!/usr/bin/env python3
"""Test runner: every function test_* in tests/test_*.py.

usage: tests/run.py [-k SUBSTRING] [-x]
Prints one line per test and, last, "N passed, N failed".  Exit status 1 if any failed.
"""
import importlib.util
import sys
import time
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))


def main(argv):
    pattern, stop = None, False
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "-k" and args:
            pattern = args.pop(0)
        elif a == "-x":
            stop = True
        else:
            print(f"usage: tests/run.py [-k SUBSTRING] [-x]", file=sys.stderr)
            return 2
    passed = failed = 0
    t_all = time.time()
    for path in sorted(HERE.glob("test_*.py")):
        spec = importlib.util.spec_from_file_location(path.stem, path)
        mod = importlib.util.module_from_spec(spec)
        try:
            spec.loader.exec_module(mod)
        except Exception:
            print(f"FAIL {path.name}: import error\n{traceback.format_exc()}", flush=True)
            failed += 1
            continue
        for name in [n for n in vars(mod) if n.startswith("test_") and callable(getattr(mod, n))]:
            full = f"{path.stem}.{name}"
            if pattern and pattern not in full:
                continue
            t0 = time.time()
            try:
                getattr(mod, name)()
                passed += 1
                print(f"PASS {full} ({time.time() - t0:.1f} s)", flush=True)
            except Exception as e:
                failed += 1
                detail = traceback.format_exc() if not isinstance(e, AssertionError) else \
                    "".join(traceback.format_exception_only(type(e), e))
                print(f"FAIL {full} ({time.time() - t0:.1f} s)\n{detail}", flush=True)
                if stop:
                    break
        if stop and failed:
            break
    print(f"total time {time.time() - t_all:.0f} s", flush=True)
    print(f"{passed} passed, {failed} failed", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
