"""Why a hyperelastic solve found no equilibrium: the physical state it stopped in.

When Newton stops (its bound, or a load step halved to nothing), the last
equilibrium it reached says whether the way on is physically blocked, not
a matter of the mesh:

* a body's outline crosses itself: its free boundary folds onto itself,
  and a body's contact with itself is not modelled;
* two bodies' outlines overlap: a free side presses into a neighbour, and
  contact between bodies is not modelled (they are bonded where they meet);
* a body of revolution reaches across its axis;
* the rubber is crushed: an in-plane principal stretch below
  :data:`LEAST_STRETCH` (compressed to under 30 % of its length), where a
  coarse element can no longer follow the flow of the rubber around it.

:func:`physical_reason` names the first of these it finds, with the body
and the place; None if the state shows none of them (then the mesh or the
step may well be the cause, and the solver's own advice stands).
"""

from __future__ import annotations

import re

import numpy as np
import shapely

__all__ = ["LEAST_STRETCH", "physical_reason", "least_stretch"]

LEAST_STRETCH = 0.3
"""An in-plane principal stretch below this is named as the rubber crushed."""


def least_stretch(F: np.ndarray) -> np.ndarray:
    """The smaller in-plane principal stretch at each point, ``F`` of shape ``(..., 2, 2)``; shape ``(...)``.

    The smaller singular value of ``F``: ``sqrt((tr C - sqrt(tr C² - 4 det F²)) / 2)``, ``C = Fᵀ F``.

    Examples
    --------
    >>> float(least_stretch(np.array([[0.5, 0.0], [0.0, 2.0]])))
    0.5
    >>> c, s = np.cos(0.3), np.sin(0.3)
    >>> round(float(least_stretch(np.array([[c, -s], [s, c]]) @ np.diag([1.5, 0.2]))), 12)
    0.2
    """
    tr = np.einsum("...ij,...ij->...", F, F)
    det = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
    return np.sqrt(np.maximum(0.5 * (tr - np.sqrt(np.maximum(tr * tr - 4.0 * det * det, 0.0))), 0.0))


def _at(p) -> str:
    return f"[{float(p[0]):.4g}, {float(p[1]):.4g}]"


def physical_reason(contour: np.ndarray, rings, centres: np.ndarray, body: np.ndarray, F: np.ndarray, labels,
                    radius: np.ndarray | None = None) -> str | None:
    """The physical reason the state shows for no equilibrium near it, or None.

    Parameters
    ----------
    contour : (V, 2) float64 ndarray
        The bodies' outline points at the state, units.
    rings : sequence of (k_b,) int64 ndarray
        Each body's outline, as indices into ``contour``.
    centres : (E, 2) float64 ndarray
        Each cell's centre at the state, units.
    body : (E,) int64 ndarray
        Each cell's body.
    F : (E, q, 2, 2) float64 ndarray
        In-plane deformation gradient at the cells' quadrature points.
    labels : sequence of str
        Each body's name in messages (``bodies[i] 'name'``).
    radius : (V,) float64 ndarray, optional
        A body of revolution's outline points' distance from the axis, positive on the side the bodies are drawn.

    Returns
    -------
    str or None
        A clause: what, which body, where.

    Examples
    --------
    >>> square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    >>> bow = np.array([[0, 0], [1, 1], [1, 0], [0, 1]], float)
    >>> F = np.tile(np.eye(2), (1, 1, 1, 1))
    >>> physical_reason(bow, [np.arange(4)], np.zeros((1, 2)), np.zeros(1, int), F, ["bodies[0] 'b'"])
    "bodies[0] 'b' folds onto itself near [0.5, 0.5] (its outline crosses itself; a body's contact with itself is not modelled)"
    >>> physical_reason(square, [np.arange(4)], np.zeros((1, 2)), np.zeros(1, int), F, ["bodies[0] 'b'"]) is None
    True
    """
    polygons = []
    for b, ring in enumerate(rings):
        poly = shapely.Polygon(contour[ring])
        reason = shapely.is_valid_reason(poly)
        if reason != "Valid Geometry":
            found = re.search(r"\[([-+0-9.eE]+) ([-+0-9.eE]+)\]", reason)
            where = f" near {_at((float(found[1]), float(found[2])))}" if found else ""
            return (f"{labels[b]} folds onto itself{where} (its outline crosses itself; a body's contact with itself "
                    "is not modelled)")
        polygons.append(poly)
    for i in range(len(polygons)):
        for j in range(i + 1, len(polygons)):
            overlap = shapely.intersection(polygons[i], polygons[j])
            if overlap.area > 1e-6 * min(polygons[i].area, polygons[j].area):
                return (f"{labels[i]} and {labels[j]} press into each other near "
                        f"{_at(shapely.get_coordinates(overlap.representative_point())[0])} (area {overlap.area:.3g}; "
                        "contact between bodies is not modelled, they are bonded where they meet)")
    if radius is not None and radius.min() < 0.0:
        v = int(np.argmin(radius))
        b = next(b for b, ring in enumerate(rings) if v in ring)
        return f"{labels[b]} reaches across the axis near {_at(contour[v])}"
    stretch = least_stretch(F).min(axis=-1)
    e = int(np.argmin(stretch))
    if stretch[e] < LEAST_STRETCH:
        return (f"{labels[int(body[e])]} is crushed near {_at(centres[e])} (compressed to {100 * stretch[e]:.0f} % of "
                "its length there)")
    return None
