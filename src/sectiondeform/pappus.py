"""Volumes of revolution of polygonal sections (Pappus's centroid theorem).

A section turned about an axis of its plane sweeps the volume
``V = 2 pi Q``, where ``Q`` is the first moment of the section's area about
the axis: the area times the distance of its centroid from the axis. Here
``Q`` is signed: distances are measured positive to the left of the axis
(from its first point towards its second), areas positive for
counter-clockwise polygons, so ``|2 pi Q|`` is the volume of a section
lying on one side of the axis.

In the axis's frame (``u`` along the axis, ``d`` its signed distance) the
first moment of a polygon is, exactly,
``Q = 1/6 sum (d_i + d_{i+1}) (u_i d_{i+1} - u_{i+1} d_i)``. For a polygon
``fixed + k moving`` whose vertices are affine in ``k``, ``d`` is affine and
the cross products quadratic in ``k``: ``Q`` is a cubic in ``k``
(:func:`moment_coefficients`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["axis_frame", "signed_distance", "first_moment", "curve_moment", "volume", "moment_coefficients"]


def _next(a):
    return np.concatenate((a[1:], a[:1]))


def axis_frame(axis) -> tuple[np.ndarray, np.ndarray]:
    """Origin and rotation of the axis's frame.

    Parameters
    ----------
    axis : ((float, float), (float, float))
        Two distinct points of the axis, units.

    Returns
    -------
    origin : (2,) float64 ndarray
        The first point.
    rotation : (2, 2) float64 ndarray
        Rows: the unit direction of the axis, then its unit left normal (a
        proper rotation, so areas keep their sign).
    """
    p0, p1 = np.asarray(axis, dtype=np.float64)
    e = (p1 - p0) / math.hypot(*(p1 - p0))
    return p0, np.array([e, [-e[1], e[0]]])


def _to_frame(points: np.ndarray, axis) -> np.ndarray:
    origin, rot = axis_frame(axis)
    return (np.asarray(points, dtype=np.float64) - origin) @ rot.T


def signed_distance(points: np.ndarray, axis) -> np.ndarray:
    """Signed distance of each point from the axis, ``(N,)``, units (positive to its left)."""
    origin, rot = axis_frame(axis)
    return (np.asarray(points, dtype=np.float64) - origin) @ rot[1]


def first_moment(polygon: np.ndarray, axis) -> float:
    """Signed first moment of a closed polygon's area about the axis, units³.

    Parameters
    ----------
    polygon : (N, 2) float64 ndarray
        Vertices in order, the closing edge implied.
    axis : ((float, float), (float, float))

    Examples
    --------
    A unit square from x = 2 to 3; the axis x = 0, drawn downwards, has +x
    on its left: area 1, centroid at distance 2.5.

    >>> sq = np.array([[2.0, 0.0], [3.0, 0.0], [3.0, 1.0], [2.0, 1.0]])
    >>> first_moment(sq, ((0.0, 1.0), (0.0, 0.0)))
    2.5
    """
    p = _to_frame(polygon, axis)
    q = _next(p)
    cross = p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]
    return float(((p[:, 1] + q[:, 1]) * cross).sum() / 6.0)


def curve_moment(curves, axis) -> float:
    """Exact signed first moment about the axis of the area the curves enclose, units³.

    Parameters
    ----------
    curves : sequence of Curve
        A closed contour, each curve starting where the one before ends (a
        gap counts as its chord, :func:`~sectiondeform.curves.closed_parts`).
    axis : ((float, float), (float, float))

    Each curve's share is exact in its kind (:meth:`~sectiondeform.curves.Curve.moment_about`:
    closed forms for polylines and arcs, Gauss quadrature of Green's
    theorem for B-splines), so a contour of curves has its exact moment,
    not its polygon's.

    Examples
    --------
    A half-disc of radius 1 on the x axis: Q = 2/3 (area pi/2, centroid 4/(3 pi)).

    >>> from sectiondeform.curves import Arc, Polyline
    >>> half = [Polyline([[-1.0, 0.0], [1.0, 0.0]]), Arc([0.0, 0.0], 1.0, 0.0, 180.0)]
    >>> round(curve_moment(half, ((0.0, 0.0), (1.0, 0.0))), 15)
    0.666666666666667
    """
    from .curves import closed_parts

    origin, rot = axis_frame(axis)
    return float(sum(c.moment_about(origin, rot) for c in closed_parts(curves)))


def volume(polygon: np.ndarray, axis) -> float:
    """Volume swept by a polygon lying on one side of the axis, turned a full turn about it, units³."""
    return abs(2.0 * math.pi * first_moment(polygon, axis))


def moment_coefficients(fixed: np.ndarray, moving: np.ndarray, axis) -> np.ndarray:
    """Coefficients of the first moment of the polygon ``fixed + k moving`` about the axis, as a cubic in ``k``.

    Parameters
    ----------
    fixed, moving : (N, 2) float64 ndarray
        Vertices as ``fixed + k * moving``, units.
    axis : ((float, float), (float, float))

    Returns
    -------
    (4,) float64 ndarray
        ``c`` with ``first_moment(fixed + k moving) = c[0] + c[1] k + c[2] k² + c[3] k³``.

    Examples
    --------
    A unit-wide strip on the axis y = 0, its height scaled by k: Q = k²/2.

    >>> f = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]])
    >>> m = np.array([[0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [0.0, 1.0]])
    >>> moment_coefficients(f, m, ((0.0, 0.0), (1.0, 0.0))).tolist()
    [0.0, 0.0, 0.5, 0.0]
    """
    origin, rot = axis_frame(axis)
    f = (np.asarray(fixed, dtype=np.float64) - origin) @ rot.T
    g = np.asarray(moving, dtype=np.float64) @ rot.T
    f1, g1 = _next(f), _next(g)
    s0, s1 = f[:, 1] + f1[:, 1], g[:, 1] + g1[:, 1]
    x0 = f[:, 0] * f1[:, 1] - f1[:, 0] * f[:, 1]
    x1 = f[:, 0] * g1[:, 1] - g1[:, 0] * f[:, 1] + g[:, 0] * f1[:, 1] - f1[:, 0] * g[:, 1]
    x2 = g[:, 0] * g1[:, 1] - g1[:, 0] * g[:, 1]
    return np.array([(s0 * x0).sum(), (s0 * x1 + s1 * x0).sum(), (s0 * x2 + s1 * x1).sum(), (s1 * x2).sum()]) / 6.0
