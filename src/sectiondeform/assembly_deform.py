"""Deforming an assembly with the paper's model, body by body from the support up.

Prepare (once): every body becomes a version-1 section
(:meth:`~sectiondeform.assembly.Assembly.body_case`), from the top of the
assembly down. Each lower node of a body is given its source: the support
(at its arc-length fraction on the support) or the upper curve of one of the
body's foundations. The nodes resting on a foundation are inserted into the
foundation's upper polyline as characteristic points, and the foundation's
own upper points lying strictly inside such a run of nodes are taken out of
it, before the foundation is prepared: on a shared piece both bodies then
have exactly the same points.

Place (once per target): from the support up, each body's lower nodes go
where their sources send them (the target at the support fractions; the
foundation's image of the inserted point), then the body's own placement
meets its own law. A point of a shared piece therefore has one image, the
same for both bodies, bit for bit. The foundation's upper points taken out
of its polyline are given back on the resting body's deformed lower
polyline, at their place along it (so the result's ``upper`` keeps one
image per characteristic point of the case).

Every result is checked: each body's law (its area, or its volume of
revolution) to :data:`AREA_TOLERANCE`, shared points coinciding to 1e-9 of
the assembly's size, every body's contour simple, no overlap between
deformed bodies, and, for a body of revolution, no deformed body crossing
the axis. The overlap is measured (a polygon overlay) only for two bodies
that a cheaper test cannot clear: their boxes apart, or their prepared
polygons' interiors disjoint with the slivers of the points taken out
bounded by area (:func:`_no_overlap`).

Everything a placement needs besides the target (which lower node comes
from where, the upper bookkeeping, the contour's positions of the points
taken out) is worked out once, when the assembly is prepared.
"""

from __future__ import annotations

import time

import numpy as np
import shapely

from .assembly import Assembly
from .assembly_result import AssemblyResult, BodyResult
from .curves import Curve, Polyline, as_points, polygon_area
from .errors import CaseError, GeometryError, LawError, MeshError, SectionDeformError
from .models import get_model
from .pappus import signed_distance, volume
from .result import ResultQuality
from .section import build_section

__all__ = ["AssemblyDeformer", "deform_assembly", "AREA_TOLERANCE", "BOND_TOLERANCE", "OVERLAP_TOLERANCE"]

AREA_TOLERANCE = 1e-9
BOND_TOLERANCE = 1e-9
"""Largest distance between the two images of a shared point, as a fraction of the assembly's size."""
OVERLAP_TOLERANCE = 1e-9
"""Largest overlap area of two deformed bodies, as a fraction of the smaller body's area."""
SUPPORT = -1


def _renamed(exc: SectionDeformError, label: str) -> SectionDeformError:
    """``exc`` with its message prefixed by the body it is about."""
    if isinstance(exc, CaseError):
        return CaseError(f"{label}: {exc.field}" if exc.field else label, exc.problem)
    return type(exc)(f"{label}: {exc}")


def _cumulative(points: np.ndarray) -> np.ndarray:
    return np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))))


class _Body:
    """What the deformer keeps of one body: section, prepared model, node sources, upper bookkeeping."""

    def __init__(self, section, original_upper):
        self.section = section
        self.prepared = None
        self.original_upper = original_upper  # (m0, 2) the case's characteristic points
        self.kept = np.arange(len(original_upper))  # index in section.upper of each original point, -1 if taken out
        self.taken = []  # (original index, resting body, node index, t) of the points taken out
        self.source = np.full(len(section.lower), SUPPORT)  # SUPPORT or a foundation body per lower node
        self.where = np.zeros(len(section.lower))  # support fraction, or index in the foundation's upper
        self.contour_order = None


class AssemblyDeformer:
    """An assembly prepared once for deformation onto any number of targets.

    Parameters
    ----------
    assembly : Assembly
    model : str, optional
        ``"paper"`` (body by body) or ``"hyperelastic"`` (all bodies in one
        solve, :mod:`~sectiondeform.assembly_hyperelastic`); by default
        ``assembly.options.model``.
    element_size : float, optional
        Element size of every body's layered mesh, units; overrides the case's.

    Raises
    ------
    CaseError
        For a model that does not deform assemblies, or a material the model
        cannot take.
    GeometryError, MeshError
        Naming the body whose section or mesh cannot be built.
    """

    def __init__(self, assembly: Assembly, model: str | None = None, element_size: float | None = None):
        t0 = time.perf_counter()
        self.assembly = assembly
        self.model_name = model or assembly.model
        if self.model_name not in ("paper", "hyperelastic"):
            raise CaseError("options.model", f"the {self.model_name} model does not deform assemblies yet; use the paper model (--model paper)")
        self.model = get_model(self.model_name)
        lay = assembly.layout
        self.layout = lay
        n = len(assembly.bodies)
        self.bodies: list[_Body | None] = [None] * n
        for b in reversed(lay.order):
            self.bodies[b] = self._build(b, element_size)
        options = assembly.options.for_model(self.model_name)
        self.joint = None
        if self.model_name == "hyperelastic":
            from .assembly_hyperelastic import JointHyperelastic
            from .assembly_hyperelastic_revolution import JointRevolution

            self.joint = (JointHyperelastic if assembly.revolution is None else JointRevolution)(self, options)
            for b, prepared in enumerate(self.joint.body_meshes):
                self.bodies[b].prepared = prepared
        for b in lay.order if self.joint is None else ():
            try:
                self.bodies[b].prepared = self.model.prepare(self.bodies[b].section, options)
            except SectionDeformError as exc:
                raise _renamed(exc, assembly.label(b)) from None
        self.fixed_parts = tuple(self._fixed_parts(b) for b in range(n))
        self.prepare_seconds = time.perf_counter() - t0

    # -- preparing -------------------------------------------------------

    def _section(self, b: int, upper: Curve | None, element_size):
        try:
            return build_section(self.assembly.body_case(b, upper), element_size)
        except SectionDeformError as exc:
            raise _renamed(exc, self.assembly.label(b)) from None

    def _build(self, b: int, element_size) -> _Body:
        """Body ``b``'s section, with the lower nodes of the bodies resting on it in its upper polyline."""
        lay = self.layout
        base = self._section(b, None, element_size)
        original = np.array(base.upper)
        resting = lay.resting_on(b)
        if not resting:
            body = _Body(base, original)
        else:
            body = self._with_resting(b, original, resting, element_size)
        self._sources(b, body)
        return body

    def _with_resting(self, b: int, original: np.ndarray, resting, element_size) -> _Body:
        tol = self.layout.tolerance
        line = shapely.LineString(original)
        params = _cumulative(original)
        m = len(original)
        taken = np.zeros(m, dtype=bool)
        taken_by = {}
        inserts = []  # (param, point, resting body, node index)
        for r in resting:
            rb = self.bodies[r]
            idx = np.flatnonzero(rb.source == b)
            if not len(idx):
                continue
            pts = rb.section.lower[idx]
            par = shapely.line_locate_point(line, shapely.points(pts))
            inserts += [(float(p), pts[k], r, int(i)) for k, (p, i) in enumerate(zip(par, idx))]
            for run in np.split(np.arange(len(idx)), np.flatnonzero(np.diff(idx) != 1) + 1):
                lo, hi = par[run].min(), par[run].max()
                inside = (params > lo) & (params < hi)
                inside[0] = inside[-1] = False
                for k in np.flatnonzero(inside & ~taken):
                    taken_by[int(k)] = (r, idx[run])
                taken |= inside
        # Merge the kept points and the inserted nodes along the original upper curve.
        entries = [(params[k], 0 if k < m - 1 else 2, original[k], ("kept", int(k))) for k in range(m) if not taken[k]]
        entries += [(p, 1, pt, ("node", r, i)) for p, pt, r, i in inserts]
        entries.sort(key=lambda e: (e[0], e[1]))
        points, point_params, kept_index, node_index = [], [], {}, {}
        for p, _, pt, what in entries:
            if points and np.hypot(*(pt - points[-1])) <= tol:
                j = len(points) - 1
                if what[0] == "kept":  # a point of the case's own upper curve keeps its place
                    points[-1] = pt
            else:
                points.append(np.asarray(pt, dtype=float))
                point_params.append(p)
                j = len(points) - 1
            if what[0] == "kept":
                kept_index[what[1]] = j
            else:
                node_index[(what[1], what[2])] = j
        upper = np.array(points)
        section = self._section(b, Polyline(upper), element_size)
        if len(section.upper) != len(upper):  # pragma: no cover - a polyline's points are its characteristic points
            raise MeshError(f"{self.assembly.label(b)}: its upper polyline with the resting nodes lost points")
        body = _Body(section, original)
        body.kept = np.array([kept_index.get(k, -1) for k in range(m)])
        for (r, i), j in node_index.items():
            self.bodies[r].where[i] = j
        # The points taken out: their place on the resting body's lower polyline (segment, fraction).
        for k, (r, run) in sorted(taken_by.items()):
            nodes = self.bodies[r].section.lower[run]
            along = float(shapely.line_locate_point(shapely.LineString(nodes), shapely.Point(original[k])))
            cum = _cumulative(nodes)
            s = int(np.clip(np.searchsorted(cum, along, side="right") - 1, 0, len(nodes) - 2))
            t = float(np.clip((along - cum[s]) / (cum[s + 1] - cum[s]), 0.0, 1.0))
            body.taken.append((k, r, int(run[s]), t))
        # Contour order: the prepared upper points and the taken-out ones, along the original upper.
        all_params = np.concatenate((point_params, params[[k for k, *_ in body.taken]]))
        body.contour_order = np.argsort(all_params, kind="stable")
        return body

    def _sources(self, b: int, body: _Body) -> None:
        """Classify body ``b``'s lower nodes: on the support (with their fraction) or on a foundation."""
        lay = self.layout
        a = self.assembly
        low = body.section.lower
        support = lay.fine["support"]
        on_support = shapely.distance(shapely.points(low), shapely.LineString(support)) <= lay.tolerance
        found = lay.foundations[b]
        if found:
            d = np.stack([shapely.distance(shapely.points(low), shapely.LineString(lay.fine["uppers"][j])) for j in found])
            nearest = np.asarray(found)[np.argmin(d, axis=0)]
            body.source = np.where(on_support, SUPPORT, nearest)
        else:
            body.source = np.full(len(low), SUPPORT)
        sup = body.source == SUPPORT
        if a.bodies[b].lower.to_json() == a.support.to_json():
            body.where[sup] = body.section.fractions[sup]
        else:
            line = shapely.LineString(support)
            body.where[sup] = shapely.line_locate_point(line, shapely.points(low[sup])) / line.length

    # -- placing ---------------------------------------------------------

    def deform(self, target: Curve | np.ndarray | None = None, *, start: AssemblyResult | None = None) -> AssemblyResult:
        """Deform the assembly: the support onto ``target`` (the case's by default), each body under its law.

        Parameters
        ----------
        target : Curve or (k, 2) array_like, optional
            Where the support goes, A' to B', units.
        start : AssemblyResult, optional
            An earlier result of this deformer to start the solve from (a
            warm start; the hyperelastic model only, the paper model has no
            path to follow and ignores it). The answer depends on ``target``
            and ``start`` alone, bit for bit; without ``start`` on ``target``
            alone.

        Returns
        -------
        AssemblyResult
            Its ``state`` is the hyperelastic model's solution, for the next
            ``start``.

        Raises
        ------
        MeshError, LawError, GeometryError
            Naming the body: an inverted element, an unmet law, a crossing
            contour; or two deformed bodies that overlap or come apart.
        CaseError
            If ``start`` is not a result of this deformer's assembly.
        """
        return self._run(target, start, preview=False)

    def preview(self, target: Curve | np.ndarray | None = None, *, start: AssemblyResult | None = None) -> AssemblyResult:
        """A fast deformation for dragging the target (interactive preview).

        The paper model answers exactly as :meth:`deform`; the hyperelastic
        model takes one linearised step from ``start`` (a result of this
        deformer) or from the undeformed assembly, with the factorisation at
        hand: every body's law is met exactly and the interfaces stay
        bonded, every check of :meth:`deform` is made, but the shape is
        first-order in the change of target (each body's ``info.preview`` is
        True, the result's ``state`` is ``start``'s): call :meth:`deform`
        when the drag ends. Arguments as :meth:`deform`.
        """
        return self._run(target, start, preview=self.joint is not None)

    def _run(self, target, start, preview: bool) -> AssemblyResult:
        t0 = time.perf_counter()
        a = self.assembly
        if target is None:
            curve = a.target
        elif isinstance(target, Curve):
            curve = target
        else:
            curve = Polyline(as_points(target, "target", min_count=2))
        if not curve.length > 1e-9 * self.assembly.support.length:
            raise CaseError("target", "the target has zero length")
        if start is not None and not isinstance(start, AssemblyResult):
            raise CaseError("start", f"give an earlier AssemblyResult of this deformer, not {type(start).__name__}")
        n = len(self.bodies)
        lowers, images, placements = [None] * n, [None] * n, [None] * n
        state = None
        if self.joint is not None:
            place = self.joint.preview if preview else self.joint.place
            laws = tuple(body.law for body in a.bodies)
            lowers, images, placements, state = place(curve, laws, start.state if start is not None else None)
        for b in self.layout.order if self.joint is None else ():
            body = self.bodies[b]
            fixed = self.fixed_parts[b]
            nodes = np.empty((len(body.source), 2))
            nodes[fixed["support_nodes"]] = curve.at_fractions(fixed["support_fractions"])
            for j, on, where in fixed["on_foundations"]:
                nodes[on] = images[j][where]
            try:
                with np.errstate(all="ignore"):
                    placement = body.prepared.place(nodes, a.bodies[b].law)
            except (MeshError, LawError, GeometryError) as exc:
                raise _renamed(exc, a.label(b)) from exc
            lowers[b], images[b], placements[b] = nodes, placement.upper, placement
        results = tuple(self._body_result(b, lowers, images, placements[b]) for b in range(n))
        self._check(results, lowers, images)
        seconds = time.perf_counter() - t0
        warnings = tuple(f"{a.label(b)}: {w}" for b in range(n) for w in placements[b].warnings)
        return AssemblyResult(name=a.name, units=a.units, model=self.model_name, bodies=results,
                              timings={"prepare_s": self.prepare_seconds, "place_s": seconds}, warnings=warnings,
                              axis=a.revolution.axis if a.revolution is not None else None, state=state)

    def _fixed_parts(self, b: int) -> dict:
        """What body ``b``'s results share whatever the target: its initial curves, contour, initial volume, points taken out."""
        a = self.assembly
        body = self.bodies[b]
        sec = body.section
        initial_upper = np.array(sec.upper)
        if body.contour_order is not None:
            initial_taken = body.original_upper[[k for k, *_ in body.taken]].reshape(-1, 2)
            initial_upper = np.concatenate((initial_upper, initial_taken))[body.contour_order]
        taken = np.array([row for row in body.taken], dtype=np.float64).reshape(-1, 4)
        initial_contour = np.concatenate((sec.lower, initial_upper[1:-1]))
        side = None
        if a.revolution is not None:
            before = signed_distance(initial_contour, a.revolution.axis)
            side = float(np.sign(before[np.argmax(np.abs(before))]))
        # Where the points taken out sit in the contour, and the last point before each that is not one
        # (the contour is the prepared polygon with these points inserted: see _sliver).
        inserted = np.zeros(0, dtype=np.int64)
        anchor = np.zeros(0, dtype=np.int64)
        if body.contour_order is not None and len(body.taken):
            if (body.contour_order[[0, -1]] >= len(sec.upper)).any():  # pragma: no cover - taken points lie inside runs
                raise MeshError(f"{a.label(b)}: a point taken out of its upper polyline falls at an end of it")
            is_taken = body.contour_order[1:-1] >= len(sec.upper)
            inserted = len(sec.lower) + np.flatnonzero(is_taken)
            own = np.concatenate((np.arange(len(sec.lower)), len(sec.lower) + np.flatnonzero(~is_taken)))
            anchor = own[np.searchsorted(own, inserted) - 1]
        sup = body.source == SUPPORT
        on = tuple((j, np.flatnonzero(body.source == j), body.where[body.source == j].astype(np.int64))
                   for j in self.layout.foundations[b])
        kept = np.flatnonzero(body.kept >= 0)
        rs, i = taken[:, 1].astype(np.int64), taken[:, 2].astype(np.int64)
        groups = tuple((int(r), np.flatnonzero(rs == r), i[rs == r], taken[rs == r, 3:]) for r in np.unique(rs))
        return {
            "support_nodes": np.flatnonzero(sup), "support_fractions": body.where[sup].copy(), "on_foundations": on,
            "kept": kept, "kept_index": body.kept[kept], "taken_groups": groups,
            "initial_lower": np.array(sec.lower),
            "initial_contour": initial_contour,
            "volume_initial": volume(sec.contour, a.revolution.axis) if a.revolution is not None else None,
            "axis_side": side,
            "taken_k": taken[:, 0].astype(np.int64),
            "inserted": inserted, "anchor": anchor,
        }

    def _upper_images(self, b: int, lowers, images) -> tuple[np.ndarray, np.ndarray]:
        """Images of the case's upper points of body ``b``, and of the points taken out of it."""
        fixed = self.fixed_parts[b]
        up = np.empty_like(self.bodies[b].original_upper)
        up[fixed["kept"]] = images[b][fixed["kept_index"]]
        taken = np.empty((len(fixed["taken_k"]), 2))
        for r, rows, i, t in fixed["taken_groups"]:
            low = lowers[r]
            taken[rows] = (1.0 - t) * low[i] + t * low[i + 1]
        up[fixed["taken_k"]] = taken
        return up, taken

    def _body_result(self, b: int, lowers, images, placement) -> BodyResult:
        a = self.assembly
        body = self.bodies[b]
        sec = body.section
        fixed = self.fixed_parts[b]
        up, taken = self._upper_images(b, lowers, images)
        contour_upper = images[b]
        if body.contour_order is not None:
            contour_upper = np.concatenate((images[b], taken))[body.contour_order]
        final_polygon = np.concatenate((lowers[b], images[b][1:-1]))
        final = abs(polygon_area(final_polygon))
        law = a.bodies[b].law
        wanted = law.target_area(sec.area) if law.measure == "area" else None
        volumes = {}
        if a.revolution is not None:
            v0 = fixed["volume_initial"]
            volumes = {"volume_initial": v0, "volume_final": volume(final_polygon, a.revolution.axis)}
            if law.measure == "volume":
                volumes["volume_target"] = abs(law.target(v0))
        prepared = body.prepared
        return BodyResult(
            name=a.bodies[b].name,
            lower=lowers[b],
            upper=up,
            contour=np.concatenate((lowers[b], contour_upper[1:-1])),
            initial_lower=fixed["initial_lower"],
            initial_upper=body.original_upper,
            initial_contour=fixed["initial_contour"],
            area_initial=sec.area,
            area_target=wanted,
            area_final=final,
            initial_mesh=prepared.initial_mesh,
            final_mesh=placement.final_mesh,
            quality=ResultQuality(prepared.quality, placement.quality),
            info=placement.info,
            **volumes,
        )

    def _check(self, results, lowers, images) -> None:
        """Each law, the bonds, simple contours, no overlap; refuse naming the bodies.

        The overlap of two deformed bodies is refused above
        :data:`OVERLAP_TOLERANCE` of the smaller body's area. Their
        intersection area is measured (a polygon overlay) only when a cheaper
        test cannot show it is below that: bounding boxes apart, or (see
        :func:`_no_overlap`) the prepared polygons' interiors disjoint, an
        exact topological test, with the slivers between each contour and its
        prepared polygon bounded by area.
        """
        a = self.assembly
        label = a.label
        rings = [None] * len(results)
        for b, r in enumerate(results):
            if not abs(r.final - r.target) <= AREA_TOLERANCE * r.target:
                raise LawError(f"{label(b)}: the final {r.measure} {r.final:.9g} misses the target {r.target:.9g} by more than 1e-9")
            rings[b] = shapely.linearrings(r.contour)
            if not shapely.is_simple(rings[b]):
                raise GeometryError(f"{label(b)}: the deformed contour crosses itself; the target or the law is too severe for this body")
            if a.revolution is not None:
                after = signed_distance(r.contour, a.revolution.axis)
                if (self.fixed_parts[b]["axis_side"] * after < -self.layout.tolerance).any():
                    raise GeometryError(f"{label(b)}: the deformed body crosses the revolution axis; "
                                        "the target brings it too close to the axis")
        size = a.size
        for b in range(len(self.bodies)):
            for j, on, where in self.fixed_parts[b]["on_foundations"]:
                if not len(on):
                    continue
                gap = np.hypot(*(lowers[b][on] - images[j][where]).T).max()
                if not gap <= BOND_TOLERANCE * size:
                    raise GeometryError(f"{label(b)} and {label(j)}: the shared piece comes apart by {gap:.3g} after deformation")
        n = len(results)
        if n < 2:
            return
        boxes = np.array([np.concatenate((r.contour.min(axis=0), r.contour.max(axis=0))) for r in results])
        prepared = [None] * n
        polygons = [None] * n
        for i in range(n):
            for j in range(i + 1, n):
                if (boxes[i, 2:] < boxes[j, :2]).any() or (boxes[j, 2:] < boxes[i, :2]).any():
                    continue  # apart: the polygons do not meet
                for k in (i, j):
                    if prepared[k] is None:
                        fixed = self.fixed_parts[k]
                        ring = np.concatenate((lowers[k], images[k][1:-1]))
                        prepared[k] = _Prepared(results[k].contour, ring, results[k].area_final, fixed["inserted"], fixed["anchor"],
                                                rings[k])
                if _no_overlap(prepared[i], prepared[j], OVERLAP_TOLERANCE):
                    continue
                for k in (i, j):
                    if polygons[k] is None:
                        polygons[k] = shapely.Polygon(results[k].contour)
                if not polygons[i].intersects(polygons[j]):
                    continue
                area = shapely.intersection(polygons[i], polygons[j]).area
                if area > OVERLAP_TOLERANCE * min(polygons[i].area, polygons[j].area):
                    raise GeometryError(
                        f"{label(i)} and {label(j)}: the deformed bodies overlap (area {area:.3g}); "
                        "the target or the laws are too severe for this assembly"
                    )


class _Prepared:
    """A deformed body's contour beside its prepared polygon (the contour without the points taken out).

    Parameters
    ----------
    contour : (k, 2) float64 ndarray
        The result's contour, units.
    ring : (p, 2) float64 ndarray
        The prepared polygon, units: the body's deformed lower nodes then
        the image of its prepared upper polyline without its ends, whose
        shared pieces are the resting bodies' lower nodes bit for bit;
        ``contour`` is ``ring`` with the points at ``inserted`` put in.
    area : float
        Area of ``ring``, units².
    inserted, anchor : (q,) int ndarray
        Positions in ``contour`` of the points not in ``ring``, and of the
        last point of ``ring`` before each.
    contour_ring : shapely.LinearRing, optional
        ``contour`` as a ring, already found simple (then, with nothing
        inserted, the polygon is built on it).

    Attributes
    ----------
    polygon : shapely.Polygon or None
        The prepared polygon; None when ``ring`` is not simple.
    sliver : float
        Upper bound of the area between the contour and the prepared
        polygon, units² (:func:`_sliver`).
    area : float
    """

    def __init__(self, contour, ring, area, inserted, anchor, contour_ring=None):
        self.sliver = _sliver(contour, inserted, anchor)
        self.area = area
        if not len(inserted) and contour_ring is not None:  # the ring is the contour, found simple
            self.polygon = shapely.polygons(contour_ring)
            return
        ring = shapely.linearrings(ring)
        self.polygon = shapely.polygons(ring) if shapely.is_simple(ring) else None


def _sliver(contour: np.ndarray, inserted: np.ndarray, anchor: np.ndarray) -> float:
    """Upper bound of the area between a contour and the same contour without its points at ``inserted``, units².

    The points ``inserted`` of ``contour`` ``(k, 2)`` were put between two
    consecutive points of the shorter polygon; ``anchor`` is the point of
    the shorter polygon before each. For one edge ``u v`` of the shorter
    polygon and the points ``t1 ... tq`` put in it, the two polygons differ
    by the closed path ``u t1 ... tq v``, whose winding number, integrated
    in absolute value, is at most the sum of its fan's triangles
    ``|u t_m t_m+1|`` (and ``|u tq v|``): for two simple rings of one
    orientation, the area of their symmetric difference is at most that sum
    over every inserted point.
    """
    if not len(inserted):
        return 0.0
    u = contour[anchor]
    p = contour[inserted] - u
    q = contour[(inserted + 1) % len(contour)] - u
    return 0.5 * float(np.abs(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]).sum())


def _no_overlap(p: _Prepared, q: _Prepared, tolerance: float) -> bool:
    """Whether two deformed bodies surely overlap by at most ``tolerance`` of the smaller area; False if unsure.

    True when the prepared polygons' interiors are disjoint (GEOS's relate,
    exact on segments that are bit for bit the same, as a shared piece's
    are) and the slivers between each contour and its prepared polygon
    add up to at most half the allowed area: the contours' overlap is then
    at most that sum (the overlap of two regions lies in the overlap of
    their prepared polygons plus the two symmetric differences). False
    sends the caller to the full measurement.
    """
    if p.polygon is None or q.polygon is None:
        return False
    if not p.sliver + q.sliver <= 0.5 * tolerance * min(p.area, q.area):
        return False
    return not shapely.relate_pattern(p.polygon, q.polygon, "T********")


def deform_assembly(assembly: Assembly, model: str | None = None, element_size: float | None = None) -> AssemblyResult:
    """Deform an assembly once onto its own target: :class:`AssemblyDeformer` then :meth:`AssemblyDeformer.deform`."""
    return AssemblyDeformer(assembly, model, element_size).deform()
