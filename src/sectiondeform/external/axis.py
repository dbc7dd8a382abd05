"""The section of a body of revolution in the solvers' axisymmetric frame: r from the axis, z along it.

Abaqus and CalculiX axisymmetric elements (CAX*) take node coordinates
(r, z): r ≥ 0 the distance from the axis of revolution, z along it. A case
gives its axis as two points of the section's plane; :class:`AxisFrame` maps
the case's (x, y) to (r, z) and back:

    z = (X − P0) · e,   r = (X − P0) · n,

with P0 the axis's first point, e the unit vector from it to the second, and
n the unit normal to e pointing to the side of the axis where the bodies
are. A point on the axis maps to r = 0. When (n, e) has the opposite
handedness of (x, y) the map is a mirror image, and the deck reverses each
element's node order so that elements stay counter-clockwise in (r, z).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import CaseError

__all__ = ["AxisFrame", "axis_frame", "reverse_orientation"]


@dataclass(frozen=True)
class AxisFrame:
    """The map from the case's plane to the solvers' (r, z).

    Attributes
    ----------
    origin : (float, float)
        P0, the axis's first point, units.
    along : (float, float)
        e, unit vector along the axis (z direction).
    outward : (float, float)
        n, unit normal to the axis towards the bodies (r direction).
    """

    origin: tuple
    along: tuple
    outward: tuple

    @property
    def mirrored(self) -> bool:
        """Whether (x, y) → (r, z) reverses orientation (counter-clockwise becomes clockwise)."""
        n, e = self.outward, self.along
        return n[0] * e[1] - n[1] * e[0] < 0

    def to_rz(self, points) -> np.ndarray:
        """(r, z) of points of the case's plane, ``(N, 2)`` float64, units.

        Examples
        --------
        >>> f = axis_frame(((0.0, -250.0), (1.0, -250.0)), np.array([[0.0, 0.0]]))
        >>> f.to_rz(np.array([[3.0, -250.0], [3.0, 0.0]])).tolist()
        [[0.0, 3.0], [250.0, 3.0]]
        """
        d = np.asarray(points, dtype=np.float64) - np.asarray(self.origin)
        return np.column_stack((d @ np.asarray(self.outward), d @ np.asarray(self.along)))

    def from_rz(self, rz) -> np.ndarray:
        """Points of the case's plane from (r, z), ``(N, 2)`` float64, units."""
        rz = np.asarray(rz, dtype=np.float64)
        return np.asarray(self.origin) + rz[:, :1] * np.asarray(self.outward) + rz[:, 1:] * np.asarray(self.along)

    def comment(self) -> str:
        """One line for the deck's comment block."""
        o, e, n = (np.round(np.asarray(v, dtype=float), 12).tolist() for v in (self.origin, self.along, self.outward))
        return (f"axisymmetric frame: r = (X - {o}) . {n}, z = (X - {o}) . {e} (node coordinates are (r, z), "
                f"not the case's (x, y){'; mirrored, so element node order is reversed' if self.mirrored else ''})")


def axis_frame(axis, points) -> AxisFrame:
    """The frame of an axis, with r pointing to the side where ``points`` lie.

    Parameters
    ----------
    axis : ((float, float), (float, float))
        Two distinct points of the axis, units.
    points : (N, 2) array_like
        Points of the bodies (all on one side of the axis).

    Returns
    -------
    AxisFrame

    Raises
    ------
    CaseError
        If the points lie on both sides of the axis (an axisymmetric
        section must not cross it).
    """
    p0, p1 = (np.asarray(p, dtype=np.float64) for p in axis)
    e = (p1 - p0) / np.hypot(*(p1 - p0))
    n = np.array([-e[1], e[0]])
    side = (np.asarray(points, dtype=np.float64) - p0) @ n
    scale = max(float(np.abs(side).max()), 1.0)
    if side.min() < -1e-9 * scale and side.max() > 1e-9 * scale:
        raise CaseError("revolution.axis", "the bodies lie on both sides of the axis; an axisymmetric section must lie "
                        "on one side of its axis")
    if side.max() <= 1e-9 * scale:
        n = -n
    return AxisFrame(tuple(p0.tolist()), tuple(e.tolist()), tuple((n + 0.0).tolist()))


#: Node permutation that reverses an element's orientation, per mesh kind (Abaqus node order).
_REVERSE = {
    "triangle": [0, 2, 1],
    "triangle6": [0, 2, 1, 5, 4, 3],
    "quad": [0, 3, 2, 1],
    "quad8": [0, 3, 2, 1, 7, 6, 5, 4],
}


def reverse_orientation(cells: np.ndarray, kind: str) -> np.ndarray:
    """The same elements with the opposite orientation, ``(M, k)``.

    Examples
    --------
    >>> reverse_orientation(np.array([[1, 2, 3, 4, 5, 6]]), "triangle6").tolist()
    [[1, 3, 2, 6, 5, 4]]
    """
    return np.asarray(cells)[:, _REVERSE[kind]]
