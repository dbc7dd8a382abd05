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
* :func:`offset_normals`, :func:`offset_root`: the directions and the size
  of the normal offset that makes a law exact (a quadratic in the offset for
  an area, solved without cancellation).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from ..errors import LawError
from .elements import p2_gradients, p2_values

__all__ = ["edge_weights", "rigid_fit", "offset_normals", "offset_root"]


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
    tang = np.roll(ring, -1, axis=0) - np.roll(ring, 1, axis=0)
    length = np.hypot(tang[:, 0], tang[:, 1])
    ok = movable & (length > 0)
    v = np.zeros_like(ring)
    v[ok] = np.column_stack((tang[ok, 1], -tang[ok, 0])) / length[ok, None]
    return v


def offset_root(c0: float, c1: float, c2: float, signed_area: float) -> float:
    """The offset k nearest zero with c0 + c1 k + c2 k² = 0 (c1 ≠ 0), without cancellation.

    The area of a contour whose movable points move by k along fixed
    normals is quadratic in k; the wanted offset is the root of smaller
    magnitude (the one that tends to -c0 / c1 as c2 vanishes).

    Raises
    ------
    LawError
        If the quadratic has no real root: no offset gives ``signed_area``.

    Examples
    --------
    >>> offset_root(-1.0, 1.0, 0.0, 2.0), round(offset_root(-3.0, 2.0, 1.0, 2.0), 12)
    (1.0, 1.0)
    """
    if abs(c2 * c0) <= 1e-12 * c1 * c1:
        return -c0 / c1
    disc = c1 * c1 - 4.0 * c2 * c0
    if disc < 0:
        raise LawError(f"law: no normal offset of the upper curve gives the area {abs(signed_area):.6g}")
    return c0 / (-0.5 * (c1 + math.copysign(math.sqrt(disc), c1)))
