"""The large arrays (runtime/base/bigalloc.c: the Newton matrix, the band
factors, the output's buffers) hold what malloc, calloc and realloc blocks
hold, under AddressSanitizer + UBSan; and in the release build, where the
kernel offers transparent huge pages (mode "always" or "madvise"), touched
blocks of 64 MiB are backed by them: the reason for the advice (a 10,000-element
static run took about 68,000 page faults without it).  So are small blocks once
the heap is advised (bk_big_heap)."""
from functools import lru_cache
import subprocess

import pytest

from util import build_runtime_program


@lru_cache(maxsize=None)
def harness(variant):
    return build_runtime_program(["bigalloc_check.c"], "bigalloc_check", variant)


def run(variant, mib, *more):
    r = subprocess.run([str(harness(variant)), str(mib), *more], capture_output=True, text=True, timeout=300)
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


def test_small_blocks_on_huge_pages_after_the_heap_is_advised():
    """bk_big_heap, first thing in the solver: glibc's heap from its next 2 MiB
    boundary advised (a small run's 200 fresh 4 kB pages cost 2 ms on a virtual
    machine).  1 MB of small blocks allocated after it hold what was written,
    and where the kernel offers transparent huge pages they lie where huge
    pages may back them (smaps THPeligible); under AddressSanitizer (not
    glibc's heap) it declines."""
    got = run("sanitize", 1, "heap")
    assert int(got["small_bad"]) == 0 and got["heap"] == "0", got
    got = run("release", 1, "heap")
    assert int(got["small_bad"]) == 0 and int(got["bad"]) == 0, got
    if got["thp"] not in ("always", "madvise"):
        pytest.skip(f"transparent huge pages are {got['thp']} on this machine")
    # the advice in effect where they lie, but for the first (it may begin below
    # the boundary); whether a whole page was free at the touch is the kernel's
    assert got["heap"] == "1" and int(got["small_eligible"]) >= 255, got
    # nothing of the advised range touched before the advice: a range with a
    # small page in it gets small pages only.  bk_big_heap's first version
    # advised from the boundary inside its probe block, whose allocation had
    # written the heap top's header past the block's end: inside the first
    # huge page's range in about every other process (where the heap starts
    # is random), so several fresh processes
    for _ in range(8):
        got = run("release", 1, "heap")
        assert got["advised_rss_kb"] == "0", got
