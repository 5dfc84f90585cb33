"""The section resultants function of a continuum pair (bk_pair.sections): which
quadrature points sample which axial station, and the C function that sums their
tractions into the force and moment resultants n and m."""
from gen.c_functions import _block, _prologue
from gen.continuum import lowered_body, rule_parts
from gen.program import c_double


def sections_plan(elem, rname):
    """(sample xi, [(part, [(point index, station or -1 for all, 1/wx)])]) of an
    integration: the sample points are the axial Gauss stations of its first
    rule part; a part with the same stations adds its section points to each
    station, a part with one station along the axis (a centreline part of
    selective reduced integration) holds a stress the element takes constant
    along the axis and adds it to every station."""
    from gen.quadrature import gauss_unit
    _, parts, _ = rule_parts(elem, rname)
    counts = [rp.points for rp in elem.rule(rname)]
    nx0 = counts[0][0]
    xs = tuple(x for x, _ in gauss_unit(nx0))
    plan = []
    for part, (nx, ny, nz) in zip(parts, counts):
        if nx != nx0 and nx != 1:
            raise ValueError(f"{elem.name} {rname}: rule part {part.energy} has {nx} axial stations, "
                             f"the first part {nx0}: no common sample points")
        wx = [w for _, w in gauss_unit(nx)]
        pts = []
        for p in range(len(part.rule)):
            ix = p // (ny * nz)
            pts.append((p, ix if nx == nx0 else -1, 1.0 / wx[ix]))
        plan.append((part, pts))
    return xs, plan


def sections_function(elem, mat, rname, fname):
    """C lines of <pair>_<rule>_sections: the first Piola-Kirchhoff traction
    P N0 (N0 = e_x) of every point of the integration, weighted by the point's
    weight over its axial Gauss weight and the length (the section weight
    w_y w_z b h), summed per axial station into n = int P N0 dA0 and
    m = int (r - r_c) x P N0 dA0, r from the element's shape functions (a layer:
    over its band of the height, the table's weights carrying the band's share)."""
    xs, plan = sections_plan(elem, rname)
    nsh, ns = elem.nshape, len(xs)
    sig = (f"void {fname}(const double *restrict geom, const double *restrict q, const double *restrict tab, "
           "const double *restrict mat, double *restrict sec)")
    shape = f"bk_element_{elem.name}.shape"
    lines = [sig, "{", "    const double l = geom[BK_GEOM_L], b = geom[BK_GEOM_B], h = geom[BK_GEOM_H];",
             "    /* a layer's band of the height (bk_kernel.h): the points' heights mapped onto it */",
             "    const double lo = geom[BK_GEOM_BAND_LO], hi = geom[BK_GEOM_BAND_HI];",
             "    const int band = lo != 0.0 || hi != 0.0;",
             f"    static const double xs[{ns}] = {{{', '.join(c_double(x) for x in xs)}}};",
             f"    double N0[{ns}][{nsh}];",
             f"    for (int i = 0; i < {9 * ns}; ++i) sec[i] = 0.0;",
             f"    for (int k = 0; k < {ns}; ++k) {{",
             f"        {shape}(geom, xs[k], 0.0, 0.0, N0[k]);",
             f"        for (int a = 0; a < {nsh}; ++a)",
             "            for (int i = 0; i < 3; ++i) sec[9 * k + i] += N0[k][a] * q[3 * a + i];",
             "    }"]
    counts = [rp.points for rp in elem.rule(rname)]
    for (part, pts), (_, _, nz) in zip(plan, counts):
        low = lowered_body(elem, mat, part.energy, "traction")
        n = len(pts)
        sx = [part.rule[p][0][0] for p, _, _ in pts]
        lines += [f"    {{   /* energy part \"{part.energy}\": {n} points */",
                  f"        static const double px[{n}] = {{{', '.join(c_double(x) for x in sx)}}};",
                  f"        static const double py[{n}] = {{{', '.join(c_double(part.rule[p][0][1] - 0.5) for p, _, _ in pts)}}};",
                  f"        static const double pz[{n}] = {{{', '.join(c_double(part.rule[p][0][2] - 0.5) for p, _, _ in pts)}}};",
                  f"        static const double cw[{n}] = {{{', '.join(c_double(c) for _, _, c in pts)}}};",
                  f"        static const int st[{n}] = {{{', '.join(str(k) for _, k, _ in pts)}}};"]
        lines += _prologue(low, "        ")
        lines += [f"        for (int p = 0; p < {n}; ++p) {{",
                  f"            const double *restrict t = tab + {part.tab_offset} + {part.stride} * p;",
                  f"            double tr[3], N[{nsh}], Nc[{nsh}], arm[3] = {{0.0, 0.0, 0.0}};"]
        lines += _block(low, "            ")
        zmap = ("band ? (lo - 0.5 + (pz[p] + 0.5) * (1.0 - lo - hi)) * h : pz[p] * h" if nz > 1
                else "band ? geom[BK_GEOM_BAND_AXIS] * h : pz[p] * h")   # one point: the neutral axis (gen/continuum.py)
        lines += [f"            const double zp = {zmap};",
                  f"            {shape}(geom, px[p], py[p] * b, zp, N);",
                  f"            {shape}(geom, px[p], 0.0, 0.0, Nc);",
                  f"            for (int a = 0; a < {nsh}; ++a)",
                  "                for (int i = 0; i < 3; ++i) arm[i] += (N[a] - Nc[a]) * q[3 * a + i];",
                  "            const double c = cw[p] / l;",
                  f"            for (int k = 0; k < {ns}; ++k) {{",
                  "                if (st[p] >= 0 && st[p] != k)",
                  "                    continue;",
                  "                double *restrict o = sec + 9 * k;",
                  "                for (int i = 0; i < 3; ++i) o[3 + i] += c * tr[i];",
                  "                o[6] += c * (arm[1] * tr[2] - arm[2] * tr[1]);",
                  "                o[7] += c * (arm[2] * tr[0] - arm[0] * tr[2]);",
                  "                o[8] += c * (arm[0] * tr[1] - arm[1] * tr[0]);",
                  "            }", "        }", "    }"]
    lines += ["}", ""]
    source = "stress" if len(plan) == 1 else "stress:" + "+".join(p.energy for p, _ in plan)
    return lines, xs, source
