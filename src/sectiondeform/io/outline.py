"""From the pieces of a drawing (DXF or SVG) to a body's curves and the target: options, layers, contours.

Two ways to name the section's curves:

*Layers* (the default): the pieces tagged ``LOWER`` form the lower curve,
``UPPER`` the upper one, ``TARGET`` the target (DXF layer names, SVG ids or
classes; other names with ``layers={"lower": ..., ...}``, matched without
regard to case). Each is chained by its end points. The lower curve runs
A -> B so that the section lies on its left (the contour lower + upper is
counter-clockwise), the upper one from B back to A; the target runs the
same general way as A -> B (its chord points along B - A). A DXF or SVG
written by this package stores A and A' and restores them exactly.

*One closed contour* (``split=(A, B)``): the pieces tagged ``CONTOUR`` (or,
if there is no such name, every piece that is not on the target) must form
one closed loop. It is turned into a polyline within the chordal error; A
and B are the points of the loop nearest to the two points given (inserted
as vertices; a point farther than ``split_tol`` from the loop is an error); the lower curve is the way round from A to B named by
``lower_side`` (``"shorter"``, the default, ``"longer"``, ``"ccw"`` or
``"cw"`` around the section) and the upper curve the rest, from B to A.

The target is the ``TARGET`` pieces if there are any, else
``target_arc=S``: a circular arc as long as the lower curve, tangent to the
chord AB at its midpoint; S is its sagitta (depth over its own chord):
S > 0 bends its ends towards the section, so the section's base becomes
concave, as in the paper's example; S < 0 bends them away; S = 0 is the
chord's direction, stretched to the lower curve's length. ``|S|`` must be
below length / π (a half circle).

Messy drawings: ``bbox`` keeps only the pieces with both ends inside it;
``snap`` snaps free ends closer than it; ``close_gap`` closes gaps up to it
with a straight piece; ``simplify`` simplifies polylines within that
distance (Douglas-Peucker, shapely; A and B kept). Every such change is
reported. All lengths are in drawing units; ``units`` converts the case
to other units at the end. The options are a :class:`DrawingOptions`.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from dataclasses import dataclass, fields
from pathlib import Path
from types import MappingProxyType

import numpy as np

from ..curves import Arc, Curve, Polyline, polygon_area
from ..errors import CaseError
from ..laws import Law
from .chaining import fmt_point, one_chain
from .pieces import Piece, pin_ends
from .units import mm_per_unit

__all__ = [
    "DrawingOptions", "Context", "make_target_arc", "inside_bbox", "curves_from_layers", "curves_from_contour",
    "orient_target", "find_target", "say", "unused_pieces", "ROLES", "SIDES", "SPLIT_FRACTION", "JSON_KEYS",
]

ROLES = ("lower", "upper", "target", "contour")
SIDES = ("shorter", "longer", "ccw", "cw")
# Largest distance of a split point from the contour, as a fraction of the contour's diagonal.
SPLIT_FRACTION = 0.02
# The options a case JSON's "drawing" object may give (the others come from the case itself).
JSON_KEYS = ("layers", "split", "split_tol", "lower_side", "target_arc", "bbox", "snap", "close_gap", "join_tol",
             "simplify", "units")


def say(report, line: str) -> None:
    """Append ``line`` to ``report`` unless it is None."""
    if report is not None:
        report.append(line)


def _length(value, name: str, allow_none: bool = True) -> float | None:
    """A finite length >= 0 (or None), else a one-line error naming ``name``."""
    if value is None and allow_none:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
        raise CaseError(name, f"must be a finite number >= 0, got {value!r}")
    return float(value)


def _points(value, name: str, count: int) -> tuple:
    try:
        arr = np.array(value, dtype=np.float64).reshape(count, 2)
    except (TypeError, ValueError, OverflowError):
        raise CaseError(name, f"expected {count} points [x, y], got {value!r}") from None
    if not np.isfinite(arr).all():
        raise CaseError(name, f"coordinates must be finite numbers, got {value!r}")
    return tuple(tuple(p) for p in arr.tolist())


@dataclass(frozen=True)
class DrawingOptions:
    """How the pieces of a drawing become a case (see the module docstring).

    Every length is in drawing units. Unknown keys are refused by
    :meth:`from_mapping`, naming the nearest known one.

    Attributes
    ----------
    layers : Mapping, optional
        Role (``lower``, ``upper``, ``target``, ``contour``) -> name.
    split : ((2,), (2,)), optional
        Points near A and B on a single closed contour.
    split_tol : float, optional
        Largest distance of a split point from the contour; default
        :data:`SPLIT_FRACTION` of the contour's diagonal.
    lower_side : str
        ``"shorter"`` (default), ``"longer"``, ``"ccw"`` or ``"cw"``.
    target_arc : float, optional
        Sagitta of the built-in target arc.
    bbox : (4,) float, optional
        ``xmin, ymin, xmax, ymax``: keep pieces with both ends inside.
    snap, close_gap : float
        Gap snapping and closing distances (0: never).
    join_tol : float, optional
        End points closer than this are one point; default 1e-6 of the
        selection's diagonal.
    simplify : float, optional
        Simplify polylines within this distance.
    chordal_error : float, optional
        Chordal error of the polylines made from curves; also written to
        the case's options.
    units : str, optional
        Convert the case to these units (``"mm"``, ``"in"``...).
    law : Law, optional
        Overrides the law stored in the drawing.
    name : str, optional
    target : Curve, optional
        Target given elsewhere (a case JSON), drawing units.
    """

    layers: Mapping | None = None
    split: tuple | None = None
    split_tol: float | None = None
    lower_side: str = "shorter"
    target_arc: float | None = None
    bbox: tuple | None = None
    snap: float = 0.0
    close_gap: float = 0.0
    join_tol: float | None = None
    simplify: float | None = None
    chordal_error: float | None = None
    units: str | None = None
    law: Law | None = None
    name: str | None = None
    target: Curve | None = None

    def __post_init__(self):
        set_ = lambda key, value: object.__setattr__(self, key, value)  # noqa: E731 - frozen
        if self.layers is not None:
            if not isinstance(self.layers, Mapping):
                raise CaseError("layers", f"expected a mapping of role to name, got {type(self.layers).__name__}")
            for role, value in self.layers.items():
                if role not in ROLES:
                    raise CaseError("layers", f"unknown role {role!r}; use {', '.join(ROLES)}")
                if not isinstance(value, str) or not value:
                    raise CaseError(f"layers.{role}", f"expected a name, got {value!r}")
            set_("layers", MappingProxyType(dict(self.layers)))
        if self.split is not None:
            set_("split", _points(self.split, "split", 2))
        if self.bbox is not None:
            box = _points(self.bbox, "bbox", 2)
            (x0, y0), (x1, y1) = box
            if not (x0 < x1 and y0 < y1):
                raise CaseError("bbox", f"expected xmin, ymin, xmax, ymax with xmin < xmax and ymin < ymax, got {list(self.bbox)}")
            set_("bbox", (x0, y0, x1, y1))
        if self.lower_side not in SIDES:
            raise CaseError("lower_side", f"unknown side {self.lower_side!r}; use one of {', '.join(SIDES)}")
        for key in ("snap", "close_gap"):
            set_(key, _length(getattr(self, key) or 0.0, key, allow_none=False))
        for key in ("split_tol", "join_tol", "simplify", "chordal_error"):
            set_(key, _length(getattr(self, key), key))
        if self.target_arc is not None:
            t = self.target_arc
            if isinstance(t, bool) or not isinstance(t, (int, float)) or not math.isfinite(t):
                raise CaseError("target_arc", f"must be a finite number, got {t!r}")
            set_("target_arc", float(t))
        if self.units is not None:
            mm_per_unit(self.units, "units")

    @classmethod
    def from_mapping(cls, mapping: Mapping, field: str = "", allowed=None) -> DrawingOptions:
        """Options from a mapping of names to values; an unknown name is an error naming the nearest one.

        Parameters
        ----------
        mapping : Mapping
            Keys among the attributes of this class; None values are left out.
        field : str
            Where the mapping sits (``"drawing"`` in a case JSON), for messages.
        allowed : sequence of str, optional
            The keys accepted there; default every attribute.

        Raises
        ------
        CaseError
            An unknown key, or a value out of range.

        Examples
        --------
        >>> DrawingOptions.from_mapping({"snapp": 0.1})
        Traceback (most recent call last):
        ...
        sectiondeform.errors.CaseError: snapp: unknown drawing option; did you mean snap?
        """
        known = tuple(allowed or (f.name for f in fields(cls)))
        for key in mapping:
            if key not in known:
                close = difflib.get_close_matches(str(key), known, n=1)
                hint = f"did you mean {close[0]}?" if close else f"use one of {', '.join(known)}"
                raise CaseError(f"{field}.{key}" if field else str(key), f"unknown drawing option; {hint}")
        return cls(**{k: v for k, v in mapping.items() if v is not None})


def make_target_arc(a, b, length: float, sagitta: float, section_side: float) -> Curve:
    """The built-in target: an arc as long as the lower curve, tangent to AB at its midpoint.

    Parameters
    ----------
    a, b : (2,) array_like
        Ends A and B of the lower curve, units.
    length : float
        Length of the lower curve (and of the arc), units.
    sagitta : float
        Depth of the arc over its own chord, units; > 0 bends the ends
        towards the section, < 0 away, 0 gives a straight target.
    section_side : float
        +1 if the section lies left of A -> B, -1 if right.

    Returns
    -------
    Curve
        An :class:`~sectiondeform.curves.Arc` from A' (A's side) to B', or
        a two-point polyline when ``sagitta`` is 0.

    Raises
    ------
    CaseError
        If A = B, or ``|sagitta|`` >= length / π.

    Examples
    --------
    >>> t = make_target_arc([0, 0], [110, 0], 110.0, 12.9, +1)
    >>> round(t.length, 9), np.round(t.at_fractions(np.array([0.5])), 9).tolist()
    (110.0, [[55.0, 0.0]])
    >>> bool(t.start[1] > 0)
    True
    """
    from scipy.optimize import brentq

    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    chord = b - a
    c = math.hypot(*chord)
    if c == 0:
        raise CaseError("target_arc", "A and B coincide; the lower curve has no chord")
    u = chord / c
    mid = 0.5 * (a + b)
    if sagitta == 0:
        return Polyline(np.vstack((mid - 0.5 * length * u, mid + 0.5 * length * u)))
    ratio = abs(sagitta) / length
    if ratio >= 1.0 / math.pi:
        raise CaseError("target_arc", f"the sagitta {sagitta} is too deep for an arc of length {length:.6g}; keep it below {length / math.pi:.6g} (a half circle)")
    theta = brentq(lambda t: (1.0 - math.cos(t)) / (2.0 * t) - ratio, 1e-12, math.pi)
    radius = length / (2.0 * theta)
    towards = section_side * np.array([-u[1], u[0]])
    center = mid + math.copysign(1.0, sagitta) * radius * towards
    phi = math.degrees(math.atan2(mid[1] - center[1], mid[0] - center[0]))
    half = math.degrees(theta)
    arc = Arc(center, radius, phi - half, phi + half)
    if np.dot(arc.end - arc.start, u) < 0:
        arc = arc.reversed()
    return arc


def _nearest_on_ring(ring: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, int, float]:
    """``ring`` ((N, 2), closed implicitly) with the point nearest ``p`` inserted; its index and distance."""
    s0, s1 = ring, np.roll(ring, -1, axis=0)
    d = s1 - s0
    dd = np.einsum("ij,ij->i", d, d)
    t = np.clip(np.einsum("ij,ij->i", p - s0, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    proj = s0 + t[:, None] * d
    dist = np.hypot(*(proj - p).T)
    i = int(np.argmin(dist))
    q = proj[i]
    if np.array_equal(q, s0[i]):
        return ring, i, float(dist[i])
    if np.array_equal(q, s1[i]):
        return ring, (i + 1) % len(ring), float(dist[i])
    return np.insert(ring, i + 1, q, axis=0), i + 1, float(dist[i])


@dataclass(frozen=True)
class Context:
    """What the steps of :func:`case_from_drawing` share: names and tolerances."""

    what: str  # "layer" (DXF) or "id/class" (SVG)
    roles: Mapping  # role -> name as given
    tol: float  # join tolerance
    chord: float  # chordal error of polylines made from curves
    diag: float  # diagonal of the pieces' ends
    options: DrawingOptions

    def where(self, role: str) -> str:
        return f"{self.what} {self.roles[role]}"

    def has(self, pieces, role: str) -> bool:
        key = self.roles[role].upper()
        return any(key in p.tags for p in pieces)

    def select(self, pieces, role: str) -> list[Piece]:
        key = self.roles[role].upper()
        chosen = [p for p in pieces if key in p.tags]
        bad = [p for p in chosen if p.curve is None]
        if bad:
            raise CaseError(self.where(role), f"unsupported entity {bad[0].source}; use LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE, SPLINE or ELLIPSE (paths, lines, polylines, polygons, circles in SVG)")
        return chosen

    def chain(self, pieces, where: str, closed: bool, report):
        o = self.options
        path, rep = one_chain(pieces, where, self.tol, o.snap, o.close_gap, closed=closed)
        for line in rep.lines(where):
            say(report, line)
        return path.curve


def inside_bbox(pieces, bbox, report) -> list[Piece]:
    """The pieces with both ends inside ``bbox`` (pieces without a curve are kept, to be refused if used)."""
    x0, y0, x1, y1 = bbox

    def inside(p):
        e = np.vstack(p.curve.ends)
        return np.all((e[:, 0] >= x0) & (e[:, 0] <= x1) & (e[:, 1] >= y0) & (e[:, 1] <= y1))

    kept = [p for p in pieces if p.curve is None or inside(p)]
    say(report, f"bbox: kept {sum(p.curve is not None for p in kept)} of {sum(p.curve is not None for p in pieces)} pieces")
    return kept


def _split_ring(ring: np.ndarray, pa: np.ndarray, pb: np.ndarray, lower_side: str, limit: float, where: str):
    """Lower and upper point runs of a closed ring split at the points nearest ``pa`` and ``pb``.

    Returns ``(lower, upper, lower_length)``; the lower run goes A -> B, the
    upper one B -> A. A split point farther than ``limit`` from the ring is
    an error naming the distance.
    """
    ring, ia, da = _nearest_on_ring(ring, pa)
    ring = np.roll(ring, -ia, axis=0)
    ring, ib, db = _nearest_on_ring(ring, pb)
    for label, p, d in (("A", pa, da), ("B", pb, db)):
        if d > limit:
            raise CaseError("split", f"{label} {fmt_point(p)} is {d:.4g} from the {where}, more than option split_tol ({limit:.4g}); "
                                     "give a point on the contour")
    if ib == 0:
        raise CaseError("split", f"A {fmt_point(pa)} and B {fmt_point(pb)} fall on the same contour point")
    forward = ring[: ib + 1]
    backward = np.vstack((ring[ib:], ring[:1]))[::-1]
    ccw = polygon_area(ring) > 0
    lens = [float(np.hypot(*np.diff(w, axis=0).T).sum()) for w in (forward, backward)]
    pick = {"shorter": int(lens[1] < lens[0]), "longer": int(lens[1] >= lens[0]),
            "ccw": 0 if ccw else 1, "cw": 1 if ccw else 0}[lower_side]
    return (forward, backward)[pick], (backward, forward)[pick][::-1], lens[pick]


def curves_from_contour(pieces, ctx: Context, report) -> tuple[Curve, Curve]:
    """Lower and upper curves from one closed contour split at ``options.split``."""
    if ctx.has(pieces, "contour"):
        where = ctx.where("contour")
        chosen = ctx.select(pieces, "contour")
    else:
        where = "contour"
        target_key = ctx.roles["target"].upper()
        chosen = [p for p in pieces if target_key not in p.tags]
        bad = [p for p in chosen if p.curve is None]
        if bad:
            raise CaseError(where, f"unsupported entity {bad[0].source}; restrict the contour with option layers (the contour's layer) or option bbox")
    ring = ctx.chain(chosen, where, True, report).characteristic_points(ctx.chord)[:-1]
    pa, pb = (np.asarray(p, dtype=np.float64) for p in ctx.options.split)
    size = float(np.hypot(*np.ptp(ring, axis=0))) or 1.0
    limit = ctx.options.split_tol if ctx.options.split_tol is not None else SPLIT_FRACTION * size
    lower_pts, upper_pts, length = _split_ring(ring, pa, pb, ctx.options.lower_side, limit, where)
    say(report, f"{where}: A {fmt_point(lower_pts[0])}, B {fmt_point(lower_pts[-1])}; lower {len(lower_pts)} points "
                 f"(length {length:.6g}), upper {len(upper_pts)} points")
    return Polyline(lower_pts), Polyline(upper_pts)


def _fit_upper(lower: Curve, upper: Curve) -> tuple[Curve, float]:
    """``upper`` turned to run from the lower curve's end back to its start; the gap left."""
    a, b = lower.ends
    s, e = upper.ends
    same = np.hypot(*(s - b)) + np.hypot(*(e - a))
    swap = np.hypot(*(e - b)) + np.hypot(*(s - a))
    return (upper, same) if same <= swap else (upper.reversed(), swap)


def curves_from_layers(pieces, ctx: Context, meta: dict, path: Path, report) -> tuple[Curve, Curve]:
    """Lower and upper curves from their own layers (ids/classes), oriented counter-clockwise."""
    missing = [ctx.roles[r] for r in ("lower", "upper") if not ctx.has(pieces, r)]
    if missing:
        found = sorted({t for p in pieces for t in p.tags if t})
        raise CaseError(
            str(path),
            f"{ctx.what} {' and '.join(repr(m) for m in missing)} not found (the drawing has: {', '.join(found) or 'none'}); "
            "name the lower and upper layers (option layers), or give the split points (option split) for one closed contour",
        )
    lower = ctx.chain(ctx.select(pieces, "lower"), ctx.where("lower"), False, report)
    upper = ctx.chain(ctx.select(pieces, "upper"), ctx.where("upper"), False, report)
    upper, gap = _fit_upper(lower, upper)
    if gap > max(2 * ctx.tol, 2 * ctx.options.snap):
        a, b = lower.ends
        s, e = upper.ends
        where_gap = a if np.hypot(*(e - a)) > np.hypot(*(s - b)) else b
        raise CaseError(
            ctx.where("upper"),
            f"does not meet the ends of {ctx.where('lower')}: a gap of {gap:.4g} near {fmt_point(where_gap)}; "
            "lower and upper must together make one closed contour",
        )
    hint = meta.get("lower_start")
    if hint is not None:
        a, b = lower.ends
        h = np.asarray(hint, dtype=np.float64)
        flip = np.hypot(*(b - h)) < np.hypot(*(a - h))
    else:
        ring = np.vstack((lower.characteristic_points(ctx.chord), upper.characteristic_points(ctx.chord)[1:-1]))
        flip = polygon_area(ring) < 0
    if flip:
        lower, upper = lower.reversed(), upper.reversed()
    a, b = lower.ends
    return lower, pin_ends(upper, b, a, ctx.diag)


def unused_pieces(pieces, ctx: Context) -> list[Piece]:
    """The pieces of a one-body drawing no curve of the case comes from (the target's too when ``target_arc`` replaces it)."""
    o = ctx.options
    target = ctx.roles["target"].upper()
    drawn_target = ctx.has(pieces, "target") and o.target_arc is None
    if o.split is not None and not ctx.has(pieces, "contour"):
        return [] if drawn_target else [p for p in pieces if target in p.tags]
    used = {ctx.roles[r].upper() for r in (("contour",) if o.split is not None else ("lower", "upper"))}
    if drawn_target:
        used.add(target)
    return [p for p in pieces if not p.tags & used]


def orient_target(target: Curve, a, b, hint) -> Curve:
    """``target`` running the same general way as A -> B, or from the stored start point ``hint``."""
    s, e = target.ends
    if hint is not None:
        h = np.asarray(hint, dtype=np.float64)
        flip = np.hypot(*(e - h)) < np.hypot(*(s - h))
    else:
        flip = np.dot(e - s, np.asarray(b) - np.asarray(a)) < 0
    return target.reversed() if flip else target


def find_target(pieces, support: Curve, curves, ctx: Context, meta: dict, path: Path, report) -> Curve:
    """The target: drawn, the built-in arc (as long as the support), or given; else an error saying how to give one.

    ``curves``: the bodies' curves, which say on which side of the support the bodies lie.
    """
    o = ctx.options
    a, b = support.ends
    if ctx.has(pieces, "target") and o.target_arc is None:
        drawn = ctx.chain(ctx.select(pieces, "target"), ctx.where("target"), False, None)
        return orient_target(drawn, a, b, meta.get("target_start"))
    if o.target_arc is not None:
        inner = np.vstack([c.characteristic_points(ctx.chord) for c in curves])
        u = b - a
        side = 1.0 if (u[0] * (inner[:, 1].mean() - a[1]) - u[1] * (inner[:, 0].mean() - a[0])) >= 0 else -1.0
        say(report, f"target: arc of length {support.length:.6g}, sagitta {o.target_arc:g}")
        return make_target_arc(a, b, support.length, o.target_arc, side)
    if o.target is not None:
        return o.target
    raise CaseError(
        str(path),
        f"no target: draw it on {ctx.where('target')!r}, give option target_arc (an arc as long as the support), "
        "or a target in the case JSON",
    )
