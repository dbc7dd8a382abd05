"""From the solved mesh to the section's points, and the law's offset.

* :func:`edge_weights`: every contour point lies on a boundary edge's
  stretch of the contour. It is located by its parameter on that
  (quadratic) edge and its small offset ``d`` from the edge (the true curve
  between two mesh nodes bulges off the edge). Its image is ``x(t) + F(t) d``:
  the edge's image plus the offset carried by the local deformation
  gradient, a first-order extrapolation with the element's own shape
  functions. Linear in the node positions, so it is a sparse matrix; no
  point is dropped, the order is kept, an identity or a rigid motion is
  reproduced exactly.
* :func:`rigid_fit`: the rotation and translation that best carry points
  onto others (least squares), the cold start.
* :func:`offset_normals`, :func:`offset_to_law`: the directions and the
  size of the normal offset that makes a law exact (a quadratic in the
  offset for an area, a cubic for a volume of revolution).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from ..errors import LawError
from ..laws import law_roots
from .elements import p2_gradients, p2_values

__all__ = ["edge_weights", "rigid_fit", "offset_normals", "offset_to_law"]


def _edge_curve(a, m, b, t):
    """Quadratic edge through a (t=0), m (t=1/2), b (t=1): point, first and second derivative."""
    t = t[:, None]
    x = a * (1 - t) * (1 - 2 * t) + m * 4 * t * (1 - t) + b * t * (2 * t - 1)
    dx = a * (4 * t - 3) + m * (4 - 8 * t) + b * (4 * t - 1)
    ddx = 4 * a - 8 * m + 4 * b
    return x, dx, ddx


def edge_weights(nodes: np.ndarray, cells: np.ndarray, cell: np.ndarray, loc: np.ndarray, direction: np.ndarray,
                 t: np.ndarray, points: np.ndarray) -> sp.csr_matrix:
    """Matrix ``W`` with ``W @ x_nodes`` the images of points lying along given (quadratic) cell edges.

    Parameters
    ----------
    nodes : (N, 2) float64 ndarray
        Initial node positions, units.
    cells : (E, 6) int64 ndarray
        ``triangle6`` cells.
    cell, loc, direction : (m,) int64 ndarray
        Per point: the cell holding its edge, the local edge (0, 1, 2 for
        cell nodes 0-1, 1-2, 2-0), and +1 when ``t`` runs along the cell's
        edge direction, -1 otherwise.
    t : (m,) float64 ndarray
        First guess of each point's parameter along its edge, in [0, 1].
    points : (m, 2) float64 ndarray
        The points, units.

    Returns
    -------
    (m, N) scipy.sparse.csr_matrix
        Weights ``N_a + grad N_a . d`` on the six nodes of each point's cell.
    """
    cn = cells[cell]
    ends = np.array([[0, 1], [1, 2], [2, 0]])[loc]
    first = np.where(direction > 0, ends[:, 0], ends[:, 1])
    second = np.where(direction > 0, ends[:, 1], ends[:, 0])
    rows = np.arange(len(t))
    a, b = nodes[cn[rows, first]], nodes[cn[rows, second]]
    m = nodes[cn[rows, 3 + loc]]
    for _ in range(4):  # project the point on the quadratic edge
        x, dx, ddx = _edge_curve(a, m, b, t)
        r = x - points
        t = np.clip(t - np.einsum("ij,ij->i", r, dx) / (np.einsum("ij,ij->i", dx, dx) + np.einsum("ij,ij->i", r, ddx)), 0, 1)
    x, _, _ = _edge_curve(a, m, b, t)
    d = points - x
    tau = np.where(direction > 0, t, 1.0 - t)
    local = np.select(
        [loc[:, None] == 0, loc[:, None] == 1],
        [np.column_stack((tau, 0 * tau)), np.column_stack((1 - tau, tau))],
        np.column_stack((0 * tau, 1 - tau)),
    )
    vals = p2_values(local)  # (m, 6)
    dref = p2_gradients(local)  # (m, 6, 2)
    xe = nodes[cn]
    jac = np.einsum("pai,paj->pij", xe, dref)
    grad = np.einsum("paj,pji->pai", dref, np.linalg.inv(jac))
    w = vals + np.einsum("pai,pi->pa", grad, d)
    return sp.csr_matrix((w.ravel(), (np.repeat(rows, 6), cn.ravel())), shape=(len(t), len(nodes)))


def rigid_fit(src: np.ndarray, dst: np.ndarray, weights: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Rotation ``Q`` (2, 2) and translation ``t`` (2,) minimising ``sum w |Q src + t - dst|^2``.

    Examples
    --------
    >>> q, t = rigid_fit(np.array([[0.0, 0], [1, 0]]), np.array([[1.0, 1], [1, 2]]))
    >>> q.round(12).tolist(), t.round(12).tolist()
    ([[0.0, -1.0], [1.0, 0.0]], [1.0, 1.0])
    """
    w = np.ones(len(src)) if weights is None else weights
    w = w / w.sum()
    cs, cd = w @ src, w @ dst
    a, b = src - cs, dst - cd
    c = np.einsum("p,pi,pj->ij", w, b, a)  # sum w b a^T
    ang = math.atan2(c[1, 0] - c[0, 1], c[0, 0] + c[1, 1])
    q = np.array([[math.cos(ang), -math.sin(ang)], [math.sin(ang), math.cos(ang)]])
    return q, cd - q @ cs


def offset_normals(ring: np.ndarray, movable: np.ndarray) -> np.ndarray:
    """The directions a law's offset moves a closed polyline's points along, ``(k, 2)``.

    The unit normal of the chord between each movable point's two
    neighbours (outward for a counter-clockwise ring), zero for the other
    points and where the neighbours coincide.
    """
    if len(ring) < 3:
        tang = np.roll(ring, -1, axis=0) - np.roll(ring, 1, axis=0)
    else:  # the same differences by slices (np.roll copies the ring twice: a third of a drag preview's correction)
        tang = np.empty_like(ring)
        tang[1:-1] = ring[2:] - ring[:-2]
        tang[0] = ring[1] - ring[-1]
        tang[-1] = ring[0] - ring[-2]
    length = np.hypot(tang[:, 0], tang[:, 1])
    ok = movable & (length > 0)
    v = np.zeros_like(ring)
    v[ok, 0] = tang[ok, 1] / length[ok]
    v[ok, 1] = -tang[ok, 0] / length[ok]
    return v


def offset_to_law(ring: np.ndarray, movable: np.ndarray, law, wanted: float) -> tuple[np.ndarray, float]:
    """Offset the movable points of a closed polyline along their normals so its law's quantity is ``wanted``.

    The quantity of ``ring + k v`` (``v`` the normals, :func:`offset_normals`)
    is a polynomial in ``k`` (:meth:`~sectiondeform.laws.Law.coefficients`:
    a quadratic for an area, a cubic for a volume of revolution); of its
    real roots (:func:`~sectiondeform.laws.law_roots`) the one nearest 0,
    the smallest correction, is taken.

    Parameters
    ----------
    ring : (k, 2) float64 ndarray
        Closed polyline (the closing edge implied), units.
    movable : (k,) bool ndarray
        The points that may move; each along the normal of the chord
        between its two neighbours, by one common distance.
    law : Law
        Gives :meth:`~sectiondeform.laws.Law.coefficients` (signed).
    wanted : float
        Wanted signed quantity (units² or units³).

    Returns
    -------
    ring : (k, 2) float64 ndarray
    offset : float
        The distance applied, units (positive: outward for a
        counter-clockwise ring).

    Raises
    ------
    LawError
        If no offset meets the law (no movable point, or no real root).

    Examples
    --------
    The top corners of a unit square moved out (along the chords between
    their neighbours) to give it the area 1.5, its base kept:

    >>> from sectiondeform.laws import AreaRatio
    >>> sq = np.array([[0.0, 0], [1, 0], [1, 1], [0, 1]])
    >>> out, k = offset_to_law(sq, np.array([False, False, True, True]), AreaRatio(1.5), 1.5)
    >>> round(AreaRatio(1.5).quantity(out), 12), out[:2].tolist()
    (1.5, [[0.0, 0.0], [1.0, 0.0]])
    """
    v = offset_normals(ring, movable)
    c = np.array(law.coefficients(ring, v), dtype=np.float64)
    if not np.abs(c[1:]).max() > 1e-14 * float(np.abs(c).max() + abs(wanted)):
        raise LawError(f"law: no point of the upper curve is free to move to meet the {law.measure}")
    roots = law_roots(c, wanted)
    if not roots:
        raise LawError(f"law: no normal offset of the upper curve gives the {law.measure} {abs(wanted):.6g}")
    k = min(roots, key=abs)
    return ring + k * v, float(k)
