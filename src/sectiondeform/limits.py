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
    "MAX_FE_VERTICES",
    "MAX_LAYERED_NODES",
    "MAX_LOWER_NODES",
    "MAX_NEWTON_ITERATIONS",
    "MAX_NEWTON_WORK",
    "MAX_SPLINE_PIECES",
    "MAX_UPPER_POINTS",
    "bounded",
    "newton_budget",
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

MAX_NEWTON_ITERATIONS = 100
"""Newton iterations of one hyperelastic solve, all load steps together (a step's predictor counts one)."""

MAX_NEWTON_WORK = 150_000
"""Newton iterations x unknowns of one hyperelastic solve.

About 6 iterations on the largest mesh (25 000 unknowns, a factorisation
of about a second each); the shared cases need at most 60 000 (the grooved
tread at 16 elements through the thickness: 5 iterations on 11 805 unknowns).
"""


def bounded(count: float, limit: int, what: str, fix: str, error=GeometryError) -> float:
    """``count`` unchanged, or raise ``error`` naming it, the bound and the fix.

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
        raise error(f"section: {shown} {what} needed, more than the bound {limit}; {fix}")
    return count



def newton_budget(unknowns: int) -> int:
    """Newton iterations one hyperelastic solve on ``unknowns`` unknowns may take.

    ``min(MAX_NEWTON_ITERATIONS, MAX_NEWTON_WORK // unknowns)``, at least 1.

    Examples
    --------
    >>> newton_budget(700), newton_budget(25_000)
    (100, 6)
    """
    return max(1, min(MAX_NEWTON_ITERATIONS, MAX_NEWTON_WORK // max(int(unknowns), 1)))
