"""Target families of a study: the case's target bent, crowned, stretched, scaled, rotated, moved.

Every transformation works in the target's own frame: origin at the point
half-way along the target, x along the chord A'B', y along its left normal
(the section's side for a section that runs counter-clockwise, lower then
upper, as in the paper's example). They apply in this order: bend, crown,
stretch, scale, rotate, translate.
"""

from __future__ import annotations

import math

import numpy as np

from ..curves import Curve, Polyline
from ..errors import CaseError

__all__ = ["TRANSFORMS", "transformed_target"]

TRANSFORMS = ("bend_radius", "crown", "stretch", "scale", "rotate_deg", "translate_x", "translate_y")

SAMPLES = 1025  # points along the target at uniform arc-length fractions (plus the curve's own vertices)


def _frame(curve: Curve) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Origin (middle point), chord direction t and left normal n, each ``(2,)``."""
    ends = curve.at_fractions(np.array([0.0, 0.5, 1.0]))
    chord = ends[2] - ends[0]
    c = math.hypot(*chord)
    if not c > 1e-12 * max(curve.length, 1e-300):
        raise CaseError("target", "the target's ends coincide; a transformed target needs a chord A'B'")
    t = chord / c
    return ends[1], t, np.array([-t[1], t[0]])


def transformed_target(curve: Curve, bend_radius=None, crown=None, stretch=None, scale=None,
                       rotate_deg=None, translate_x=None, translate_y=None) -> Curve:
    """The target ``curve`` transformed; ``curve`` itself when every amount is None.

    Parameters
    ----------
    curve : Curve
        The case's target, A' to B'.
    bend_radius : float, optional
        Replace the target by the circular arc of radius ``|bend_radius|`` (units)
        and of the target's length, touching the target's middle point with the
        chord's direction; centre on the left of A'B' (the section's side, a
        concave support) when > 0, on the right (a convex drum) when < 0.
    crown : float, optional
        Add a crown of this sagitta (units): every point moves along the left
        normal by the height of the circular arc through the ends with sagitta
        ``crown`` (a straight target becomes exactly that arc).
    stretch : float, optional
        Factor along the chord, about the middle point (> 0).
    scale : float, optional
        Uniform factor about the middle point (> 0).
    rotate_deg : float, optional
        Counter-clockwise rotation about the middle point, degrees.
    translate_x, translate_y : float, optional
        Translation, units.

    Returns
    -------
    Curve
        A :class:`~sectiondeform.curves.Polyline` through ``SAMPLES`` points or more.

    Examples
    --------
    >>> straight = Polyline(np.array([[0.0, 0.0], [110.0, 0.0]]))
    >>> arc = transformed_target(straight, crown=5.0)
    >>> np.round(arc.at_fractions(np.array([0.0, 0.5, 1.0])), 9).tolist()
    [[0.0, 0.0], [55.0, 5.0], [110.0, 0.0]]
    """
    amounts = (bend_radius, crown, stretch, scale, rotate_deg, translate_x, translate_y)
    if all(a is None for a in amounts):
        return curve
    origin, t, n = _frame(curve)
    s = np.linspace(0.0, 1.0, SAMPLES)
    if isinstance(curve, Polyline):
        s = np.union1d(s, curve.discretise(0.0)[1])
    if bend_radius is not None:
        r = float(bend_radius)
        if r == 0.0 or not math.isfinite(r):
            raise CaseError("bend_radius", f"must be a finite non-zero radius, got {bend_radius!r}")
        angle = (s - 0.5) * curve.length / r
        x, y = r * np.sin(angle), r * (1.0 - np.cos(angle))
    else:
        rel = curve.at_fractions(s) - origin
        x, y = rel @ t, rel @ n
    if crown:
        h = float(crown)
        x0, a = 0.5 * (x[-1] + x[0]), 0.5 * abs(x[-1] - x[0])
        radius = (a * a + h * h) / (2.0 * abs(h))
        u = np.minimum(np.abs(x - x0), radius)
        y = y + math.copysign(1.0, h) * (np.sqrt(radius * radius - u * u) - (radius - abs(h)))
    if stretch is not None:
        x = x * float(stretch)
    if scale is not None:
        x, y = x * float(scale), y * float(scale)
    if rotate_deg:
        c, si = math.cos(math.radians(rotate_deg)), math.sin(math.radians(rotate_deg))
        x, y = c * x - si * y, si * x + c * y
    points = origin + x[:, None] * t + y[:, None] * n
    points += np.array([translate_x or 0.0, translate_y or 0.0])
    return Polyline(points)
