"""The model reader's integers (runtime/model/reader.c: its own decimal
parser, in place of strtol's locale and base handling) accept exactly the
tokens the C library's strtol(t, &end, 10) reads whole within the asked
range, with the same values: 2,000,000 random tokens (long digit strings,
signs, leading zeros, tokens strtol reads in part or not at all) read by
rd_inum and by strtol in the harness tests/reader_int_check.c, under
AddressSanitizer + UBSan."""
import subprocess

from util import build_runtime_program


def test_integers_as_strtol_reads_them():
    exe = build_runtime_program(["reader_int_check.c"], "reader_int_check", "sanitize")
    r = subprocess.run([str(exe), "2000000", "20261206"], capture_output=True, text=True, timeout=600)
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    assert r.returncode == 0, (r.stdout, r.stderr[-4000:])
    got = dict(kv.split("=") for kv in r.stdout.split())
    assert int(got["differ"]) == 0, (got, r.stderr[-2000:])
    # both kinds were tried: a good share accepted, a good share refused
    assert 0.2 * 2000000 < int(got["accepted"]) < 0.8 * 2000000, got
