"""How the bodies of a problem rest on the support and on each other, checked.

:func:`layout` checks that

- every point of a body's lower curve lies on its foundation, the support
  or other bodies' upper curves, within ``options.contact_tolerance``
  (default :data:`CONTACT_FRACTION` of the problem's bounding-box
  diagonal); otherwise the error gives the gap and its place;
- bodies' interiors do not overlap (the error gives the overlap area);
- no body rests on itself through others (the error names the cycle);
- no rigid part starts (at its contour less its travel) inside a body
  (touching is allowed; the error gives the overlap area and its place);
- a piece shared by two bodies is in exactly one body's lower curve (a
  piece in both upper curves, or in both lower curves, is refused);
- every hole of a body is a closed curve strictly inside its contour, apart
  from it and from the other holes (:func:`check_holes`);

and :func:`check_axis` that the axis of a body of revolution crosses no
body and that every body lies on the same side of it. Every message is one
line naming the bodies (``bodies[1] 'cover'``) and where. The curves are
compared through fine polylines (within a quarter of the contact
tolerance) sampled densely, so curved pieces that coincide are recognised
as shared.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import shapely

from .curves import Curve
from .errors import GeometryError
from .pappus import signed_distance

__all__ = ["Layout", "layout", "check_axis", "check_holes", "problem_size", "CONTACT_FRACTION", "SAMPLES"]

CONTACT_FRACTION = 1e-6
"""Default contact tolerance, as a fraction of the problem's bounding-box diagonal."""
HOLE_TOLERANCES = 4.0
"""A hole is more than this many contact tolerances across (its points closer than one tolerance are one point)."""
SAMPLES = 1024
"""Points sampled evenly along every curve for the resting and sharing checks (besides its vertices)."""


def problem_size(support: Curve, bodies) -> float:
    """Bounding-box diagonal of the support and every body, units."""
    pts = [support.at_fractions(np.linspace(0.0, 1.0, 65))]
    for b in bodies:
        pts += [b.lower.at_fractions(np.linspace(0.0, 1.0, 65)), b.upper.at_fractions(np.linspace(0.0, 1.0, 65))]
    return float(np.hypot(*np.ptp(np.concatenate(pts), axis=0)))


@dataclass(frozen=True, eq=False)
class Layout:
    """How the bodies of a problem rest on each other.

    Attributes
    ----------
    order : tuple of int
        Body indices from the support up: every body after its foundations.
    foundations : tuple of tuple of int
        Per body, the bodies its lower curve rests on (sorted).
    on_support : tuple of bool
        Per body, whether part of its lower curve rests on the support.
    tolerance : float
        Contact tolerance, units.
    """

    order: tuple
    foundations: tuple
    on_support: tuple
    tolerance: float
    fine: dict = field(default_factory=dict, repr=False)

    def resting_on(self, j: int) -> tuple:
        """Indices of the bodies that rest on body ``j``."""
        return tuple(i for i, f in enumerate(self.foundations) if j in f)


def _fine(curve: Curve, tol: float) -> np.ndarray:
    """A polyline within ``tol`` of ``curve``, ``(k, 2)``."""
    pts, _ = curve.discretise(tol)
    return pts


def _samples(curve: Curve, fine: np.ndarray, fractions: np.ndarray) -> np.ndarray:
    """Points of ``curve``: its fine polyline's vertices and :data:`SAMPLES` evenly spaced, in order.

    Both sets are ordered by their fraction of the curve (the fine polyline's
    from :meth:`~sectiondeform.curves.Curve.discretise`, which measures them
    as :meth:`~sectiondeform.curves.Curve.at_fractions` does).
    """
    s = np.linspace(0.0, 1.0, SAMPLES + 1)
    order = np.argsort(np.concatenate((fractions, s)), kind="stable")
    return np.concatenate((fine, curve.at_fractions(s)))[order]


def _distance(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """Distance of each point to a polyline, ``(n,)``."""
    return shapely.distance(shapely.points(points), shapely.LineString(polyline))


def _shared_length(points: np.ndarray, polyline: np.ndarray, tol: float) -> tuple[float, np.ndarray | None]:
    """Length of the run of ``points`` lying within ``tol`` of ``polyline``, and a point of it.

    Consecutive points both within ``tol`` (and their midpoint) count: two
    curves that only touch at a point share no length.
    """
    near = _distance(points, polyline) <= tol
    mids = 0.5 * (points[1:] + points[:-1])
    both = near[1:] & near[:-1]
    if both.any():
        both[both] &= _distance(mids[both], polyline) <= tol
    if not both.any():
        return 0.0, None
    steps = np.hypot(*(points[1:] - points[:-1]).T)
    return float(steps[both].sum()), mids[np.argmax(both)]


def _where(p) -> str:
    return str(np.round(np.asarray(p, dtype=float), 6).tolist())


def layout(problem) -> Layout:
    """Check how the bodies rest on the support and on each other; the resting order.

    Raises
    ------
    GeometryError
        One line naming the bodies and the place: a lower curve resting on
        nothing (with the gap), a piece shared by two upper curves or by two
        lower curves, overlapping interiors (with the area), a cycle.
    """
    bodies = problem.bodies
    label = lambda i: problem.label(i) or "the section"  # noqa: E731
    size = problem_size(problem.support, bodies)
    tol = problem.options.contact_tolerance
    if tol is None:
        tol = CONTACT_FRACTION * size
    fine_tol = 0.25 * tol
    support = _fine(problem.support, fine_tol)
    lower_fine = [b.lower.discretise(fine_tol) for b in bodies]  # points and their fractions of the curve
    upper_fine = [b.upper.discretise(fine_tol) for b in bodies]
    lowers, uppers = [f for f, _ in lower_fine], [f for f, _ in upper_fine]
    low_pts = [_samples(b.lower, *f) for b, f in zip(bodies, lower_fine)]
    up_pts = [_samples(b.upper, *f) for b, f in zip(bodies, upper_fine)]
    n = len(bodies)

    for i in range(n):
        for j in range(i + 1, n):
            length, where = _shared_length(up_pts[i], uppers[j], tol)
            if length > 0:
                raise GeometryError(
                    f"{label(i)} and {label(j)}: their upper curves share a piece of length {length:.6g} near {_where(where)}; "
                    "a shared piece belongs to the lower curve of the body that rests on the other"
                )
            length, where = _shared_length(low_pts[i], lowers[j], tol)
            if length > 0:
                raise GeometryError(
                    f"{label(i)} and {label(j)}: their lower curves share a piece of length {length:.6g} near {_where(where)}; "
                    "a shared piece belongs to the lower curve of exactly one of them"
                )

    support_json = problem.support.to_json()
    foundations, on_support = [], []
    for i in range(n):
        found = []
        is_support = bodies[i].lower.to_json() == support_json  # the paper's one body: its lower curve is the support
        gaps = [("the support", np.zeros(len(low_pts[i])) if is_support else _distance(low_pts[i], support))]
        for j in range(n):
            if j == i:
                continue
            gaps.append((label(j), _distance(low_pts[i], uppers[j])))
            length, _ = _shared_length(low_pts[i], uppers[j], tol)
            if length > 0:
                found.append(j)
        d = np.min([g for _, g in gaps], axis=0)
        if (d > tol).any():
            k = int(np.argmax(d))
            nearest = min(gaps, key=lambda g: g[1][k])[0]
            raise GeometryError(
                f"{label(i)}: its lower curve rests on nothing near {_where(low_pts[i][k])}: gap {d[k]:.6g} to {nearest} "
                f"(contact tolerance {tol:.3g}); put every point of a lower curve on the support or on another body's upper curve"
            )
        support_length = 1.0 if is_support else _shared_length(low_pts[i], support, tol)[0]
        foundations.append(tuple(found))
        on_support.append(support_length > 0)

    polygons = []
    for i in range(n):
        ring = np.concatenate((lowers[i], uppers[i][1:-1]))
        poly = shapely.Polygon(ring) if len(ring) >= 3 else shapely.Polygon()  # a flat body: refused by its section
        poly = poly if poly.is_valid else shapely.make_valid(poly)
        holes = check_holes(bodies[i].holes, poly, tol, label(i) or "body")
        polygons.append(shapely.difference(poly, shapely.union_all(holes)) if holes else poly)
    for i in range(n):
        for j in range(i + 1, n):
            overlap = shapely.intersection(polygons[i], polygons[j])
            allowed = tol * min(polygons[i].length, polygons[j].length)
            if overlap.area > allowed:
                c = shapely.get_coordinates(overlap.representative_point())[0]
                raise GeometryError(
                    f"{label(i)} and {label(j)}: their interiors overlap (area {overlap.area:.6g} near {_where(c)}); "
                    "bodies may share pieces of their outlines, not their insides"
                )

    _check_rigid_start(problem, polygons, tol)
    order = _resting_order(foundations, label)
    return Layout(order=order, foundations=tuple(foundations), on_support=tuple(on_support), tolerance=float(tol),
                  fine={"support": support, "uppers": tuple(uppers)})


def _check_rigid_start(problem, polygons, tol: float) -> None:
    """Refuse a rigid part whose outline crosses itself, whose start position (contour less travel) overlaps a
    body's interior, or whose end position lies across the target.

    Touching is allowed: an overlap of area up to the contact tolerance
    times the shorter perimeter is taken as touching, as between bodies;
    the target may run along a part's outline (a seal bonded in a housing
    that is a rigid part), not through it: the bodies bonded there would
    end inside the part, an equilibrium no loading reaches.
    """
    parts = getattr(problem, "rigid", ())
    if not parts:
        return
    from .section import ring_crossing  # here: the section's module is heavy for a command line building its parser

    target = shapely.LineString(_fine(problem.target, 0.25 * tol))
    for k, part in enumerate(parts):
        end = _fine(part.contour, 0.25 * tol)
        crossing = ring_crossing(end[:-1] if np.array_equal(end[0], end[-1]) else end)
        if crossing is not None:
            raise GeometryError(f"rigid[{k}] {part.name!r}: its contour crosses itself near {_where(crossing[2])}; a "
                                "part's outline is a simple closed curve")
        poly = shapely.Polygon(end)
        if not poly.is_valid:
            poly = shapely.make_valid(poly)
        across = shapely.intersection(target, poly.buffer(-tol))
        if across.length > tol:
            c = shapely.get_coordinates(across.representative_point())[0]
            raise GeometryError(
                f"rigid[{k}] {part.name!r}: its end position (contour) lies across the target for a length of "
                f"{across.length:.6g} near {_where(c)}; the bodies bonded there would end inside the part: "
                "move the part's contour or the target"
            )
        poly = shapely.Polygon(end - np.asarray(part.travel))
        if not poly.is_valid:
            poly = shapely.make_valid(poly)
        for i, body in enumerate(polygons):
            overlap = shapely.intersection(poly, body)
            if overlap.area > tol * min(poly.length, body.length):
                c = shapely.get_coordinates(overlap.representative_point())[0]
                who = problem.label(i) or "the body"
                raise GeometryError(
                    f"rigid[{k}] {part.name!r}: its start position (contour less travel) overlaps {who} "
                    f"(area {overlap.area:.6g} near {_where(c)}); a part starts outside the bodies: "
                    "lengthen its travel or move its contour"
                )


def check_holes(holes, contour, tol: float, name: str, labels=None) -> list:
    """Check a body's holes against its contour polygon ``contour``; their polygons.

    Each hole must be a closed curve (its ends within ``tol``), more than
    :data:`HOLE_TOLERANCES` ``* tol`` across, that does not cross itself,
    lie strictly inside the contour, farther than ``tol`` from it and from
    every other hole. ``labels`` (one str per hole) name
    the holes in messages instead of ``name: holes[k]`` (a drawing's reader
    names the layer and entity).

    Raises
    ------
    GeometryError
        One line naming the body (``name``) and the hole: open, too small
        for the tolerance (with the size it needs), crossing itself, outside the body, touching its contour or another hole.
    """
    polys = []
    outline = contour.boundary
    for k, hole in enumerate(holes):
        what = labels[k] if labels is not None else f"{name}: holes[{k}]"
        gap = float(np.hypot(*(hole.end - hole.start)))
        if gap > tol:
            raise GeometryError(f"{what}: the curve is open (its ends are {gap:.6g} apart, tolerance {tol:.3g}); "
                                "a hole is a closed curve: end it where it starts")
        size = float(np.hypot(*np.ptp(hole.at_fractions(np.linspace(0.0, 1.0, 65)), axis=0)))
        if size <= HOLE_TOLERANCES * tol:
            raise GeometryError(f"{what}: it is {size:.3g} across, too small for the contact tolerance {tol:.3g} (points "
                                f"closer than it are one point); draw it more than {HOLE_TOLERANCES * tol:.3g} across, set a "
                                "smaller options.contact_tolerance, or delete it (a hole this small changes nothing)")
        ring = _fine(hole, 0.25 * tol)
        line = shapely.LinearRing(ring)
        if not line.is_simple:
            raise GeometryError(f"{what}: the curve crosses itself; a hole is a simple closed curve")
        poly = shapely.Polygon(ring)
        if not poly.area > 0:
            raise GeometryError(f"{what}: the curve encloses no area")
        if contour.contains(poly.representative_point()) and not contour.covers(poly):  # partly out: where it crosses
            c = shapely.get_coordinates(line.intersection(outline).representative_point())[0]
            raise GeometryError(f"{what}: it crosses the body's contour near {_where(c)}; a hole lies strictly inside "
                                "its body (draw it inside, or as another body)")
        if not contour.covers(poly):
            c = shapely.get_coordinates(poly.representative_point())[0]
            raise GeometryError(f"{what}: it lies outside the body's contour near {_where(c)}; a hole lies strictly inside "
                                "its body (draw it inside, or as another body)")
        d = float(shapely.distance(outline, line))
        if d <= tol:
            p = shapely.get_coordinates(shapely.shortest_line(line, outline))[0]
            raise GeometryError(f"{what}: it touches the body's contour near {_where(p)} (gap {d:.3g}, tolerance {tol:.3g}); "
                                "a hole stays apart from the contour (an open notch is part of the contour)")
        for j, other in enumerate(polys):
            d = float(shapely.distance(other.exterior, line))
            if d <= tol or other.contains(poly.representative_point()) or poly.contains(other.representative_point()):
                p = shapely.get_coordinates(shapely.shortest_line(line, other.exterior))[0]
                raise GeometryError(f"{what}: it touches or overlaps {labels[j] if labels is not None else f'holes[{j}]'} near {_where(p)}; holes stay apart "
                                    "(draw one hole around both)")
        polys.append(poly)
    return polys


def check_axis(problem) -> None:
    """Check that the axis of revolution crosses no body and that all bodies lie on one side of it.

    A body may touch the axis (a solid of revolution's section), not cross
    it; points within the contact tolerance of the axis count as on it.

    Raises
    ------
    GeometryError
        One line naming the body: crossed by the axis (with a point on each
        side), or lying on the other side from the first body.
    """
    axis = problem.revolution.axis
    tol = problem.layout.tolerance
    side0, first = 0.0, None
    for i, body in enumerate(problem.bodies):
        pts = np.concatenate((_fine(body.lower, 0.25 * tol), _fine(body.upper, 0.25 * tol)))
        d = signed_distance(pts, axis)
        lo, hi = int(np.argmin(d)), int(np.argmax(d))
        if d[lo] < -tol and d[hi] > tol:
            raise GeometryError(
                f"{problem.label(i)}: the revolution axis crosses it (points {_where(pts[lo])} and {_where(pts[hi])} "
                "lie on either side); a section of revolution lies on one side of its axis: move the axis or the body"
            )
        side = d[hi] if d[hi] > tol else d[lo]
        if first is None:
            side0, first = side, i
        elif side * side0 < 0:
            raise GeometryError(
                f"{problem.label(i)}: it lies on the other side of the revolution axis from {problem.label(first)}; "
                "all bodies of a section of revolution lie on one side of the axis"
            )


def _resting_order(foundations, label) -> tuple:
    """Bodies from the support up (Kahn); a cycle is refused naming its bodies."""
    n = len(foundations)
    waiting = {i: set(f) for i, f in enumerate(foundations)}
    order: list[int] = []
    while waiting:
        ready = sorted(i for i, f in waiting.items() if not f)
        if not ready:
            i = min(waiting)
            path = [i]
            while True:  # walk down the foundations until a body comes back
                i = min(waiting[i])
                if i in path:
                    path = path[path.index(i):] + [i]
                    break
                path.append(i)
            chain = " on ".join(label(k) for k in path)
            raise GeometryError(f"{chain}: these bodies rest on each other in a cycle; a body cannot rest, directly or through others, on itself")
        for i in ready:
            order.append(i)
            del waiting[i]
        for f in waiting.values():
            f.difference_update(ready)
    assert len(order) == n
    return tuple(order)
