"""One P2 triangle mesh of several bodies that share pieces of their contours.

The contours (closed polylines, one per body, and the rings of its holes) are merged into one planar
graph: contour points closer than a tolerance become one *vertex*, and the
contour edges between vertices its edges, each kept once. A piece shared by
two bodies is then one run of edges. The graph is cut into *chains* at its
corners: vertices met by other than two edges (where pieces meet), vertices
where it turns by more than :data:`CORNER_DEG`, and
the points asked for (each body's A and B). Every chain gets mesh nodes at
equal steps of about ``h`` along its arc length (more where it turns), the
same nodes for both bodies of a shared piece. Interior nodes are a
hexagonal lattice per body, half a step off its contour; a Delaunay
triangulation of all nodes is made to contain every chain segment by
splitting the missing ones (a conforming Delaunay mesh). Each
triangle is tagged with the body holding its centroid (a triangle inside a
hole belongs to none and is dropped); the interior nodes
are smoothed while no triangle turns over; mid-edge nodes of chain segments
are put on the chain (isoparametric edges).

Every vertex (contour point) is located on a chain segment, so that
:func:`~sectiondeform.fem.mapping.edge_weights` gives its image from the
solved node positions: a vertex shared by two bodies has one image.

The displacement is shared across the bodies' interfaces (bonded), the
pressure is not: each body has its own P1 pressure unknowns
(:func:`body_pressure_cells`), so the pressure is continuous within a body
and jumps across an interface between bodies of different stiffness, as the
exact one does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import shapely
from scipy.sparse.csgraph import connected_components
from scipy.spatial import Delaunay, cKDTree

from ..errors import MeshError
from ..limits import MAX_FE_VERTICES, bounded
from .elements import geometry
from .mapping import edge_weights

__all__ = ["UnionMesh", "Chain", "union_mesh", "body_pressure_cells", "vertex_estimate", "SizeField"]


CORNER_DEG = 15.0
"""A contour turning by more than this at a point makes it a corner: a mesh node, where chains are cut."""
PIECE_TURN_DEG = 30.0
"""A chain's steps are shortened so that none turns by more than this."""
CONFORM_ITERATIONS = 40
"""Passes of the conforming loop (split the segments Delaunay missed, triangulate again) at most."""
SMOOTH_ITERATIONS = 4
"""Laplace smoothing passes of the interior nodes (each kept only while no triangle turns over)."""
SLIVER = 1e-7
"""A triangle whose height is under this fraction of its longest edge is a sliver (:func:`_mend_slivers`)."""


@dataclass(frozen=True, eq=False)
class Chain:
    """A run of graph edges between two corners, with its mesh nodes.

    Attributes
    ----------
    vertices : (k,) int64 ndarray
        Graph vertices along the chain, corner to corner.
    s : (k,) float64 ndarray
        Arc length at each vertex, from 0, units.
    node_s : (j,) float64 ndarray
        Arc length of each mesh node on the chain, from 0 to ``s[-1]``, units.
    nodes : (j,) int64 ndarray
        Their mesh node indices.
    mids : (j - 1,) int64 ndarray
        Mid-edge node of each segment between consecutive nodes.
    """

    vertices: np.ndarray
    s: np.ndarray
    node_s: np.ndarray
    nodes: np.ndarray
    mids: np.ndarray


@dataclass(frozen=True, eq=False)
class UnionMesh:
    """A P2 mesh of several bodies with shared nodes on shared pieces.

    Attributes
    ----------
    nodes : (N, 2) float64 ndarray
        Corner nodes first (chain nodes, then interior), then mid-edge nodes, units.
    cells : (E, 6) int64 ndarray
        Counter-clockwise ``triangle6`` cells.
    body : (E,) int64 ndarray
        The body of each cell.
    n_vertices : int
        Number of corner nodes.
    points : (V, 2) float64 ndarray
        The graph's vertices: the contour points, merged, units.
    rings : tuple of (k_b,) int64 ndarray
        Each body's contour as vertex indices, in the order given.
    chains : tuple of Chain
    edge_chain : dict
        ``(min(u, w), max(u, w))`` of a graph edge -> its chain's index.
    vertex_weights : (V, N) scipy.sparse.csr_matrix
        Image of every vertex from the node positions.
    size : float
        Target edge length h, units (the smallest anywhere).
    cell_size : (E,) float64 ndarray
        Each cell's target edge length, units: its body's size, or the
        fine size near the body's fine zone (:class:`SizeField`).
    pressure_cells : (E, 3) int64 ndarray
        The pressure unknown at each cell's corners: one per body at each
        corner node (:func:`body_pressure_cells`).
    n_pressures : int
        Number of pressure unknowns: ``n_vertices`` plus one for every
        further body at a corner node shared by several.
    holes : tuple of tuple of (k,) int64 ndarray
        Per body, each hole's ring as vertex indices, in the order given.
    """

    nodes: np.ndarray
    cells: np.ndarray
    body: np.ndarray
    n_vertices: int
    points: np.ndarray
    rings: tuple
    chains: tuple
    edge_chain: dict
    vertex_weights: sp.csr_matrix
    size: float
    cell_size: np.ndarray
    pressure_cells: np.ndarray
    n_pressures: int
    holes: tuple = ()

    def chain_of(self, u: int, w: int) -> int:
        """Index of the chain holding the graph edge ``u``-``w``."""
        return self.edge_chain[(min(u, w), max(u, w))]


def _merge(rings, tol: float):
    """Contour points merged within ``tol``: the vertices and each ring as vertex indices."""
    pts = np.concatenate(rings)
    pairs = cKDTree(pts).query_pairs(tol, output_type="ndarray")
    n = len(pts)
    graph = sp.coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n)) if len(pairs) else sp.coo_matrix((n, n))
    _, label = connected_components(graph, directed=False)
    _, first, inverse = np.unique(label, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")  # vertices numbered by first appearance
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    ids = rank[inverse]
    vertices = pts[np.sort(first)]
    out, k = [], 0
    for r in rings:
        out.append(ids[k : k + len(r)])
        k += len(r)
    return vertices, out


def _chains(points, rings, fixed):
    """Cut the graph of the rings' edges into chains between corners: lists of vertex indices.

    A corner is a fixed vertex, a vertex with other than two neighbours, or
    one where the contour turns by more than :data:`CORNER_DEG`. The graph's
    edges and the corners are found with whole-array operations; the walk
    along each chain, from the corners in increasing order (then from any
    vertex of a loop without corners), follows each vertex's neighbours in
    increasing order.
    """
    n = len(points)
    pairs = [np.column_stack((r, np.roll(r, -1))) for r in rings if len(r)]
    pairs = np.concatenate(pairs).astype(np.int64) if pairs else np.zeros((0, 2), np.int64)
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    keys = np.unique(_edge_keys(pairs, n))
    lo, hi = keys // n, keys % n
    # Each vertex's neighbours in the order of the sorted edges (u < w): by (min, max) of the edge.
    ends = np.concatenate((lo, hi))
    others = np.concatenate((hi, lo))
    order = np.lexsort((np.concatenate((keys, keys)), ends))
    ends, others = ends[order], others[order]
    present, start, degree = np.unique(ends, return_index=True, return_counts=True)
    corner = np.zeros(n, bool)
    corner[np.asarray(fixed, dtype=np.int64)] = True
    corner[present[degree != 2]] = True
    two = present[degree == 2]
    if len(two):
        first = others[start[degree == 2]]
        second = others[start[degree == 2] + 1]
        a, b = points[two] - points[first], points[second] - points[two]
        turn = np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b)))
        corner[two[turn > math.radians(CORNER_DEG)]] = True
    in_graph = np.zeros(n, bool)
    in_graph[present] = True
    corner &= in_graph
    adj = {v: nb.tolist() for v, nb in zip(present.tolist(), np.split(others, start[1:]))}
    is_corner = corner.tolist()
    walked = [False] * n  # a vertex inside a chain already walked (each is inside one chain)
    end_edges, chains = set(), []  # each walked chain's first and last edges, (min, max)
    for c in np.flatnonzero(corner).tolist() + present.tolist():  # a loop without corners starts anywhere
        for nxt in adj[c]:
            if (walked[nxt] and not is_corner[nxt]) or (min(c, nxt), max(c, nxt)) in end_edges:
                continue
            is_corner[c] = True
            path = [c, nxt]
            prev, v = c, nxt
            while not is_corner[v]:
                walked[v] = True
                nb = adj[v]
                prev, v = v, (nb[0] if nb[0] != prev else nb[1])
                path.append(v)
            end_edges.add((min(c, nxt), max(c, nxt)))
            end_edges.add((min(prev, v), max(prev, v)))
            chains.append(path)
    return chains, np.flatnonzero(is_corner).tolist()


def vertex_estimate(polygons, sizes) -> float:
    """About how many vertices :func:`union_mesh` gives ``polygons`` (shapely) at element ``sizes`` ``(B,)``, units.

    A contour step per size along each outline, a hexagonal lattice point per
    ``h² √3 / 2`` of area.
    """
    return sum(float(p.length) / h + abs(float(p.area)) / (h * h * math.sqrt(3.0) / 2.0) for p, h in zip(polygons, sizes))


def _edge_keys(pairs: np.ndarray, n: int) -> np.ndarray:
    return np.minimum(pairs[:, 0], pairs[:, 1]) * n + np.maximum(pairs[:, 0], pairs[:, 1])


def _steps(pts: np.ndarray, h: float) -> int:
    seg = np.diff(pts, axis=0)
    length = float(np.hypot(*seg.T).sum())
    theta = 0.0
    if len(seg) > 1:
        theta = float(np.abs(np.arctan2(seg[:-1, 0] * seg[1:, 1] - seg[:-1, 1] * seg[1:, 0],
                                        np.einsum("ij,ij->i", seg[:-1], seg[1:]))).sum())
    return max(1, int(round(length / h)), math.ceil(theta / math.radians(PIECE_TURN_DEG) - 1e-9))  # h = inf: the turns' count


def _at(pts: np.ndarray, s: np.ndarray, at: np.ndarray) -> np.ndarray:
    return np.column_stack((np.interp(at, s, pts[:, 0]), np.interp(at, s, pts[:, 1])))


STALL_ITERATIONS = 3
"""Passes of the conforming loop without fewer missing segments than its best, after which it gives up."""


def _blocked_message(bpts: np.ndarray, missing: np.ndarray, h: float) -> str:
    """Why contour segments stay out of the triangulation: where, and the contour node in the way if there is one."""
    a, b = bpts[missing[:, 0]], bpts[missing[:, 1]]
    mid, rad = 0.5 * (a + b), 0.5 * np.hypot(*(b - a).T)
    tree = cKDTree(bpts)
    for i, near in enumerate(tree.query_ball_point(mid, rad * (1 + 1e-9))):
        others = [j for j in near if j not in (missing[i, 0], missing[i, 1])]
        if others:
            p = bpts[others[0]]
            return (f"mesh: the mesh (h = {h:.4g}) cannot follow the contour segment ({a[i, 0]:.6g}, {a[i, 1]:.6g})-"
                    f"({b[i, 0]:.6g}, {b[i, 1]:.6g}): the contour point ({p[0]:.6g}, {p[1]:.6g}) of another piece lies "
                    "on it or next to it; let touching bodies share their points there (or keep them apart)")
    return (f"mesh: the mesh (h = {h:.4g}) cannot be made to follow {len(missing)} contour segment(s), the first "
            f"({a[0, 0]:.6g}, {a[0, 1]:.6g})-({b[0, 0]:.6g}, {b[0, 1]:.6g}), however they are split; "
            "check that the bodies' contours do not cross or touch without sharing their points")


GRADING = 0.5
"""How fast the target size grows away from a fine zone: this much per unit of distance (:class:`SizeField`)."""


class SizeField:
    """The mesh's target edge length at points: each body's size, finer near its fine zone.

    At a distance ``d`` from body ``b``'s zone the size is
    ``h_b / 2**k``, the power of two just under ``min(h_b, h_b / ratio +
    GRADING * d)``: ``h_b / ratio`` on the zone, coarser by halvings away
    from it, ``h_b`` from about ``h_b / GRADING`` on.

    Parameters
    ----------
    sizes : (B,) float64 ndarray
        Each body's element size h_b, units.
    fine : sequence of (shapely geometry or None), or None
        Per body, where it is meshed finer.
    ratio : int
        The size on a zone is the body's over this: 1, 2, 4 or 8.
    origin : (2,) float64 ndarray
        Subtracted from the geometries' coordinates (the mesh's own origin).
    """

    def __init__(self, sizes: np.ndarray, fine, ratio: int, origin: np.ndarray):
        self.sizes = np.asarray(sizes, dtype=np.float64)
        if ratio not in (1, 2, 4, 8):
            raise ValueError(f"fine_ratio: {ratio!r} is not 1, 2, 4 or 8")
        self.levels = int(ratio).bit_length() - 1
        zones = [None] * len(self.sizes) if fine is None or ratio == 1 else list(fine)
        if len(zones) != len(self.sizes):
            raise ValueError(f"fine: {len(zones)} zones for {len(self.sizes)} bodies")
        self.zones = [None if z is None or shapely.is_empty(z) else shapely.transform(z, lambda c: c - origin) for z in zones]
        for z in self.zones:
            if z is not None:
                shapely.prepare(z)
        self.smallest = float(min(h / 2 ** (self.levels if z is not None else 0) for h, z in zip(self.sizes, self.zones)))

    def graded(self, bodies) -> bool:
        """Whether any of ``bodies`` has a fine zone."""
        return any(self.zones[b] is not None for b in bodies)

    def level(self, b: int, q: np.ndarray) -> np.ndarray:
        """Halvings of body ``b``'s size at points ``q`` ``(n, 2)``, ``(n,)`` int64 (0 far from its zone)."""
        if self.zones[b] is None:
            return np.zeros(len(q), np.int64)
        h = self.sizes[b]
        want = np.minimum(h, h / 2 ** self.levels + GRADING * shapely.distance(self.zones[b], shapely.points(q)))
        return np.clip(np.ceil(np.log2(h / want) - 1e-9), 0, self.levels).astype(np.int64)

    def at(self, q: np.ndarray, bodies) -> np.ndarray:
        """The smallest target size of ``bodies`` at points ``q`` ``(n, 2)``, ``(n,)`` float64, units."""
        out = np.full(len(q), np.inf)
        for b in bodies:
            out = np.minimum(out, self.sizes[b] / 2.0 ** self.level(b, q))
        return out


def _node_s(p: np.ndarray, s: np.ndarray, h: float, size_at=None) -> np.ndarray:
    """Arc lengths of a chain's mesh nodes ``(n + 1,)``, from 0 to ``s[-1]``: steps of about ``h``, or of ``size_at``.

    ``size_at`` maps points ``(m, 2)`` to target sizes ``(m,)``; the steps
    then follow it (equal steps of its inverse integrated along the chain).
    Either way a step turns by at most :data:`PIECE_TURN_DEG`.
    """
    length = float(s[-1])
    if size_at is None:
        n = _steps(p, h)
        ns = length * np.arange(n + 1) / n
    else:
        t = np.linspace(0.0, length, max(2, math.ceil(4.0 * length / h) + 1))
        density = 1.0 / size_at(_at(p, s, t))
        count = np.concatenate(([0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(t))))
        n = max(_steps(p, math.inf), int(round(float(count[-1]))))
        ns = np.interp(np.arange(n + 1) * (count[-1] / n), count, t)
    ns[0], ns[-1] = 0.0, length  # exactly the chain's ends (a ring's outline picks its nodes by arc length)
    return ns


def _graded_lattice(poly, field: SizeField, b: int) -> np.ndarray:
    """Body ``b``'s interior points: lattices of halved sizes where its :class:`SizeField` asks for them.

    Each level's lattice is kept where the field's level is its own; a
    coarser point crowding a finer level's points (nearer than half its
    step) is dropped.
    """
    h = float(field.sizes[b])
    if field.zones[b] is None:
        return _lattice(poly, h)
    kept = np.zeros((0, 2))
    zx0, zy0, zx1, zy1 = field.zones[b].bounds
    for k in range(field.levels, -1, -1):  # finest first
        # Level k (> 0) lies nearer the zone than GRADING * d = h / 2**(k - 1) - h / 2**levels: its lattice is
        # made over the zone's box grown by that alone (the same points as over the whole body, a fraction of them).
        reach = (h / 2 ** (k - 1) - h / 2**field.levels) / GRADING if k else math.inf
        pts = _lattice(poly, h / 2**k, (zx0 - reach, zy0 - reach, zx1 + reach, zy1 + reach))
        pts = pts[field.level(b, pts) == k]
        if len(kept) and len(pts):
            pts = pts[cKDTree(kept).query(pts)[0] >= 0.5 * h / 2**k]
        kept = np.concatenate((kept, pts))
    return kept


def _lattice(poly, h: float, window=None) -> np.ndarray:
    """Hexagonal lattice points of spacing ``h`` inside ``poly`` (holes allowed), half a step off its boundary.

    ``window`` ``(x0, y0, x1, y1)``, units: only the points within it (the
    same points as without it, the lattice anchored at ``poly``'s bounds).
    """
    x0, y0, x1, y1 = poly.bounds
    dy = h * math.sqrt(3.0) / 2.0
    ys = np.arange(y0 + 0.5 * dy, y1, dy)
    xs = np.arange(x0 + 0.25 * h, x1 + h, h)
    rows = np.arange(len(ys))
    if window is not None:
        rows = rows[(ys >= window[1]) & (ys <= window[3])]
        xs = xs[(xs >= window[0] - h) & (xs <= window[2])]
    gx, gy = np.meshgrid(xs, ys[rows])
    gx = gx + 0.5 * h * (rows[:, None] % 2)
    pts = np.column_stack((gx.ravel(), gy.ravel()))
    inside = shapely.contains_xy(poly, pts[:, 0], pts[:, 1])
    pts = pts[inside]
    d = shapely.distance(poly.boundary, shapely.points(pts))  # the holes' rings too
    return pts[d >= 0.5 * h]


def _mend_slivers(pts: np.ndarray, tri: np.ndarray, body: np.ndarray, seg_keys: set) -> tuple[np.ndarray, np.ndarray]:
    """``(tri, body)`` without slivers: ``tri`` ``(T, 3)`` counter-clockwise and each triangle's body ``(T,)``.

    Delaunay joins chain nodes on a straight piece of contour into
    triangles of no height where that piece lies on the points' hull (a fan
    from one node along the piece). Their area is rounding, of either sign,
    their shape functions undefined, and their centroids fall on the
    contour, inside a body or not. A sliver whose longest edge no other
    triangle shares lies outside the body, along its contour: it is dropped
    (and the next of its fan with it, pass after pass). One sharing its
    longest edge ``(u, w)`` with a triangle ``(w, u, q)`` of its body is
    flipped with it into ``(u, m, q)`` and ``(m, w, q)`` (the same area,
    both proper), unless that edge is a contour segment (``seg_keys``:
    :func:`_edge_keys` of the contour's segments). At most ten passes.
    """
    n = len(pts)
    for _ in range(10):
        p = pts[tri]
        edges = p[:, [1, 2, 0]] - p  # edge k runs from corner k to corner k + 1
        length2 = (edges * edges).sum(axis=2)
        longest = length2.argmax(axis=1)
        slivers = np.flatnonzero(np.abs(_signed_areas(pts, tri)) <= 0.5 * SLIVER * length2.max(axis=1))
        if not len(slivers):
            break
        keys = _edge_keys(np.concatenate((tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]])), n)
        owner = {}
        for i, key in enumerate(keys.tolist()):
            owner.setdefault(key, []).append(i % len(tri))
        done, drop = set(), []
        for s in slivers.tolist():
            k = int(longest[s])
            u, w, m = int(tri[s, k]), int(tri[s, (k + 1) % 3]), int(tri[s, (k + 2) % 3])
            key = min(u, w) * n + max(u, w)
            others = [t for t in owner.get(key, []) if t != s]
            if not others and key not in seg_keys:
                drop.append(s)
                continue
            if s in done or len(others) != 1 or others[0] in done or key in seg_keys or body[others[0]] != body[s]:
                continue
            t = others[0]
            q = int(next(v for v in tri[t] if v not in (u, w)))
            new = np.array([[u, m, q], [m, w, q]])
            a = _signed_areas(pts, new)
            new[a < 0] = new[a < 0][:, [0, 2, 1]]
            if np.abs(a).min() <= 0.5 * SLIVER * length2[t].max():
                continue
            tri[s], tri[t] = new
            done.update((s, t))
        if not drop and not done:
            break
        keep = np.ones(len(tri), bool)
        keep[drop] = False
        tri, body = tri[keep], body[keep]
    return tri, body


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


def union_mesh(rings, fixed, h, tol: float, holes=None, fine=None, fine_ratio: int = 2) -> UnionMesh:
    """Mesh several bodies, given by their contours, with P2 triangles of size about ``h`` (per body).

    Parameters
    ----------
    rings : sequence of (k_b, 2) float64 ndarray
        Each body's closed contour (closing edge implied), either
        orientation, units. Contours may share pieces (the same points
        within ``tol``); their interiors must not overlap.
    fixed : sequence of (j_b,) int64 ndarray
        Per body, contour indices that must be mesh nodes (its A and B).
    h : float or (B,) float64 array_like
        Target edge length, units, for all bodies or per body. A piece of
        contour shared by bodies of different sizes takes the smallest.
    tol : float
        Contour points closer than this are one point, units.
    holes : sequence of sequence of (k, 2) float64 ndarray, optional
        Per body, the closed rings of its holes (inside its contour, apart
        from it and from each other): their boundaries are chains like the
        contours', no triangle lies inside them.
    fine : sequence of (shapely geometry or None), optional
        Per body, where it is meshed finer (for instance the pieces of its
        contour a rigid part will press): the contour and the lattice take
        the body's size over ``fine_ratio`` there, coarser by halvings away
        from it (:class:`SizeField`).
    fine_ratio : int
        1, 2, 4 or 8.

    Returns
    -------
    UnionMesh

    Raises
    ------
    MeshError
        If the triangulation cannot be made to conform, or does not cover
        every body exactly.

    Examples
    --------
    >>> low = np.array([[0, 0], [2, 0], [2, 1], [0, 1]], float)
    >>> top = np.array([[0, 1], [2, 1], [2, 2], [0, 2]], float)
    >>> m = union_mesh([low, top], [np.array([0, 1]), np.array([0, 1])], 0.5, 1e-9)
    >>> [round(float(_signed_areas(m.nodes, m.cells[m.body == b, :3]).sum()), 9) for b in (0, 1)]
    [2.0, 2.0]
    """
    rings = [np.asarray(r, dtype=np.float64) for r in rings]
    # Mesh about the bodies' first point: far from the origin, small features lose their digits to Qhull and
    # to the areas' cross products (a 0.06 mm body at 1e5 mm looped in the conforming splits, then met no area).
    origin = rings[0][0].copy() if len(rings) and len(rings[0]) else np.zeros(2)
    rings = [r - origin for r in rings]
    holes = [[np.asarray(r, dtype=np.float64) - origin for r in hb] for hb in holes] if holes is not None else [[] for _ in rings]
    sizes = np.broadcast_to(np.asarray(h, dtype=np.float64), (len(rings),))
    if not (np.all(sizes > 0) and np.all(np.isfinite(sizes))):
        raise MeshError(f"mesh: the element sizes {sizes.tolist()!r} are not positive finite lengths; check the bodies' scale")
    field = SizeField(sizes, fine, fine_ratio, origin)
    h = field.smallest
    polys = [shapely.Polygon(r, hb) for r, hb in zip(rings, holes)]
    with np.errstate(all="ignore"):
        estimate = vertex_estimate(polys, sizes)
    bounded(estimate, MAX_FE_VERTICES, "mesh vertices",
            "lower options.elements_through_thickness, or simplify the bodies' small features", MeshError)
    hole_owner = [b for b, hb in enumerate(holes) for _ in hb]
    # Holes lie apart from every contour and from each other (the layout checks it): their points are vertices of
    # their own, never merged. Merged within ``tol`` like the contours', the ~1000 points of a small circle (1e-4 of
    # the bodies' size across) would run together into one vertex, and the hole would vanish from the mesh.
    points, ids = _merge(rings, tol)
    hole_ids, start = [], len(points)
    for r in (r for hb in holes for r in hb):
        hole_ids.append(np.arange(start, start + len(r)))
        start += len(r)
    points = np.concatenate([points] + [r for hb in holes for r in hb])
    all_ids = list(ids) + hole_ids
    fixed_v = np.concatenate([ids[b][np.asarray(f, dtype=np.int64)] for b, f in enumerate(fixed)])
    paths, corners = _chains(points, all_ids, fixed_v)
    # Each graph edge and a body it bounds, (key, body) pairs once each: a chain bounds its edges' bodies.
    owned = [*enumerate(ids), *zip(hole_owner, hole_ids)]
    n_bodies = len(rings)
    edge_body = np.unique(np.concatenate(
        [_edge_keys(np.column_stack((r, np.roll(r, -1))), len(points)) * n_bodies + b for b, r in owned]))
    edge_key, edge_owner = edge_body // n_bodies, edge_body % n_bodies
    geo = []
    for path in paths:
        p = points[path]
        s = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))))
        keys = _edge_keys(np.column_stack((path[:-1], path[1:])), len(points))
        bodies = np.unique(edge_owner[np.isin(edge_key, keys)]).tolist()
        h_chain = float(field.sizes[bodies].min())
        ns = _node_s(p, s, h_chain, (lambda q, bodies=bodies: field.at(q, bodies)) if field.graded(bodies) else None)
        geo.append((np.asarray(path), s, ns))
    interior = np.concatenate([_graded_lattice(p, field, b) for b, p in enumerate(polys)] + [np.zeros((0, 2))])
    corner_index = {v: k for k, v in enumerate(corners)}
    best, stalled = math.inf, 0
    for _ in range(CONFORM_ITERATIONS):
        # Chain nodes: corners first, then each chain's inner nodes in order.
        bpts = [points[corners]]
        chain_nodes, k = [], len(corners)
        for path, s, ns in geo:
            inner = _at(points[path], s, ns[1:-1])
            bpts.append(inner)
            chain_nodes.append(np.concatenate(([corner_index[path[0]]], np.arange(k, k + len(inner)), [corner_index[path[-1]]])))
            k += len(inner)
        bpts = np.concatenate(bpts)
        nb = len(bpts)
        seg = np.concatenate([np.column_stack((c[:-1], c[1:])) for c in chain_nodes])
        mid = 0.5 * (bpts[seg[:, 0]] + bpts[seg[:, 1]])
        rad = 0.5 * np.hypot(*(bpts[seg[:, 1]] - bpts[seg[:, 0]]).T)
        if len(interior):
            hits = cKDTree(interior).query_ball_point(mid, rad * 1.02)
            bad = np.unique(np.concatenate([np.asarray(x, dtype=np.int64) for x in hits] + [np.zeros(0, np.int64)]))
            interior = np.delete(interior, bad, axis=0)
        pts = np.concatenate((bpts, interior))
        bounded(len(pts), MAX_FE_VERTICES, f"mesh vertices (h = {h:.4g}, splitting the contour segments the "
                "triangulation misses)", "lower options.elements_through_thickness, or simplify the bodies' small "
                "features", MeshError, "mesh")
        tri = Delaunay(pts).simplices
        e = np.concatenate((tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]))
        missing = ~np.isin(_edge_keys(seg, len(pts)), _edge_keys(e, len(pts)))
        if not missing.any():
            break
        count = int(missing.sum())
        best, stalled = (count, 0) if count < best else (best, stalled + 1)
        if stalled >= STALL_ITERATIONS:  # halving does not help: something other than lattice points blocks them
            raise MeshError(_blocked_message(bpts, seg[missing], h))
        start = 0
        for c, (path, s, ns) in enumerate(geo):
            m = missing[start : start + len(ns) - 1]
            start += len(ns) - 1
            if m.any():
                geo[c] = (path, s, np.sort(np.concatenate((ns, 0.5 * (ns[:-1] + ns[1:])[m]))))
    else:
        raise MeshError(f"mesh: the mesh (h = {h:.4g}) does not conform to the bodies' contours; try a finer one")
    centroid = pts[tri].mean(axis=1)
    flat = np.abs(_signed_areas(pts, tri)) <= 1e-9 * h * h
    body = np.full(len(tri), -1)
    for b, p in enumerate(polys):
        inside = shapely.contains_xy(p, centroid[:, 0], centroid[:, 1]) & (body < 0)
        body[inside] = b
    keep = (body >= 0) & ~flat
    tri, body = tri[keep], body[keep]
    areas = _signed_areas(pts, tri)
    tri[areas < 0] = tri[areas < 0][:, [0, 2, 1]]
    seg_keys = _edge_keys(seg, len(pts))
    tri, body = _mend_slivers(pts, tri, body, set(seg_keys.tolist()))
    if not np.isin(seg_keys, _edge_keys(np.concatenate((tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]])), len(pts))).all():
        raise MeshError(f"mesh: the mesh (h = {h:.4g}) leaves a contour segment without an element (a sliver along a "
                        "straight piece of contour); try another options.elements_through_thickness")
    areas = _signed_areas(pts, tri)
    for b, ring in enumerate(ids):
        want = abs(float(shapely.area(shapely.Polygon(bpts[_ring_nodes(ring, geo, chain_nodes)])))) - sum(
            abs(float(shapely.area(shapely.Polygon(bpts[_ring_nodes(r, geo, chain_nodes)]))))
            for r, o in zip(hole_ids, hole_owner) if o == b)
        got = float(np.abs(areas[body == b]).sum())
        if not math.isclose(got, want, rel_tol=1e-9):
            raise MeshError(f"mesh: the mesh (h = {h:.4g}) does not cover body {b} exactly ({got:.9g} for {want:.9g})")
    used = np.zeros(len(pts), bool)
    used[tri] = True
    if not used.all():
        remap = np.cumsum(used) - 1
        pts, tri = pts[used], remap[tri]  # chain nodes come first and are all used
    pts = _smooth(pts, tri, nb, SMOOTH_ITERATIONS)
    nodes, cells, edge_cell = _midnodes(pts, tri)
    chains = []
    nv = len(pts)
    for (path, s, ns), cn in zip(geo, chain_nodes):
        keys = np.minimum(cn[:-1], cn[1:]) * nv + np.maximum(cn[:-1], cn[1:])
        cell, loc = edge_cell(keys)
        mids = cells[cell, 3 + loc]
        nodes[mids] = _at(points[path], s, 0.5 * (ns[:-1] + ns[1:]))  # on the contour
        chains.append(Chain(path, s, ns, cn, mids))
    g = geometry(nodes, cells)
    bad = np.flatnonzero(g.detj_ratio < 0.2)
    if len(bad):  # a mid-node on a tight curve: straighten that element's edges
        corner = cells[bad, :3]
        pairs = np.array([[0, 1], [1, 2], [2, 0]])
        nodes[cells[bad, 3:]] = 0.5 * (nodes[corner[:, pairs[:, 0]]] + nodes[corner[:, pairs[:, 1]]])
    edge_chain = {}
    for c, ch in enumerate(chains):
        for u, w in zip(ch.vertices[:-1], ch.vertices[1:]):
            edge_chain[(min(int(u), int(w)), max(int(u), int(w)))] = c
    weights = _vertex_weights(nodes, cells, nv, points, chains, edge_cell)
    body = body.astype(np.int64)
    pressure_cells, n_pressures = body_pressure_cells(cells, body, nv)
    per_body = tuple(tuple(r for r, o in zip(hole_ids, hole_owner) if o == b) for b in range(len(rings)))
    centroid = nodes[cells[:, :3]].mean(axis=1)
    cell_size = np.empty(len(cells))
    for b in range(len(rings)):
        on = body == b
        cell_size[on] = field.at(centroid[on], [b])
    nodes += origin
    points = points + origin
    return UnionMesh(nodes, cells, body, nv, points, tuple(ids), tuple(chains), edge_chain, weights, float(h), cell_size,
                     pressure_cells, n_pressures, per_body)


def body_pressure_cells(cells: np.ndarray, body: np.ndarray, n_vertices: int) -> tuple[np.ndarray, int]:
    """One P1 pressure unknown per body at each corner node: continuous within a body, not across bodies.

    A corner node of one body keeps its own index as its pressure unknown; at
    a node shared by several bodies the lowest-numbered body keeps it and
    each other body gets a new unknown, numbered from ``n_vertices`` on in
    the order of (node, body). A one-body mesh's unknowns are its corner
    nodes, ``cells[:, :3]``.

    Parameters
    ----------
    cells : (E, 6) int64 ndarray
        P2 cells, their corner nodes first (numbered ``0 .. n_vertices - 1``).
    body : (E,) int64 ndarray
        The body of each cell.
    n_vertices : int
        Number of corner nodes.

    Returns
    -------
    pressure_cells : (E, 3) int64 ndarray
        The pressure unknown at each cell's corners.
    n_pressures : int
        Number of pressure unknowns.

    Examples
    --------
    Two triangles of two bodies sharing the edge 1-2:

    >>> cells = np.array([[0, 1, 2, 4, 5, 6], [1, 3, 2, 7, 8, 5]])
    >>> pc, n = body_pressure_cells(cells, np.array([0, 1]), 4)
    >>> pc.tolist(), n
    ([[0, 1, 2], [4, 3, 5]], 6)
    """
    corner = np.asarray(cells, dtype=np.int64)[:, :3]
    body = np.asarray(body, dtype=np.int64)
    count = int(body.max()) + 1 if len(body) else 1
    key = corner * count + body[:, None]
    uniq, inverse = np.unique(key.ravel(), return_inverse=True)
    node = uniq // count
    first = np.ones(len(uniq), bool)
    first[1:] = node[1:] != node[:-1]  # sorted by node then body: the node's lowest body
    index = np.empty(len(uniq), np.int64)
    index[first] = node[first]
    index[~first] = n_vertices + np.arange(int((~first).sum()))
    return index[inverse].reshape(-1, 3), int(n_vertices + (~first).sum())


def _ring_nodes(ring, geo, chain_nodes) -> np.ndarray:
    """A ring's chain nodes in its order (each node once): its outline in the mesh.

    Each edge ``u``-``w`` of the ring lies on one chain's segment ``k``; it
    contributes the chain's nodes at arc lengths in ``[s_k, s_k+1)`` walked
    forward, or in ``(s_k, s_k+1]`` walked backward. Vectorised: the directed
    edges are looked up in one sorted array, the node runs gathered at once.
    """
    nv = int(max(int(np.max(path)) for path, _, _ in geo)) + 1
    keys, first, count, step, flat = [], [], [], [], []
    offset = 0
    for c, (path, s, ns) in enumerate(geo):
        path = np.asarray(path, dtype=np.int64)
        f_lo, f_hi = np.searchsorted(ns, s[:-1], "left"), np.searchsorted(ns, s[1:], "left")
        b_lo, b_hi = np.searchsorted(ns, s[:-1], "right"), np.searchsorted(ns, s[1:], "right")
        keys += [path[:-1] * nv + path[1:], path[1:] * nv + path[:-1]]
        first += [offset + f_lo, offset + b_hi - 1]  # a backward run starts at its last node
        count += [f_hi - f_lo, b_hi - b_lo]
        step += [np.ones(len(path) - 1, np.int64), -np.ones(len(path) - 1, np.int64)]
        flat.append(np.asarray(chain_nodes[c], dtype=np.int64))
        offset += len(ns)
    keys, first, count, step = (np.concatenate(x) for x in (keys, first, count, step))
    flat = np.concatenate(flat)
    order = np.argsort(keys, kind="stable")
    ring = np.asarray(ring, dtype=np.int64)
    nxt = np.roll(ring, -1)
    use = ring != nxt
    pos = order[np.searchsorted(keys, ring[use] * nv + nxt[use], sorter=order)]
    first, count, step = first[pos], count[pos], step[pos]
    run = np.repeat(np.arange(len(pos)), count)
    within = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
    return flat[first[run] + step[run] * within]


def _midnodes(pts, tri):
    """Mid-edge nodes of every edge; the cells; a lookup from edge keys to (cell, local edge)."""
    nv = len(pts)
    local = np.array([[0, 1], [1, 2], [2, 0]])
    e = tri[:, local]
    lo, hi = e.min(axis=2), e.max(axis=2)
    uniq, inv = np.unique((lo * nv + hi).ravel(), return_inverse=True)
    inv = inv.reshape(-1, 3)
    a, b = uniq // nv, uniq % nv
    nodes = np.concatenate((pts, 0.5 * (pts[a] + pts[b])))
    cells = np.column_stack((tri, nv + inv)).astype(np.int64)
    where = np.full(len(uniq), -1)
    where[inv.ravel()] = np.arange(inv.size)

    def edge_cell(keys):
        k = np.searchsorted(uniq, keys)
        if not (np.all(k < len(uniq)) and np.all(uniq[np.minimum(k, len(uniq) - 1)] == keys)):
            raise MeshError("mesh: the mesh's edges do not follow the bodies' contours")
        pos = where[k]
        return pos // 3, pos % 3

    return nodes, cells, edge_cell


def _vertex_weights(nodes, cells, nv, points, chains, edge_cell):
    """Weights of every vertex on its chain segment (a corner is its own node)."""
    V = len(points)
    rows, cols, vals = [], [], []
    done = np.zeros(V, bool)
    cell_l, loc_l, dir_l, t_l, who = [], [], [], [], []
    for ch in chains:
        for end, node in ((ch.vertices[0], ch.nodes[0]), (ch.vertices[-1], ch.nodes[-1])):
            if not done[end]:
                done[end] = True
                rows.append(end)
                cols.append(node)
                vals.append(1.0)
        inner = np.arange(1, len(ch.vertices) - 1)
        inner = inner[~done[ch.vertices[inner]]]
        if not len(inner):
            continue
        done[ch.vertices[inner]] = True
        s = ch.s[inner]
        j = np.clip(np.searchsorted(ch.node_s, s, side="right") - 1, 0, len(ch.node_s) - 2)
        u, w = ch.nodes[j], ch.nodes[j + 1]
        cell, loc = edge_cell(np.minimum(u, w) * nv + np.maximum(u, w))
        first = cells[cell, np.array([0, 1, 2])[loc]]
        cell_l.append(cell)
        loc_l.append(loc)
        dir_l.append(np.where(first == u, 1, -1))
        t_l.append(np.clip((s - ch.node_s[j]) / (ch.node_s[j + 1] - ch.node_s[j]), 0.0, 1.0))
        who.append(ch.vertices[inner])
    corner = sp.csr_matrix((vals, (rows, cols)), shape=(V, len(nodes)))
    if not who:
        return corner
    who = np.concatenate(who)
    w = edge_weights(nodes, cells, np.concatenate(cell_l), np.concatenate(loc_l), np.concatenate(dir_l),
                     np.concatenate(t_l), points[who])
    moved = sp.csr_matrix((np.ones(len(who)), (who, np.arange(len(who)))), shape=(V, len(who)))
    return (corner + moved @ w).tocsr()
