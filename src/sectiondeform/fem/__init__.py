"""Finite elements for the hyperelastic model: the mesher of one or several bodies, Taylor-Hood P2/P1
triangles, the physics of the rubbers, contact with rigid parts, the Newton solver and the mapping
back to the contour.

Modules, in pipeline order: :mod:`.union_mesh`, :mod:`.elements`, :mod:`.neohooke`, :mod:`.rubber`,
:mod:`.axisymmetric`, :mod:`.contact`, :mod:`.newton`, :mod:`.mapping`.
"""
