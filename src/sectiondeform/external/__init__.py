"""Hand a case to the finite-element solvers engineers trust: Abaqus/CalculiX decks, CalculiX runs.

:mod:`.deck` writes one complete ``.inp`` deck of any problem (one conforming
mesh from :mod:`.mesh`, a set, section and material per body, support motion,
step; reals by :mod:`.inp_number`); :mod:`.calculix` runs ``ccx``; :mod:`.frd`
reads its results; :mod:`.solve` turns them into a :class:`~sectiondeform.result.Result`;
:mod:`.validation` hands it to ``validate`` as a reference.
"""

DEFAULT_MESH_SIZE = 0.1
"""Triangle size of a deck's mesh, as a fraction of the section's mean thickness."""
DEFAULT_ELEMENT = "CPE6"
"""Element of a plane deck: quadratic, does not lock in CalculiX 2.20 at kappa/mu = 1000."""
DEFAULT_AXI_ELEMENT = "CAX6"
"""Element of a deck of a body of revolution."""
