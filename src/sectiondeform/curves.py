"""Planar curves as the case file gives them: polyline, B-spline, arc, chain.

Every curve answers three questions, all in the case's length ``units``:

- ``at_fractions(s)``: the points at normalised arc length ``s`` in [0, 1]
  (how a point of the lower curve finds its place on the target);
- ``discretise(tol)``: an adaptive polyline within chordal error ``tol``
  (short steps where the curve bends, long ones where it is straight), with
  the arc-length fraction of each vertex;
- ``characteristic_points(tol)``: the points the deformation maps (a
  polyline's own vertices, all of them; the discretisation for other kinds).

Curves are immutable; ``curve_from_json`` and ``Curve.to_json`` convert to
and from the CURVE objects of the case format.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .checks import COORDINATE_LIMIT, number
from .errors import CaseError
from .limits import MAX_CURVE_POINTS, MAX_SPLINE_PIECES, bounded

__all__ = [
    "Curve",
    "Polyline",
    "BSpline",
    "Arc",
    "Chain",
    "curve_from_json",
    "as_points",
    "polygon_area",
    "DEFAULT_CHORDAL_FRACTION",
    "zigzag_fraction",
    "cross",
]

# Default chordal error of the polylines made from curves, as a fraction of
# the size (bounding-box diagonal) of what is discretised.
DEFAULT_CHORDAL_FRACTION = 1e-4

# Gauss-Legendre nodes for arc-length quadrature on each sub-interval.
# (numpy.polynomial.legendre.leggauss(5), written out: its import costs start-up time)
_GL_X = np.array([-0.906179845938664, -0.5384693101056831, 0.0, 0.5384693101056831, 0.906179845938664])
_GL_W = np.array([0.23692688505618928, 0.4786286704993663, 0.5688888888888887, 0.4786286704993663, 0.23692688505618928])


def as_points(value, field: str, min_count: int = 1) -> np.ndarray:
    """Convert a list of ``[x, y]`` pairs to a checked ``(N, 2)`` float64 array.

    Parameters
    ----------
    value : array_like
        Nested sequence of ``[x, y]`` pairs.
    field : str
        Name of the input for error messages, e.g. ``"lower.polyline"``.
    min_count : int
        Smallest acceptable number of points.

    Returns
    -------
    (N, 2) float64 ndarray
        A new array (never a view of the input).

    Raises
    ------
    CaseError
        If the value is not a list of pairs of finite numbers, or too short.

    Examples
    --------
    >>> as_points([[0, 0], [1, 2]], "lower.polyline").shape
    (2, 2)
    """
    if isinstance(value, (str, bytes, dict)) or value is None:
        raise CaseError(field, f"expected a list of [x, y] pairs, got {type(value).__name__}")
    if isinstance(value, np.ndarray):
        arr = value
    else:
        try:
            arr = np.array(value)
        except (TypeError, ValueError, OverflowError):
            arr = None
        if arr is None or arr.dtype.kind not in "iuf" or arr.ndim != 2 or _has_bool(value):
            _first_bad_pair(value, field)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise CaseError(field, f"expected a list of [x, y] pairs, got an array of shape {arr.shape}")
    if arr.dtype.kind not in "iuf":
        if not isinstance(value, np.ndarray):
            _first_bad_pair(value, field)
        raise CaseError(field, f"coordinates must be numbers, got an array of {arr.dtype}")
    with np.errstate(all="ignore"):
        arr = np.array(arr, dtype=np.float64)
    if len(arr) < min_count:
        raise CaseError(field, f"needs at least {min_count} points, got {len(arr)}")
    bad = ~(np.isfinite(arr).all(axis=1) & (np.abs(arr) <= COORDINATE_LIMIT).all(axis=1))
    if bad.any():
        i = int(np.argmax(bad))
        raise CaseError(f"{field}[{i}]", f"coordinates must be finite numbers within +-{COORDINATE_LIMIT:g}, got {arr[i].tolist()}")
    return arr


def _has_bool(value) -> bool:
    """Whether a nested list of pairs holds a bool (numpy takes ``true`` for 1)."""
    return any(type(c) is bool for pair in value if isinstance(pair, (list, tuple)) for c in pair)


def _first_bad_pair(value, field: str) -> None:
    """Raise the one-line error for the first entry of ``value`` that is not a pair of numbers."""
    try:
        items = list(value)
    except TypeError:
        raise CaseError(field, f"expected a list of [x, y] pairs, got {type(value).__name__}") from None
    for i, pair in enumerate(items):
        if isinstance(pair, (str, bytes, dict)) or not hasattr(pair, "__len__") or len(pair) != 2:
            raise CaseError(f"{field}[{i}]", f"expected an [x, y] pair, got {_number_text(pair)}")
        for c in pair:
            number(c, f"{field}[{i}]", low=-COORDINATE_LIMIT, high=COORDINATE_LIMIT)
    raise CaseError(field, "expected a list of [x, y] pairs of numbers")


def _number_text(value) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."
def polygon_area(points: np.ndarray) -> float:
    """Signed area of a closed polygon (shoelace), positive when counter-clockwise.

    Parameters
    ----------
    points : (N, 2) float64 ndarray
        Vertices in order; the closing edge back to the first is implied.

    Returns
    -------
    float
        Area in units².

    Examples
    --------
    >>> polygon_area(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]))
    2.0
    """
    if len(points) == 0:
        return 0.0
    points = points - points[0]  # about a vertex: no cancellation far from the origin
    x, y = points[:, 0], points[:, 1]
    x1, y1 = np.concatenate((x[1:], x[:1])), np.concatenate((y[1:], y[:1]))  # np.roll(., -1), cheaper
    return 0.5 * float(np.dot(x, y1) - np.dot(x1, y))


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The z component of the cross product of 2D vectors, ``(..., 2)`` each -> ``(...)``.

    Examples
    --------
    >>> float(cross(np.array([1.0, 0.0]), np.array([0.0, 2.0])))
    2.0
    """
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def zigzag_fraction(points: np.ndarray) -> float:
    """Fraction of the vertices of a polyline where its turning changes side, in [0, 1].

    About 0 for a smooth curve drawn or discretised (it turns one way over
    long runs), about 1/2 for a scanned or digitised outline whose noise
    turns it left and right at random.

    Parameters
    ----------
    points : (N, 2) float64 ndarray

    Returns
    -------
    float
        0 when fewer than three vertices turn.

    Examples
    --------
    >>> t = np.linspace(0.0, np.pi, 50)
    >>> zigzag_fraction(np.column_stack((np.cos(t), np.sin(t))))
    0.0
    >>> zigzag_fraction(np.array([[0, 0], [1, 1], [2, 0], [3, 1], [4, 0]], dtype=float))
    1.0
    """
    d = np.diff(np.asarray(points, dtype=np.float64), axis=0)
    turn = np.sign(d[:-1, 0] * d[1:, 1] - d[:-1, 1] * d[1:, 0])
    turn = turn[turn != 0]
    if len(turn) < 3:
        return 0.0
    return float(np.mean(turn[1:] != turn[:-1]))


def closed_parts(curves) -> list[Curve]:
    """The pieces of a closed contour of ``curves``, with a straight segment closing every gap between two.

    Pieces read from files may miss their neighbours by rounding (a
    millionth of a millimetre); the enclosed area and its moments are those
    of the contour the polygon of the pieces closes, so each gap counts as
    its chord. ``curves`` is a sequence of :class:`Curve` in order, the last
    one ending near the first one's start.
    """
    parts = [p for c in curves for p in c.parts()]
    out = []
    for p, q in zip(parts, parts[1:] + parts[:1]):
        out.append(p)
        if not np.array_equal(p.end, q.start):
            out.append(Polyline(np.stack((p.end, q.start))))
    return out


def _affine(matrix, offset) -> tuple[np.ndarray, np.ndarray]:
    """``matrix`` as ``(2, 2)`` and ``offset`` as ``(2,)`` float64 arrays."""
    return (np.asarray(matrix, dtype=np.float64).reshape(2, 2),
            np.asarray(offset, dtype=np.float64).reshape(2))


def _unique(values: np.ndarray) -> np.ndarray:
    """Sorted distinct values, as ``np.unique`` (which imports numpy.ma on first use, 20 ms)."""
    v = np.sort(values)
    return v[np.concatenate(([True], v[1:] != v[:-1]))] if len(v) else v


def _cumulative_length(points: np.ndarray) -> np.ndarray:
    """Cumulative chord length along an ``(N, 2)`` polyline, ``(N,)``, starting at 0."""
    seg = np.hypot(*np.diff(points, axis=0).T)
    return np.concatenate(([0.0], np.cumsum(seg)))


class Curve:
    """Base class of the curve kinds; subclasses are frozen dataclasses."""

    kind: str = ""

    @property
    def length(self) -> float:  # pragma: no cover - abstract
        """Arc length of the curve, in case units."""
        raise NotImplementedError

    @property
    def start(self) -> np.ndarray:
        """First point, ``(2,)``."""
        return self.at_fractions(np.array([0.0]))[0]

    @property
    def end(self) -> np.ndarray:
        """Last point, ``(2,)``."""
        return self.at_fractions(np.array([1.0]))[0]

    @property
    def ends(self) -> tuple[np.ndarray, np.ndarray]:
        """Exact first and last point, ``(2,)`` float64 each, units.

        Unlike :attr:`start` and :attr:`end` (evaluated at fractions 0 and
        1), the stored points where a kind has them (polyline vertices,
        the end control points of a clamped B-spline).
        """
        return self.start, self.end

    def reversed(self) -> Curve:  # pragma: no cover - abstract
        """The same curve run the other way, of the same kind."""
        raise NotImplementedError

    def transformed(self, matrix, offset=(0.0, 0.0), tol: float = 1e-3) -> Curve:  # pragma: no cover - abstract
        """The image of the curve under the affine map ``p -> matrix @ p + offset``.

        Parameters
        ----------
        matrix : (2, 2) array_like
        offset : (2,) array_like
            Units of the result.
        tol : float
            Chordal error of a polyline standing for an image that is not
            of the same kind (an arc under a non-uniform map), in the units
            of the result.

        Returns
        -------
        Curve
            Exact for every map where the kind allows it (polylines and
            B-splines always, arcs under similarities).
        """
        raise NotImplementedError

    def scaled(self, factor: float) -> Curve:
        """The curve scaled by ``factor`` about the origin (a change of units)."""
        return self.transformed(factor * np.eye(2))

    def with_end_moved(self, at_end: bool, point) -> Curve | None:
        """The curve with its first (or last, ``at_end``) point exactly at ``point`` ``(2,)``.

        For closing tiny gaps when pieces are joined. None when the kind
        cannot move an end alone (an arc).
        """
        return None

    def joined(self, other: Curve) -> Curve | None:
        """One curve of this kind for ``self`` then ``other`` (which starts where self ends), or None."""
        return None

    def simplified(self, tol: float) -> Curve:
        """The curve with its polyline runs simplified within ``tol`` (ends kept); other kinds as they are."""
        return self

    @property
    def point_count(self) -> int:
        """Points that define the curve for a report: a polyline's vertices, 1 per other piece."""
        return 1

    def parts(self) -> tuple[Curve, ...]:
        """The curves that are not chains, in order: ``(self,)`` for every kind but :class:`Chain`."""
        return (self,)

    def at_fractions(self, s: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        """Points at normalised arc lengths ``s`` (``(K,)`` in [0, 1]); returns ``(K, 2)``."""
        raise NotImplementedError

    def discretise(self, tol: float) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
        """Adaptive polyline within chordal error ``tol``: ``(N, 2)`` points, ``(N,)`` fractions."""
        raise NotImplementedError

    def characteristic_points(self, tol: float) -> np.ndarray:
        """Points that the deformation maps, ``(N, 2)``: the discretisation by default."""
        return self.discretise(tol)[0]

    def refinements(self, tol: float, factor: float = 4.0) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        """:meth:`discretise` at ``tol``, ``tol / factor``, ``tol / factor**2``, ... in turn (endless).

        Each item equals ``discretise`` at that chordal error; a kind whose
        discretisation refines the previous one continues from it.
        """
        while True:
            yield self.discretise(tol)
            tol /= factor

    def characteristic_refinements(self, tol: float, factor: float = 4.0) -> Iterator[np.ndarray]:
        """:meth:`characteristic_points` at ``tol``, ``tol / factor``, ... in turn, like :meth:`refinements`."""
        if type(self).characteristic_points is Curve.characteristic_points:
            yield from (points for points, _ in self.refinements(tol, factor))
        else:
            while True:
                yield self.characteristic_points(tol)
                tol /= factor

    def to_json(self) -> dict:  # pragma: no cover - abstract
        """The CURVE object of the case format."""
        raise NotImplementedError

    def green(self) -> float:  # pragma: no cover - abstract
        """Exact 1/2 * integral of (x dy - y dx) along the curve, units².

        Summed over the curves of a closed contour it gives the enclosed
        signed area (positive counter-clockwise).
        """
        raise NotImplementedError

    def moment_x(self) -> float:  # pragma: no cover - abstract
        """Exact -1/2 * integral of y² dx along the curve, units³.

        Summed over the curves of a closed contour it gives the first
        moment of the enclosed area about the x axis, the integral of y over
        the area (signed as :meth:`green`): Green's theorem with ``L = -y²/2``.
        """
        raise NotImplementedError

    def green_about(self, origin) -> float:
        """:meth:`green` about ``origin`` ``(2,)`` instead of (0, 0), units².

        Summed over a closed contour it is the enclosed signed area, whatever
        the origin; about a point of the section it keeps its digits where
        the section is small and far from (0, 0).
        """
        origin = np.asarray(origin, dtype=np.float64)
        return (self.transformed(np.eye(2), -origin) if origin.any() else self).green()

    def moment_about(self, origin, rotation) -> float:
        """:meth:`moment_x` in the frame ``p -> rotation @ (p - origin)``, units³.

        ``rotation`` ``(2, 2)`` is a proper rotation (rows: the frame's x
        and y directions): summed over a closed contour, the first moment of
        the enclosed area about the frame's x axis, as Pappus's theorem
        needs it (:func:`~sectiondeform.pappus.curve_moment`).
        """
        rotation = np.asarray(rotation, dtype=np.float64)
        return self.transformed(rotation, -rotation @ np.asarray(origin, dtype=np.float64)).moment_x()


@dataclass(frozen=True, eq=False)
class Polyline(Curve):
    """A polyline through ``vertices``, ``(N, 2)`` float64, N >= 2.

    Examples
    --------
    >>> p = Polyline(np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 4.0]]))
    >>> p.length
    7.0
    >>> p.at_fractions(np.array([0.5])).tolist()
    [[3.0, 0.5]]
    """

    vertices: np.ndarray
    kind = "polyline"

    def __post_init__(self):
        v = np.array(self.vertices, dtype=np.float64)
        v.setflags(write=False)
        object.__setattr__(self, "vertices", v)

    @cached_property
    def _cum(self) -> np.ndarray:
        return _cumulative_length(self.vertices)

    @property
    def length(self) -> float:
        return float(self._cum[-1])

    def at_fractions(self, s):
        s = np.asarray(s, dtype=np.float64)
        cum = self._cum
        d = np.minimum(np.maximum(s, 0.0), 1.0) * cum[-1]  # np.clip, without its overhead
        # Skip zero-length segments so that np.interp sees increasing abscissae.
        keep = np.concatenate(([True], cum[1:] > cum[:-1]))
        c, v = cum[keep], self.vertices[keep]
        out = np.empty((len(d), 2))
        out[:, 0], out[:, 1] = np.interp(d, c, v[:, 0]), np.interp(d, c, v[:, 1])
        return out

    def discretise(self, tol):
        keep = _douglas_peucker(self.vertices, tol)
        return self.vertices[keep].copy(), self._cum[keep] / self._cum[-1]

    def characteristic_points(self, tol):
        return self.vertices.copy()

    def green(self):
        v = self.vertices
        return 0.5 * float(np.sum(v[:-1, 0] * v[1:, 1] - v[1:, 0] * v[:-1, 1]))

    def moment_x(self):
        x, y = self.vertices[:, 0], self.vertices[:, 1]
        return -float(np.sum((x[1:] - x[:-1]) * (y[:-1] * y[:-1] + y[:-1] * y[1:] + y[1:] * y[1:]))) / 6.0

    def to_json(self):
        return {"polyline": self.vertices.tolist()}

    @property
    def ends(self):
        return self.vertices[0], self.vertices[-1]

    def reversed(self):
        return Polyline(self.vertices[::-1])

    def transformed(self, matrix, offset=(0.0, 0.0), tol=1e-3):
        m, b = _affine(matrix, offset)
        return Polyline(self.vertices @ m.T + b)

    def with_end_moved(self, at_end, point):
        v = self.vertices.copy()
        v[-1 if at_end else 0] = point
        return Polyline(v)

    def joined(self, other):
        if not isinstance(other, Polyline):
            return None
        return Polyline(np.concatenate((self.vertices, other.vertices[1:])))

    def simplified(self, tol):
        if len(self.vertices) <= 2:
            return self
        import shapely  # imported here: start-up time of the command line

        line = shapely.simplify(shapely.LineString(self.vertices), tol, preserve_topology=True)
        return Polyline(np.asarray(line.coords, dtype=np.float64)[:, :2])

    @property
    def point_count(self):
        return len(self.vertices)


def _douglas_peucker(points: np.ndarray, tol: float) -> np.ndarray:
    """Indices of the vertices kept by Douglas-Peucker within ``tol`` (ends always kept).

    Zero-length segments are dropped first. Returns a sorted ``(K,)`` int array.
    """
    n = len(points)
    moved = np.concatenate(([True], np.hypot(*np.diff(points, axis=0).T) > 0))
    idx = np.flatnonzero(moved)
    if idx[-1] != n - 1:
        idx[-1] = n - 1
    keep = np.zeros(n, dtype=bool)
    keep[idx[0]] = keep[idx[-1]] = True
    stack = [(0, len(idx) - 1)]
    while stack:
        a, b = stack.pop()
        if b - a < 2:
            continue
        pa, pb = points[idx[a]], points[idx[b]]
        mid = points[idx[a + 1 : b]]
        d = pb - pa
        norm = math.hypot(*d)
        if norm == 0.0:
            dist = np.hypot(*(mid - pa).T)
        else:
            dist = np.abs(d[0] * (mid[:, 1] - pa[1]) - d[1] * (mid[:, 0] - pa[0])) / norm
        k = int(np.argmax(dist))
        if dist[k] > tol:
            m = a + 1 + k
            keep[idx[m]] = True
            stack.extend(((a, m), (m, b)))
    return np.flatnonzero(keep)


@dataclass(frozen=True, eq=False)
class Arc(Curve):
    """A circular arc, counter-clockwise when ``end_deg > start_deg``.

    Examples
    --------
    >>> a = Arc(np.array([0.0, 0.0]), 1.0, 0.0, 90.0)
    >>> round(a.length, 12) == round(math.pi / 2, 12)
    True
    >>> np.round(a.at_fractions(np.array([1.0])), 12).tolist()
    [[0.0, 1.0]]
    """

    center: np.ndarray
    radius: float
    start_deg: float
    end_deg: float
    kind = "arc"

    def __post_init__(self):
        c = np.array(self.center, dtype=np.float64)
        c.setflags(write=False)
        object.__setattr__(self, "center", c)

    @property
    def _sweep(self) -> float:
        return math.radians(self.end_deg - self.start_deg)

    @property
    def length(self):
        return abs(self._sweep) * self.radius

    def at_fractions(self, s):
        th = math.radians(self.start_deg) + np.clip(np.asarray(s, dtype=np.float64), 0, 1) * self._sweep
        return self.center + self.radius * np.column_stack((np.cos(th), np.sin(th)))

    def discretise(self, tol):
        x = tol / self.radius
        # The angle whose sagitta is tol; 2 sqrt(2 x) where 1 - x rounds to 1.
        step = (2.0 * math.acos(1.0 - x) if x > 1e-8 else 2.0 * math.sqrt(2.0 * x)) if x < 1 else math.pi / 2
        n = abs(self._sweep) / min(step, math.pi / 2) if step > 0 else math.inf
        n = max(1, math.ceil(bounded(n, MAX_CURVE_POINTS, "points on an arc", "raise options.chordal_error") - 1e-9)) \
            if abs(self._sweep) > 0 else 1
        s = np.linspace(0.0, 1.0, n + 1)
        return self.at_fractions(s), s

    def green(self):
        (cx, cy), r = self.center, self.radius
        a0, a1 = math.radians(self.start_deg), math.radians(self.end_deg)
        return 0.5 * (r * cx * (math.sin(a1) - math.sin(a0)) - r * cy * (math.cos(a1) - math.cos(a0)) + r * r * (a1 - a0))

    def moment_x(self):
        # x = cx + r cos a, y = cy + r sin a: -1/2 y² dx = r/2 (cy² sin a + 2 cy r sin² a + r² sin³ a) da.
        (_, cy), r = self.center, self.radius

        def primitive(a):
            c = math.cos(a)
            return -cy * cy * c + cy * r * (a - math.sin(a) * c) + r * r * (c * c * c / 3.0 - c)

        return 0.5 * r * (primitive(math.radians(self.end_deg)) - primitive(math.radians(self.start_deg)))

    @property
    def ends(self):
        a = np.radians([self.start_deg, self.end_deg])
        pts = self.center + self.radius * np.column_stack((np.cos(a), np.sin(a)))
        return pts[0], pts[1]

    def reversed(self):
        return Arc(self.center, self.radius, self.end_deg, self.start_deg)

    def transformed(self, matrix, offset=(0.0, 0.0), tol=1e-3):
        # An arc stays an arc under a similarity (uniform scale, rotation,
        # reflection); under any other map it becomes an ellipse, given back
        # as a polyline within tol of it.
        m, b = _affine(matrix, offset)
        if (m == np.eye(2)).all():  # a translation keeps the angles exactly
            return Arc(self.center + b, self.radius, self.start_deg, self.end_deg)
        mtm = m.T @ m
        scale2 = 0.5 * (mtm[0, 0] + mtm[1, 1])
        if abs(mtm[0, 1]) <= 1e-12 * scale2 and abs(mtm[0, 0] - mtm[1, 1]) <= 1e-12 * scale2:
            det = float(np.linalg.det(m))
            ms = m @ (self.start - self.center)
            a0 = math.degrees(math.atan2(ms[1], ms[0]))
            sweep = (self.end_deg - self.start_deg) * (1.0 if det > 0 else -1.0)
            return Arc(m @ self.center + b, self.radius * math.sqrt(abs(det)), a0, a0 + sweep)
        stretch = math.sqrt(float(np.linalg.eigvalsh(mtm).max()))  # largest stretch of the map
        pts, _ = self.discretise(tol / stretch)
        return Polyline(pts @ m.T + b)

    def to_json(self):
        return {
            "arc": {
                "center": self.center.tolist(),
                "radius": float(self.radius),
                "start_deg": float(self.start_deg),
                "end_deg": float(self.end_deg),
            }
        }


@dataclass(frozen=True, eq=False)
class BSpline(Curve):
    """A clamped B-spline of ``degree`` with ``(n, 2)`` control points and ``knots``.

    ``knots`` has ``n + degree + 1`` non-decreasing entries, the first and the
    last ``degree + 1`` equal (clamped). Arc-length fractions are computed by
    Gauss-Legendre quadrature of the speed on a fine parameter table.

    Examples
    --------
    >>> b = BSpline(1, np.array([[0.0, 0.0], [2.0, 0.0]]), None)
    >>> round(b.length, 12)
    2.0
    """

    degree: int
    control_points: np.ndarray
    knots: np.ndarray | None = None
    kind = "bspline"
    MAX_DEPTH = 40  # halvings of a knot interval's fifth
    _spline: object = field(init=False, repr=False, default=None)

    def __post_init__(self):
        c = np.array(self.control_points, dtype=np.float64)
        c.setflags(write=False)
        object.__setattr__(self, "control_points", c)
        p, n = self.degree, len(c)
        if self.knots is None:
            inner = np.linspace(0.0, 1.0, n - p + 1)[1:-1]
            t = np.concatenate((np.zeros(p + 1), inner, np.ones(p + 1)))
        else:
            t = np.array(self.knots, dtype=np.float64)
        t.setflags(write=False)
        object.__setattr__(self, "knots", t)
        bounded(len(c), MAX_SPLINE_PIECES, "B-spline control points", "fit the curve with fewer control points")
        object.__setattr__(self, "_spline", _Spline(t, c, p))

    @cached_property
    def _table(self) -> tuple[np.ndarray, np.ndarray]:
        """Parameter samples ``u`` and cumulative arc length at them, both ``(K,)``."""
        p, t = self.degree, self.knots
        breaks = _unique(t[p : len(t) - p])
        u = np.concatenate(
            [np.linspace(a, b, 65)[:-1] for a, b in zip(breaks[:-1], breaks[1:])] + [breaks[-1:]]
        )
        a, b = u[:-1], u[1:]
        half = 0.5 * (b - a)
        q = (0.5 * (a + b))[:, None] + half[:, None] * _GL_X[None, :]
        d = self._spline.derivative()(q.ravel()).reshape(q.shape + (2,))
        speed = np.hypot(d[..., 0], d[..., 1])
        seg = half * (speed @ _GL_W)
        return u, np.concatenate(([0.0], np.cumsum(seg)))

    @property
    def length(self):
        return float(self._table[1][-1])

    def _u_of_fraction(self, s):
        u, cum = self._table
        return np.interp(np.clip(s, 0, 1) * cum[-1], cum, u)

    def at_fractions(self, s):
        return self._spline(self._u_of_fraction(np.asarray(s, dtype=np.float64)))

    def discretise(self, tol):
        return next(self.refinements(tol))

    def _deviation(self, a: np.ndarray, b: np.ndarray, pa: np.ndarray, pb: np.ndarray) -> np.ndarray:
        """Largest distance of the curve at 1/4, 1/2, 3/4 of each interval ``[a, b]`` from its chord, ``(K,)``."""
        probe = a[:, None] + _PROBES * (b - a)[:, None]
        pm = self._spline(probe.ravel()).reshape(-1, 3, 2)
        d = pb - pa
        norm = np.hypot(d[:, 0], d[:, 1])
        rel = pm - pa[:, None, :]
        cross = np.abs(d[:, None, 0] * rel[..., 1] - d[:, None, 1] * rel[..., 0])
        if norm.all():
            return (cross / norm[:, None]).max(axis=1)
        # A chord of zero length (the curve comes back): the distance to its end.
        dist = np.where(norm[:, None] > 0, cross / np.where(norm > 0, norm, 1)[:, None],
                        np.hypot(rel[..., 0], rel[..., 1]))
        return dist.max(axis=1)

    def refinements(self, tol, factor=4.0):
        # Bisection from five parameters per knot interval: an interval whose
        # curve strays more than tol from its chord (at 1/4, 1/2, 3/4) is
        # halved, down to MAX_DEPTH halvings. The intervals split at tol are
        # split at any smaller error too, so each finer discretisation starts
        # from the leaves of the previous one and evaluates only new points.
        p, t = self.degree, self.knots
        breaks = _unique(t[p : len(t) - p])
        u = _unique(np.concatenate([np.linspace(a, b, 5) for a, b in zip(breaks[:-1], breaks[1:])]))
        values = self._spline(u)
        kept_u, kept_p = [u], [values]
        a, b, pa, pb = u[:-1], u[1:], values[:-1], values[1:]
        dist, depth = self._deviation(a, b, pa, pb), np.zeros(len(a), dtype=np.int64)
        tu, cum = self._table
        while True:
            leaves = []
            while True:
                split = dist > tol
                leaves.append((a[~split], b[~split], pa[~split], pb[~split], dist[~split], depth[~split]))
                if not split.any():
                    break
                a, b, pa, pb, depth = a[split], b[split], pa[split], pb[split], depth[split] + 1
                mid = 0.5 * (a + b)
                bounded(sum(map(len, kept_u)) + len(mid), MAX_CURVE_POINTS, "points on a B-spline",
                        "raise options.chordal_error or smooth the B-spline")
                pmid = self._spline(mid)
                kept_u.append(mid)
                kept_p.append(pmid)
                a, b = np.concatenate((a, mid)), np.concatenate((mid, b))
                pa, pb, depth = np.concatenate((pa, pmid)), np.concatenate((pmid, pb)), np.concatenate((depth, depth))
                dist = np.where(depth < self.MAX_DEPTH, self._deviation(a, b, pa, pb), -np.inf)
            bounded(sum(map(len, kept_u)), MAX_CURVE_POINTS, "points on a B-spline",
                    "raise options.chordal_error or smooth the B-spline")
            u = np.concatenate(kept_u)
            order = np.argsort(u, kind="stable")
            u = u[order]
            yield np.concatenate(kept_p)[order], np.interp(u, tu, cum) / cum[-1]
            a, b, pa, pb, dist, depth = (np.concatenate(parts) for parts in zip(*leaves))
            tol /= factor

    def green(self):
        u, _ = self._table
        a, b = u[:-1], u[1:]
        half = 0.5 * (b - a)
        q = ((0.5 * (a + b))[:, None] + half[:, None] * _GL_X[None, :]).ravel()
        p, d = self._spline(q), self._spline.derivative()(q)
        integrand = (p[:, 0] * d[:, 1] - p[:, 1] * d[:, 0]).reshape(-1, len(_GL_X))
        return 0.5 * float(np.sum(half * (integrand @ _GL_W)))

    def moment_x(self):
        # Gauss-Legendre on every knot span, exact for y² x' of degree 3 p - 1.
        x_gl, w_gl = np.polynomial.legendre.leggauss(max(5, (3 * self.degree) // 2 + 1))
        u, _ = self._table
        a, b = u[:-1], u[1:]
        half = 0.5 * (b - a)
        q = ((0.5 * (a + b))[:, None] + half[:, None] * x_gl[None, :]).ravel()
        p, d = self._spline(q), self._spline.derivative()(q)
        integrand = (p[:, 1] * p[:, 1] * d[:, 0]).reshape(-1, len(x_gl))
        return -0.5 * float(np.sum(half * (integrand @ w_gl)))

    @property
    def ends(self):
        return self.control_points[0], self.control_points[-1]

    def reversed(self):
        t = self.knots
        return BSpline(self.degree, self.control_points[::-1], (t[0] + t[-1] - t)[::-1])

    def transformed(self, matrix, offset=(0.0, 0.0), tol=1e-3):
        m, b = _affine(matrix, offset)  # B-splines are affine invariant
        return BSpline(self.degree, self.control_points @ m.T + b, self.knots)

    def with_end_moved(self, at_end, point):
        cp = self.control_points.copy()
        cp[-1 if at_end else 0] = point
        return BSpline(self.degree, cp, self.knots)

    def to_json(self):
        return {
            "bspline": {
                "degree": int(self.degree),
                "control_points": self.control_points.tolist(),
                "knots": self.knots.tolist(),
            }
        }


@dataclass(frozen=True, eq=False)
class Chain(Curve):
    """Pieces joined end to start, each a :class:`Curve`.

    Examples
    --------
    >>> c = Chain((Polyline([[0, 0], [1, 0]]), Polyline([[1, 0], [1, 1]])))
    >>> c.length
    2.0
    >>> c.at_fractions(np.array([0.75])).tolist()
    [[1.0, 0.5]]
    """

    pieces: tuple
    kind = "chain"

    @cached_property
    def _bounds(self) -> np.ndarray:
        lengths = np.array([p.length for p in self.pieces])
        return np.concatenate(([0.0], np.cumsum(lengths))) / lengths.sum()

    @property
    def length(self):
        return float(sum(p.length for p in self.pieces))

    def at_fractions(self, s):
        s = np.clip(np.asarray(s, dtype=np.float64), 0, 1)
        b = self._bounds
        which = np.clip(np.searchsorted(b, s, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty((len(s), 2))
        for i, piece in enumerate(self.pieces):
            m = which == i
            if m.any():
                width = b[i + 1] - b[i]
                local = (s[m] - b[i]) / width if width > 0 else np.zeros(m.sum())
                out[m] = piece.at_fractions(local)
        return out

    def _join(self, parts: list[np.ndarray]) -> np.ndarray:
        return np.concatenate([parts[0]] + [q[1:] for q in parts[1:]])

    def discretise(self, tol):
        b = self._bounds
        pts, fr = [], []
        for i, piece in enumerate(self.pieces):
            q, s = piece.discretise(tol)
            pts.append(q)
            fr.append(b[i] + s * (b[i + 1] - b[i]))
        return self._join(pts), self._join(fr)

    def characteristic_points(self, tol):
        return self._join([p.characteristic_points(tol) for p in self.pieces])

    def refinements(self, tol, factor=4.0):
        b = self._bounds
        for parts in zip(*(piece.refinements(tol, factor) for piece in self.pieces)):
            yield self._join([q for q, _ in parts]), self._join([b[i] + s * (b[i + 1] - b[i]) for i, (_, s) in enumerate(parts)])

    def characteristic_refinements(self, tol, factor=4.0):
        for parts in zip(*(piece.characteristic_refinements(tol, factor) for piece in self.pieces)):
            yield self._join(list(parts))

    def green(self):
        return float(sum(p.green() for p in self.pieces))

    def moment_x(self):
        return float(sum(p.moment_x() for p in self.pieces))

    def to_json(self):
        return {"chain": [p.to_json() for p in self.pieces]}

    @cached_property
    def ends(self):
        # Once per chain: a chain nested n deep asks its first and its last piece, which may be one
        # and the same chain, so an uncached property did 2**n work.
        return self.pieces[0].ends[0], self.pieces[-1].ends[1]

    def reversed(self):
        return Chain(tuple(p.reversed() for p in self.pieces[::-1]))

    def transformed(self, matrix, offset=(0.0, 0.0), tol=1e-3):
        return Chain(tuple(p.transformed(matrix, offset, tol) for p in self.pieces))

    def with_end_moved(self, at_end, point):
        i = -1 if at_end else 0
        moved = self.pieces[i].with_end_moved(at_end, point)
        if moved is None:
            return None
        pieces = list(self.pieces)
        pieces[i] = moved
        return Chain(tuple(pieces))

    def simplified(self, tol):
        return Chain(tuple(p.simplified(tol) for p in self.pieces))

    @property
    def point_count(self):
        return sum(p.point_count for p in self.pieces)

    def parts(self):
        return tuple(q for p in self.pieces for q in p.parts())


_PROBES = np.array([0.25, 0.5, 0.75])  # where an interval's chordal error is measured


def _de_boor(t: np.ndarray, c: np.ndarray, k: int, i: np.ndarray, x: np.ndarray) -> np.ndarray:
    """De Boor's algorithm: the spline ``(t, c, k)`` at ``x`` ``(K,)``, in knot intervals ``i``, ``(K, 2)``."""
    d = c[i[:, None] + np.arange(-k, 1)]  # (K, k + 1, 2)
    for r in range(1, k + 1):
        j = i[:, None] + np.arange(r, k + 1)  # every j of this round at once, from the old values
        lo, hi = t[j - k], t[j + 1 - r]
        alpha = ((x[:, None] - lo) / (hi - lo))[..., None]
        d[:, r:] = (1.0 - alpha) * d[:, r - 1 : k] + alpha * d[:, r:]
    return d[:, k]


class _Spline:
    """A clamped B-spline ``(t, c, k)`` as polynomial pieces, evaluated in numpy.

    The same map as ``scipy.interpolate.BSpline(t, c, k)`` (to rounding),
    kept here so that reading and discretising a case does not import
    scipy.interpolate (most of a command's start-up time). Each knot
    interval holds the Taylor coefficients of its piece at its left knot
    (computed once by de Boor's algorithm); a call is a search and Horner's
    rule.

    Examples
    --------
    >>> s = _Spline(np.array([0.0, 0.0, 1.0, 1.0]), np.array([[0.0, 0.0], [2.0, 4.0]]), 1)
    >>> s(np.array([0.25])).tolist(), s.derivative()(np.array([0.5])).tolist()
    ([[0.5, 1.0]], [[2.0, 4.0]])
    """

    def __init__(self, t: np.ndarray, c: np.ndarray, k: int, pieces=None):
        self.t, self.c, self.k = t, c, k
        if pieces is None:
            pieces = _taylor_pieces(t, c, k)
        self._x0, self._coef = pieces  # (P,) left knots, (P, k + 1, 2) highest power first

    def __call__(self, x: np.ndarray) -> np.ndarray:
        """Points at parameters ``x`` ``(K,)``, ``(K, 2)``."""
        x = np.asarray(x, dtype=np.float64)
        i = np.searchsorted(self._x0, x, side="right")  # the piece is i - 1, the first one left of x0[0]
        i = np.maximum(i - 1, 0, out=i)
        dx = (x - self._x0[i])[:, None]
        coef = self._coef[i]
        out = coef[:, 0]
        for m in range(1, self.k + 1):
            out = out * dx + coef[:, m]
        return out

    def derivative(self) -> _Spline:
        """The derivative, a spline of degree ``k - 1``."""
        t, c, k = self.t, self.c, self.k
        span = t[k + 1 : len(c) + k] - t[1 : len(c)]
        dc = k * np.diff(c, axis=0) / np.where(span > 0, span, 1.0)[:, None]
        powers = np.arange(k, 0, -1)[None, :, None]
        return _Spline(t[1:-1], dc, k - 1, (self._x0, self._coef[:, :k] * powers))


def _taylor_pieces(t: np.ndarray, c: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Left knot and Taylor coefficients (highest power first) of each piece of ``(t, c, k)``."""
    i = np.arange(k, len(c))
    x0 = t[i]
    coef = np.empty((len(i), k + 1, 2))
    tm, cm, fact = t, c, 1.0
    for m in range(k + 1):  # m-th derivative: knots t[m:-m], degree k - m, interval i - m
        with np.errstate(invalid="ignore", divide="ignore"):  # empty pieces (repeated knots) are never used
            coef[:, k - m] = _de_boor(tm, cm, k - m, i - m, x0) / fact
        if m < k:
            span = tm[k - m + 1 : len(cm) + k - m] - tm[1 : len(cm)]
            cm = (k - m) * np.diff(cm, axis=0) / np.where(span > 0, span, 1.0)[:, None]
            tm, fact = tm[1:-1], fact * (m + 1)
    return x0, coef


# --------------------------------------------------------------------------
# Reading CURVE objects


def _number(value, field: str) -> float:
    """A finite number within the coordinate range (:func:`~sectiondeform.checks.number`)."""
    return number(value, field, low=-COORDINATE_LIMIT, high=COORDINATE_LIMIT)


def curve_from_json(obj, field: str = "curve", join_tol: float | None = None) -> Curve:
    """Build a :class:`Curve` from a CURVE object of the case format.

    Parameters
    ----------
    obj : dict
        One of ``{"polyline": ...}``, ``{"bspline": ...}``, ``{"arc": ...}``,
        ``{"chain": [...]}``.
    field : str
        Where the object sits in the case, for error messages (``"upper"``).
    join_tol : float, optional
        Largest gap allowed between the pieces of a chain, in case units;
        by default 1e-6 of the chain's size.

    Returns
    -------
    Curve

    Raises
    ------
    CaseError
        Naming the field at fault: unknown kind, missing key, bad numbers,
        degenerate curve, chain pieces that do not join.

    Examples
    --------
    >>> curve_from_json({"polyline": [[0, 0], [1, 0]]}, "lower").length
    1.0
    >>> curve_from_json({"circle": {}}, "lower")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: lower: unknown curve kind 'circle'; use one of polyline, bspline, arc, chain
    """
    kinds = ("polyline", "bspline", "arc", "chain")
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected a curve object such as {{\"polyline\": [...]}}, got {type(obj).__name__}")
    if len(obj) != 1:
        keys = ", ".join(sorted(obj)) or "none"
        raise CaseError(field, f"a curve object has exactly one key ({', '.join(kinds)}), got {keys}")
    (kind, body), = obj.items()
    sub = f"{field}.{kind}"
    if kind == "polyline":
        pts = as_points(body, sub, min_count=2)
        curve = Polyline(pts)
    elif kind == "arc":
        if not isinstance(body, dict):
            raise CaseError(sub, "expected an object with center, radius, start_deg, end_deg")
        for key in ("center", "radius", "start_deg", "end_deg"):
            if key not in body:
                raise CaseError(f"{sub}.{key}", "missing")
        center = as_points([body["center"]], f"{sub}.center")[0]
        radius = _number(body["radius"], f"{sub}.radius")
        if radius <= 0:
            raise CaseError(f"{sub}.radius", f"must be positive, got {radius}")
        a0 = _number(body["start_deg"], f"{sub}.start_deg")
        a1 = _number(body["end_deg"], f"{sub}.end_deg")
        if a0 == a1:
            raise CaseError(f"{sub}.end_deg", "equals start_deg: the arc has zero length")
        if abs(a1 - a0) > 360:
            raise CaseError(f"{sub}.end_deg", f"the arc sweeps {abs(a1 - a0)} degrees; at most 360")
        curve = Arc(center, radius, a0, a1)
    elif kind == "bspline":
        if not isinstance(body, dict):
            raise CaseError(sub, "expected an object with degree, control_points and optional knots")
        if "degree" not in body:
            raise CaseError(f"{sub}.degree", "missing")
        deg = body["degree"]
        if isinstance(deg, bool) or not isinstance(deg, int) or deg < 1:
            raise CaseError(f"{sub}.degree", f"must be a whole number >= 1, got {deg!r}")
        if "control_points" not in body:
            raise CaseError(f"{sub}.control_points", "missing")
        cp = as_points(body["control_points"], f"{sub}.control_points", min_count=deg + 1)
        knots = body.get("knots")
        if knots is not None:
            if not isinstance(knots, (list, tuple, np.ndarray)):
                raise CaseError(f"{sub}.knots", f"expected a list of numbers, got {type(knots).__name__}")
            t = np.array([_number(v.item() if isinstance(v, np.generic) else v, f"{sub}.knots[{i}]")
                          for i, v in enumerate(knots)], dtype=np.float64)
            n_exp = len(cp) + deg + 1
            if t.ndim != 1 or len(t) != n_exp:
                raise CaseError(f"{sub}.knots", f"expected {n_exp} knots (control points + degree + 1), got {t.size}")
            if not np.isfinite(t).all():
                raise CaseError(f"{sub}.knots", "knots must be finite numbers")
            if np.any(np.diff(t) < 0):
                raise CaseError(f"{sub}.knots", "knots must be non-decreasing")
            if np.ptp(t[: deg + 1]) or np.ptp(t[-deg - 1 :]):
                raise CaseError(f"{sub}.knots", f"the spline must be clamped: the first and last {deg + 1} knots equal")
            if t[-1] <= t[0]:
                raise CaseError(f"{sub}.knots", "the knot vector spans no interval")
        else:
            t = None
        curve = BSpline(deg, cp, t)
    elif kind == "chain":
        if not isinstance(body, list) or not body:
            raise CaseError(sub, "expected a non-empty list of curve objects")
        pieces = tuple(curve_from_json(p, f"{sub}[{i}]", join_tol) for i, p in enumerate(body))
        pts = np.concatenate([np.vstack((p.start, p.end)) for p in pieces])
        size = float(np.hypot(*np.ptp(pts, axis=0))) or 1.0
        tol = join_tol if join_tol is not None else 1e-6 * size
        for i in range(1, len(pieces)):
            gap = float(np.hypot(*(pieces[i].start - pieces[i - 1].end)))
            if gap > tol:
                raise CaseError(
                    f"{sub}[{i}]",
                    f"starts {gap:.6g} away from where {sub}[{i - 1}] ends; each piece must start where the one before ends",
                )
        curve = Chain(pieces)
    else:
        raise CaseError(field, f"unknown curve kind {kind!r}; use one of {', '.join(kinds)}")
    if not curve.length > 0:
        raise CaseError(sub, "the curve has zero length")
    return curve
