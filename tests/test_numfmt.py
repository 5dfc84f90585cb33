"""bk_fmt_g17 (runtime/base/numfmt.c), the CSV tables' "%.17g", and bk_fmt_e / bk_fmt_g,
their "%.Ne" / "%.Ng" (newton.csv, stability.csv, energy.csv): the same text as glibc's
snprintf (and strtod of the 17 digits gives the double back), checked by the C harness
tests/numfmt_check.c (AddressSanitizer + UBSan) over edge values, every exact
halfway case form, 2 x 10^6 random bit patterns and 10^6 CSV-like values; and
on values chosen here against Python's own correctly rounded formatting
(David Gay's dtoa, not glibc's printf).  (Speed: `numfmt_check --bench`.)"""
import math
import random
import struct
import subprocess
from fractions import Fraction
from functools import lru_cache

from util import build_runtime_program

NRANDOM, NNICE = 2_000_000, 1_000_000


@lru_cache(maxsize=None)
def harness():
    return build_runtime_program(["numfmt_check.c"], "numfmt_check", "sanitize")


def test_same_text_as_glibc_and_round_trip():
    """No mismatch with snprintf("%.17g") and no round-trip failure in any set (the
    allowed number of mismatches is zero); every set ran its full count."""
    r = subprocess.run([str(harness()), str(NRANDOM), str(NNICE)], capture_output=True, text=True,
                       timeout=600)
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    assert r.returncode == 0, f"numfmt_check failed ({r.returncode}):\n{r.stdout}\n{r.stderr[-4000:]}"
    sets = {}
    for line in r.stdout.splitlines():
        d = dict(kv.split("=", 1) for kv in line.split())
        name = d.pop("set")
        sets[name] = {k: int(v) for k, v in d.items()}
    for name, d in sets.items():
        assert d["mismatch"] == 0 and d["roundtrip"] == 0, (name, d)
    assert sets["random"]["n"] == NRANDOM
    assert sets["nice"]["n"] >= NNICE
    assert sets["halfway"]["n"] >= NNICE // 4
    assert sets["edge"]["n"] > 50_000


def _bits(v):
    return struct.unpack("<Q", struct.pack("<d", v))[0]


def _halfway_values(rng, n):
    """Doubles whose exact decimal has 18 significant digits, the last a 5."""
    out = []
    while len(out) < n:
        j = rng.randint(2, 26)
        lo, hi = -(-10**17 // 5**j), min((10**18 - 1) // 5**j, 2**53 - 1)
        if lo > hi:
            continue
        m = rng.randint(lo, hi) | 1
        if m > hi:
            continue
        v = math.ldexp(m, -j)
        assert Fraction(v) * 10**(j - 1) % 1 == Fraction(1, 2)      # 17 digits and a half
        out.append(v)
    return out


def test_same_text_as_python_formatting():
    """Values chosen here (halfway cases, carries such as 9.9999999999999999e22,
    the notation switches, short decimals, random bits) formatted by the
    harness against Python's '%.17g' and float()."""
    rng = random.Random(20240611)
    vals = [0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, 0.1, 1 / 3,
            2251799813685247.75, 1234567890123456.25, 0.5, 1e16, 1e17, 1e-4, 1e-5, 9.9999999999999999e22,
            float.fromhex("0x1.3de005bd620dfp+216"), float.fromhex("0x1.f92bacb3cb40cp+717")]
    vals += _halfway_values(rng, 20000)
    for k in range(-325, 309):
        for s in ("1e%d", "9.9999999999999999e%d", "9.99999999999999995e%d", "5e%d"):
            v = float(s % k)
            if math.isfinite(v):
                vals += [v, math.nextafter(v, 0), math.nextafter(v, math.inf)]
    vals += [float(f"{rng.randrange(10**rng.randint(1, 9))}e{rng.randint(-30, 30)}") for _ in range(20000)]
    vals += [struct.unpack("<d", struct.pack("<Q", rng.getrandbits(64)))[0] for _ in range(40000)]
    vals = [v for v in vals if math.isfinite(v)]
    vals += [-v for v in vals[:30000]]
    text = "".join("%016x\n" % _bits(v) for v in vals)
    r = subprocess.run([str(harness()), "--stdin"], input=text, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0 and "runtime error" not in r.stderr, r.stderr[-4000:]
    got = r.stdout.splitlines()
    assert len(got) == len(vals)
    bad = [(v.hex(), g, "%.17g" % v) for v, g in zip(vals, got) if g != "%.17g" % v or _bits(float(g)) != _bits(v)]
    assert not bad, f"{len(bad)} of {len(vals)} differ, e.g. {bad[:5]}"
    # the halfway cases go to even, as glibc and Python do
    assert got[8:10] == ["2251799813685247.8", "1234567890123456.2"]


def test_inf_and_nan_as_glibc_writes_them():
    specials = [0x7FF0000000000000, 0xFFF0000000000000, 0x7FF8000000000000, 0xFFF8000000000000, 0x7FF0000000000001]
    r = subprocess.run([str(harness()), "--stdin"], input="".join("%016x\n" % b for b in specials),
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr[-4000:]
    assert r.stdout.split() == ["inf", "-inf", "nan", "-nan", "nan"]
