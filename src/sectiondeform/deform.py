"""The pipeline: problem -> stack of sections -> model -> checked result, once or for many targets.

>>> import sectiondeform as sd
>>> deformer = sd.Deformer(sd.load_case(sd.example_case_path()))
>>> result = deformer.deform()                      # the case's own target
>>> round(result.area_final, 1)
3503.2

``Deformer`` keeps the bodies' sections, meshes and point locations, so
``deformer.deform(other_target)`` redoes only the placement: the
interactive use. It works the same for one body or several, plane or
revolution, with either model: the paper's model places the bodies from
the support up, the hyperelastic one solves them all at once.

Prepare once, place many: the lower curves were sampled finely enough for
the case's own target. Another target is sampled at the same arc-length
fractions of the support; where it bends more than the case's target, the
deformed lower polyline strays from it. Every placement measures that
deviation (the target's points at the mid-fractions against the chords'
midpoints) and, above the chordal error, says so in ``result.warnings``.

Every result is checked before it is returned: each body's law (its area,
or its volume of revolution) to :data:`AREA_TOLERANCE`, finite points, no
final element inverted, every body's contour simple, shared points
coinciding to :data:`BOND_TOLERANCE` of the problem's size, no overlap
between deformed bodies, no body crossing the axis of revolution. A
section that would come out turned over (its lower curve drawn the other
way than its target) is refused.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping, Sequence

import numpy as np
import shapely

from .curves import Curve, Polyline, as_points, polygon_area
from .errors import CaseError, GeometryError, LawError, MeshError
from .laws import Law, check_growth
from .models import get_model
from .models.hyperelastic_contact import contact_results
from .pappus import signed_distance, volume
from .problem import V1, Problem
from .result import RESULT_V1, RESULT_V2, BodyResult, Result, ResultQuality
from .stack import Stack, Target, renamed
from .verify import check_placement, inverted

__all__ = ["Deformer", "deform", "AREA_TOLERANCE", "BOND_TOLERANCE", "OVERLAP_TOLERANCE", "TARGET_DEVIATION_SLACK"]

AREA_TOLERANCE = 1e-9
BOND_TOLERANCE = 1e-9
"""Largest distance between the two images of a shared point, as a fraction of the problem's size."""
OVERLAP_TOLERANCE = 1e-9
"""Largest overlap area of two deformed bodies, as a fraction of the smaller body's area."""
TURNED_OVER_NEAR = 0.05  # a target this close to the reversed support (fraction of its length) is a drawing error
TARGET_DEVIATION_SLACK = 1.5
"""A target is reported as under-sampled when it strays from the deformed lower
polyline by more than this times the chordal error."""


def _centroid(ring: np.ndarray) -> np.ndarray:
    """Area centroid of a closed polygon ``(N, 2)``."""
    x, y = ring[:, 0], ring[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    a = c.sum()
    if a == 0:
        return ring.mean(axis=0)
    return np.array([((x + x1) * c).sum(), ((y + y1) * c).sum()]) / (3.0 * a)


class Deformer:
    """A problem prepared once for deformation onto any number of targets.

    Parameters
    ----------
    problem : Problem
    model : str, optional
        A name of :data:`~sectiondeform.models.MODEL_NAMES`; by default ``problem.options.model``.
    element_size : float, optional
        Element size of every body's section, units; overrides the case's.
    check : bool
        Check every deformed contour for self-intersection (shapely).

    Attributes
    ----------
    problem : Problem
    stack : Stack
        The bodies' sections and the sources of their lower nodes.
    prepared : Prepared
        The model's state that depends on the bodies alone (meshes, locations).

    Raises
    ------
    GeometryError, MeshError
        Naming the body whose section or mesh cannot be built.
    CaseError
        For a material the model cannot take.
    """

    def __init__(self, problem: Problem, model: str | None = None, element_size: float | None = None, check: bool = True):
        t0 = time.perf_counter()
        if not isinstance(problem, Problem):
            raise CaseError("problem", f"expected a Problem (sectiondeform.load_case), got {type(problem).__name__}")
        self.problem = problem
        self.model_name = model or problem.model
        self.model = get_model(self.model_name)
        self.stack = Stack(problem, element_size)
        self.prepared = self.model.prepare(self.stack, problem.options.for_model(self.model_name))
        for b, body in enumerate(self.prepared.bodies):  # checked once, independently of the model
            bad = inverted(body.initial_mesh)
            if bad:
                raise renamed(MeshError(f"initial mesh: {bad}; lower options.element_size or smooth the section's corners"),
                              problem.label(b))
        self.check = check
        self.prepare_seconds = time.perf_counter() - t0

    @property
    def case(self) -> Problem:
        """The problem (the name of the case file it came from)."""
        return self.problem

    @property
    def section(self):
        """The section of a one-body problem (:class:`~sectiondeform.section.Section`)."""
        if len(self.stack.bodies) != 1:
            raise CaseError("section", f"the problem has {len(self.stack.bodies)} bodies; read deformer.stack.sections[i]")
        return self.stack.bodies[0].section

    @property
    def fractions(self) -> np.ndarray:
        """The support's arc-length fractions at which the target is sampled, ``(k,)``."""
        return self.stack.fractions

    @property
    def chordal_error(self) -> float:
        """The finest chordal error of the bodies' sections, units."""
        return min(s.chordal_error for s in self.stack.sections)

    def target_nodes(self, target: Curve | np.ndarray | None = None) -> np.ndarray:
        """The target at :attr:`fractions`, ``(k, 2)``: the drag fast path's ``target_nodes``.

        ``target`` may be a :class:`~sectiondeform.curves.Curve`, any
        ``(j, 2)`` polyline (j >= 2, taken as a :class:`~sectiondeform.curves.Polyline`),
        or None for the case's own.
        """
        return self._checked_nodes(self._target_curve(target).at_fractions(self.fractions))

    def _target_curve(self, target) -> Curve:
        if target is None:
            return self.problem.target
        if isinstance(target, Curve):
            return target
        return Polyline(as_points(target, "target", min_count=2))

    def _checked_nodes(self, nodes) -> np.ndarray:
        nodes = as_points(nodes, "target_nodes", min_count=1)
        if len(nodes) != len(self.fractions):
            raise CaseError(
                "target_nodes",
                f"expected {len(self.fractions)} nodes (one per support fraction, deformer.fractions), got {len(nodes)}; "
                "give the target as a curve or polyline instead",
            )
        steps = nodes[1:] - nodes[:-1]
        length = np.hypot(steps[:, 0], steps[:, 1]).sum()
        if not length > 1e-9 * self.stack.support_length:
            raise CaseError("target", "the target has zero length")
        return nodes

    def target_deviation(self, target: Curve | np.ndarray | None = None) -> float:
        """Largest distance, in units, between the target and its polyline at :attr:`fractions`.

        Measured at the middle of every step: the target's point at the
        mid-fraction against the midpoint of the chord. Compare with
        :attr:`chordal_error`.
        """
        curve = self._target_curve(target)
        return self._deviation(curve, curve.at_fractions(self.fractions))

    def _deviation(self, curve: Curve, nodes: np.ndarray) -> float:
        s = self.fractions
        if len(s) < 2:
            return 0.0
        mids = curve.at_fractions(0.5 * (s[1:] + s[:-1]))
        d = mids - 0.5 * (nodes[1:] + nodes[:-1])
        return float(np.hypot(d[:, 0], d[:, 1]).max())

    def laws(self, law=None) -> tuple:
        """One law per body: the case's, or ``law`` given as one :class:`Law` (one body), a sequence or a mapping by name."""
        bodies = self.problem.bodies
        if law is None:
            return tuple(b.law for b in bodies)
        if isinstance(law, Law):
            if len(bodies) != 1:
                raise CaseError("law", f"the problem has {len(bodies)} bodies; give one law per body (a list, or a dict by body name)")
            return (self._bound(0, law),)
        if isinstance(law, Mapping):
            names = [b.name for b in bodies]
            for key in law:
                if key not in names:
                    raise CaseError("law", f"no body is called {key!r}; the bodies are {', '.join(map(repr, names))}")
            return tuple(self._bound(i, law.get(b.name, b.law)) for i, b in enumerate(bodies))
        if isinstance(law, Sequence) and len(law) == len(bodies) and all(isinstance(x, Law) for x in law):
            return tuple(self._bound(i, x) for i, x in enumerate(law))
        raise CaseError("law", f"expected a Law, or one Law per body ({len(bodies)}), got {type(law).__name__}")

    def _bound(self, i: int, law: Law) -> Law:
        """``law`` bound to the problem's axis (a volume law), as the case's own laws are."""
        rev = self.problem.revolution
        if not law.needs_axis:
            return law
        if rev is None:  # the growth of an extruded body
            return check_growth(law if law.axis is None else law.about(None), f"bodies[{i}].law")
        return law if law.axis == rev.axis else law.about(rev.axis)

    def travels(self, travel=None) -> tuple | None:
        """The rigid parts' travels ``((dx, dy), ...)`` (units, the problem's order) for ``travel``; None for None.

        ``travel`` is a mapping of part name to ``(dx, dy)`` (the parts not
        named keep the problem's), or one ``(dx, dy)`` per part, in order.
        A part starts where the problem starts it (its contour less its
        travel) and ends this far from there.
        """
        if travel is None:
            return None
        parts = self.problem.rigid
        if not parts:
            raise CaseError("travel", "the problem has no rigid parts; give a travel only to a problem with rigid parts")
        if isinstance(travel, Mapping):
            names = [p.name for p in parts]
            for key in travel:
                if key not in names:
                    raise CaseError("travel", f"no rigid part is called {key!r}; the parts are {', '.join(map(repr, names))}")
            pairs = [travel.get(p.name, p.travel) for p in parts]
        elif isinstance(travel, Sequence) and not isinstance(travel, str) and len(travel) == len(parts):
            pairs = list(travel)
        else:
            raise CaseError("travel", f"expected one (dx, dy) per rigid part ({len(parts)}), or a dict by part name, "
                                      f"got {travel!r}")
        out = []
        for part, pair in zip(parts, pairs):
            try:
                v = np.asarray(pair, dtype=np.float64)
            except (TypeError, ValueError):
                v = np.zeros(0)
            if v.shape != (2,) or not np.isfinite(v).all():
                raise CaseError(f"travel[{part.name!r}]", f"expected two finite numbers (dx, dy), got {pair!r}")
            out.append((float(v[0]), float(v[1])))
        return tuple(out)

    def deform(self, target: Curve | np.ndarray | None = None, law=None, *,
               target_nodes: np.ndarray | None = None, start: Result | None = None, travel=None) -> Result:
        """Deform the problem: the support onto ``target``, each body under its law.

        Parameters
        ----------
        target : Curve or (k, 2) array_like, optional
            Where the support goes, A' to B', units: a curve, or any
            polyline. By default the case's own target.
        law : Law, sequence of Law, or mapping of name to Law, optional
            The laws to use instead of the case's: one :class:`Law` for a
            one-body problem, else one per body (in order, or by name).
        target_nodes : (k, 2) array_like, optional
            Fast path for dragging: the target already at the support
            fractions (:attr:`fractions`, :meth:`target_nodes`), instead of
            ``target``. The target between two nodes is their chord; no
            deviation is measured.
        start : Result, optional
            An earlier result of this deformer to start the solve from (a
            warm start; the hyperelastic model only). Without it the answer
            depends on the other arguments alone, bit for bit.
        travel : mapping or sequence, optional
            The rigid parts' travels instead of the problem's (:meth:`travels`):
            a study of the squeeze, or a part dragged on the page, without
            preparing the problem again. From a ``start`` solved at other
            travels, the parts are loaded from where they ended there.

        Returns
        -------
        Result

        Raises
        ------
        MeshError, LawError, GeometryError
            Naming the body: an inverted element, an unmet law, a crossing
            contour; two deformed bodies that overlap or come apart; a
            section that would come out turned over.
        CaseError
            If the target is not a curve or a polyline of finite points, or
            ``start`` is not a result of this deformer.
        """
        return self._run(self.prepared.place, target, law, target_nodes, start, travel)

    def preview(self, target: Curve | np.ndarray | None = None, law=None, *,
                target_nodes: np.ndarray | None = None, start: Result | None = None, travel=None) -> Result:
        """A fast deformation for dragging the target or a rigid part (interactive preview).

        The paper model answers exactly as :meth:`deform`; the hyperelastic
        model takes one linearised step from ``start`` (a result of this
        deformer) or from the undeformed bodies, with the factorisation at
        hand: every law is met exactly and the interfaces stay bonded,
        every check of :meth:`deform` is made, but the shape is first-order
        in the change of target (each body's ``info.preview`` is True):
        call :meth:`deform` when the drag ends. From a ``start`` with rigid
        parts, a ``travel`` other than ``start``'s moves them in the same
        linear step (the contact figures are then ``start``'s). Arguments
        as :meth:`deform`.
        """
        return self._run(self.prepared.preview, target, law, target_nodes, start, travel)

    def _run(self, placer, target, law, target_nodes, start, travel=None) -> Result:
        t0 = time.perf_counter()
        laws = self.laws(law)
        travels = self.travels(travel)
        warnings: list[str] = []
        if target_nodes is not None:
            if target is not None:
                raise CaseError("target_nodes", "give either target or target_nodes, not both")
            nodes = self._checked_nodes(target_nodes)
            where = Target(self.fractions, nodes)
        else:
            curve = self._target_curve(target)
            if not curve.length > 1e-9 * self.stack.support_length:
                raise CaseError("target", "the target has zero length")
            nodes = self._checked_nodes(curve.at_fractions(self.fractions))
            where = Target(self.fractions, nodes, curve)
            deviation = self._deviation(curve, nodes)
            tol = self.chordal_error
            if deviation > TARGET_DEVIATION_SLACK * tol:
                warnings.append(
                    f"target: the deformed lower curve strays {deviation:.3g} {self.problem.units} from the target "
                    f"(chordal error {tol:.3g}): the section was sampled for another target; "
                    "prepare again on a case with this target for a resolved lower curve"
                )
        if start is not None and not isinstance(start, Result):
            raise CaseError("start", f"give an earlier Result of this deformer, not {type(start).__name__}")
        with np.errstate(all="ignore"):
            placed = placer(where, laws, start.state if start is not None else None, travels)
            bodies = tuple(self._body_result(b, placed, laws[b]) for b in range(len(laws)))
            self._check(bodies, placed)
        problem = self.problem
        label = problem.label
        warnings += [f"{label(b)}: {w}" if label(b) else w for b in range(len(laws)) for w in placed.placements[b].warnings]
        rigid, support_force, history, contact_warnings = contact_results(placed.state)
        warnings += contact_warnings
        result = Result(
            name=problem.name, units=problem.units, model=self.model_name, bodies=bodies,
            timings={"prepare_s": self.prepare_seconds, "place_s": time.perf_counter() - t0}, warnings=tuple(warnings),
            axis=problem.revolution.axis if problem.revolution is not None else None,
            dialect=RESULT_V1 if problem.dialect == V1 else RESULT_V2, state=placed.state,
            rigid=rigid, support_force=support_force, history=history,
        )
        if target is None and target_nodes is None:
            result = self._check_not_turned_over(result)
        return result

    def _body_result(self, b: int, placed, law: Law) -> BodyResult:
        """Body ``b``'s result from a placement: its curves, measures, meshes and figures."""
        problem, stack = self.problem, self.stack
        body = stack.bodies[b]
        fixed = stack.fixed_parts[b]
        lowers, images = placed.lowers, placed.images
        placement = placed.placements[b]
        up, taken = stack.upper_images(b, lowers, images)
        contour_upper = images[b]
        if body.contour_order is not None:
            contour_upper = np.concatenate((images[b], taken))[body.contour_order]
        polygon = np.concatenate((lowers[b], images[b][1:-1]))
        holes = tuple(np.asarray(h) for h in placement.holes)
        if not (np.isfinite(polygon).all() and np.isfinite(placement.final_mesh.points).all()
                and all(np.isfinite(h).all() for h in holes)):
            raise renamed(GeometryError("result: the deformation produced non-finite points; the target or the law is too severe "
                                        "for this section"), problem.label(b))
        volumes = {}
        if problem.revolution is not None:
            v0 = fixed["volume_initial"]
            axis = problem.revolution.axis
            volumes = {"volume_initial": v0, "volume_final": volume(polygon, axis) - sum(volume(h, axis) for h in holes)}
            if law.measure == "volume":
                volumes["volume_target"] = abs(law.target(v0))
        prepared = self.prepared.bodies[b]
        return BodyResult(
            name=problem.bodies[b].name,
            lower=lowers[b],
            upper=up,
            contour=np.concatenate((lowers[b], contour_upper[1:-1])),
            initial_lower=fixed["initial_lower"],
            initial_upper=body.original_upper,
            initial_contour=fixed["initial_contour"],
            area_initial=fixed["area_initial"],
            area_target=(abs(placement.target) if placement.target is not None else law.target_area(fixed["area_initial"]))
            if law.measure == "area" else None,
            area_final=abs(polygon_area(polygon)) - sum(abs(polygon_area(h)) for h in holes),
            initial_mesh=prepared.initial_mesh,
            final_mesh=placement.final_mesh,
            quality=ResultQuality(prepared.quality, placement.quality),
            info=placement.info,
            holes=holes,
            initial_holes=body.section.holes,
            **volumes,
        )

    def _check(self, results, placed) -> None:
        """Each law, finite points and sound elements, simple contours, the axis, the bonds, no overlap.

        The overlap of two deformed bodies is refused above
        :data:`OVERLAP_TOLERANCE` of the smaller body's area. Their
        intersection area is measured (a polygon overlay) only when a cheaper
        test cannot show it is below that: bounding boxes apart, or (see
        :func:`_no_overlap`) the prepared polygons' interiors disjoint, an
        exact topological test, with the slivers between each contour and its
        prepared polygon bounded by area.
        """
        problem, stack = self.problem, self.stack
        label = problem.label
        lowers, images = placed.lowers, placed.images
        rings = [None] * len(results)
        for b, r in enumerate(results):
            if not abs(r.final - r.target) <= AREA_TOLERANCE * r.target:
                raise renamed(LawError(f"law: the final {r.measure} {r.final:.9g} misses the target {r.target:.9g} by more than 1e-9"),
                              label(b))
            failed = check_placement(r)  # independent checks: no NaN, no final element inverted anywhere
            if failed:
                kind = MeshError if "mesh" in failed[0].split(":")[0] else GeometryError
                raise renamed(kind(f"result: refused, an independent check failed: {failed[0]}"), label(b))
            rings[b] = shapely.linearrings(r.contour)
            if self.check and not shapely.is_simple(rings[b]):
                raise renamed(GeometryError("result: the deformed contour crosses itself; the target or the law is too severe "
                                            "for this section"), label(b))
            failed = hole_failure(r.contour, r.holes, r.initial_holes)
            if failed:
                raise renamed(GeometryError(f"result: {failed}; the target or the law is too severe for this hollow section "
                                            "(the contact of a hole's sides with each other is not modelled)"), label(b))
            if problem.revolution is not None:
                after = signed_distance(r.contour, problem.revolution.axis)
                if (stack.fixed_parts[b]["axis_side"] * after < -stack.layout.tolerance).any():
                    raise renamed(GeometryError("result: the deformed body crosses the revolution axis; the target brings it "
                                                "too close to the axis"), label(b))
        size = problem.size
        for b in range(len(results)):
            for j, on, where in stack.fixed_parts[b]["on_foundations"]:
                if not len(on):
                    continue
                gap = np.hypot(*(lowers[b][on] - images[j][where]).T).max()
                if not gap <= BOND_TOLERANCE * size:
                    raise GeometryError(f"{label(b)} and {label(j)}: the shared piece comes apart by {gap:.3g} after deformation")
        self._check_overlaps(results, lowers, images, rings)

    def _check_overlaps(self, results, lowers, images, rings) -> None:
        n = len(results)
        if n < 2:
            return
        label = self.problem.label
        boxes = np.array([np.concatenate((r.contour.min(axis=0), r.contour.max(axis=0))) for r in results])
        prepared = [None] * n
        polygons = [None] * n
        for i in range(n):
            for j in range(i + 1, n):
                if (boxes[i, 2:] < boxes[j, :2]).any() or (boxes[j, 2:] < boxes[i, :2]).any():
                    continue  # apart: the polygons do not meet
                for k in (i, j):
                    if prepared[k] is None:
                        fixed = self.stack.fixed_parts[k]
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
                        "the target or the laws are too severe for these bodies"
                    )

    def _check_not_turned_over(self, result: Result) -> Result:
        """Refuse, or flag, bodies that come out on the other side of the target than of the support.

        That happens when the support (a one-body case's lower curve) is
        drawn the other way than the target (B to A): the target starts near
        the support's end B and ends near its start A, and the deformed
        bodies lie on the other side of the target than the initial ones of
        the support. When the target is the support reversed (ends and
        points within ``TURNED_OVER_NEAR`` of its length), that is refused;
        when it is only near it (a quarter of the length: a half turn on
        purpose cannot be told from a drawing error), the result carries a
        warning.
        """
        support = self.problem.support
        s = self.fractions
        low0, low1 = support.at_fractions(s), self.problem.target.at_fractions(s)
        length = support.length
        ends = max(np.hypot(*(low1[0] - low0[-1])), np.hypot(*(low1[-1] - low0[0])))
        if ends >= 0.25 * length:
            return result
        areas = np.array([b.area_initial for b in result.bodies])
        c0 = np.average([_centroid(b.initial_contour) for b in result.bodies], axis=0, weights=areas)
        c1 = np.average([_centroid(b.contour) for b in result.bodies], axis=0, weights=areas)
        if float((c0 - low0.mean(axis=0)) @ (c1 - low1.mean(axis=0))) >= 0:
            return result
        fix = "reverse the lower curve or the target"
        apart = shapely.hausdorff_distance(shapely.linestrings(low0), shapely.linestrings(low1))
        if ends < TURNED_OVER_NEAR * length and apart < TURNED_OVER_NEAR * length:
            raise GeometryError(
                "target: the section would come out turned over, on the other side of the target than of "
                f"its lower curve (the lower curve runs the other way than the target); {fix}"
            )
        note = (f"target: its ends are within {ends / length:.2g} of the support's length of the support's "
                "ends swapped and the section comes out on the other side of it (turned over); "
                f"if the lower curve was drawn the other way than the target, {fix}")
        return dataclasses.replace(result, warnings=(*result.warnings, note))


def hole_failure(contour: np.ndarray, holes, initial_holes) -> str | None:
    """What is wrong with a deformed body's holes, naming the hole; None when each stays open and inside.

    A hole fails when it closes (its area changes sign or vanishes), its
    boundary crosses itself, or it crosses or touches the contour or another
    hole.

    Parameters
    ----------
    contour : (k, 2) float64 ndarray
        The deformed contour.
    holes, initial_holes : sequence of (k_h, 2) float64 ndarray
        Each hole after and before deformation.
    """
    if not len(holes):
        return None
    outer = shapely.Polygon(contour)
    polys = []
    for k, (h, h0) in enumerate(zip(holes, initial_holes)):
        a, a0 = polygon_area(h), polygon_area(h0)
        if not a * a0 > 0 or not abs(a) > 1e-9 * abs(a0):
            return f"holes[{k}] closes (its area goes from {abs(a0):.6g} to {a if a * a0 > 0 else -abs(a):.3g})"
        ring = shapely.linearrings(h)
        if not shapely.is_simple(ring):
            return f"holes[{k}]: its deformed boundary crosses itself"
        poly = shapely.Polygon(h)
        if not (outer.contains(poly) and not shapely.intersects(outer.exterior, ring)):
            return f"holes[{k}]: its deformed boundary crosses or touches the body's contour"
        for j, other in enumerate(polys):
            if other.intersects(poly):
                return f"holes[{k}]: its deformed boundary crosses or touches holes[{j}]"
        polys.append(poly)
    return None


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


def deform(problem: Problem, model: str | None = None, element_size: float | None = None) -> Result:
    """Deform a problem once onto its own target: :class:`Deformer` then :meth:`Deformer.deform`.

    Parameters
    ----------
    problem : Problem
        One body or several (:func:`~sectiondeform.io.case.load_case`).
    model : str, optional
        ``"paper"`` or ``"hyperelastic"``; by default the case's.
    element_size : float, optional
        Element size, units.

    Returns
    -------
    Result
    """
    return Deformer(problem, model, element_size).deform()
