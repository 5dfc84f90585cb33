"""Plausibility of a beam's values before the solve: warnings naming the likely
mistake when a modulus, a density or a size lies far outside what solids and
structures have (a scene in millimetres with E in MPa, a density in g/cm^3).
Warnings only: an unusual but meant value still runs."""
from gen.scene.materials import small_strain

E_RANGE = (1e3, 1e12)          # Pa: 1 kPa (soft gels) .. 1000 GPa (diamond)
RHO_RANGE = (1.0, 3e4)         # kg/m^3: foams .. osmium
SIZE_RANGE = (1e-4, 1e4)       # m: 0.1 mm .. 10 km


def beam_warnings(where, mname, law, params, rho, section, length, index):
    """Warnings of one beam: its material's small-strain E and its density,
    its length and its section against its length."""
    out = []
    ss = small_strain(index, law, params)
    if ss is not None:
        E = ss[0]
        if 0 < E < E_RANGE[0]:
            out.append(f"material.{mname}: E = {E:.4g} Pa is below 1 kPa, softer than any solid: a value in MPa "
                       f"or kPa where Pa are expected? ({E:.4g} MPa = {E * 1e6:.4g} Pa)")
        elif E > E_RANGE[1]:
            out.append(f"material.{mname}: E = {E:.4g} Pa is above 1000 GPa, stiffer than diamond: a value for "
                       f"lengths in mm, or in kPa where Pa are expected?")
    if 0 < rho < RHO_RANGE[0]:
        out.append(f"material.{mname}: rho = {rho:.4g} kg/m^3 is below 1 kg/m^3, lighter than any foam: a value "
                   f"in g/cm^3 or t/mm^3 where kg/m^3 are expected?")
    elif rho > RHO_RANGE[1]:
        out.append(f"material.{mname}: rho = {rho:.4g} kg/m^3 is above 30,000 kg/m^3, denser than any "
                   f"material: a value in other units where kg/m^3 are expected?")
    if length < SIZE_RANGE[0]:
        out.append(f"{where}: length {length:.4g} m is below 0.1 mm: lengths in m expected (a scene in mm "
                   f"or um?)")
    elif length > SIZE_RANGE[1]:
        out.append(f"{where}: length {length:.4g} m is above 10 km: lengths in m expected (a scene in mm?)")
    _shape, b, h = section
    if max(b, h) > length:
        out.append(f"{where}: section {b:.4g} x {h:.4g} m is larger than the beam's length {length:.4g} m: a "
                   f"beam model needs a slender body (swapped values, or the section in other units?)")
    return out
