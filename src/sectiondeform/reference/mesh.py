"""One conforming quality triangulation of a problem's bodies, for the finite-element reference and the solver decks.

The bodies' contours (each body's section, as
:func:`~sectiondeform.section.build_section` discretises it) are merged into
one planar graph: points closer than the problem's contact tolerance are one
vertex, and a vertex lying on another contour's edge splits that edge, so a
piece two bodies share is one run of edges. Every edge is split to the
element size (the smaller of its bodies'), edges on the support at equal
steps of the support's arc-length fraction and on the support curve itself.
Shewchuk's Triangle (the PyPI package ``triangle``, extra ``[fem]``: its
licence forbids commercial use without permission) meshes the graph with one
region per body (its own largest triangle) and a minimum angle of 30 degrees;
every triangle carries its body. A shared piece is a chain of segments with
one set of nodes, interior to the mesh: the bodies are bonded by
construction. One body is the same mesh with one region. A body's holes
(its section's hole rings) are rings of their own vertices, never merged
with another contour's (a small hole's points are closer than the
tolerance), split to the body's element size and left empty: a hole's
boundary is a free boundary of the mesh, and no triangle lies inside it.

The element size is per body: ``mesh_size`` x the body's mesh scale (its
mean thickness, or the square root of its area if smaller). A node on the
support carries its arc-length fraction there: the section's own fractions
where the body's lower curve is the support, else its place on the
support's fine polyline; a node Triangle adds on a support segment gets the
fraction of its place along that segment.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import CaseError, MeshError, require
from ..section import build_section, polygon_area

__all__ = ["ReferenceMesh", "triangulate", "thin_polyline", "MIN_ANGLE_DEG"]

MIN_ANGLE_DEG = 30.0

SUPPORT_MARK, OTHER_MARK = 1, 2


@dataclass(frozen=True, eq=False)
class ReferenceMesh:
    """A conforming triangulation of the bodies of a problem (one or several).

    Attributes
    ----------
    points : (N, 2) float64 ndarray
        Vertex coordinates, units.
    triangles : (M, 3) int64 ndarray
        Vertex indices of each triangle, counter-clockwise.
    body : (M,) int64 ndarray
        The body of each triangle.
    lower_nodes : (n_s,) int64 ndarray
        Vertices on the support, by increasing fraction (the prescribed ones).
    lower_fractions : (n_s,) float64 ndarray
        Arc-length fraction of each of ``lower_nodes`` on the support.
    upper_nodes : tuple of (m_b,) int64 ndarray
        Per body, the vertex of each of its upper characteristic points, B to A.
    contour_nodes : tuple of (k_b,) int64 ndarray
        Per body, the vertex of each point of its section's contour (a point
        shared by two bodies is one vertex).
    sizes : (B,) float64 ndarray
        Element size of each body, units.
    sections : tuple of Section
        The bodies' sections as meshed (their upper points, thinned for a deck).
    hole_nodes : tuple of tuple of (k_h,) int64 ndarray
        Per body, the vertex of each point of each of its holes (the
        section's ``holes``, in order): free boundaries.
    """

    points: np.ndarray
    triangles: np.ndarray
    body: np.ndarray
    lower_nodes: np.ndarray
    lower_fractions: np.ndarray
    upper_nodes: tuple
    contour_nodes: tuple
    sizes: np.ndarray
    sections: tuple = ()
    hole_nodes: tuple = ()

    @property
    def size(self) -> float:
        """The smallest element size, units."""
        return float(self.sizes.min())

    def areas(self) -> np.ndarray:
        """Signed area of each triangle, ``(M,)``, units² (> 0: counter-clockwise)."""
        p = self.points[self.triangles]
        d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        return 0.5 * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])

    def body_area(self, b: int) -> float:
        """Total area of body ``b``'s triangles, units²."""
        return float(self.areas()[self.body == b].sum())

    @property
    def min_angle_deg(self) -> float:
        """Smallest interior angle of any triangle, degrees."""
        p = self.points[self.triangles]
        e = np.roll(p, -1, axis=1) - p
        a = -np.roll(e, 1, axis=1)
        cosang = np.einsum("mkd,mkd->mk", e, a) / (np.linalg.norm(e, axis=2) * np.linalg.norm(a, axis=2))
        return float(np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0))).min())


def _merge(rings: list[np.ndarray], tol: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """Contour points merged within ``tol`` (first appearance keeps its place); each ring as vertex indices."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    pts = np.concatenate(rings)
    n = len(pts)
    pairs = cKDTree(pts).query_pairs(tol, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    _, first, inverse = np.unique(label, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    ids = rank[inverse]
    out, k = [], 0
    for r in rings:
        out.append(ids[k : k + len(r)])
        k += len(r)
    return pts[np.sort(first)], out


def _node_edges(points: np.ndarray, ring: np.ndarray, tol: float) -> list[tuple[int, int]]:
    """The ring's edges, each split at the vertices that lie on it (within ``tol``), as vertex pairs."""
    import shapely

    a = points[ring]
    b = points[np.roll(ring, -1)]
    lines = shapely.linestrings(np.stack((a, b), axis=1))
    edge, vertex = shapely.STRtree(shapely.points(points)).query(lines, predicate="dwithin", distance=tol)
    d = (b - a)[edge]
    length = np.hypot(d[:, 0], d[:, 1])
    t = np.einsum("kj,kj->k", points[vertex] - a[edge], d) / np.where(length > 0, length * length, 1.0)
    inner = (t * length > tol) & ((1.0 - t) * length > tol)
    edge, vertex, t = edge[inner], vertex[inner], t[inner]
    order = np.lexsort((t, edge))
    edge, vertex = edge[order], vertex[order]
    edges = []
    for e, (u, w) in enumerate(zip(ring, np.roll(ring, -1))):
        if u == w:
            continue
        inside = vertex[np.searchsorted(edge, e, "left"):np.searchsorted(edge, e, "right")]
        chain = [int(u), *map(int, inside), int(w)]
        edges += list(zip(chain[:-1], chain[1:]))
    return edges


def thin_polyline(points: np.ndarray, spacing: float, corner_deg: float = 10.0) -> np.ndarray:
    """Indices of the vertices of an open polyline kept so that kept ones are about ``spacing`` apart.

    The ends and every vertex where the polyline turns by more than
    ``corner_deg`` are kept; between them a vertex is kept once the arc
    length since the last kept one reaches ``spacing``.

    Examples
    --------
    >>> thin_polyline(np.column_stack((np.arange(7.0), np.zeros(7))), 2.5).tolist()
    [0, 3, 6]
    """
    seg = np.diff(points, axis=0)
    length = np.hypot(seg[:, 0], seg[:, 1])
    heading = np.arctan2(seg[:, 1], seg[:, 0])
    turn = np.abs((np.diff(heading) + np.pi) % (2 * np.pi) - np.pi)
    corner = np.concatenate(([True], np.degrees(turn) > corner_deg, [True]))
    keep, since = [0], 0.0
    for i in range(1, len(points)):
        since += length[i - 1]
        if corner[i] or since >= spacing:
            keep.append(i)
            since = 0.0
    return np.asarray(keep, dtype=np.int64)


def _thinned(sections, sizes, tol: float) -> list:
    """Each section with its upper points about size / 3 apart, keeping those other bodies touch."""
    from scipy.spatial import cKDTree

    out = []
    for b, (sec, h) in enumerate(zip(sections, sizes)):
        upper = np.asarray(sec.upper, dtype=np.float64)
        keep = np.zeros(len(upper), dtype=bool)
        keep[thin_polyline(upper, h / 3.0)] = True
        others = [np.asarray(s.contour) for k, s in enumerate(sections) if k != b]
        if others:
            keep |= cKDTree(np.concatenate(others)).query(upper)[0] <= tol
        thin = dataclasses.replace(sec, upper=upper[keep])
        holes = sum(abs(polygon_area(h)) for h in sec.holes)
        out.append(dataclasses.replace(thin, area=abs(polygon_area(thin.contour)) - holes))
    return out


def _support_fractions(problem, sections, points, ids, tol):
    """Which merged vertices lie on the support, and their arc-length fractions there."""
    import shapely

    line = shapely.LineString(problem.layout.fine["support"])
    on = shapely.distance(shapely.points(points), line) <= tol
    frac = np.where(on, shapely.line_locate_point(line, shapely.points(points)) / line.length, np.nan)
    support = problem.support.to_json()
    for b, (body, sec) in enumerate(zip(problem.bodies, sections)):
        if body.lower.to_json() == support:  # exact fractions of the body's own lower curve
            low = ids[b][: len(sec.lower)]
            frac[low] = sec.fractions
            on[low] = True
    return on, frac, line


def _graph(problem, points, ids, sizes, on, frac, line, tol, hole_ids=(), fine=None):
    """The split edges of the planar graph: vertices, segments, markers, support segments and the support's sag.

    ``hole_ids`` are each body's hole rings as vertex indices: their edges as they are (nothing lies on them).
    ``fine``: ``(zone, ratio)``, the contour's edges within the shapely geometry ``zone`` split ``ratio`` times finer.
    """
    import shapely

    edge_size: dict[tuple[int, int], float] = {}
    for b, ring in enumerate(ids):
        for u, w in _node_edges(points, ring, tol):
            key = (min(u, w), max(u, w))
            edge_size[key] = min(edge_size.get(key, math.inf), float(sizes[b]))
    if fine is not None:
        zone, ratio = fine
        keys = list(edge_size)
        mids = shapely.points(0.5 * (points[[k[0] for k in keys]] + points[[k[1] for k in keys]]))
        for key, near in zip(keys, shapely.intersects(zone, mids)):
            if near:
                edge_size[key] /= ratio
    for b, hb in enumerate(hole_ids):
        for ring in hb:
            for u, w in zip(ring.tolist(), np.roll(ring, -1).tolist()):
                edge_size[(min(u, w), max(u, w))] = float(sizes[b])
    vertices, segments, marks, sub_support = [points], [], [], []
    k, sag = len(points), 0.0
    for (u, w), h in edge_size.items():
        pu, pw = points[u], points[w]
        n = max(1, math.ceil(math.hypot(*(pw - pu)) / h - 1e-9))
        t = np.arange(1, n) / n
        on_support = bool(on[u] and on[w] and shapely.distance(shapely.Point(0.5 * (pu + pw)), line) <= tol)
        if on_support:
            s = frac[u] + t * (frac[w] - frac[u])
            new = np.asarray(problem.support.at_fractions(s), dtype=np.float64).reshape(-1, 2)
            if len(new):  # off the chord u-w by the support's curvature
                d = (pw - pu) / max(math.hypot(*(pw - pu)), 1e-300)
                sag = max(sag, float(np.abs((new - pu) @ np.array([-d[1], d[0]])).max()))
            fr = np.concatenate(([frac[u]], s, [frac[w]]))
        else:
            new = pu + t[:, None] * (pw - pu)
        chain = [u, *range(k, k + len(new)), w]
        k += len(new)
        vertices.append(new)
        segments += list(zip(chain[:-1], chain[1:]))
        marks += [SUPPORT_MARK if on_support else OTHER_MARK] * (len(chain) - 1)
        if on_support:
            sub_support += [(a, c, fr[i], fr[i + 1]) for i, (a, c) in enumerate(zip(chain[:-1], chain[1:]))]
    return np.concatenate(vertices), segments, marks, sub_support, sag


def _regions(rings, sizes, holes):
    """Triangle's regions (a point inside each body, its attribute b + 1 and largest area) and the union's holes.

    ``holes`` are each body's hole rings: a hole is a hole of the union, so Triangle leaves it empty.
    """
    import shapely

    polys = [shapely.Polygon(r, list(hb)) for r, hb in zip(rings, holes)]
    regions = []
    for b, p in enumerate(polys):
        q = p.point_on_surface()
        regions.append([q.x, q.y, b + 1, math.sqrt(3.0) / 4.0 * sizes[b] ** 2])
    holes = []
    union = shapely.union_all([p.buffer(0) for p in polys])
    for part in getattr(union, "geoms", [union]):
        for ring in part.interiors:
            q = shapely.Polygon(ring).point_on_surface()
            holes.append([q.x, q.y])
    return np.asarray(regions, dtype=np.float64), holes


def _triangle(vertices, segments, marks, sub_support, regions, holes):
    """Run Triangle; returns its points, counter-clockwise triangles, each triangle's body and vertex markers."""
    tr = require("triangle", "fem", "the finite-element reference mesh")
    vmarks = np.full(len(vertices), OTHER_MARK, dtype=np.int32)
    for a, c, *_ in sub_support:
        vmarks[[a, c]] = SUPPORT_MARK
    data = {"vertices": vertices, "segments": np.asarray(segments, dtype=np.int32),
            "vertex_markers": vmarks[:, None], "segment_markers": np.asarray(marks, dtype=np.int32)[:, None],
            "regions": regions}
    if holes:
        data["holes"] = np.asarray(holes, dtype=np.float64)
    try:
        out = tr.triangulate(data, f"pq{MIN_ANGLE_DEG:g}AaQ")
    except Exception as exc:  # pragma: no cover - Triangle's own failures
        raise MeshError(f"reference mesh: Triangle failed on the bodies ({exc})") from exc
    pts = np.asarray(out["vertices"], dtype=np.float64)
    tri = np.asarray(out["triangles"], dtype=np.int64)
    body = np.asarray(out["triangle_attributes"]).ravel().round().astype(np.int64) - 1
    if len(pts) < len(vertices) or not np.array_equal(pts[: len(vertices)], vertices):
        raise MeshError("reference mesh: Triangle moved or dropped a boundary node")  # pragma: no cover
    if (body < 0).any():
        raise MeshError("reference mesh: part of the union of the bodies belongs to no body")  # pragma: no cover
    p = pts[tri]
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    cw = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] < 0
    tri[cw] = tri[cw][:, ::-1]
    return pts, tri, body, np.asarray(out["vertex_markers"]).ravel()


def _lower(pts, n_given, marks, sub_support):
    """The support's nodes by increasing fraction, and their fractions (Triangle's added ones interpolated)."""
    added = np.flatnonzero((marks == SUPPORT_MARK) & (np.arange(len(pts)) >= n_given))
    node_frac = np.full(len(pts), np.nan)
    for a, c, s0, s1 in sub_support:
        node_frac[a], node_frac[c] = s0, s1
    if len(added) and sub_support:
        sa = np.array([[a, c] for a, c, *_ in sub_support])
        ss = np.array([[s0, s1] for *_, s0, s1 in sub_support])
        a0, d = pts[sa[:, 0]], pts[sa[:, 1]] - pts[sa[:, 0]]
        q = pts[added]
        t = np.clip(np.einsum("kjd,jd->kj", q[:, None, :] - a0[None], d) / np.einsum("jd,jd->j", d, d), 0.0, 1.0)
        dist = np.linalg.norm(a0[None] + t[..., None] * d[None] - q[:, None, :], axis=2)
        j = np.argmin(dist, axis=1)
        tj = t[np.arange(len(q)), j]
        node_frac[added] = ss[j, 0] + tj * (ss[j, 1] - ss[j, 0])
    lower = np.flatnonzero(~np.isnan(node_frac))
    order = np.argsort(node_frac[lower], kind="stable")
    return lower[order].astype(np.int64), node_frac[lower][order]


def triangulate(problem, mesh_size: float, sections=None, thin: bool = False, fine=None) -> ReferenceMesh:
    """One conforming quality triangulation of all the bodies of a problem.

    Parameters
    ----------
    problem : Problem
        One body or several, plane or of revolution.
    mesh_size : float
        Element size as a fraction of each body's mesh scale (dimensionless).
    sections : sequence of Section, optional
        The bodies' sections (by default built from ``problem.body_case``).
    thin : bool
        Keep only upper points about a third of the element size apart
        (and those other bodies touch): a solver deck maps the rest by its
        shape functions, the reference needs every upper point as a node.
    fine : (shapely geometry, int), optional
        A zone and a ratio: the bodies' contour edges within the zone are
        split that many times finer (Triangle's quality bound grades the
        elements from them inward).

    Returns
    -------
    ReferenceMesh

    Raises
    ------
    CaseError
        If ``mesh_size`` is not a finite number > 0.
    MeshError
        If Triangle fails or a body is not covered exactly.
    MissingExtraError
        Without the package ``triangle``.

    Examples
    --------
    >>> from sectiondeform.io.case import case_from_dict
    >>> square = lambda y: [[2, y], [2, y + 1], [0, y + 1], [0, y]]
    >>> p = case_from_dict({"format": "section-case/2", "support": {"polyline": [[0, 0], [2, 0]]},
    ...     "target": {"polyline": [[0, 0], [2, 0]]}, "bodies": [
    ...     {"name": "low", "lower": {"polyline": [[0, 0], [2, 0]]}, "upper": {"polyline": square(0)},
    ...      "law": {"area_ratio": 1}},
    ...     {"name": "top", "lower": {"polyline": [[0, 1], [2, 1]]}, "upper": {"polyline": square(1)},
    ...      "law": {"area_ratio": 1}}]})
    >>> m = triangulate(p, 0.5)
    >>> [round(m.body_area(b), 12) for b in (0, 1)], m.min_angle_deg > 20
    ([2.0, 2.0], True)
    """
    if isinstance(mesh_size, bool) or not isinstance(mesh_size, (int, float, np.floating)) \
            or not math.isfinite(mesh_size) or mesh_size <= 0:
        raise CaseError("mesh_size", f"must be a finite number > 0, got {mesh_size!r}")
    tol = problem.layout.tolerance
    if sections is None:
        sections = [build_section(problem.body_case(b)) for b in range(len(problem.bodies))]
    sizes = np.array([mesh_size * s.mesh_scale for s in sections])
    if thin:
        sections = _thinned(sections, sizes, tol)
    rings = [np.asarray(s.contour, dtype=np.float64) for s in sections]
    points, ids = _merge(rings, tol)
    on, frac, line = _support_fractions(problem, sections, points, ids, tol)
    holes = [[np.asarray(h, dtype=np.float64) for h in s.holes] for s in sections]
    # A hole's points are vertices of their own (the layout keeps holes apart from every contour and each other).
    hole_ids, start = [], len(points)
    for hb in holes:
        hole_ids.append([])
        for h in hb:
            hole_ids[-1].append(np.arange(start, start + len(h), dtype=np.int64))
            start += len(h)
    points = np.concatenate([points, *(h for hb in holes for h in hb)])
    on = np.concatenate((on, np.zeros(len(points) - len(on), dtype=bool)))
    frac = np.concatenate((frac, np.full(len(points) - len(frac), np.nan)))
    vertices, segments, marks, sub_support, sag = _graph(problem, points, ids, sizes, on, frac, line, tol, hole_ids, fine)
    pts, tri, body, vmarks = _triangle(vertices, segments, marks, sub_support, *_regions(rings, sizes, holes))
    lower_nodes, lower_fractions = _lower(pts, len(vertices), vmarks, sub_support)
    upper_nodes = [np.concatenate(([ring[len(sec.lower) - 1]], ring[len(sec.lower):], [ring[0]])).astype(np.int64)
                   for sec, ring in zip(sections, ids)]
    mesh = ReferenceMesh(points=pts, triangles=tri, body=body, lower_nodes=lower_nodes, lower_fractions=lower_fractions,
                         upper_nodes=tuple(upper_nodes), contour_nodes=tuple(r.astype(np.int64) for r in ids),
                         sizes=sizes, sections=tuple(sections),
                         hole_nodes=tuple(tuple(h for h in hb) for hb in hole_ids))
    for b, sec in enumerate(sections):
        got, want = mesh.body_area(b), sec.area
        # Support nodes sit on the support curve, not on its chords: allow the area between them.
        if not abs(got - want) <= 1e-9 * want + sec.lower_length * sag:
            where = problem.label(b) or "the section"
            raise MeshError(f"reference mesh: the triangles of {where} cover {got:.9g} for its area {want:.9g}")
    for arr in (pts, tri, body, lower_nodes, lower_fractions, *upper_nodes, *(h for hb in hole_ids for h in hb)):
        arr.setflags(write=False)
    return mesh
