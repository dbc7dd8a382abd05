"""The axis of a body of revolution, as the finite-element reference uses it.

A section of a body of revolution lies in a half-plane bounded by the axis,
a line of the section's plane. A point ``x`` of the section is at the
distance ``r(x) = n · (x − a)`` from the axis, ``a`` a point of the axis and
``n`` its unit normal pointing to the section's side. Under an in-plane
displacement ``u`` the hoop stretch is ``(R + n · u) / R``, ``R`` the
initial distance: linear in ``u``, so its derivative is the constant
``n / R``.

Volumes are Pappus's: the volume swept by a plane region turning about the
axis is 2π × its first moment ∫ r dA (area × centroid distance). The
functions here compute it for polygons and for the quadratic triangles of
the reference mesh, so the reference needs nothing from the paper model's
own volume helpers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import number
from ..errors import CaseError

__all__ = ["Axis", "axis_from_points", "polygon_first_moment", "polygon_volume", "p2_first_moments"]


@dataclass(frozen=True)
class Axis:
    """A line of the section's plane, oriented towards the section.

    Attributes
    ----------
    point : (2,) float64 ndarray
        A point of the axis, units.
    normal : (2,) float64 ndarray
        Unit normal of the axis, pointing to the side of the section.
    """

    point: np.ndarray
    normal: np.ndarray

    def radius(self, points) -> np.ndarray:
        """Signed distance of ``points`` (..., 2) from the axis, positive on the section's side; (...), units."""
        p = np.asarray(points, dtype=np.float64)
        return (p[..., 0] - self.point[0]) * self.normal[0] + (p[..., 1] - self.point[1]) * self.normal[1]


def axis_from_points(axis, section_points: np.ndarray, field: str = "revolution.axis") -> Axis:
    """The :class:`Axis` through two points, oriented towards a section that it must not touch.

    Parameters
    ----------
    axis : ((float, float), (float, float)) or object with ``.axis``
        Two distinct points of the axis, units (a ``revolution`` object's
        ``axis`` list, or anything carrying one).
    section_points : (N, 2) float64 ndarray
        The section's contour, units.
    field : str
        Where the axis sits in the case, for messages.

    Returns
    -------
    Axis

    Raises
    ------
    CaseError
        If the points are not two distinct finite points, or the axis
        touches or crosses the section.

    Examples
    --------
    >>> square = np.array([[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]])
    >>> ax = axis_from_points([[0, 0], [1, 0]], square)
    >>> ax.radius(square).tolist()
    [1.0, 1.0, 2.0, 2.0]
    >>> axis_from_points([[0, 0], [0, 1]], square + [-0.5, 0.0])
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: revolution.axis: the axis crosses or touches the section (distances from -0.5 to 0.5); a body of revolution lies on one side of its axis
    """
    axis = getattr(axis, "axis", axis)
    try:
        pts = [[number(v, f"{field}[{i}]") for v in p] for i, p in enumerate(axis)]
    except TypeError:
        raise CaseError(field, f"expected two points [[x, y], [x, y]], got {axis!r}") from None
    if len(pts) != 2 or any(len(p) != 2 for p in pts):
        raise CaseError(field, f"expected two points [[x, y], [x, y]], got {axis!r}")
    a, b = np.array(pts[0]), np.array(pts[1])
    d = b - a
    length = math.hypot(*d)
    if length == 0.0:
        raise CaseError(field, "the two points coincide; give two distinct points of the axis")
    normal = np.array([-d[1], d[0]]) / length
    r = Axis(a, normal).radius(section_points)
    if r.max() <= 0.0:
        normal = -normal
        r = -r
    if r.min() <= 0.0:
        raise CaseError(field, f"the axis crosses or touches the section (distances from {r.min():.6g} to {r.max():.6g}); "
                        "a body of revolution lies on one side of its axis")
    return Axis(a, normal)


def polygon_first_moment(polygon, axis: Axis) -> float:
    """First moment ∫ r dA of a closed polygon about the axis, units³, signed (positive counter-clockwise).

    Exact for a polygon: it is a sum of signed triangles fanned from a point
    of the axis, and the integral of the linear r over a triangle is its
    area times the mean of r at its corners.

    Parameters
    ----------
    polygon : (N, 2) float64 array_like
    axis : Axis

    Returns
    -------
    float

    Examples
    --------
    >>> ax = Axis(np.zeros(2), np.array([0.0, 1.0]))
    >>> polygon_first_moment([[0, 1], [2, 1], [2, 3], [0, 3]], ax)   # area 4, centroid at r = 2
    8.0
    """
    p = np.asarray(polygon, dtype=np.float64)
    q = np.roll(p, -1, axis=0)
    r = axis.radius(p) + axis.radius(q)
    # ∫ r dA over the triangle (a, p, q), a on the axis (r = 0 there): cross / 2 × (r_p + r_q) / 3.
    ps, qs = p - axis.point, q - axis.point
    cross = ps[:, 0] * qs[:, 1] - ps[:, 1] * qs[:, 0]
    return float(np.sum(cross * r) / 6.0)


def polygon_volume(polygon, axis: Axis) -> float:
    """Volume swept by a closed polygon turning once about the axis (Pappus), units³, signed."""
    return 2.0 * math.pi * polygon_first_moment(polygon, axis)


def p2_first_moments(initial: np.ndarray, deformed: np.ndarray, cells: np.ndarray, axis: Axis) -> np.ndarray:
    """First moment ∫ r dA about the axis of each deformed quadratic triangle, from its six nodes.

    Exact (the integrand r · det J is a polynomial of degree 4 on the
    reference triangle, integrated by a degree-4 rule).

    Parameters
    ----------
    initial : (N, 2) float64 ndarray
        Initial node positions (they tell which mid-edge node sits on which
        edge), units.
    deformed : (N, 2) float64 ndarray
        Deformed node positions, units.
    cells : (M, 6) int64 ndarray
        Three corners (counter-clockwise) then the three mid-edge nodes,
        in any order.
    axis : Axis

    Returns
    -------
    (M,) float64 ndarray
        Units³ (per radian: the swept volume is 2π times it).

    Examples
    --------
    >>> ax = Axis(np.zeros(2), np.array([0.0, 1.0]))
    >>> p = np.array([[0, 1], [2, 1], [0, 3], [1, 1], [1, 2], [0, 2]], dtype=float)
    >>> round(float(p2_first_moments(p, p, np.arange(6)[None], ax)[0]), 12)   # area 2, centroid at r = 5/3
    3.333333333333
    """
    corners = initial[cells[:, :3]]
    edges = 0.5 * (corners + np.roll(corners, -1, axis=1))  # edges (0, 1), (1, 2), (2, 0)
    mids = initial[cells[:, 3:]]
    match = np.argmin(np.linalg.norm(mids[:, None, :, :] - edges[:, :, None, :], axis=-1), axis=2)
    mid_nodes = np.take_along_axis(cells[:, 3:], match, axis=1)
    x = np.concatenate((deformed[cells[:, :3]], deformed[mid_nodes]), axis=1)  # (M, 6, 2)
    # Strang–Fix / Dunavant 6-point rule, degree 4, weights summing to the reference area 1/2.
    a, b = 0.445948490915965, 0.091576213509771
    wa, wb = 0.111690794839005, 0.054975871827661
    l1 = np.array([a, 1 - 2 * a, a, b, 1 - 2 * b, b])
    l2 = np.array([a, a, 1 - 2 * a, b, b, 1 - 2 * b])
    w = np.array([wa, wa, wa, wb, wb, wb])
    l0 = 1.0 - l1 - l2
    N = np.stack((l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), 4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0))
    d1 = np.stack((1 - 4 * l0, 4 * l1 - 1, 0 * l1, 4 * (l0 - l1), 4 * l2, -4 * l2))
    d2 = np.stack((1 - 4 * l0, 0 * l1, 4 * l2 - 1, -4 * l1, 4 * l1, 4 * (l0 - l2)))
    pos = np.einsum("kq,mkd->mqd", N, x)
    j1, j2 = np.einsum("kq,mkd->mqd", d1, x), np.einsum("kq,mkd->mqd", d2, x)
    det = j1[..., 0] * j2[..., 1] - j1[..., 1] * j2[..., 0]
    return np.sum(axis.radius(pos) * det * w, axis=1)
