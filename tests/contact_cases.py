"""Contact problems for the tests: a rubber block with nested refinement inserts under a rigid cylinder or sphere.

The block (bonded on its base) holds, at the top where the indenter
touches, inserts of the same rubber resting in notches of each other: each
insert is a body with its own, smaller element size (the hyperelastic
model sizes each body's elements by its own thickness), so the mesh is fine
under the contact and coarse far from it, and the bodies bonded to each
other are one block of one material.
"""

from __future__ import annotations

import numpy as np

from sectiondeform.io.case import case_from_dict

LEVELS = ((20.0, 10.0), (4.0, 2.0), (1.2, 0.6), (0.4, 0.2))
"""Width and depth of the block and of each insert, in units of the indenter's radius (full widths, plane)."""


def _poly(points) -> dict:
    return {"polyline": [[float(x), float(y)] for x, y in points]}


def indentation_case(depth: float, revolution: bool, radius: float = 1.0, shear_modulus: float = 1.0,
                     through: float = 8.0, levels=LEVELS, bulk_to_shear: float = 1e4) -> dict:
    """A case: a block of width ``levels[0][0] R``, depth ``levels[0][1] R``, indented by ``depth`` by a rigid cylinder (plane) or sphere (revolution).

    Plane: the block spans ``x`` in ``[-W/2, W/2]``; revolution: the axis is
    the ``y`` axis and the block spans ``x`` in ``[0, W/2]``. The indenter
    touches the block's top (``y = 0``) at its start and travels ``depth``
    down.
    """
    R = radius
    lo = 0.0 if revolution else None
    bodies = []
    for k, (w, d) in enumerate(levels):
        w, d = w * R / 2.0, d * R
        left = lo if revolution else -w
        nxt = levels[k + 1] if k + 1 < len(levels) else None
        top = [(w, 0.0)]
        if nxt is not None:
            wn, dn = nxt[0] * R / 2.0, nxt[1] * R
            top += [(wn, 0.0), (wn, -dn)]
            top += [(0.0, -dn)] if revolution else [(-wn, -dn), (-wn, 0.0)]
            if revolution:
                top += []
        if k == 0:
            lower = [(left, -d), (w, -d)]
            upper = [(w, -d), *top] + ([(0.0, -d)] if revolution else [(-w, 0.0), (-w, -d)])
            if revolution and nxt is not None:
                upper = [(w, -d), *top, (0.0, -d)]
            elif revolution:
                upper = [(w, -d), (w, 0.0), (0.0, 0.0), (0.0, -d)]
        else:
            lower = [(left, -d), (w, -d), (w, 0.0)] if revolution else [(-w, 0.0), (-w, -d), (w, -d), (w, 0.0)]
            if revolution:
                upper = [*top, (0.0, 0.0), (0.0, -d)] if nxt is None else [*top, (0.0, -d)]
                if nxt is None:
                    upper = [(w, 0.0), (0.0, 0.0), (0.0, -d)]
            else:
                upper = [*top, (-w, 0.0)] if nxt is not None else [(w, 0.0), (0.0, 0.0), (-w, 0.0)]
        law = {"volume_ratio": 1.0} if revolution else {"area_ratio": 1.0}
        bodies.append({"name": f"level{k}", "lower": _poly(lower), "upper": _poly(upper), "law": law,
                       "material": {"shear_modulus": shear_modulus, "bulk_to_shear": bulk_to_shear}})
    W, D = levels[0][0] * R / 2.0, levels[0][1] * R
    base = [(0.0 if revolution else -W, -D), (W, -D)]
    angles = np.linspace(-0.5 * np.pi, 0.5 * np.pi, 721) if revolution else np.linspace(-np.pi, np.pi, 1441)
    ring = np.column_stack((R * np.cos(angles), R + R * np.sin(angles) - depth))
    if revolution:
        ring = np.vstack((ring, ring[:1]))
    case = {"format": "section-case/2", "name": "indentation", "units": "mm", "support": _poly(base), "target": _poly(base),
            "bodies": bodies, "rigid": [{"name": "indenter", "contour": _poly(ring), "travel": [0.0, -depth]}],
            "options": {"model": "hyperelastic", "elements_through_thickness": through}}
    if revolution:
        case["revolution"] = {"axis": [[0.0, 0.0], [0.0, 1.0]]}
    return case


def indentation_problem(depth: float, revolution: bool, **kw):
    """:func:`indentation_case` as a Problem."""
    return case_from_dict(indentation_case(depth, revolution, **kw))
