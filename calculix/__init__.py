"""CalculiX (ccx) as an independent reference for beamkit's continuum beams.

A straight-beam scene (rectangular section, clamp, end force and/or gravity,
svk / neo_hookean / mooney_rivlin / arruda_boyce) is turned into a C3D20R solid
deck, run with Debian's `ccx` on 2-3 meshes refined by a constant factor, and
the sensor displacements are extrapolated (Richardson).

Modules, one job each:
  scene        read and check the scene (refuses what a solid deck cannot represent)
  mesh         structured C3D20R brick mesh in the beam's frame
  deck         scene + mesh -> ccx input deck (materials, constraints, loads, steps)
  run          run ccx in a work directory, cached under out/calculix/ by deck hash
  results      parse ccx's .dat output (node displacements, time histories)
  extrapolate  Richardson extrapolation with the observed order
  study        the mesh study: decks for each mesh, runs, extrapolation, checks
  data         the committed references (references/data/calculix_silicone.json)
  uniaxial     closed-form uniaxial-stress responses of our laws and of ccx's,
               to state the remaining law differences

Nothing here imports sympy.
"""
from calculix.scene import read_scene          # noqa: F401
from calculix.study import reference, Study    # noqa: F401
from calculix.data import reference_data       # noqa: F401
