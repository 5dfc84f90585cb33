"""Uniaxial stress (free lateral contraction) in closed form, for our laws and for
the CalculiX laws the deck uses in their place: how much the two differ at the
strains of a case.

W(l1, l, l) with principal stretches l1 (axial) and l (lateral, both); the
lateral stretch makes the lateral nominal stress dW/dl vanish (bisection), and
the axial nominal stress is dW/dl1.  Derivatives are complex-step derivatives,
exact to round-off, so the nearly incompressible laws (kappa = 1000 mu) compare
to many digits.

    python3 -m calculix.uniaxial SCENE [--set K=V ...]   # table at -20 ... +50 % strain
"""
import cmath
import sys

AB_C = (1 / 2, 1 / 20, 11 / 1050, 19 / 7000, 519 / 673750)


def _inv(l1, l):
    I1 = l1 * l1 + 2 * l * l
    I2 = 2 * l1 * l1 * l * l + l**4
    J = l1 * l * l
    return I1, I2, J


def energies(mat):
    """(ours, ccx's) strain-energy functions W(l1, l) of a calculix.scene.Material,
    with the ccx law calculix.deck writes (for neo_hookean also *HYPERFOAM, which ccx 2.20 does not run here)."""
    p, law = mat.p, mat.law
    if law == "svk":
        def w(l1, l):
            E = [(l1 * l1 - 1) / 2, (l * l - 1) / 2, (l * l - 1) / 2]
            return p["lambda"] / 2 * sum(E)**2 + p["mu"] * sum(e * e for e in E)
        return w, {"*ELASTIC": w}
    if law == "neo_hookean":
        lam, mu, nu = p["lambda"], p["mu"], p["nu"]
        beta = nu / (1 - 2 * nu)
        K = lam + 2 * mu / 3

        def ours(l1, l):
            I1, _, J = _inv(l1, l)
            return mu / 2 * (I1 - 3) - mu * cmath.log(J) + lam / 2 * cmath.log(J)**2

        def foam(l1, l):
            I1, _, J = _inv(l1, l)
            return mu / 2 * (I1 - 3 + (J**(-2 * beta) - 1) / beta)

        def nh(l1, l):
            I1, _, J = _inv(l1, l)
            return mu / 2 * (J**(-2 / 3) * I1 - 3) + K / 2 * (J - 1)**2
        return ours, {"*HYPERFOAM N=1": foam, "NEO HOOKE": nh}
    if law == "mooney_rivlin":
        def w(l1, l):
            I1, I2, J = _inv(l1, l)
            return (p["c10"] * (J**(-2 / 3) * I1 - 3) + p["c01"] * (J**(-4 / 3) * I2 - 3)
                    + p["kappa"] / 2 * (J - 1)**2)
        return w, {"MOONEY-RIVLIN": w}
    if law == "arruda_boyce":
        mu, lm, k = p["mu"], p["lambda_m"], p["kappa"]

        def dev(l1, l):
            I1, _, J = _inv(l1, l)
            Ib = J**(-2 / 3) * I1
            return mu * sum(c / lm**(2 * i) * (Ib**(i + 1) - 3**(i + 1)) for i, c in enumerate(AB_C))

        def ours(l1, l):
            return dev(l1, l) + k / 2 * (_inv(l1, l)[2] - 1)**2

        def ccx(l1, l):
            J = _inv(l1, l)[2]
            return dev(l1, l) + k / 2 * ((J * J - 1) / 2 - cmath.log(J))
        return ours, {"ARRUDA-BOYCE": ccx}
    raise ValueError(f"law {law!r}")


def _d(f, x, h=1e-20):
    return f(complex(x, h)).imag / h


def uniaxial(w, l1):
    """(axial nominal stress, lateral stretch) in uniaxial stress at axial stretch l1."""
    g = lambda l: _d(lambda z: w(l1, z), l)
    lo, hi = 0.2, 1.5
    glo, ghi = g(lo), g(hi)
    if glo * ghi > 0:
        raise ValueError(f"no lateral equilibrium bracketed at stretch {l1}")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        gm = g(mid)
        if gm == 0 or hi - lo < 1e-15:
            break
        if (gm > 0) == (ghi > 0):
            hi, ghi = mid, gm
        else:
            lo, glo = mid, gm
    lat = 0.5 * (lo + hi)
    return _d(lambda z: w(z, lat), l1), lat


def compare(mat, strains=(-0.2, -0.1, -0.05, 0.05, 0.1, 0.2, 0.5)):
    """[(strain, ours P11, {ccx law: (P11, relative difference)})]."""
    ours, theirs = energies(mat)
    rows = []
    for e in strains:
        P, _ = uniaxial(ours, 1 + e)
        rows.append((e, P, {name: (uniaxial(w, 1 + e)[0], uniaxial(w, 1 + e)[0] / P - 1) for name, w in theirs.items()}))
    return rows


def main(argv=None):
    import argparse
    from calculix.scene import read_scene
    ap = argparse.ArgumentParser(prog="python3 -m calculix.uniaxial")
    ap.add_argument("scene")
    ap.add_argument("--set", dest="sets", action="append", default=[])
    a = ap.parse_args(argv)
    mat = read_scene(a.scene, a.sets).material
    E, nu = mat.small_strain()
    print(f"law {mat.law}, small-strain E = {E:.6g} Pa, nu = {nu:.6g}: uniaxial nominal stress, ours vs CalculiX")
    for e, P, other in compare(mat):
        print(f"  strain {e:+.2f}: ours {P:+.6e} Pa   " + "   ".join(
            f"{name} {Pc:+.6e} ({d:+.2e})" for name, (Pc, d) in other.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
