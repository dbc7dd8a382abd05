"""Finite-element reference of an assembly of bonded bodies (extra ``[fem]``).

The same physics as the one-body reference (:mod:`sectiondeform.reference.solver`),
on all bodies at once:

* **One conforming mesh of the union.** The bodies' contours (each body's
  section, as :func:`~sectiondeform.section.build_section` discretises it)
  are merged into one planar graph: points closer than the assembly's
  contact tolerance are one vertex, and a vertex lying on another contour's
  edge splits that edge, so a piece two bodies share is one run of edges.
  Every edge is split to the element size (the smaller of its bodies'),
  edges on the support at equal steps of the support's arc-length fraction
  and on the support curve itself (as the one-body mesh places its lower
  nodes). Shewchuk's Triangle meshes the graph with one region per body
  (its own maximum triangle area) and a minimum angle of 30 degrees; every
  triangle carries its body. A shared piece is a chain of segments with one
  set of nodes, interior to the mesh: the bodies are bonded by
  construction, with no gap and no overlap.
* **Per-body physics.** Each body's rubber (its ``material``, moduli in the
  case's units so a stiffness contrast matters; neo-Hookean, Mooney–Rivlin
  or Yeoh) and its own load parameter: the out-of-plane stretch λz = 1 / r
  of its area law in generalised plane strain, the growth v of its volume
  law for a body of revolution. All are ramped together with the support
  motion (:func:`~sectiondeform.reference.solver.solve_mixed` with a load
  per body).
* **Supports.** Only the nodes on the support are prescribed: a node at
  arc-length fraction s of the support goes to the target at s (the
  fraction of a body's lower vertex is the section's own where the body's
  lower curve is the support, else its place on the support's fine
  polyline, as the fast models take it). Everything else is free, and the
  shared pieces move with the mesh.

The fine size is per body: ``mesh_size`` × the body's mesh scale (its mean
thickness, or the square root of its area if smaller).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import CaseError, MeshError, require
from ..models.base import MeshData
from ..section import build_section
from . import DEFAULT_MESH_SIZE, _material, _positive, _ratio
from .mesh import MIN_ANGLE_DEG
from .revolution import Axis, axis_from_points

__all__ = ["AssemblyMesh", "BodyReference", "AssemblyReference", "triangulate_assembly", "solve_assembly_reference"]

SUPPORT_MARK, OTHER_MARK = 1, 2


@dataclass(frozen=True, eq=False)
class AssemblyMesh:
    """A conforming triangulation of the bodies of an assembly.

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
    """

    points: np.ndarray
    triangles: np.ndarray
    body: np.ndarray
    lower_nodes: np.ndarray
    lower_fractions: np.ndarray
    upper_nodes: tuple
    contour_nodes: tuple
    sizes: np.ndarray

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


def triangulate_assembly(assembly, mesh_size: float = DEFAULT_MESH_SIZE, sections=None) -> AssemblyMesh:
    """One conforming quality triangulation of all the bodies of an assembly.

    Parameters
    ----------
    assembly : Assembly
    mesh_size : float
        Element size as a fraction of each body's mesh scale (dimensionless).
    sections : sequence of Section, optional
        The bodies' sections (by default built from ``assembly.body_case``).

    Returns
    -------
    AssemblyMesh

    Raises
    ------
    MeshError
        If Triangle fails, a body is not covered exactly, or a body's
        upper points are not mesh vertices.
    MissingExtraError
        Without the package ``triangle``.

    Examples
    --------
    >>> from sectiondeform.assembly import assembly_from_dict
    >>> square = lambda y: {"polyline": [[2, y + 1], [0, y + 1], [0, y]]}
    >>> a = assembly_from_dict({"format": "section-case/2", "support": {"polyline": [[0, 0], [2, 0]]},
    ...     "target": {"polyline": [[0, 0], [2, 0]]}, "bodies": [
    ...     {"name": "low", "lower": {"polyline": [[0, 0], [2, 0]]}, "upper": {"polyline": [[2, 0], *square(0)["polyline"]]},
    ...      "law": {"area_ratio": 1}},
    ...     {"name": "top", "lower": {"polyline": [[0, 1], [2, 1]]}, "upper": {"polyline": [[2, 1], *square(1)["polyline"]]},
    ...      "law": {"area_ratio": 1}}]})
    >>> m = triangulate_assembly(a, 0.5)
    >>> [round(m.body_area(b), 12) for b in (0, 1)], m.min_angle_deg > 20
    ([2.0, 2.0], True)
    """
    import shapely

    tr = require("triangle", "fem", "the finite-element reference mesh")
    mesh_size = _positive(mesh_size, "mesh_size")
    lay = assembly.layout
    tol = lay.tolerance
    if sections is None:
        sections = [build_section(assembly.body_case(b)) for b in range(len(assembly.bodies))]
    sizes = np.array([mesh_size * s.mesh_scale for s in sections])
    rings = [np.asarray(s.contour, dtype=np.float64) for s in sections]
    points, ids = _merge(rings, tol)
    nv = len(points)

    # Support fractions of the vertices on the support.
    support_line = shapely.LineString(lay.fine["support"])
    on_support = shapely.distance(shapely.points(points), support_line) <= tol
    frac = np.where(on_support, shapely.line_locate_point(support_line, shapely.points(points)) / support_line.length, np.nan)
    support_json = assembly.support.to_json()
    for b, (body, sec) in enumerate(zip(assembly.bodies, sections)):
        if body.lower.to_json() == support_json:  # exact fractions of the body's own lower curve
            low = ids[b][: len(sec.lower)]
            frac[low] = sec.fractions
            on_support[low] = True

    # Edges of the planar graph, each once, with the smallest size of the bodies it bounds.
    edge_size: dict[tuple[int, int], float] = {}
    for b, ring in enumerate(ids):
        for u, w in _node_edges(points, ring, tol):
            key = (min(u, w), max(u, w))
            edge_size[key] = min(edge_size.get(key, math.inf), float(sizes[b]))
    vertices, segments, marks = [points], [], []
    sub_support = []  # (vertex, vertex, s0, s1) of each support segment
    k, sag = nv, 0.0
    for (u, w), h in edge_size.items():
        pu, pw = points[u], points[w]
        n = max(1, math.ceil(math.hypot(*(pw - pu)) / h - 1e-9))
        mid = 0.5 * (pu + pw)
        support_edge = bool(on_support[u] and on_support[w] and shapely.distance(shapely.Point(mid), support_line) <= tol)
        t = np.arange(1, n) / n
        if support_edge:
            s = frac[u] + t * (frac[w] - frac[u])
            new = np.asarray(assembly.support.at_fractions(s), dtype=np.float64).reshape(-1, 2)
            if len(new):  # off the chord u-w by the support's curvature
                d = (pw - pu) / max(math.hypot(*(pw - pu)), 1e-300)
                sag = max(sag, float(np.abs((new - pu) @ np.array([-d[1], d[0]])).max()))
        else:
            s = None
            new = pu + t[:, None] * (pw - pu)
        chain = [u] + list(range(k, k + len(new))) + [w]
        k += len(new)
        vertices.append(new)
        segments += list(zip(chain[:-1], chain[1:]))
        marks += [SUPPORT_MARK if support_edge else OTHER_MARK] * (len(chain) - 1)
        if support_edge:
            fr = np.concatenate(([frac[u]], s, [frac[w]]))
            sub_support += [(a, c, fr[i], fr[i + 1]) for i, (a, c) in enumerate(zip(chain[:-1], chain[1:]))]
    vertices = np.concatenate(vertices)
    vmarks = np.full(len(vertices), OTHER_MARK, dtype=np.int32)
    for a, c, *_ in sub_support:
        vmarks[[a, c]] = SUPPORT_MARK
    # One region per body (attribute b + 1, its own largest triangle), holes where the union has them.
    polys = [shapely.Polygon(r) for r in rings]
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
    data = {"vertices": vertices, "segments": np.asarray(segments, dtype=np.int32),
            "vertex_markers": vmarks[:, None], "segment_markers": np.asarray(marks, dtype=np.int32)[:, None],
            "regions": np.asarray(regions, dtype=np.float64)}
    if holes:
        data["holes"] = np.asarray(holes, dtype=np.float64)
    try:
        out = tr.triangulate(data, f"pq{MIN_ANGLE_DEG:g}AaQ")
    except Exception as exc:  # pragma: no cover - Triangle's own failures
        raise MeshError(f"reference mesh: Triangle failed on the assembly ({exc})") from exc
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
    # Support vertices added by Triangle: the fraction of the support segment they split.
    marks_out = np.asarray(out["vertex_markers"]).ravel()
    added = np.flatnonzero((marks_out == SUPPORT_MARK) & (np.arange(len(pts)) >= len(vertices)))
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
    lower_nodes, lower_fractions = lower[order], node_frac[lower][order]
    upper_nodes = []
    for sec, ring in zip(sections, ids):
        n_l = len(sec.lower)
        upper_nodes.append(np.concatenate(([ring[n_l - 1]], ring[n_l:], [ring[0]])).astype(np.int64))
    mesh = AssemblyMesh(points=pts, triangles=tri, body=body, lower_nodes=lower_nodes.astype(np.int64),
                        lower_fractions=lower_fractions, upper_nodes=tuple(upper_nodes),
                        contour_nodes=tuple(r.astype(np.int64) for r in ids), sizes=sizes)
    for b, sec in enumerate(sections):
        got = mesh.body_area(b)
        want = sec.area
        # Support nodes sit on the support curve, not on its chords: allow the area between them.
        slack = 1e-9 * want + sec.lower_length * sag
        if not abs(got - want) <= slack:
            raise MeshError(f"reference mesh: the triangles of {assembly.label(b)} cover {got:.9g} for its area {want:.9g}")
    for arr in (pts, tri, body, mesh.lower_nodes, lower_fractions, *upper_nodes):
        arr.setflags(write=False)
    return mesh


@dataclass(frozen=True, eq=False)
class BodyReference:
    """The finite-element reference's figures of one body of an assembly.

    Attributes
    ----------
    name : str
    upper : (m, 2) float64 ndarray
        Deformed upper characteristic points, B' to A', in the order of the
        body's section ``upper``, units.
    initial_upper : (m, 2) float64 ndarray
        The same points before deformation.
    area_initial, area_final : float
        Area of the body's triangles before, and ∫ det F2D dA after, units².
    area_target : float or None
        r × initial area under an area law, None for a body of revolution.
    volume_initial, volume_target, volume_final : float or None
        2π ∫ R dA, v × initial and 2π ∫ r dA of the deformed body (a body
        of revolution), units³; None in plane strain.
    load : float
        The body's load parameter: λz = 1 / r (plane) or the growth v.
    volume_change : float
        ∫ (Je − 1) w dA / ∫ w dA over the body: what its finite bulk
        modulus gave up.
    elements : int
        The body's triangles.
    """

    name: str
    upper: np.ndarray
    initial_upper: np.ndarray
    area_initial: float
    area_final: float
    area_target: float | None
    volume_initial: float | None
    volume_target: float | None
    volume_final: float | None
    load: float
    volume_change: float
    elements: int

    @property
    def relative_error(self) -> float:
        """Relative error of the body's law's measure (area, or volume for a body of revolution)."""
        if self.volume_target is not None:
            return (self.volume_final - self.volume_target) / self.volume_target
        return (self.area_final - self.area_target) / self.area_target


@dataclass(frozen=True, eq=False)
class AssemblyReference:
    """The converged finite-element solution of an assembly.

    Attributes
    ----------
    bodies : tuple of BodyReference
    initial_mesh, mesh : MeshData
        The whole mesh before and after, ``kind="triangle6"``.
    body : (M,) int64 ndarray
        Body of each cell of ``mesh``.
    mesh_data : AssemblyMesh
        The corner triangulation.
    pressure : (N,) float64 ndarray
        Pressure at each mesh vertex, units of the moduli; at a vertex of an
        interface, the pressure on the side of the body of lowest index (it
        jumps across).
    jacobian_min : float
        Smallest det F2D at any quadrature point.
    strain_energy : float
        Stored energy (per unit depth, or of the whole body of revolution).
    materials : tuple
        Each body's rubber.
    axis : Axis or None
    elements, dofs, iterations, steps, cuts : int
    seconds : float
    timings : dict
        ``mesh_s``, ``setup_s``, ``solve_s``.
    """

    bodies: tuple
    initial_mesh: MeshData
    mesh: MeshData
    body: np.ndarray
    mesh_data: AssemblyMesh
    pressure: np.ndarray
    jacobian_min: float
    strain_energy: float
    materials: tuple
    axis: Axis | None
    elements: int
    dofs: int
    iterations: int
    steps: int
    cuts: int
    seconds: float
    timings: dict = field(default_factory=dict)

    @property
    def revolution(self) -> bool:
        """True for a body of revolution."""
        return self.axis is not None

    def summary(self) -> dict:
        """The scalar figures as a plain dictionary (for reports)."""
        out = {k: getattr(self, k) for k in ("jacobian_min", "strain_energy", "elements", "dofs", "iterations",
                                               "steps", "cuts", "seconds")}
        out["materials"] = []
        for m in self.materials:
            d = m.to_json()
            d.setdefault("model", m.model)
            out["materials"].append(d)
        out["bodies"] = [{"name": b.name, "load": b.load, "elements": b.elements, "volume_change": b.volume_change,
                          "relative_error": b.relative_error} for b in self.bodies]
        out["timings"] = dict(self.timings)
        return out


def solve_assembly_reference(
    assembly,
    target=None,
    *,
    mesh_size: float = DEFAULT_MESH_SIZE,
    bulk_to_shear: float | None = None,
    tol: float = 1e-8,
    initial_step: float = 1.0,
    progress=None,
) -> AssemblyReference:
    """Solve an assembly of bonded bodies by finite elements: the reference for the fast models.

    Parameters
    ----------
    assembly : Assembly
        A version-2 case, any number of bodies; each body's ``material`` and
        law are used, and the case's ``revolution``.
    target : Curve, optional
        The support's image (``at_fractions(s) -> (k, 2)``); by default the case's.
    mesh_size : float
        Element size as a fraction of each body's mesh scale.
    bulk_to_shear : float, optional
        κ / μ of every body, at least 100; by default each material's, else
        the case's ``options.bulk_to_shear``, else 1000.
    tol, initial_step, progress
        As for :func:`~sectiondeform.reference.solve_reference`.

    Returns
    -------
    AssemblyReference

    Raises
    ------
    CaseError
        For a law that does not fit the kinematics, a material not nearly
        incompressible, or an argument out of range.
    ConvergenceError
        If Newton cannot apply the full load even with small steps.
    MeshError
        If the union cannot be triangulated.
    MissingExtraError
        Without the extra ``[fem]``.
    """
    from .solver import MixedProblem, solve_mixed

    t0 = time.perf_counter()
    a = assembly
    target = a.target if target is None else target
    if not hasattr(target, "at_fractions"):
        raise CaseError("target", f"expected a curve with at_fractions(s), got {type(target).__name__}")
    explicit_bulk = bulk_to_shear is not None
    if bulk_to_shear is None:
        bulk_to_shear = a.options.for_model("hyperelastic").bulk_to_shear
    mesh_size = _positive(mesh_size, "mesh_size")
    sections = [build_section(a.body_case(b)) for b in range(len(a.bodies))]
    rubbers = []
    for b, body in enumerate(a.bodies):
        try:
            rubbers.append(_material(body.material_data or None, bulk_to_shear, None, explicit_bulk=explicit_bulk))
        except CaseError as exc:
            raise CaseError(f"bodies[{b}].{exc.field}", exc.problem) from None
    contour = np.concatenate([s.contour for s in sections])
    ax = None if a.revolution is None else axis_from_points(a.revolution.axis, contour)
    ratios = []
    for b, (body, sec) in enumerate(zip(a.bodies, sections)):
        try:
            ratios.append(_ratio(body.law, revolution=ax is not None, area=sec.area))
        except CaseError as exc:
            raise CaseError(f"bodies[{b}].{exc.field}", exc.problem) from None
    ratios = np.array(ratios)
    mesh = triangulate_assembly(a, mesh_size, sections)
    t1 = time.perf_counter()
    problem = MixedProblem(mesh, material=rubbers, axis=ax, groups=mesh.body)
    if progress is not None:
        kind = "body of revolution" if ax is not None else "generalised plane strain"
        progress(f"reference: {len(mesh.triangles)} P2/P1 triangles over {len(a.bodies)} bodies "
                 f"(h = {', '.join(f'{h:.4g}' for h in mesh.sizes)}), {problem.n_u + problem.n_p} unknowns, {kind}")
    support = np.asarray(target.at_fractions(problem.dirichlet_fractions), dtype=np.float64)
    load = ratios if ax is not None else 1.0 / ratios
    scale = min(s.mesh_scale for s in sections)
    t2 = time.perf_counter()
    x, report = solve_mixed(problem, support, load, length_scale=scale, tol=tol, initial_step=initial_step,
                            progress=progress)
    t3 = time.perf_counter()
    return _solution(a, problem, mesh, sections, x, report, ratios, load,
                     {"mesh_s": t1 - t0, "setup_s": t2 - t1, "solve_s": t3 - t2}, t3 - t0)


def _solution(a, problem, mesh: AssemblyMesh, sections, x, report, ratios, load, timings, seconds) -> AssemblyReference:
    ub = problem.ubasis
    skm = problem.skmesh
    u = x[: problem.n_u]
    u_vert = u[ub.nodal_dofs].T
    u_edge = u[ub.facet_dofs].T
    p0 = np.concatenate((mesh.points, skm.p[:, skm.facets].mean(axis=1).T))
    cells = np.column_stack((mesh.triangles, len(mesh.points) + skm.t2f.T)).astype(np.int64)
    p1 = p0 + np.concatenate((u_vert, u_edge))
    mat = problem.material(x, load, tangent=False)
    dx, wdx = problem.dx, problem.wdx
    revolution = problem.revolution
    two_pi = 2.0 * math.pi
    # One value per vertex: at an interface, the body of the lowest index (the pressure jumps there).
    pressure = np.empty(len(mesh.points))
    pressure[problem.pressure_vertex[::-1]] = x[problem.n_u:][::-1]
    bodies = []
    for b, (body, sec) in enumerate(zip(a.bodies, sections)):
        on = mesh.body == b
        area0 = float(dx[on].sum())
        area1 = float(np.sum(mat["det2"][on] * dx[on]))
        vol0 = two_pi * float(wdx[on].sum()) if revolution else None
        bodies.append(BodyReference(
            name=body.name,
            upper=p1[mesh.upper_nodes[b]].copy(),
            initial_upper=np.array(sec.upper, dtype=np.float64),
            area_initial=area0,
            area_final=area1,
            area_target=None if revolution else float(ratios[b] * area0),
            volume_initial=vol0,
            volume_target=float(ratios[b] * vol0) if revolution else None,
            volume_final=two_pi * float(np.sum(mat["stretch3"][on] * mat["det2"][on] * wdx[on])) if revolution else None,
            load=float(load[b]),
            volume_change=float(np.sum((mat["Je"][on] - 1.0) * wdx[on]) / wdx[on].sum()),
            elements=int(on.sum()),
        ))
    for arr in (p0, p1, cells, pressure):
        arr.setflags(write=False)
    return AssemblyReference(
        bodies=tuple(bodies),
        initial_mesh=MeshData(points=p0, cells=cells, kind="triangle6"),
        mesh=MeshData(points=p1, cells=cells, kind="triangle6"),
        body=mesh.body,
        mesh_data=mesh,
        pressure=pressure,
        jacobian_min=float(mat["det2"].min()),
        strain_energy=float(np.sum(mat["psi"] * wdx)) * (two_pi if revolution else 1.0),
        materials=tuple(problem.rubbers),
        axis=problem.axis,
        elements=int(len(mesh.triangles)),
        dofs=int(problem.n_u + problem.n_p),
        iterations=report.iterations,
        steps=report.steps,
        cuts=report.cuts,
        seconds=float(seconds),
        timings=timings,
    )
