"""The generated beam-to-beam distance kernels (gen/contact_pairs.py ->
out/kernels/contact_pairs.c): point-point, point-edge and edge-edge distances
and the squared cosine of two segments' angle, with their gradients and Hessians against central differences and against
distances computed another way in tests/contact_pairs_check.c (the cross
product; the closest points of two lines), built with AddressSanitizer +
UBSan."""
import subprocess

from util import BUILD, ROOT, ensure_dir


def results():
    exe = ensure_dir(BUILD / "contact") / "contact_pairs_check"
    r = subprocess.run(["cc", "-std=c11", "-O1", "-g", "-Wall", "-Wextra", "-Werror", "-fsanitize=address,undefined",
                        "-fno-sanitize-recover=all", f"-I{ROOT / 'out' / 'kernels'}", f"-I{ROOT / 'runtime'}",
                        str(ROOT / "tests" / "contact_pairs_check.c"), str(ROOT / "out" / "kernels" / "contact_pairs.c"),
                        "-o", str(exe), "-lm"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and not r.stderr, r.stderr
    return dict(kv.split("=", 1) for kv in r.stdout.split())


def test_distances_match_another_computation_and_their_differences():
    d = results()
    assert float(d["closed_err"]) < 1e-12, d         # |p - q|, |w x e| / |e|, |closest points of two lines|, 1 - |u x v|^2/(|u| |v|)^2
    assert float(d["grad_err"]) < 1e-6, d            # gradient against differences of the distance
    assert float(d["hess_err"]) < 1e-5, d            # Hessian against differences of the gradient
    assert float(d["hess_sym_err"]) == 0.0, d        # written symmetric
