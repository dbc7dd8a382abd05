"""A coarse body-fitted P2 triangle mesh of a section (own mesher, scipy + shapely only).

The contour (the section's lower nodes then its upper points, a closed
polyline) is cut into *pieces* at its corners: A, B and every vertex where
the contour turns by more than ``CORNER_DEG`` (so every corner, re-entrant
groove corners included, is a mesh node). Each piece gets equal steps of
about ``h`` along its arc length, more if it turns by more than
``PIECE_TURN_DEG`` per step. Interior nodes are a hexagonal lattice of
spacing ``h`` kept half a step away from the boundary; a Delaunay
triangulation (scipy/Qhull) of all nodes then contains every boundary
segment, or the missing segments are split and it is redone (a conforming
Delaunay mesh). Triangles outside the contour are dropped, the interior
nodes are smoothed (Laplace) while no triangle turns over, and the mid-edge
nodes of boundary edges are put on the contour (isoparametric edges).

Everything is permissively licensed: Qhull (scipy), GEOS through shapely
(already the core's dependency). No ``triangle`` or gmsh.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import Delaunay, cKDTree

from ..errors import MeshError
from ..limits import MAX_FE_VERTICES, bounded
from .elements import geometry

__all__ = ["CoarseMesh", "RingGeometry", "coarse_mesh", "CORNER_DEG", "PIECE_TURN_DEG"]

CORNER_DEG = 15.0
PIECE_TURN_DEG = 30.0
CONFORM_ITERATIONS = 40
SMOOTH_ITERATIONS = 4


@dataclass(frozen=True, eq=False)
class RingGeometry:
    """A closed polyline parametrised by arc length.

    Attributes
    ----------
    points : (N, 2) float64 ndarray
        Vertices, the closing edge implied, units.
    s : (N + 1,) float64 ndarray
        Arc length at each vertex, the first repeated at the end (``s[-1]`` is
        the perimeter), units.
    """

    points: np.ndarray
    s: np.ndarray

    @classmethod
    def of(cls, points: np.ndarray) -> RingGeometry:
        seg = np.diff(np.concatenate((points, points[:1])), axis=0)
        return cls(points, np.concatenate(([0.0], np.cumsum(np.hypot(seg[:, 0], seg[:, 1])))))

    @property
    def perimeter(self) -> float:
        return float(self.s[-1])

    def at(self, s: np.ndarray) -> np.ndarray:
        """Points at arc lengths ``s`` (taken modulo the perimeter), ``(k, 2)``."""
        closed = np.concatenate((self.points, self.points[:1]))
        s = np.mod(s, self.perimeter)
        return np.column_stack((np.interp(s, self.s, closed[:, 0]), np.interp(s, self.s, closed[:, 1])))

    def turning(self) -> np.ndarray:
        """Signed turning angle at each vertex, radians, ``(N,)``."""
        seg = np.diff(np.concatenate((self.points, self.points[:1])), axis=0)
        prev = np.roll(seg, 1, axis=0)
        return np.arctan2(prev[:, 0] * seg[:, 1] - prev[:, 1] * seg[:, 0], np.einsum("ij,ij->i", prev, seg))


@dataclass(frozen=True, eq=False)
class CoarseMesh:
    """A P2 triangle mesh fitted to a section's contour.

    Node order inside a cell follows :mod:`~sectiondeform.fem.elements`.

    Attributes
    ----------
    nodes : (N, 2) float64 ndarray
        Corner nodes first (``n_vertices`` of them, boundary vertices first in
        contour order), then mid-edge nodes, units.
    cells : (E, 6) int64 ndarray
        Counter-clockwise ``triangle6`` cells.
    n_vertices : int
        Number of corner nodes (the pressure unknowns).
    boundary_s : (b,) float64 ndarray
        Arc length along the contour of each boundary vertex (nodes ``0..b-1``),
        increasing, units.
    boundary_edges : (b, 3) int64 ndarray
        For the boundary edge from vertex j to vertex j + 1 (cyclic): its cell,
        its local edge (0, 1, 2 for cell nodes 0-1, 1-2, 2-0) and +1 when the
        cell runs along it from j to j + 1, -1 otherwise.
    ring : RingGeometry
        The contour the mesh fits.
    size : float
        Target edge length h, units.
    """

    nodes: np.ndarray
    cells: np.ndarray
    n_vertices: int
    boundary_s: np.ndarray
    boundary_edges: np.ndarray
    ring: RingGeometry
    size: float

    @property
    def n_boundary(self) -> int:
        return len(self.boundary_s)

    def boundary_nodes_between(self, s0: float, s1: float) -> tuple[np.ndarray, np.ndarray]:
        """Boundary nodes (corners and mid-edge) with arc length in ``[s0, s1]``.

        Returns
        -------
        nodes : (k,) int64 ndarray
            Node indices sorted by arc length.
        s : (k,) float64 ndarray
            Their arc lengths, units.
        """
        b = self.n_boundary
        s_end = np.append(self.boundary_s[1:], self.ring.perimeter)
        cells, local = self.boundary_edges[:, 0], self.boundary_edges[:, 1]
        mids = self.cells[cells, 3 + local]
        s_mid = 0.5 * (self.boundary_s + s_end)
        ids = np.concatenate((np.arange(b), mids))
        s = np.concatenate((self.boundary_s, s_mid))
        tol = 1e-12 * self.ring.perimeter
        keep = (s >= s0 - tol) & (s <= s1 + tol)
        order = np.argsort(s[keep], kind="stable")
        return ids[keep][order], s[keep][order]


def _boundary_positions(ring: RingGeometry, corners: np.ndarray, h: float) -> np.ndarray:
    """Arc lengths of the coarse boundary vertices: corners plus equal steps between them."""
    turn = np.abs(ring.turning())
    n = len(ring.points)
    corners = np.unique(corners)
    out = []
    for k, c in enumerate(corners):
        nxt = corners[(k + 1) % len(corners)]
        s0 = ring.s[c]
        s1 = ring.s[nxt] if nxt > c else ring.perimeter + ring.s[nxt]
        inner = np.arange(c + 1, nxt if nxt > c else nxt + n) % n
        theta = float(turn[inner].sum()) if len(inner) else 0.0
        steps = max(1, int(round((s1 - s0) / h)), math.ceil(theta / math.radians(PIECE_TURN_DEG) - 1e-9))
        out.append(s0 + (s1 - s0) * np.arange(steps) / steps)
    return np.concatenate(out)


def _lattice(poly, h: float) -> np.ndarray:
    """Hexagonal lattice points of spacing ``h`` inside ``poly`` (holes allowed), half a step off its boundary."""
    x0, y0, x1, y1 = poly.bounds
    dy = h * math.sqrt(3.0) / 2.0
    ys = np.arange(y0 + 0.5 * dy, y1, dy)
    xs = np.arange(x0 + 0.25 * h, x1 + h, h)
    gx, gy = np.meshgrid(xs, ys)
    gx = gx + 0.5 * h * (np.arange(len(ys))[:, None] % 2)
    pts = np.column_stack((gx.ravel(), gy.ravel()))
    inside = shapely.contains_xy(poly, pts[:, 0], pts[:, 1])
    pts = pts[inside]
    d = shapely.distance(poly.boundary, shapely.points(pts))  # the holes' rings too
    return pts[d >= 0.5 * h]


def _drop_encroaching(interior: np.ndarray, bpts: np.ndarray) -> np.ndarray:
    """Remove interior points inside the diametral circle of a boundary segment."""
    if not len(interior):
        return interior
    a, b = bpts, np.roll(bpts, -1, axis=0)
    mid, rad = 0.5 * (a + b), 0.5 * np.hypot(*(b - a).T)
    hits = cKDTree(interior).query_ball_point(mid, rad * 1.02)
    bad = np.unique(np.concatenate([np.asarray(h, dtype=np.int64) for h in hits] + [np.zeros(0, np.int64)]))
    return np.delete(interior, bad, axis=0)


def _signed_areas(pts: np.ndarray, tri: np.ndarray) -> np.ndarray:
    p0, p1, p2 = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    return 0.5 * ((p1[:, 0] - p0[:, 0]) * (p2[:, 1] - p0[:, 1]) - (p2[:, 0] - p0[:, 0]) * (p1[:, 1] - p0[:, 1]))


def _smooth(pts: np.ndarray, tri: np.ndarray, n_fixed: int, iterations: int) -> np.ndarray:
    """Laplace smoothing of the free nodes (index >= n_fixed) while every triangle stays positive."""
    n = len(pts)
    e = np.concatenate((tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]))
    e = np.unique(np.sort(e, axis=1), axis=0)
    i, j = np.concatenate((e[:, 0], e[:, 1])), np.concatenate((e[:, 1], e[:, 0]))
    deg = np.bincount(i, minlength=n).astype(float)
    for _ in range(iterations):
        nb = np.column_stack((np.bincount(i, weights=pts[j, 0], minlength=n), np.bincount(i, weights=pts[j, 1], minlength=n)))
        new = pts.copy()
        new[n_fixed:] = nb[n_fixed:] / deg[n_fixed:, None]
        if _signed_areas(new, tri).min() <= 0:
            break
        pts = new
    return pts


def coarse_mesh(ring_points: np.ndarray, fixed: np.ndarray, h: float) -> CoarseMesh:
    """Mesh the polygon ``ring_points`` with P2 triangles of size about ``h``.

    Parameters
    ----------
    ring_points : (N, 2) float64 ndarray
        The closed contour, either orientation, the closing edge implied,
        units. Must be simple.
    fixed : (k,) int64 ndarray
        Contour vertex indices that must be mesh nodes (e.g. A and B) on top
        of the detected corners.
    h : float
        Target edge length, units.

    Returns
    -------
    CoarseMesh

    Raises
    ------
    MeshError
        If the triangulation cannot be made to conform to the contour.

    Examples
    --------
    >>> sq = np.array([[0, 0], [4, 0], [4, 2], [0, 2]], float)
    >>> m = coarse_mesh(sq, np.array([0]), 1.0)
    >>> m.n_boundary, round(float(abs(_signed_areas(m.nodes, m.cells[:, :3]).sum())), 9)
    (12, 8.0)
    """
    if not (h > 0 and math.isfinite(h)):
        raise MeshError(f"section: the element size {h!r} is not a positive finite length; check the section's scale")
    ring = RingGeometry.of(np.asarray(ring_points, dtype=np.float64))
    poly = shapely.Polygon(ring.points)
    # Bound the mesh before building it: boundary steps plus lattice points.
    with np.errstate(all="ignore"):
        estimate = ring.perimeter / h + abs(float(shapely.area(poly))) / (h * h * math.sqrt(3.0) / 2.0)
    bounded(estimate, MAX_FE_VERTICES, "mesh vertices",
            "lower options.elements_through_thickness, or simplify the section's small features", MeshError)
    turn = np.abs(ring.turning())
    corners = np.concatenate((np.asarray(fixed, dtype=np.int64), np.flatnonzero(turn > math.radians(CORNER_DEG))))
    s_b = _boundary_positions(ring, corners, h)
    bounded(len(s_b), MAX_FE_VERTICES, "mesh boundary vertices",
            "simplify the section's sharp corners or lower options.elements_through_thickness", MeshError)
    interior = _lattice(poly, h)
    for _ in range(CONFORM_ITERATIONS):
        # Each pass splits the missing segments: bound the vertices before building them.
        bounded(len(s_b) + len(interior), MAX_FE_VERTICES, "mesh vertices (conforming to the contour)",
                "simplify the section's small features or lower options.elements_through_thickness", MeshError)
        bpts = ring.at(s_b)
        interior = _drop_encroaching(interior, bpts)
        pts = np.concatenate((bpts, interior))
        tri = Delaunay(pts).simplices
        nb = len(s_b)
        seg = np.column_stack((np.arange(nb), (np.arange(nb) + 1) % nb))
        e = np.concatenate((tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]))
        key = lambda a: np.minimum(a[:, 0], a[:, 1]) * len(pts) + np.maximum(a[:, 0], a[:, 1])  # noqa: E731, B023 - used in this iteration only
        missing = ~np.isin(key(seg), key(e))
        if not missing.any():
            break
        s_end = np.append(s_b[1:], ring.perimeter)
        s_b = np.sort(np.concatenate((s_b, 0.5 * (s_b + s_end)[missing])))
    else:
        raise MeshError(f"section: the coarse mesh (h = {h:.4g}) does not conform to the contour; try a finer one")
    centroid = pts[tri].mean(axis=1)
    flat = np.abs(_signed_areas(pts, tri)) <= 1e-9 * h * h  # collinear hull points
    tri = tri[shapely.contains_xy(poly, centroid[:, 0], centroid[:, 1]) & ~flat]
    areas = _signed_areas(pts, tri)
    tri[areas < 0] = tri[areas < 0][:, [0, 2, 1]]
    if not math.isclose(float(np.abs(areas).sum()), abs(shapely.area(shapely.Polygon(bpts))), rel_tol=1e-9):
        raise MeshError(f"section: the coarse mesh (h = {h:.4g}) does not cover the contour exactly")
    used = np.zeros(len(pts), bool)
    used[tri] = True
    if not used.all():  # interior lattice points cut off by the contour
        remap = np.cumsum(used) - 1
        pts, tri = pts[used], remap[tri]
    pts = _smooth(pts, tri, nb, SMOOTH_ITERATIONS)
    nodes, cells, edges = _add_midnodes(pts, tri, nb, s_b, ring)
    return CoarseMesh(nodes, cells, len(pts), s_b, edges, ring, float(h))


def _add_midnodes(pts, tri, nb, s_b, ring):
    nv = len(pts)
    local = np.array([[0, 1], [1, 2], [2, 0]])
    e = tri[:, local]  # (E, 3, 2)
    lo, hi = e.min(axis=2), e.max(axis=2)
    uniq, inv = np.unique((lo * nv + hi).ravel(), return_inverse=True)
    inv = inv.reshape(-1, 3)
    a, b = uniq // nv, uniq % nv
    mid = 0.5 * (pts[a] + pts[b])
    count = np.bincount(inv.ravel(), minlength=len(uniq))
    # Boundary edges: vertex j to j + 1 (cyclic); put their mid-nodes on the contour.
    s_end = np.append(s_b[1:], ring.perimeter)
    j = np.arange(nb)
    jn = (j + 1) % nb
    bkey = np.minimum(j, jn) * nv + np.maximum(j, jn)
    bid = np.minimum(np.searchsorted(uniq, bkey), len(uniq) - 1)
    if not (np.all(uniq[bid] == bkey) and np.all(count[bid] == 1)):
        raise MeshError("section: the coarse mesh's boundary edges do not follow the contour")
    mid[bid] = ring.at(0.5 * (s_b + s_end))
    cells = np.column_stack((tri, nv + inv)).astype(np.int64)
    nodes = np.concatenate((pts, mid))
    g = geometry(nodes, cells)
    bad = np.flatnonzero(g.detj_ratio < 0.2)
    if len(bad):  # a mid-node on a tight curve: straighten that element's boundary edges
        straight = np.isin(bid, inv[bad].ravel())
        nodes[nv + bid[straight]] = 0.5 * (pts[j[straight]] + pts[jn[straight]])
    # Which cell holds each boundary edge, its local edge and its direction.
    flat = inv.ravel()
    where = np.full(len(uniq), -1)
    where[flat] = np.arange(len(flat))
    pos = where[bid]
    cell, loc = pos // 3, pos % 3
    first = tri[cell, local[loc, 0]]
    direction = np.where(first == j, 1, -1)
    return nodes, cells, np.column_stack((cell, loc, direction)).astype(np.int64)
