"""Mechanical laws ML: Se(t+1) = f(Se(t)) (paper eq. 1).

A law is a small frozen object that sets one quantity of the deformed
section from the initial one: the area (``{"area_ratio": 0.8}``), or the
volume of revolution about an axis (``{"volume_ratio": 1.0}``). Each law is
a class registered under the case-file key it reads; a new law is a new
class, not a new branch. A model asks a law, generically:

- :meth:`Law.quantity` of a polygon (signed: positive counter-clockwise);
- :meth:`Law.target` of the initial quantity;
- :meth:`Law.coefficients` of the quantity of a polygon ``fixed + k moving``
  as a polynomial in ``k`` (the paper model's nodes are affine in its height
  scale ``k``: the area is a quadratic, the volume a cubic);
- :attr:`Law.growth`: the volumetric growth of the body's material the law
  stands for (cure shrinkage, swelling), None for none.

``{"volume_ratio": r}`` means the volume of revolution of a body of
revolution, and, without an axis, the isotropic growth of an extruded body
(a growth stretch r^(1/3) in every direction, the extrusion free along its
length): its section's area is then the volume per unit length over the
axial stretch, r^(2/3) for a free body (:meth:`VolumeRatio.target`), what
the mechanics give for a bonded one (the hyperelastic model).

The hyperelastic model also asks an area law for its out-of-plane stretch,
the physical reason a volume-preserving section changes area.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from . import pappus
from .checks import number
from .curves import closed_parts
from .errors import CaseError, LawError

__all__ = ["Law", "AreaRatio", "VolumeRatio", "law_from_json", "check_growth", "area_coefficients", "law_roots", "LAWS",
           "RATIO_RANGE", "GROWTH_RANGE"]

RATIO_RANGE = (0.01, 100.0)
"""Accepted area and volume ratios, inclusive: beyond them no rubber section means anything."""
GROWTH_RANGE = (0.1, 10.0)
"""Accepted growth of an extruded body (its volume ratio), inclusive: curing shrinks a rubber by a few per cent,
the strongest solvents swell it a few times; beyond, no growth of a rubber means anything."""

LAWS: dict[str, type[Law]] = {}


def _next(a):
    return np.concatenate((a[1:], a[:1]))


def area_coefficients(fixed: np.ndarray, moving: np.ndarray) -> np.ndarray:
    """Signed area of the polygon ``fixed + k moving`` as a quadratic in ``k``: ``(3,)``, constant first.

    Examples
    --------
    >>> f = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]])
    >>> m = np.array([[0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [0.0, 1.0]])
    >>> area_coefficients(f, m).tolist()
    [0.0, 1.0, 0.0]
    """
    fixed = fixed - fixed[0]  # about a vertex: no cancellation far from the origin (moving is a displacement)
    f1, g1 = _next(fixed), _next(moving)

    def cross(a, b):
        return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]

    return 0.5 * np.array([cross(fixed, f1).sum(), (cross(fixed, g1) + cross(moving, f1)).sum(), cross(moving, g1).sum()])


def law_roots(coefficients, wanted: float) -> list[float]:
    """The real ``k`` where a law's polynomial (degree <= 3) takes the value ``wanted``.

    A law's quantity of a polygon ``fixed + k moving`` is a polynomial in
    ``k`` (:meth:`Law.coefficients`): a quadratic for an area, a cubic for a
    volume of revolution. A leading coefficient negligible against the
    others is dropped; quadratics are solved by the cancellation-free
    formula, cubics by :func:`numpy.roots` (the companion matrix's
    eigenvalues) polished by two Newton steps. Used for the paper model's
    height scale and the hyperelastic model's law offset alike.

    Parameters
    ----------
    coefficients : sequence of float
        ``c`` with ``q(k) = c[0] + c[1] k + ...``, at most 4.
    wanted : float
        Wanted value of ``q``, signed as the coefficients.

    Returns
    -------
    list of float
        The finite real roots (none when the polynomial is constant).

    Examples
    --------
    >>> law_roots([0.0, 0.0, 0.0, 1.0], 8.0)  # k³ = 8
    [2.0]
    >>> sorted(round(k, 12) for k in law_roots([0.0, 3.0, -1.0], 2.0))  # 3k - k² = 2: k = 1 or 2
    [1.0, 2.0]
    """
    c = np.array(coefficients, dtype=np.float64)
    c[0] -= wanted
    while len(c) > 1 and abs(c[-1]) <= 1e-14 * float(np.abs(c[:-1]).sum()):
        c = c[:-1]
    if len(c) == 4:
        raw = np.roots(c[::-1])
        roots = [float(r.real) for r in raw if abs(r.imag) <= 1e-9 * (1.0 + abs(r))]
        dc = c[1:] * np.arange(1, len(c))
        for i, k in enumerate(roots):
            for _ in range(2):
                slope = np.polynomial.polynomial.polyval(k, dc)
                if slope == 0:
                    break
                k -= np.polynomial.polynomial.polyval(k, c) / slope
            roots[i] = float(k)
    elif len(c) == 3:
        c0, c1, c2 = (float(v) for v in c)
        disc = c1 * c1 - 4.0 * c2 * c0
        if disc < 0:
            roots = []
        else:
            q = -0.5 * (c1 + math.copysign(math.sqrt(disc), c1))
            roots = [q / c2] + ([c0 / q] if q != 0 else [])
    elif len(c) == 2:
        roots = [-float(c[0]) / float(c[1])]
    else:
        roots = []
    return [r for r in roots if math.isfinite(r)]


class Law:
    """Base class of the mechanical laws.

    A subclass sets ``key`` (its case-file key) and ``measure`` (the name of
    its quantity, for results and messages), and gives :meth:`target`; a law
    on another quantity than the area also gives :meth:`quantity` and
    :meth:`coefficients`. ``needs_axis`` marks a law bound to the case's
    axis of revolution when there is one; ``growth`` is the volumetric
    growth of the material the law stands for (None: none).
    """

    key: ClassVar[str] = ""
    measure: ClassVar[str] = "area"
    needs_axis: ClassVar[bool] = False
    growth: ClassVar[float | None] = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.key:
            LAWS[cls.key] = cls

    def quantity(self, polygon: np.ndarray) -> float:
        """The law's quantity of a closed polygon ``(N, 2)``, signed (positive counter-clockwise); here its area, units²."""
        return float(area_coefficients(np.asarray(polygon, dtype=np.float64), np.zeros_like(polygon, dtype=np.float64))[0])

    def curve_quantity(self, curves) -> float:
        """The law's quantity of the area a closed contour of curves encloses, exactly, signed as :meth:`quantity`.

        ``curves`` is a sequence of :class:`~sectiondeform.curves.Curve`,
        each starting where the one before ends (a gap counts as its chord,
        :func:`~sectiondeform.curves.closed_parts`); here the exact area
        (Green's theorem about the first curve's start, so a section far from
        the origin keeps its digits), units².
        """
        origin = curves[0].start
        return float(sum(c.green_about(origin) for c in closed_parts(curves)))

    def coefficients(self, fixed: np.ndarray, moving: np.ndarray) -> np.ndarray:
        """:meth:`quantity` of the polygon ``fixed + k moving`` (both ``(N, 2)``) as polynomial coefficients in ``k``, constant first."""
        return area_coefficients(fixed, moving)

    def target(self, initial: float) -> float:  # pragma: no cover - abstract
        """Final quantity from the initial one (signed in, signed out)."""
        raise NotImplementedError

    def target_area(self, initial_area: float) -> float:
        """Final area, in units², from the initial area (a law on the area only).

        Raises
        ------
        LawError
            For a law on another quantity (a volume), which no area alone decides.
        """
        if self.measure != "area":
            raise LawError(f"law: {self.key} sets the {self.measure}, not the area; this model cannot meet it yet (use the paper model)")
        return self.target(initial_area)

    def area_ratio(self, initial_area: float) -> float:
        """Final over initial area."""
        return self.target_area(initial_area) / initial_area

    def out_of_plane_stretch(self, initial_area: float) -> float:
        """Out-of-plane stretch of a volume-preserving section under this law (1 / area ratio)."""
        return 1.0 / self.area_ratio(initial_area)

    def to_json(self) -> dict:  # pragma: no cover - abstract
        """The ``law`` object of the case format."""
        raise NotImplementedError


@dataclass(frozen=True)
class AreaRatio(Law):
    """Final area = ``ratio`` x initial area (the paper's law, ratio 0.8).

    ``ratio`` is a finite number in :data:`RATIO_RANGE` (0.01 to 100).

    Examples
    --------
    >>> AreaRatio(0.8).target_area(4379.0)
    3503.2000000000003
    """

    ratio: float
    key: ClassVar[str] = "area_ratio"

    def __post_init__(self):
        low, high = RATIO_RANGE
        r = number(self.ratio, "law.area_ratio", low=0.0, strict_low=True)
        if not low <= r <= high:
            raise CaseError("law.area_ratio", f"must be between {low:g} and {high:g}, got {r!r}")
        object.__setattr__(self, "ratio", r)

    def target(self, initial):
        return self.ratio * initial

    def to_json(self):
        return {"area_ratio": float(self.ratio)}


@dataclass(frozen=True)
class VolumeRatio(Law):
    """Final volume = ``ratio`` x initial volume: a body of revolution, or the growth of an extruded body.

    With an axis, the volume of revolution. Without one (an extruded body),
    the isotropic growth of the material by ``ratio`` (curing, swelling:
    a growth stretch ``ratio^(1/3)`` in every direction, the extrusion free
    along its length); the law then sets the section's area, whose target
    is a free body's, ``ratio^(2/3)`` times the initial area
    (:meth:`target`). A model that solves the axial stretch ``lz`` (the
    hyperelastic model) meets ``ratio / lz`` instead
    (:meth:`area_for_axial_stretch`).

    The volume is ``2 pi`` times the section's first moment about the axis
    (Pappus: area times the centroid's distance from the axis,
    :mod:`sectiondeform.pappus`). ``ratio`` 1 is an incompressible body: its
    area changes as the inverse of its centroid's distance from the axis.

    Parameters
    ----------
    ratio : float
        In :data:`RATIO_RANGE`.
    axis : ((float, float), (float, float)), optional
        Two distinct points of the axis, units. A law read from a case gets
        it from the case's ``revolution`` (:meth:`about`); without it the
        law cannot measure anything.

    Examples
    --------
    >>> law = VolumeRatio(1.0, ((0.0, 0.0), (1.0, 0.0)))
    >>> square = np.array([[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]])
    >>> round(law.quantity(square) / np.pi, 12)  # 2 pi x area 1 x distance 1.5
    3.0
    """

    ratio: float
    axis: tuple | None = None
    key: ClassVar[str] = "volume_ratio"
    needs_axis: ClassVar[bool] = True

    @property
    def measure(self) -> str:
        """``"volume"`` about an axis, else ``"area"`` (an extruded body's section)."""
        return "volume" if self.axis is not None else "area"

    @property
    def growth(self) -> float:
        """The material's volumetric growth: ``ratio``."""
        return self.ratio

    def __post_init__(self):
        low, high = RATIO_RANGE
        r = number(self.ratio, "law.volume_ratio", low=0.0, strict_low=True)
        if not low <= r <= high:
            raise CaseError("law.volume_ratio", f"must be between {low:g} and {high:g}, got {r!r}")
        object.__setattr__(self, "ratio", r)
        if self.axis is not None:
            p0, p1 = (tuple(float(v) for v in p) for p in self.axis)
            if p0 == p1:
                raise CaseError("revolution.axis", "the two points coincide; give two distinct points of the axis")
            object.__setattr__(self, "axis", (p0, p1))

    def about(self, axis) -> VolumeRatio:
        """The same law about ``axis``."""
        return VolumeRatio(self.ratio, axis)

    def quantity(self, polygon):
        """Signed volume of revolution, ``2 pi`` x first moment about the axis, units³; the area without an axis."""
        if self.axis is None:
            return super().quantity(polygon)
        return 2.0 * np.pi * pappus.first_moment(polygon, self.axis)

    def curve_quantity(self, curves):
        """Exact signed volume of revolution of the area the curves enclose (:func:`~sectiondeform.pappus.curve_moment`), units³."""
        if self.axis is None:
            return super().curve_quantity(curves)
        return 2.0 * np.pi * pappus.curve_moment(curves, self.axis)

    def coefficients(self, fixed, moving):
        if self.axis is None:
            return super().coefficients(fixed, moving)
        return 2.0 * np.pi * pappus.moment_coefficients(fixed, moving, self.axis)

    def target(self, initial):
        """``ratio`` x the initial volume; without an axis, a free body's area, ``ratio^(2/3)`` x the initial one."""
        if self.axis is None:
            return self.area_for_axial_stretch(initial, self.ratio ** (1.0 / 3.0))
        return self.ratio * initial

    def area_for_axial_stretch(self, initial_area: float, axial_stretch: float) -> float:
        """An extruded body's area after growth when its length stretches by ``axial_stretch``: ``ratio / lz`` x the initial area.

        The material grows its volume by ``ratio`` (nearly incompressible
        otherwise), so the volume per unit initial length is ``ratio`` x the
        initial area. Signed as ``initial_area``.
        """
        return self.ratio / axial_stretch * initial_area

    def out_of_plane_stretch(self, initial_area: float) -> float:
        """A free body's axial stretch under growth, ``ratio^(1/3)`` (an extruded body); the start of a solved one."""
        if self.axis is None:
            return self.ratio ** (1.0 / 3.0)
        return super().out_of_plane_stretch(initial_area)

    def to_json(self):
        return {"volume_ratio": float(self.ratio)}


def law_from_json(obj, field: str = "law", axis=None) -> Law:
    """Build a :class:`Law` from the case's ``law`` object.

    Parameters
    ----------
    obj : object
        The parsed ``law`` object.
    field : str
        Where it sits in the case, for messages.
    axis : ((float, float), (float, float)), optional
        The case's axis of revolution; a law that binds to one
        (``volume_ratio``) is bound to it, else left as the growth of an
        extruded body (checked against :data:`GROWTH_RANGE`).

    Raises
    ------
    CaseError
        If the object is not a one-key object naming a known law, or a
        growth beyond :data:`GROWTH_RANGE`.

    Examples
    --------
    >>> law_from_json({"area_ratio": 0.9})
    AreaRatio(ratio=0.9)
    >>> law_from_json({"volume": 1})
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: law: unknown law 'volume'; use one of area_ratio, volume_ratio
    """
    if not isinstance(obj, dict) or len(obj) != 1:
        raise CaseError(field, f"expected one law object such as {{\"area_ratio\": 0.8}}, got {obj!r}")
    (key, value), = obj.items()
    if key not in LAWS:
        raise CaseError(field, f"unknown law {key!r}; use one of {', '.join(sorted(LAWS))}")
    try:
        law = LAWS[key](value)
    except CaseError as exc:  # the law's own check names "law.<key>": name where it sits in the case
        if field == "law" or exc.field != f"law.{key}":
            raise
        raise CaseError(f"{field}.{key}", exc.problem) from None
    if law.needs_axis and axis is not None:
        law = law.about(axis)
    check_growth(law, field)
    return law


def check_growth(law: Law, field: str = "law") -> Law:
    """``law``, refused in one line if it grows an extruded body beyond :data:`GROWTH_RANGE`.

    Examples
    --------
    >>> check_growth(VolumeRatio(50.0))
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: law.volume_ratio: a growth of an extruded body must be between 0.1 and 10 (its volume ratio), got 50.0
    """
    if law.growth is not None and getattr(law, "axis", True) is None:
        low, high = GROWTH_RANGE
        if not low <= law.growth <= high:
            raise CaseError(f"{field}.{law.key}", f"a growth of an extruded body must be between {low:g} and {high:g} "
                            f"(its volume ratio), got {law.growth!r}")
    return law
