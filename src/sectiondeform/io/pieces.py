"""Pieces of a drawing: one curve each, as the CAD or SVG file gives them.

A :class:`Piece` is a :class:`~sectiondeform.curves.Curve` (a polyline, a
circular arc or a clamped non-rational B-spline) together with the names
it carries (DXF layer, SVG id and classes) and where it came from, for
error messages. The functions here reverse, transform, merge and flatten
curves; every one returns new curves and leaves its input alone.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..curves import Arc, BSpline, Chain, Curve, Polyline

__all__ = [
    "Piece",
    "reverse_curve",
    "transform_curve",
    "curve_points",
    "merge_polylines",
    "curve_ends",
]


@dataclass(frozen=True, eq=False)
class Piece:
    """One curve of a drawing.

    Attributes
    ----------
    curve : Curve
        Polyline, Arc or BSpline (never a Chain), in drawing units.
    tags : frozenset of str
        Upper-cased names the piece carries: its DXF layer, or its SVG id,
        classes and those of its parent groups.
    source : str
        Where it came from, e.g. ``"LINE #5 (handle 2F)"``, for messages.
    """

    curve: Curve
    tags: frozenset
    source: str


def curve_ends(curve: Curve) -> tuple[np.ndarray, np.ndarray]:
    """Exact first and last point of a curve, each ``(2,)`` float64, units."""
    if isinstance(curve, Polyline):
        return curve.vertices[0], curve.vertices[-1]
    if isinstance(curve, BSpline):
        return curve.control_points[0], curve.control_points[-1]
    if isinstance(curve, Chain):
        return curve_ends(curve.pieces[0])[0], curve_ends(curve.pieces[-1])[1]
    return curve.start, curve.end


def reverse_curve(curve: Curve) -> Curve:
    """The same curve run the other way.

    Parameters
    ----------
    curve : Curve

    Returns
    -------
    Curve
        Same kind; a B-spline's knots are mirrored, ``t -> t0 + t1 - t``.

    Examples
    --------
    >>> reverse_curve(Polyline([[0, 0], [1, 0], [1, 1]])).vertices.tolist()
    [[1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]
    >>> a = reverse_curve(Arc([0, 0], 1.0, 0.0, 90.0)); (a.start_deg, a.end_deg)
    (90.0, 0.0)
    """
    if isinstance(curve, Polyline):
        return Polyline(curve.vertices[::-1])
    if isinstance(curve, Arc):
        return Arc(curve.center, curve.radius, curve.end_deg, curve.start_deg)
    if isinstance(curve, BSpline):
        t = curve.knots
        return BSpline(curve.degree, curve.control_points[::-1], (t[0] + t[-1] - t)[::-1])
    if isinstance(curve, Chain):
        return Chain(tuple(reverse_curve(p) for p in curve.pieces[::-1]))
    raise TypeError(f"cannot reverse a {type(curve).__name__}")


def transform_curve(curve: Curve, matrix, offset=(0.0, 0.0), tol: float = 1e-3) -> Curve:
    """Apply the affine map ``p -> matrix @ p + offset`` to a curve.

    Polylines and B-splines are mapped exactly (B-splines are affine
    invariant). An arc stays an arc under a similarity (uniform scale,
    rotation, reflection); under any other map it becomes an ellipse, given
    back as a polyline within ``tol`` of it.

    Parameters
    ----------
    curve : Curve
    matrix : (2, 2) array_like
    offset : (2,) array_like
        Units of the result.
    tol : float
        Chordal error of the polyline an elliptical image is flattened to,
        in the units of the result.

    Returns
    -------
    Curve

    Examples
    --------
    >>> flip = [[1.0, 0.0], [0.0, -1.0]]
    >>> a = transform_curve(Arc([0, 1], 1.0, 0.0, 90.0), flip)
    >>> a.center.tolist(), a.start_deg, a.end_deg
    ([0.0, -1.0], 0.0, -90.0)
    """
    m = np.asarray(matrix, dtype=np.float64).reshape(2, 2)
    b = np.asarray(offset, dtype=np.float64).reshape(2)
    if isinstance(curve, Polyline):
        return Polyline(curve.vertices @ m.T + b)
    if isinstance(curve, BSpline):
        return BSpline(curve.degree, curve.control_points @ m.T + b, curve.knots)
    if isinstance(curve, Chain):
        return Chain(tuple(transform_curve(p, m, b, tol) for p in curve.pieces))
    if isinstance(curve, Arc):
        mtm = m.T @ m
        scale2 = 0.5 * (mtm[0, 0] + mtm[1, 1])
        similar = abs(mtm[0, 1]) <= 1e-12 * scale2 and abs(mtm[0, 0] - mtm[1, 1]) <= 1e-12 * scale2
        if similar:
            det = float(np.linalg.det(m))
            start = curve.at_fractions(np.array([0.0]))[0] - curve.center
            ms = m @ start
            a0 = math.degrees(math.atan2(ms[1], ms[0]))
            sweep = (curve.end_deg - curve.start_deg) * (1.0 if det > 0 else -1.0)
            return Arc(m @ curve.center + b, curve.radius * math.sqrt(abs(det)), a0, a0 + sweep)
        smax = math.sqrt(float(np.linalg.eigvalsh(mtm).max()))  # largest stretch of the map
        pts, _ = curve.discretise(tol / smax)
        return Polyline(pts @ m.T + b)
    raise TypeError(f"cannot transform a {type(curve).__name__}")


def curve_points(curve: Curve, tol: float) -> np.ndarray:
    """A polyline standing for the curve, ``(N, 2)`` float64.

    A polyline gives its own vertices; other kinds their discretisation
    within chordal error ``tol`` (units).
    """
    if isinstance(curve, Polyline):
        return curve.vertices.copy()
    if isinstance(curve, Chain):
        parts = [curve_points(p, tol) for p in curve.pieces]
        return np.concatenate([parts[0]] + [q[1:] for q in parts[1:]])
    return curve.discretise(tol)[0]


def merge_polylines(curves: list[Curve]) -> list[Curve]:
    """Join runs of consecutive polylines into one polyline each.

    The curves must already run end to start; the shared vertex is kept once.

    Examples
    --------
    >>> out = merge_polylines([Polyline([[0, 0], [1, 0]]), Polyline([[1, 0], [2, 0]])])
    >>> len(out), out[0].vertices.tolist()
    (1, [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    """
    out: list[Curve] = []
    run: list[np.ndarray] = []

    def flush():
        if run:
            out.append(Polyline(np.concatenate([run[0]] + [r[1:] for r in run[1:]])))
            run.clear()

    for c in curves:
        if isinstance(c, Polyline):
            run.append(c.vertices)
        else:
            flush()
            out.append(c)
    flush()
    return out


def pin_ends(curve: Curve, start, end, scale: float = 1.0) -> Curve:
    """The curve with its ends moved exactly onto ``start`` and ``end``, ``(2,)`` each.

    Polyline vertices and spline end control points are moved; an arc that
    cannot move gets a straight bridge when the gap is larger than 1e-9 of
    ``scale``. Meant for gaps within a join or snap tolerance.
    """
    start, end = np.asarray(start, dtype=np.float64), np.asarray(end, dtype=np.float64)
    pieces = list(curve.pieces) if isinstance(curve, Chain) else [curve]

    def move(c: Curve, at_end: bool, p: np.ndarray) -> list[Curve]:
        q = curve_ends(c)[1 if at_end else 0]
        if np.array_equal(p, q):
            return [c]
        if isinstance(c, Polyline):
            v = c.vertices.copy()
            v[-1 if at_end else 0] = p
            return [Polyline(v)]
        if isinstance(c, BSpline):
            cp = c.control_points.copy()
            cp[-1 if at_end else 0] = p
            return [BSpline(c.degree, cp, c.knots)]
        if np.hypot(*(p - q)) <= 1e-9 * scale:
            return [c]
        bridge = Polyline(np.vstack((q, p)) if at_end else np.vstack((p, q)))
        return [c, bridge] if at_end else [bridge, c]

    first = move(pieces[0], False, start)
    pieces = first + pieces[1:]
    last = move(pieces[-1], True, end)
    pieces = pieces[:-1] + last
    return pieces[0] if len(pieces) == 1 else Chain(tuple(pieces))
