"""[[beam_contact]] tables: beams that may touch one another and, with
`self`, themselves (issue 35; runtime/assembly/beam_contact.c, the model
file's beam contact records).

Keys: beams (names, default every beam; pairs of different beams of the list
touch), self (bool, default false: each listed beam touches itself where
its segments are further apart along it than `exclude`), exclude (m, default
twice the sum of the two largest contact radii of the set), distance (the
barrier's reach, m, default 1e-3 of the model length), stiffness (N/m per
metre, default 1000 times the heaviest listed beam's weight per metre over
the reach), samples (points per element, ends included, >= 2, default 4: the
centreline is the polyline through them), contact_radius (m, default the
section's: a circle's radius, a rectangle's half-height h/2), friction (the
Coulomb coefficient mu, default 0; or static_friction and kinetic_friction
apart, as for [[contact]]) and slip (the relative slip per step below which
two beams stick, m; default 1e-7 of the model length).  The runtime grows
the Newton matrix's pattern as contacts are found, so only dynamics and static
analyses (load control or arc length) with `stability = false` take beam
contact."""
import math

import gen.scene_keys as K
from gen.scene.contact import _friction, beam_names, weight_per_length
from gen.scene.values import _dot, _norm, _sub, check_keys, get_array_of_tables, get_bool, get_int, get_number

KEYS = K.BEAM_CONTACT
from gen.scene.interactions import Interaction  # noqa: E402


def _segments(beam, first, samples, radius):
    """Each element's segments of the beam as (element, segment, p, q, s0, s1, radius) in reference positions."""
    out = []
    for k in range(beam["nelem"]):
        s0, length = beam["elem_start"][k], beam["elem_lens"][k]
        pts = [beam["geo"].at(s0 + j / (samples - 1) * length)[0] for j in range(samples)]
        h = length / (samples - 1)
        out += [(first + k, j, pts[j], pts[j + 1], s0 + j * h, s0 + (j + 1) * h, radius) for j in range(samples - 1)]
    return out


def _seg_distance(p0, p1, q0, q1):
    """Distance between the segments p0 p1 and q0 q1 (by a fine parameter search
    refined from the closed form of the lines; only for the start check)."""
    u, v, r = _sub(p1, p0), _sub(q1, q0), _sub(p0, q0)
    a, e, b, c, f = _dot(u, u), _dot(v, v), _dot(u, v), _dot(u, r), _dot(v, r)
    cands = [(0.0, None), (1.0, None), (None, 0.0), (None, 1.0)]
    den = a * e - b * b
    if den > 1e-12 * a * e:
        cands.append(((b * f - c * e) / den, (a * f - b * c) / den))
    best = math.inf
    for s, t in cands:
        if s is None:
            s = min(max((b * t - c) / a, 0.0), 1.0)
        elif t is None:
            t = min(max((b * s + f) / e, 0.0), 1.0)
        s, t = min(max(s, 0.0), 1.0), min(max(t, 0.0), 1.0)
        g = [p0[i] + s * u[i] - q0[i] - t * v[i] for i in range(3)]
        best = min(best, _norm(g))
    return best


def _check_start(ctx, where, segs, reach, exclude, self_contact, beam_of):
    """Fails when two segments that may touch start closer than their radii
    (a spatial hash of the segments' midpoints: no loop over all pairs)."""
    cell = max(max(_norm(_sub(q, p)) for _, _, p, q, *_ in segs) + 2 * max(s[6] for s in segs) + reach, 1e-12)
    grid = {}
    for n, (_, _, p, q, *_) in enumerate(segs):
        mid = [(p[i] + q[i]) / 2 for i in range(3)]
        grid.setdefault(tuple(math.floor(x / cell) for x in mid), []).append(n)
    for key, members in grid.items():
        near = [m for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                for m in grid.get((key[0] + dx, key[1] + dy, key[2] + dz), [])]
        for a in members:
            for b in near:
                if b <= a:
                    continue
                ea, ka, p0, p1, sa0, sa1, ra = segs[a]
                eb, kb, q0, q1, sb0, sb1, rb = segs[b]
                if beam_of[a] == beam_of[b] and (not self_contact or max(0.0, sb0 - sa1, sa0 - sb1) <= exclude):
                    continue
                depth = ra + rb - _seg_distance(p0, p1, q0, q1)
                if depth >= 0.0:
                    ctx.fail(where, f"beam {beam_of[a]!r} element {ea} and beam {beam_of[b]!r} element {eb} start "
                                    f"{depth:.6g} m into each other (sections must start apart: move a beam, or "
                                    f"raise `exclude` for parts of one beam)")


def beam_contacts(ctx, doc, beams, length_scale, analysis, stat):
    """The model file's beam contact sets: [(reach, stiffness, (mu_s, mu_k), slip,
    samples, exclude, self, [[(element, radius, s0)] per beam])]."""
    sets = []
    for i, ct in enumerate(get_array_of_tables(ctx, doc, "beam_contact")):
        where = f"beam_contact[{i}]"
        check_keys(ctx, ct, set(KEYS), where)
        if analysis not in ("static", "dynamic"):
            ctx.fail(where, "beam contact is available in static and dynamic analyses only (the Newton matrix's "
                            "pattern grows as contacts are found)")
        if analysis == "static" and stat.get("stability"):
            ctx.fail(where, "expected [static] stability = false (the stability check keeps the first pattern of "
                            "the Newton matrix, which beam contact grows)")
        mu = _friction(ctx, ct, where)
        slip = get_number(ctx, ct, "slip", where, default=1e-7 * length_scale, positive=True)
        names = beam_names(ctx, ct, where, beams)
        if len(set(names)) != len(names):
            ctx.fail(f"{where}.beams", "expected each beam once")
        self_contact = get_bool(ctx, ct, "self", where, False)
        if len(names) < 2 and not self_contact:
            ctx.fail(f"{where}.beams", "expected two beams or more, or self = true")
        reach = get_number(ctx, ct, "distance", where, default=1e-3 * length_scale, positive=True)
        samples = get_int(ctx, ct, "samples", where, default=4, lo=2, hi=64)
        weight = max(weight_per_length(doc, n, beams[n]["section"]) for n in names)
        kappa = get_number(ctx, ct, "stiffness", where, default=max(1e3 * weight / reach, 1e-12), positive=True)
        radii = {n: get_number(ctx, ct, "contact_radius", where, default=beams[n]["section"][2] / 2.0, nonneg=True)
                 for n in names}
        big = sorted(radii.values())[-2:]
        exclude = get_number(ctx, ct, "exclude", where, default=2.0 * (big[0] + big[-1]), nonneg=True)
        chains, segs, beam_of = [], [], []
        for n in names:
            b = beams[n]
            chains.append([(b["first_elem"] + k, radii[n], b["elem_start"][k]) for k in range(b["nelem"])])
            s = _segments(b, b["first_elem"], samples, radii[n])
            segs += s
            beam_of += [n] * len(s)
        _check_start(ctx, where, segs, reach, exclude, self_contact, beam_of)
        sets.append((reach, kappa, mu, slip, samples, exclude, int(self_contact), chains))
    return sets


def beam_contact_records(sets, fmt):
    """The model file's lines: 'beam_contacts NSET', per set 'bcset REACH
    STIFFNESS MU_S MU_K SLIP SAMPLES EXCLUDE SELF NBEAM' and per beam 'chain N e r s0 ...'."""
    out = [f"beam_contacts {len(sets)}"]
    for reach, kappa, (mu_s, mu_k), slip, samples, exclude, self_contact, chains in sets:
        out.append(f"bcset {fmt(reach)} {fmt(kappa)} {fmt(mu_s)} {fmt(mu_k)} {fmt(slip)} {samples} {fmt(exclude)} "
                   f"{self_contact} {len(chains)}")
        out += [f"chain {len(ch)} " + " ".join(f"{e} {fmt(r)} {fmt(s0)}" for e, r, s0 in ch) for ch in chains]
    return out


def _build(ctx, doc, scene):
    sets = beam_contacts(ctx, doc, scene.beams, scene.length_scale, scene.analysis, scene.stat)
    return sets or None


INTERACTION = Interaction(table="beam_contact", keys=KEYS, record="beam_contact", build=_build,
                          lines=beam_contact_records, holds=True, order=40,
                          title="beams that may touch one another and themselves (docs/explanation/contact.md)")
