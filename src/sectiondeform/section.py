"""The section as the method sees it: discretised lower curve, upper points, checks.

Paper §3.2-3.3. :func:`build_section` turns one body's curves
(:class:`SectionCurves`, :meth:`~sectiondeform.problem.Problem.body_case`)
into a :class:`Section`:

1. the chordal error ``tol`` is ``options.chordal_error`` or, by default,
   ``DEFAULT_CHORDAL_FRACTION`` (1e-4) of the section's bounding-box diagonal;
2. the upper curve gives its characteristic points (a polyline's vertices,
   the adaptive discretisation of the other kinds); where the polygon of
   each curve's chords miss (the area between the curve and its polyline,
   Green's theorem) add up to more than ``AREA_FRACTION`` (1e-5) of the
   curves' exact area, the chordal error of the upper and lower
   discretisations is divided by 4 until they do not, so the areas the law
   works on are the section's true areas. Each curve is bounded on its
   own: the two curves' errors may cancel in the contour's area (a lower
   arc gaining what an upper arc loses), and the lower curve is resampled
   finer below, which would undo the cancellation. Areas are integrated
   about the lower curve's start A, not the coordinates' origin, when A
   is farther from the origin than the section's size, so a section far
   from the origin loses no digits;
3. the lower curve is discretised adaptively, and the arc-length fractions
   at which the *target* needs vertices to stay within ``tol`` are added, so
   the deformed lower curve is resolved too (a target vertex closer than
   half the smallest element to a lower vertex is merged into it);
4. no step may exceed ``STEP_CAP_FRACTION`` (1/4) of the mesh scale
   (the mean thickness T = area / lower length, or the square root of the
   area where that is smaller), so the mesh can follow a bent target even where
   the lower curve is one straight chord;
5. the element size is the smallest step S_min (paper §3.4), kept within
   [T / 32, T / 4] unless ``options.element_size`` sets it, and divided by
   ``options.refine``; every step longer than it is split evenly.

The section is checked on the way: ends that meet, a simple contour (shapely),
non-degenerate curves. Either orientation of the contour is accepted and
recorded in :attr:`Section.orientation`.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass

import numpy as np
import shapely

from .compare import section_height
from .curves import DEFAULT_CHORDAL_FRACTION, Curve, polygon_area
from .errors import GeometryError
from .limits import MAX_LOWER_NODES, MAX_UPPER_POINTS, bounded

__all__ = ["Section", "SectionCurves", "build_section", "densified", "polygon_area", "mesh_scale", "DEFAULT_CHORDAL_FRACTION"]

JOIN_FRACTION = 1e-6
AREA_FRACTION = 1e-5
AREA_REFINEMENTS = 12
STEP_CAP_FRACTION = 0.25
ELEMENT_FLOOR_FRACTION = 1.0 / 32.0
MIN_CHORDAL_FRACTION = 1e-9


def mesh_scale(area: float, lower_length: float) -> float:
    """The length that sizes the meshes: the mean thickness, or the square root of the area if smaller.

    The mean thickness T = area / lower length measures a section that sits
    on its lower curve; a section much wider than its lower curve (a cap on
    a short foot, like a lip seal) would get elements as large as the
    section itself, so the scale never exceeds the square root of the area.

    Examples
    --------
    >>> mesh_scale(40.0, 10.0), mesh_scale(36.0, 1.0)
    (4.0, 6.0)
    """
    return min(area / lower_length, math.sqrt(area))


@dataclass(frozen=True, eq=False)
class SectionCurves:
    """One body's curves as the section stage reads them.

    Attributes
    ----------
    lower : Curve
        From A to B, on the body's foundation.
    upper : Curve
        From B back to A.
    target : Curve
        Where the lower curve goes, A' to B' (it guides the sampling of the
        lower curve only).
    options : Options
        The problem's options (``chordal_error``, ``element_size``, ``refine``).
    holes : tuple of Curve
        Closed curves inside the contour (checked by the layout).
    """

    lower: Curve
    upper: Curve
    target: Curve
    options: object
    holes: tuple = ()


@dataclass(frozen=True, eq=False)
class Section:
    """A discretised, checked section.

    Attributes
    ----------
    lower : (n, 2) float64 ndarray
        Lower-curve nodes from A to B: the base of the meshes.
    fractions : (n,) float64 ndarray
        Normalised arc length of each lower node on the lower curve.
    upper : (m, 2) float64 ndarray
        Characteristic points of the upper curve, from B to A.
    orientation : int
        +1 when lower-then-upper runs counter-clockwise (the section lies to
        the left of the lower curve), -1 when clockwise.
    area : float
        Area of the contour polygon less its holes', units², positive.
    lower_length : float
        Arc length of the lower curve, units.
    element_size : float
        Element size h of the layered mesh, units.
    chordal_error : float
        Chordal error asked for, units.
    curve_area : float
        Exact area enclosed by the curves themselves less the holes', units².
    characteristic : (m0,) int ndarray, optional
        Index in ``upper`` of each characteristic point, when ``upper`` has
        points between them (:func:`densified`); None when every upper
        point is one.
    holes : tuple of (k_h, 2) float64 ndarray
        Each hole's points, closed (the closing edge implied, the first point
        not repeated), oriented against the contour (so that the contour's
        signed area plus the holes' is the body's), at most an element
        apart: characteristic points, mapped like the upper curve's.
    """

    lower: np.ndarray
    fractions: np.ndarray
    upper: np.ndarray
    orientation: int
    area: float
    lower_length: float
    element_size: float
    chordal_error: float
    curve_area: float
    characteristic: np.ndarray | None = None
    holes: tuple = ()

    @property
    def characteristic_index(self) -> np.ndarray:
        """Index in :attr:`upper` of each characteristic point, ``(m0,)`` int."""
        if self.characteristic is None:
            return np.arange(len(self.upper))
        return self.characteristic

    @property
    def thickness(self) -> float:
        """Mean thickness T = area / lower length, units."""
        return self.area / self.lower_length

    @property
    def height(self) -> float:
        """Height above the lower curve, units: :func:`~sectiondeform.compare.section_height`."""
        return section_height(self.lower, self.upper)

    @property
    def mesh_scale(self) -> float:
        """Length that sizes the meshes of every model, units: :func:`mesh_scale`."""
        return mesh_scale(self.area, self.lower_length)

    @property
    def contour(self) -> np.ndarray:
        """Closed contour, lower then upper, shared ends written once, ``(n + m - 2, 2)``."""
        return np.concatenate((self.lower, self.upper[1:-1]))

    @property
    def size(self) -> float:
        """Bounding-box diagonal of the contour, units."""
        return float(np.hypot(*np.ptp(self.contour, axis=0)))


def _merge_fractions(primary: np.ndarray, extra: np.ndarray, gap: float) -> np.ndarray:
    """Union of two sorted fraction sets; ``extra`` values within ``gap`` of a kept one are dropped.

    The ``extra`` values are taken in increasing order, so each is compared
    with its two neighbours among ``primary`` and with the last ``extra``
    value kept: the nearest kept values on either side.
    """
    extra = np.sort(extra)
    i = np.searchsorted(primary, extra)
    below = np.abs(extra - primary[np.maximum(i - 1, 0)]) > gap
    above = np.abs(extra - primary[np.minimum(i, len(primary) - 1)]) > gap
    kept, last = [], -math.inf
    for s in extra[((i == 0) | below) & ((i == len(primary)) | above)].tolist():
        if abs(s - last) > gap:
            kept.append(s)
            last = s
    return np.sort(np.concatenate((primary, kept)))


def _split_steps(fractions: np.ndarray, max_step: float, fix: str = "raise options.element_size") -> np.ndarray:
    """Split every step of ``fractions`` longer than ``max_step`` into equal parts.

    Raises :class:`GeometryError` before building more than
    :data:`~sectiondeform.limits.MAX_LOWER_NODES` fractions.
    """
    steps = np.diff(fractions)
    with np.errstate(all="ignore"):
        parts = np.maximum(1.0, np.ceil(steps / max_step - 1e-9))
    bounded(float(parts.sum()) + 1, MAX_LOWER_NODES, "lower nodes", fix)
    parts = parts.astype(int)
    # Step i gives fractions[i] + k * (steps[i] / parts[i]), k < parts[i]: np.linspace's values.
    step = np.repeat(np.arange(len(steps)), parts)
    k = np.arange(len(step)) - np.repeat(np.cumsum(parts) - parts, parts)
    return np.concatenate((k * (steps / parts)[step] + fractions[:-1][step], fractions[-1:]))


def local_green(curve: Curve, origin: np.ndarray) -> float:
    """:meth:`Curve.green_about <sectiondeform.curves.Curve.green_about>` ``origin`` ``(2,)``, units²."""
    return curve.green_about(origin)


def open_green(points: np.ndarray, origin: np.ndarray) -> float:
    """The polyline ``points`` ``(N, 2)``'s 1/2 * sum of (x dy - y dx) about ``origin`` ``(2,)``, units².

    Minus :func:`local_green` of the curve it discretises, it is the signed
    area between the curve and its chords.

    Examples
    --------
    >>> float(open_green(np.array([[1.0, 0.0], [1.0, 1.0]]), np.zeros(2)))
    0.5
    """
    p = points - origin
    return 0.5 * float(np.dot(p[:-1, 0], p[1:, 1]) - np.dot(p[1:, 0], p[:-1, 1]))


def _sketch(curve: Curve) -> np.ndarray:
    return curve.at_fractions(np.linspace(0.0, 1.0, 65))


def build_section(case, element_size: float | None = None) -> Section:
    """Discretise and check one body's section (see the module docstring for the rules).

    Parameters
    ----------
    case : SectionCurves or Problem
        One body's curves, or a problem of one body.
    element_size : float, optional
        Element size in units; overrides ``case.options.element_size``.

    Returns
    -------
    Section

    Raises
    ------
    GeometryError
        If the ends do not meet, the contour crosses itself or has no area.
    """
    if hasattr(case, "bodies"):  # a problem: its one body
        if len(case.bodies) != 1:
            raise GeometryError(f"section: the problem has {len(case.bodies)} bodies, one section each; "
                                "build the section of problem.body_case(i)")
        case = case.body_case(0)
    opts = case.options
    sketch = np.concatenate((_sketch(case.lower), _sketch(case.upper)))
    size = float(np.hypot(*np.ptp(sketch, axis=0)))
    tol = float(opts.chordal_error if opts.chordal_error is not None else DEFAULT_CHORDAL_FRACTION * size)

    if not (np.isfinite(sketch).all() and size > 0 and math.isfinite(size)):
        raise GeometryError(f"section: the curves' size {size:.6g} is zero or not finite; check the coordinates")
    if not tol >= MIN_CHORDAL_FRACTION * size:
        raise GeometryError(
            f"options.chordal_error: {tol:.6g} is below {MIN_CHORDAL_FRACTION:g} of the section's size {size:.6g}; use a larger one"
        )
    # About A when the section is farther from (0, 0) than its own size (digits); else as given (no copy).
    origin = np.asarray(case.lower.ends[0], dtype=np.float64)
    if not float(np.hypot(*origin)) > size:
        origin = np.zeros(2)
    green_low, green_up = local_green(case.lower, origin), local_green(case.upper, origin)
    exact = abs(green_low + green_up)
    if not math.isfinite(exact):
        raise GeometryError("section: the curves' exact area is not finite; check the coordinates")
    uppers, lowers = case.upper.characteristic_refinements(tol, 4.0), case.lower.refinements(tol, 4.0)
    for _ in range(AREA_REFINEMENTS):  # chordal errors tol, tol / 4, tol / 16, ...
        upper = next(uppers)
        low_pts, low_s = next(lowers)
        bounded(len(upper), MAX_UPPER_POINTS, "upper points", "raise options.chordal_error or simplify the upper curve")
        bounded(len(low_pts), MAX_LOWER_NODES, "lower nodes", "raise options.chordal_error or simplify the lower curve")
        # Each curve's own chord error, so that neither hides the other.
        missed = abs(open_green(low_pts, origin) - green_low) + abs(open_green(upper, origin) - green_up)
        if len(upper) < 2 or missed <= AREA_FRACTION * exact:
            break
    join = JOIN_FRACTION * size
    a, b = case.lower.start, case.lower.end
    gap_b = float(np.hypot(*(upper[0] - b)))
    gap_a = float(np.hypot(*(upper[-1] - a)))
    if gap_b > join:
        raise GeometryError(
            f"upper: starts at {upper[0].tolist()}, {gap_b:.6g} from the lower curve's end B "
            f"{b.tolist()}; upper must run from B back to A (tolerance {join:.3g})"
        )
    if gap_a > join:
        raise GeometryError(
            f"upper: ends at {upper[-1].tolist()}, {gap_a:.6g} from the lower curve's start A "
            f"{a.tolist()}; upper must run from B back to A (tolerance {join:.3g})"
        )
    if len(upper) < 3:
        raise GeometryError("upper: needs at least one point between B and A to enclose an area")

    ring = np.concatenate((low_pts, upper[1:-1]))
    _check_simple(ring, len(low_pts))
    signed = polygon_area(ring)
    if not abs(signed) > 1e-12 * size * size:
        raise GeometryError("section: lower and upper enclose no area; check that upper is not the lower curve retraced")
    if missed > AREA_FRACTION * exact:
        raise GeometryError(
            f"section: the discretised curves miss the curves' exact area {exact:.9g} by {missed:.3g} "
            f"(more than {AREA_FRACTION:g} of it) after {AREA_REFINEMENTS} refinements; "
            "smooth the curves or set a smaller options.chordal_error"
        )

    length = case.lower.length
    # Mesh scale: the mean thickness, or the square root of the area for a
    # section much wider than its lower curve (a mushroom on a short foot).
    thickness = mesh_scale(abs(signed), length)
    floor = ELEMENT_FLOOR_FRACTION * thickness
    _, tgt_s = case.target.discretise(tol)
    s = _merge_fractions(low_s, tgt_s, 0.5 * floor / length)
    s = _split_steps(s, STEP_CAP_FRACTION * thickness / length, "the section is too thin against its lower curve's length")
    if element_size is None:
        element_size = opts.element_size
    if element_size is None:
        s_min = float(np.min(np.diff(s))) * length
        element_size = min(max(s_min, floor), STEP_CAP_FRACTION * thickness)
    element_size = float(element_size) / float(opts.refine)
    s = _split_steps(s, element_size / length, "raise options.element_size or lower options.refine")
    s[0], s[-1] = 0.0, 1.0
    lower = case.lower.at_fractions(s)
    lower[0], lower[-1] = a, b
    upper = upper.copy()
    upper[0], upper[-1] = b, a

    ring = np.concatenate((lower, upper[1:-1]))
    signed = polygon_area(ring)
    _check_simple(ring, len(lower))
    if abs(abs(signed) - exact) > 2.0 * AREA_FRACTION * exact:  # the finer lower curve only lowers its error
        raise GeometryError(
            f"section: the contour's area {abs(signed):.9g} misses the curves' exact area {exact:.9g} "
            f"by more than {2.0 * AREA_FRACTION:g} of it; set a smaller options.chordal_error"
        )
    for arr in (lower, s, upper):
        arr.setflags(write=False)
    orientation = 1 if signed > 0 else -1
    holes, hole_area, hole_exact = hole_rings(case.holes, tol, orientation, element_size)
    return Section(
        lower=lower,
        fractions=s,
        upper=upper,
        orientation=orientation,
        area=abs(signed) - hole_area,
        lower_length=length,
        element_size=element_size,
        chordal_error=tol,
        curve_area=exact - hole_exact,
        holes=holes,
    )


def hole_rings(holes, tol: float, orientation: int, element_size: float) -> tuple[tuple, float, float]:
    """Each hole's points within the chordal error and its area's, oriented against the contour, an element apart at most.

    Parameters
    ----------
    holes : sequence of Curve
        Closed curves (checked by the layout).
    tol : float
        Chordal error, units, at most 1e-3 of the hole's length (a hole
        smaller than the chordal error is drawn within its own size); divided
        by 4 until the hole's polygon misses its exact area by at most
        ``AREA_FRACTION`` of it. The areas are integrated about each hole's
        own start (its digits kept however far the hole lies from the origin).
    orientation : int
        The contour's: +1 counter-clockwise. Each hole runs the other way.
    element_size : float
        Largest step between two points, units (:func:`densified`).

    Returns
    -------
    rings : tuple of (k, 2) float64 ndarray
        Read-only, the closing point not repeated.
    area : float
        Sum of the rings' areas, units².
    exact : float
        Sum of the curves' exact areas, units².
    """
    rings, area, exact = [], 0.0, 0.0
    for k, hole in enumerate(holes):
        # A closed curve's area is the same about any point; about its own start it keeps its digits (about a far
        # origin, a hole 1e-5 of the section's size across lost its area to the cross products' rounding).
        own = np.asarray(hole.start, dtype=np.float64)
        green = local_green(hole, own)
        pts = None
        for pts in itertools.islice(hole.characteristic_refinements(min(tol, 1e-3 * hole.length), 4.0), AREA_REFINEMENTS):
            bounded(len(pts), MAX_UPPER_POINTS, "hole points", "raise options.chordal_error or simplify the hole")
            if len(pts) >= 4 and abs(open_green(pts, own) - green) <= AREA_FRACTION * abs(green):
                break
        else:
            raise GeometryError(f"holes[{k}]: its points miss the curve's exact area {abs(green):.9g} by more than "
                                f"{AREA_FRACTION:g} of it; smooth it or set a smaller options.chordal_error")
        ring = np.asarray(pts[:-1], dtype=np.float64)  # closed: the last point is the first
        if np.sign(polygon_area(ring)) != -orientation:
            ring = ring[::-1].copy()
        closed = np.concatenate((ring, ring[:1]))
        steps = np.hypot(*np.diff(closed, axis=0).T)
        with np.errstate(all="ignore"):
            parts = np.maximum(1, np.ceil(steps / element_size - 1e-9)).astype(np.int64)
        bounded(float(parts.sum()), MAX_UPPER_POINTS, "hole points", "raise options.element_size or simplify the hole")
        seg = np.repeat(np.arange(len(steps)), parts)
        t = (np.arange(len(seg)) - np.repeat(np.cumsum(parts) - parts, parts)) / parts[seg]
        ring = closed[seg] + t[:, None] * (closed[seg + 1] - closed[seg])
        ring.setflags(write=False)
        rings.append(ring)
        area += abs(polygon_area(ring))
        exact += abs(green)
    return tuple(rings), area, exact


def densified(section: Section, shared: np.ndarray | None = None) -> Section:
    """``section`` with points put between its upper characteristic points, at most its element size apart.

    Only the points of the upper curve are mapped by a model, so a long
    straight segment of it would stay a straight chord however the target
    bends under it; with points at most an element apart along it, the
    deformed contour follows the deformed section within the mesh's own
    resolution. The points lie on the segments, so the contour and its
    area are unchanged.

    Parameters
    ----------
    section : Section
        Its ``upper`` are characteristic points only.
    shared : (m - 1,) bool ndarray, optional
        Segments of ``upper`` to leave as they are (a piece shared with a
        body resting on it, whose lower nodes are already its points).

    Returns
    -------
    Section
        With :attr:`Section.characteristic` the index of each original point.

    Raises
    ------
    GeometryError
        Before building more than :data:`~sectiondeform.limits.MAX_UPPER_POINTS` points.
    """
    up = np.asarray(section.upper, dtype=np.float64)
    steps = np.hypot(*np.diff(up, axis=0).T)
    with np.errstate(all="ignore"):
        parts = np.maximum(1, np.ceil(steps / section.element_size - 1e-9))
    if shared is not None:
        parts[np.asarray(shared, dtype=bool)] = 1
    bounded(float(parts.sum()) + 1, MAX_UPPER_POINTS, "upper points", "raise options.element_size or simplify the upper curve")
    parts = parts.astype(np.int64)
    if (parts == 1).all():
        return section
    seg = np.repeat(np.arange(len(steps)), parts)
    t = (np.arange(len(seg)) - np.repeat(np.cumsum(parts) - parts, parts)) / parts[seg]
    upper = np.concatenate((up[seg] + t[:, None] * (up[seg + 1] - up[seg]), up[-1:]))
    characteristic = np.concatenate(([0], np.cumsum(parts)))
    upper[characteristic] = up  # the characteristic points bit for bit
    for arr in (upper, characteristic):
        arr.setflags(write=False)
    return dataclasses.replace(section, upper=upper, characteristic=characteristic)


def ring_crossing(ring: np.ndarray):
    """Where a closed ring ``(n, 2)`` (closing edge implied) crosses itself: ``(i, j, point)``, or None if it is simple.

    ``i`` and ``j`` are the first pair of non-adjacent edges that meet
    (edge ``k`` runs from point ``k`` to ``k + 1``), ``point`` ``(2,)`` where.
    """
    if shapely.LinearRing(ring).is_simple:
        return None
    edges = shapely.linestrings(np.stack((ring, np.roll(ring, -1, axis=0)), axis=1))
    tree = shapely.STRtree(edges)
    left, right = tree.query(edges, predicate="intersects")
    n = len(ring)
    far = (np.abs(left - right) > 1) & (np.abs(left - right) != n - 1)
    if not far.any():  # a repeated point or an edge doubling back on the next: no crossing to name
        return 0, 0, np.asarray(ring[0], dtype=np.float64)
    i, j = int(left[far][0]), int(right[far][0])
    pt = shapely.get_coordinates(shapely.intersection(edges[i], edges[j]))
    return i, j, (pt[0] if len(pt) else np.asarray(ring[i], dtype=np.float64))


def _check_simple(ring: np.ndarray, n_lower: int) -> None:
    """Raise :class:`GeometryError` if the closed ring crosses itself, naming where."""
    if not np.isfinite(ring).all():
        raise GeometryError("section: the discretised contour has non-finite points; check the coordinates")
    crossing = ring_crossing(ring)
    if crossing is None:
        return
    i, j, pt = crossing
    where = ""
    if i != j:
        name = lambda k: f"lower edge {k}" if k < n_lower - 1 else f"upper edge {k - n_lower + 1}"  # noqa: E731
        where = f" ({name(i)} meets {name(j)} near {np.round(pt, 6).tolist()})"
    raise GeometryError(f"section: the contour lower + upper crosses itself{where}; the section must be a simple polygon")
