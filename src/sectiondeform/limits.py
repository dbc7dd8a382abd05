"""Size bounds every stage checks up front, so no input can make a run hang or exhaust memory.

Each stage computes the size it is about to build (points of a curve, lower
nodes, mesh vertices, layers) before building it and raises a one-line
:class:`~sectiondeform.errors.SectionDeformError` naming the number and the
bound when it is over; the bounds are far above what any section of the
shared cases needs (documented in docs/reliability.md).
"""

from __future__ import annotations

import math

from .errors import GeometryError

__all__ = [
    "MAX_CURVE_POINTS",
    "MAX_DECK_TRIANGLES",
    "MAX_FE_VERTICES",
    "MAX_LAYERED_NODES",
    "MAX_LOWER_NODES",
    "MAX_NEWTON_ITERATIONS",
    "MAX_SOLVE_WORK",
    "MAX_SPLINE_PIECES",
    "MAX_STUDY_ROWS",
    "MAX_UPPER_POINTS",
    "bounded",
    "flattening_points",
    "newton_budget",
    "work_budget",
    "triangles_needed",
]

MAX_CURVE_POINTS = 200_000
"""Points of one adaptive curve discretisation."""

MAX_SPLINE_PIECES = 20_000
"""Knot intervals of one B-spline."""

MAX_LOWER_NODES = 20_000
"""Lower-curve nodes of a section (the columns of the layered mesh)."""

MAX_UPPER_POINTS = 20_000
"""Characteristic points of the upper curve."""

MAX_LAYERED_NODES = 2_000_000
"""Nodes of the paper model's layered mesh (layers x columns)."""

MAX_FE_VERTICES = 3_000
"""Triangle vertices of the hyperelastic model's mesh (about twice as many triangles), also
after the mesher's passes that split boundary segments to conform to the contour."""

MAX_FE_UNKNOWNS = 30_000
"""Free unknowns of one hyperelastic solve (about what :data:`MAX_FE_VERTICES` quadratic triangles carry):
the shared cases need at most 9,427 (the tread on its drum); a sliver of 16,240 factorises in 0.05 s with
its COLAMD column order (1.45 M entries in L and U)."""

MAX_STUDY_ROWS = 100_000
"""Rows of one parametric study (all its cases' products of axes together), checked before they are built:
at a few milliseconds a row on the paper model that is minutes of work, and a table of tens of megabytes."""

MAX_DECK_TRIANGLES = 500_000
"""Triangles of a solver deck's mesh (``export-fe``, ``solve-fe``, ``validate --reference calculix``), estimated
from the area and the element size before meshing: a deck of a few hundred megabytes, hours of CalculiX."""

MAX_NEWTON_ITERATIONS = 100
"""Newton iterations of one hyperelastic solve, all load steps together (a step's predictor counts one)."""

MAX_SOLVE_WORK = 40_000_000
"""Work of one hyperelastic solve: its Newton iterations (a contact loading: its factorisations, the attempts that
failed included), each weighted by ``unknowns ** 1.5``, what a sparse factorisation of a plane mesh costs (measured:
9.5 ms at 1,609 unknowns, about 0.35 s at 16,423, 1 s at 25,000).

About 10 iterations on the largest mesh (25,000 unknowns), 46 at 9,000, the full
:data:`MAX_NEWTON_ITERATIONS` up to 5,400. A body of revolution moved to twice its
radius takes about 30 iterations; the shared cases take at most 8.
"""


def bounded(count: float, limit: int, what: str, fix: str, error=GeometryError, where: str = "section") -> float:
    """``count`` unchanged, or raise ``error`` naming it, the bound and the fix.

    ``where`` starts the message: the input or stage at fault.

    Examples
    --------
    >>> bounded(12.5, 100, "lower nodes", "raise options.element_size")
    12.5
    >>> bounded(3163.62, 100, "mesh vertices", "raise options.element_size")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.GeometryError: section: 3164 mesh vertices needed, more than the bound 100; raise options.element_size
    >>> bounded(float("inf"), 100, "lower nodes", "raise options.element_size")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.GeometryError: section: inf lower nodes needed, more than the bound 100; raise options.element_size
    """
    if not count <= limit:  # also NaN
        shown = f"{math.ceil(count):d}" if math.isfinite(count) else f"{count:g}"  # a count is a whole number
        raise error(f"{where}: {shown} {what} needed, more than the bound {limit}; {fix}")
    return count


def flattening_points(radius: float, sweep: float, tol: float) -> float:
    """Points of a polyline within the chordal error ``tol`` of an arc of ``radius`` turning ``sweep`` radians.

    A chord of angle θ misses its arc by r (1 − cos(θ/2)), so θ = 2 acos(1 − tol / r);
    for tol ≪ r that is 2 √(2 tol / r), written so to keep its digits. For an
    ellipse, ``radius`` is its larger semi-axis (its flattest curvature
    radius is smaller, so this is an underestimate, never an overestimate
    that would refuse a fair input). Meant to be passed to :func:`bounded`
    *before* the points are computed.

    Examples
    --------
    >>> flattening_points(1.0, 2 * 3.141592653589793, 2.0)
    2.0
    >>> round(flattening_points(1e5, 6.283185307179586, 3.7e-11))
    115487244
    """
    if not radius > 0:
        return 2.0
    if not (math.isfinite(radius) and tol > 0):
        return float("inf")
    ratio = min(tol / radius, 2.0)
    step = 2.0 * math.acos(1.0 - ratio) if ratio > 1e-6 else 2.0 * math.sqrt(2.0 * ratio)
    return max(2.0, math.ceil(abs(sweep) / step) + 1.0)



def work_budget(unknowns: int) -> int:
    """Factorisations (or Newton iterations) a solve on ``unknowns`` unknowns may take: ``MAX_SOLVE_WORK / unknowns**1.5``.

    Examples
    --------
    >>> work_budget(1_609), work_budget(25_000)
    (619, 10)
    """
    return max(1, int(MAX_SOLVE_WORK / float(max(int(unknowns), 1)) ** 1.5))


def newton_budget(unknowns: int) -> int:
    """Newton iterations one hyperelastic solve on ``unknowns`` unknowns may take.

    ``min(MAX_NEWTON_ITERATIONS, work_budget(unknowns))``.

    Examples
    --------
    >>> newton_budget(700), newton_budget(9_000), newton_budget(25_000)
    (100, 46, 10)
    """
    return min(MAX_NEWTON_ITERATIONS, work_budget(unknowns))


def triangles_needed(area: float, perimeter: float, size: float) -> float:
    """At least how many triangles of side about ``size`` a region of ``area`` and ``perimeter`` takes.

    The area over an equilateral triangle's, plus a triangle per boundary
    segment: a lower estimate (quality meshes hold more), so that a bound on
    it refuses no fair mesh. Infinite for a size that is not a positive
    number.

    Examples
    --------
    >>> round(triangles_needed(100.0, 40.0, 1.0))
    271
    >>> triangles_needed(1.0, 4.0, 0.0)
    inf
    """
    if not size > 0:
        return math.inf
    return abs(area) / (math.sqrt(3.0) / 4.0 * size * size) + perimeter / size
