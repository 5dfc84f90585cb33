"""The large arrays (runtime/base/bigalloc.c: the Newton matrix, the band
factors, the output's buffers) hold what malloc, calloc and realloc blocks
hold, under AddressSanitizer + UBSan; and in the release build, where the
kernel offers transparent huge pages (mode "always" or "madvise"), touched
blocks of 64 MiB are backed by them: the reason for the advice (a 10,000-element
static run took about 68,000 page faults without it)."""
from functools import lru_cache
import subprocess

import pytest

from util import build_runtime_program


@lru_cache(maxsize=None)
def harness(variant):
    return build_runtime_program(["bigalloc_check.c"], "bigalloc_check", variant)


def run(variant, mib):
    r = subprocess.run([str(harness(variant)), str(mib)], capture_output=True, text=True, timeout=300)
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    assert r.returncode == 0, (r.stdout, r.stderr[-4000:])
    return dict(kv.split("=") for kv in r.stdout.split())


def test_blocks_hold_what_is_written():
    got = run("sanitize", 16)
    assert int(got["bad"]) == 0, got


def test_touched_blocks_on_huge_pages():
    got = run("release", 64)
    assert int(got["bad"]) == 0, got
    if got["thp"] not in ("always", "madvise"):
        pytest.skip(f"transparent huge pages are {got['thp']} on this machine")
    # three blocks of 64 MiB: all but the partial 2 MiB pages at their ends (and
    # what the kernel could not find whole pages for) on huge pages
    assert int(got["huge_kb"]) >= 3 * 48 * 1024, got
