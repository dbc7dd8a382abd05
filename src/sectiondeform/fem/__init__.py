"""Finite elements for the hyperelastic model: coarse mesher, Taylor-Hood P2/P1 triangles,
vectorised neo-Hookean assembly, Newton solver and boundary mapping.

Modules, in pipeline order: :mod:`.mesh`, :mod:`.elements`, :mod:`.assembly`,
:mod:`.newton`, :mod:`.mapping`.
"""
