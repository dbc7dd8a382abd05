"""Point location in a quad mesh and placement at the same local coordinates (paper §3.6).

A point is located by its element and its local coordinates ``(xi, eta)``
in [0, 1]² under the bilinear map of that element::

    x = (1-xi)(1-eta) p0 + xi(1-eta) p1 + xi eta p2 + (1-xi) eta p3

The inverse is solved in closed form (a quadratic in ``eta``), for all
points at once. Candidate elements come from a uniform grid of buckets over
the mesh, each bucket listing the elements whose bounding box meets it (or,
for few points, from every element's bounding box): a point inside an
element is always among its candidates. Each point
takes the candidate that contains it most deeply (or, on an edge or a
node, within the tolerance); points still unlocated are tried against
every element. Points go through in chunks, so memory stays
bounded whatever their number.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .curves import cross as _cross
from .errors import LocateError

__all__ = ["Location", "locate", "locate_some", "place", "bilinear_weights", "inverse_bilinear"]

LOCAL_TOL = 1e-6
CHUNK = 1 << 16  # points located at once
MAX_BUCKETS_PER_ELEMENT = 64.0
FEW_PAIRS = 1 << 18  # points x elements below which every element's box is tested
MAX_EXHAUSTIVE_PAIRS = 2_000_000
"""(point, element) pairs the exhaustive pass for unlocated points may test (about 1.5 s)."""


@dataclass(frozen=True, eq=False)
class Location:
    """Where points sit in a mesh.

    Attributes
    ----------
    elements : (p,) int64 ndarray
        Element index of each point.
    local : (p, 2) float64 ndarray
        Local coordinates (xi, eta) in [0, 1]².
    nodes : (p, 4) int64 ndarray
        The element's node indices, in element order.
    weights : (p, 4) float64 ndarray
        Bilinear weights of those nodes; each row sums to 1.
    """

    elements: np.ndarray
    local: np.ndarray
    nodes: np.ndarray
    weights: np.ndarray


def bilinear_weights(local: np.ndarray) -> np.ndarray:
    """Bilinear shape-function values at local coordinates, ``(p, 2)`` -> ``(p, 4)``.

    Examples
    --------
    >>> bilinear_weights(np.array([[0.5, 0.5]])).tolist()
    [[0.25, 0.25, 0.25, 0.25]]
    """
    xi, eta = local[:, 0], local[:, 1]
    return np.column_stack(((1 - xi) * (1 - eta), xi * (1 - eta), xi * eta, (1 - xi) * eta))


def place(points: np.ndarray, location: Location) -> np.ndarray:
    """Positions at the located local coordinates in a mesh with nodes ``points``.

    Parameters
    ----------
    points : (N, 2) float64 ndarray
        Node coordinates of a mesh with the same elements as the one the
        points were located in (for example the final mesh).
    location : Location

    Returns
    -------
    (p, 2) float64 ndarray
    """
    w, nodes = location.weights, location.nodes
    return np.column_stack([np.einsum("pk,pk->p", w, points[:, d][nodes]) for d in (0, 1)])


def inverse_bilinear(quad_pts: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Local coordinates of points ``x`` under the bilinear maps of ``quad_pts``.

    Parameters
    ----------
    quad_pts : (p, 4, 2) float64 ndarray
        Corner coordinates of one element per point.
    x : (p, 2) float64 ndarray

    Returns
    -------
    (p, 2) float64 ndarray
        ``(xi, eta)``; inside the element both are in [0, 1]. Points whose
        equation has no real root get NaN.

    Examples
    --------
    >>> q = np.array([[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]])
    >>> inverse_bilinear(q, np.array([[1.0, 0.25]])).tolist()
    [[0.5, 0.25]]
    """
    return _solve_local(_element_terms(quad_pts), x.T)


def _element_terms(quad_pts: np.ndarray) -> np.ndarray:
    """Per element, the terms of its bilinear map that do not depend on the point, ``(10, p)``.

    Rows: p0 (x, y), e = p1 - p0, f = p3 - p0, g = p0 - p1 + p2 - p3
    (x, y each), cross(g, f), cross(e, f).
    """
    p0, p1, p2, p3 = (quad_pts[:, i] for i in range(4))
    e, f, g = p1 - p0, p3 - p0, p0 - p1 + p2 - p3
    return np.vstack((p0.T, e.T, f.T, g.T, _cross(g, f), _cross(e, f)))


def _solve_local(terms: np.ndarray, x: np.ndarray) -> np.ndarray:
    """:func:`inverse_bilinear` from :func:`_element_terms` (one column per point), ``(p, 2)``."""
    return np.column_stack(_solve_xi_eta(terms, x))


def _solve_xi_eta(terms: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_solve_local` as two ``(p,)`` arrays, xi and eta."""
    p0x, p0y, ex, ey, fx, fy, gx, gy, k2, kef = terms
    hx, hy = x[0] - p0x, x[1] - p0y
    k1 = kef + (hx * gy - hy * gx)
    k0 = hx * ey - hy * ex
    scale = np.abs(kef) + np.abs(k1) + 1e-300
    disc = k1 * k1 - 4.0 * k0 * k2
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
        q = -0.5 * (k1 + np.copysign(sq, k1))
        r1 = np.where(np.abs(k2) > 1e-12 * scale, q / k2, np.inf)
        r2 = np.where(np.abs(q) > 0, k0 / q, -k0 / np.where(k1 != 0, k1, np.nan))
        # Linear case: k2 == 0 gives eta = -k0 / k1, which r2 equals.
        dist1 = np.abs(r1 - np.clip(r1, 0, 1))
        dist2 = np.abs(r2 - np.clip(r2, 0, 1))
        # r2 unless r1 is strictly nearer [0, 1]; a NaN distance counts as infinitely far.
        eta = np.where(~(dist1 < dist2) & (dist2 == dist2), r2, r1)
        ax, ay = ex + gx * eta, ey + gy * eta
        xi = ((hx - fx * eta) * ax + (hy - fy * eta) * ay) / (ax * ax + ay * ay)
    return xi, eta


def _try(quad_pts, x, tol):
    local = inverse_bilinear(quad_pts, x)
    ok = np.all((local >= -tol) & (local <= 1 + tol), axis=1)
    return ok, local


class _Buckets:
    """A uniform grid over the elements' bounding boxes, ``per_element`` buckets per element.

    ``members[start[b]:start[b + 1]]`` are the elements whose bounding box
    (widened by a millionth of the mesh size) meets bucket ``b``, by index.
    """

    def __init__(self, quad_pts: np.ndarray, per_element: float = 1.0):
        lo, hi = quad_pts.min(axis=1), quad_pts.max(axis=1)
        self.origin = lo.min(axis=0)
        extent = hi.max(axis=0) - self.origin
        pad = 1e-6 * float(np.hypot(*extent)) + 1e-300
        self.cell = max(float(np.sqrt(np.prod(extent + pad) / (per_element * len(quad_pts)))), pad)
        self.shape = np.maximum(1, np.ceil((extent + pad) / self.cell).astype(np.int64))
        i0, i1 = self._cells(lo - pad), self._cells(hi + pad)
        span = i1 - i0 + 1
        count = span[:, 0] * span[:, 1]
        el = np.repeat(np.arange(len(quad_pts)), count)
        k = np.arange(len(el)) - np.repeat(np.cumsum(count) - count, count)
        bucket = (i0[el, 1] + k // span[el, 0]) * self.shape[0] + i0[el, 0] + k % span[el, 0]
        self.members = el[np.argsort(bucket, kind="stable")]
        self.start = np.concatenate(([0], np.cumsum(np.bincount(bucket, minlength=int(np.prod(self.shape))))))

    def _cells(self, x: np.ndarray) -> np.ndarray:
        return np.clip(np.floor((x - self.origin) / self.cell).astype(np.int64), 0, self.shape - 1)

    def pairs(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(point, candidate element) pairs, by point: ``(q,)`` each."""
        c = self._cells(x)
        b = c[:, 1] * self.shape[0] + c[:, 0]
        outside = np.any((x < self.origin) | (x >= self.origin + self.shape * self.cell), axis=1)
        count = np.where(outside, 0, self.start[b + 1] - self.start[b])
        p = np.repeat(np.arange(len(x)), count)
        return p, self.members[np.repeat(self.start[b] - (np.cumsum(count) - count), count) + np.arange(len(p))]


class _Boxes:
    """Every element's bounding box (widened as in :class:`_Buckets`) against every point: for few points."""

    def __init__(self, quad_pts: np.ndarray):
        lo, hi = quad_pts.min(axis=1), quad_pts.max(axis=1)
        pad = 1e-6 * float(np.hypot(*(hi.max(axis=0) - lo.min(axis=0)))) + 1e-300
        self.lo, self.hi = lo - pad, hi + pad

    def pairs(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(point, candidate element) pairs, by point: ``(q,)`` each."""
        lo, hi = self.lo, self.hi
        near = (x[:, None, 0] >= lo[:, 0]) & (x[:, None, 0] <= hi[:, 0]) & (x[:, None, 1] >= lo[:, 1]) & (x[:, None, 1] <= hi[:, 1])
        return np.nonzero(near)


def _locate_chunk(terms_of, finder, x, tol):
    """Element (-1 if none) and local coordinates of each point: its deepest candidate."""
    p, el = finder.pairs(x)  # one row per (point, candidate) pair, by point
    count = np.bincount(p, minlength=len(x))
    has = np.flatnonzero(count)
    starts = np.cumsum(count) - count
    xi, eta = _solve_xi_eta(terms_of(el), x.T[:, p])
    depth = np.minimum(np.minimum(xi, 1.0 - xi), np.minimum(eta, 1.0 - eta))
    depth[depth != depth] = -np.inf  # no real root: never the deepest
    elements = np.full(len(x), -1, dtype=np.int64)
    local = np.zeros((len(x), 2))
    if has.size:
        deepest = np.full(len(x), -np.inf)
        deepest[has] = np.maximum.reduceat(depth, starts[has])
        pair = np.where(depth == deepest[p], np.arange(len(p)), len(p))
        best = np.minimum.reduceat(pair, starts[has])
        ok = deepest[has] >= -tol
        elements[has[ok]] = el[best[ok]]
        chosen = best[ok]
        local[has[ok]] = np.column_stack((xi[chosen], eta[chosen]))
    return elements, local


def _find(points: np.ndarray, quads: np.ndarray, x: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Element (-1: none) and local coordinates of each point of ``x``: :func:`locate` without the refusal."""
    x = np.asarray(x, dtype=np.float64)
    quad_pts_all = points[quads]
    if len(x) * len(quads) <= FEW_PAIRS:  # few points: test every box, map terms of candidates only
        finder = _Boxes(quad_pts_all)

        def terms_of(el):
            return _element_terms(quad_pts_all[el])
    else:  # about one bucket per point, between 1 and MAX_BUCKETS_PER_ELEMENT per element
        finder = _Buckets(quad_pts_all, min(max(len(x) / len(quads), 1.0), MAX_BUCKETS_PER_ELEMENT))
        terms = _element_terms(quad_pts_all)

        def terms_of(el):
            return terms[:, el]
    elements = np.full(len(x), -1, dtype=np.int64)
    local = np.zeros((len(x), 2))
    for lo in range(0, len(x), CHUNK):
        part = slice(lo, lo + CHUNK)
        elements[part], local[part] = _locate_chunk(terms_of, finder, x[part], tol)
    todo = np.flatnonzero(elements < 0)
    # Exhaustive pass for the few points just outside every bucket (within the tolerance of an element whose box
    # misses them), bounded: many points outside the mesh are outside it, left unlocated for the caller to refuse
    # (1,560 such points on 27,000 elements took 55 s of CPU).
    if todo.size and todo.size * len(quads) <= MAX_EXHAUSTIVE_PAIRS:
        for i in todo:
            ok, loc = _try(quad_pts_all, np.broadcast_to(x[i], (len(quads), 2)), tol)
            if ok.any():
                # Prefer the element that contains the point most deeply.
                depth = np.min(np.minimum(loc, 1 - loc), axis=1)
                best = int(np.argmax(np.where(ok, depth, -np.inf)))
                elements[i], local[i] = best, loc[best]
    return elements, np.clip(local, 0.0, 1.0)


def locate_some(points: np.ndarray, quads: np.ndarray, x: np.ndarray, tol: float = LOCAL_TOL) -> tuple[Location, np.ndarray]:
    """Locate the points of ``x`` that lie in the mesh; arguments as :func:`locate`.

    Returns
    -------
    Location
        Of the points found, in order.
    found : (p,) bool ndarray
        Which points of ``x`` lie in an element.
    """
    elements, local = _find(points, quads, x, tol)
    found = elements >= 0
    elements, local = elements[found], local[found]
    return Location(elements, local, quads[elements], bilinear_weights(local)), found


def locate(points: np.ndarray, quads: np.ndarray, x: np.ndarray, tol: float = LOCAL_TOL) -> Location:
    """Locate each point of ``x`` in the mesh ``(points, quads)``.

    Parameters
    ----------
    points : (N, 2) float64 ndarray
        Mesh node coordinates.
    quads : (M, 4) int ndarray
        Counter-clockwise node indices of each element.
    x : (p, 2) float64 ndarray
        Points to locate.
    tol : float
        Tolerance on the local coordinates; points up to ``tol`` of an
        element's size outside it are taken as on its edge.

    Returns
    -------
    Location

    Raises
    ------
    LocateError
        Naming the first point that lies in no element.

    Examples
    --------
    >>> pts = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0]])
    >>> loc = locate(pts, np.array([[0, 1, 4, 3], [1, 2, 5, 4]]), np.array([[1.5, 0.5], [0.5, 1.0]]))
    >>> loc.elements.tolist(), place(pts, loc).tolist()
    ([1, 0], [[1.5, 0.5], [0.5, 1.0]])
    """
    elements, local = _find(points, quads, x, tol)
    missing = np.flatnonzero(elements < 0)
    if missing.size:
        i = int(missing[0])
        raise LocateError(
            f"point {i} at {np.round(np.asarray(x, dtype=np.float64)[i], 9).tolist()} lies in no element of the mesh "
            f"({missing.size} point(s) unlocated)"
        )
    local = np.clip(local, 0.0, 1.0)
    return Location(elements, local, quads[elements], bilinear_weights(local))
