"""From the pieces of a drawing (DXF or SVG) to a case.

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
as vertices); the lower curve is the way round from A to B named by
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
to other units at the end.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from ..case import Case, case_from_dict, read_json
from ..curves import Arc, Chain, Curve, Polyline, curve_from_json
from ..errors import CaseError
from ..laws import AreaRatio, law_from_json
from .chaining import fmt_point, one_chain
from .pieces import curve_ends, curve_points, pin_ends, reverse_curve, transform_curve

__all__ = [
    "case_from_drawing",
    "make_target_arc",
    "read_json_case",
    "add_input_args",
    "input_options",
    "ROLES",
    "MM_PER_UNIT",
]

ROLES = ("lower", "upper", "target", "contour")
SIDES = ("shorter", "longer", "ccw", "cw")
MM_PER_UNIT = {
    "mm": 1.0, "cm": 10.0, "dm": 100.0, "m": 1000.0, "km": 1e6, "um": 1e-3, "nm": 1e-6,
    "in": 25.4, "ft": 304.8, "yd": 914.4, "mil": 0.0254, "uin": 25.4e-6, "pt": 25.4 / 72, "pc": 25.4 / 6,
    "px": 25.4 / 96,
}


def _say(report, line: str) -> None:
    if report is not None:
        report.append(line)


def _signed_area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


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
        raise CaseError("--target-arc", "A and B coincide; the lower curve has no chord")
    u = chord / c
    mid = 0.5 * (a + b)
    if sagitta == 0:
        return Polyline(np.vstack((mid - 0.5 * length * u, mid + 0.5 * length * u)))
    ratio = abs(sagitta) / length
    if ratio >= 1.0 / math.pi:
        raise CaseError("--target-arc", f"the sagitta {sagitta} is too deep for an arc of length {length:.6g}; keep it below {length / math.pi:.6g} (a half circle)")
    theta = brentq(lambda t: (1.0 - math.cos(t)) / (2.0 * t) - ratio, 1e-12, math.pi)
    radius = length / (2.0 * theta)
    towards = section_side * np.array([-u[1], u[0]])
    center = mid + math.copysign(1.0, sagitta) * radius * towards
    phi = math.degrees(math.atan2(mid[1] - center[1], mid[0] - center[0]))
    half = math.degrees(theta)
    arc = Arc(center, radius, phi - half, phi + half)
    if np.dot(arc.end - arc.start, u) < 0:
        arc = reverse_curve(arc)
    return arc


def _nearest_on_ring(ring: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, int]:
    """``ring`` ((N, 2), closed implicitly) with the point nearest ``p`` inserted; its index."""
    s0, s1 = ring, np.roll(ring, -1, axis=0)
    d = s1 - s0
    dd = np.einsum("ij,ij->i", d, d)
    t = np.clip(np.einsum("ij,ij->i", p - s0, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    proj = s0 + t[:, None] * d
    i = int(np.argmin(np.hypot(*(proj - p).T)))
    q = proj[i]
    if np.array_equal(q, s0[i]):
        return ring, i
    if np.array_equal(q, s1[i]):
        return ring, (i + 1) % len(ring)
    return np.insert(ring, i + 1, q, axis=0), i + 1


def _simplify(curve: Curve, tol: float) -> Curve:
    """Polylines of ``curve`` simplified within ``tol`` (ends kept)."""
    import shapely

    if isinstance(curve, Chain):
        parts = [_simplify(p, tol) for p in curve.pieces]
        return Chain(tuple(parts))
    if isinstance(curve, Polyline) and len(curve.vertices) > 2:
        line = shapely.simplify(shapely.LineString(curve.vertices), tol, preserve_topology=True)
        return Polyline(np.asarray(line.coords, dtype=np.float64)[:, :2])
    return curve


def _count(curve: Curve) -> int:
    if isinstance(curve, Chain):
        return sum(_count(p) for p in curve.pieces)
    return len(curve.vertices) if isinstance(curve, Polyline) else 1


def _orient_target(target: Curve, a, b, hint) -> Curve:
    s, e = curve_ends(target)
    if hint is not None:
        h = np.asarray(hint, dtype=np.float64)
        flip = np.hypot(*(e - h)) < np.hypot(*(s - h))
    else:
        flip = np.dot(e - s, np.asarray(b) - np.asarray(a)) < 0
    return reverse_curve(target) if flip else target


def case_from_drawing(drawing, *, layers=None, split=None, lower_side="shorter", target_arc=None, bbox=None,
                      snap=0.0, close_gap=0.0, join_tol=None, simplify=None, chordal_error=None, units=None,
                      law=None, name=None, target=None, report=None, **_ignored) -> Case:
    """Build a case from the pieces of a drawing (see the module docstring).

    Parameters
    ----------
    drawing : Drawing
        From :func:`sectiondeform.io.dxf.read_drawing` or
        :func:`sectiondeform.io.svg.read_drawing`.
    layers : dict, optional
        Role (``lower``, ``upper``, ``target``, ``contour``) -> name.
    split : ((2,), (2,)), optional
        Points near A and B on a single closed contour, drawing units.
    lower_side : str
        ``"shorter"``, ``"longer"``, ``"ccw"`` or ``"cw"``.
    target_arc : float, optional
        Sagitta of the built-in target arc, drawing units.
    bbox : (4,) float, optional
        ``xmin, ymin, xmax, ymax``: keep pieces with both ends inside.
    snap, close_gap : float
        Gap snapping and closing distances, drawing units (0: never).
    join_tol : float, optional
        End points closer than this are one point; default 1e-6 of the
        selection's diagonal.
    simplify : float, optional
        Simplify polylines within this distance, drawing units.
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
    report : list, optional
        Lines saying what was done (pieces, snapped gaps...) are appended.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        A missing layer, a gap, a branch, an unsupported entity, no law,
        no target; each names where.
    """
    meta = dict(drawing.meta or {})
    snap, close_gap = float(snap or 0.0), float(close_gap or 0.0)
    roles = {"lower": "LOWER", "upper": "UPPER", "target": "TARGET", "contour": "CONTOUR"}
    for role, value in (layers or {}).items():
        if role not in ROLES:
            raise CaseError("--layers", f"unknown role {role!r}; use {', '.join(ROLES)}")
        roles[role] = str(value)
    keys = {r: v.upper() for r, v in roles.items()}
    pieces = list(drawing.pieces)
    if bbox is not None:
        x0, y0, x1, y1 = bbox
        inside = []
        for p in pieces:
            if p.curve is None:
                inside.append(p)
                continue
            e = np.vstack(curve_ends(p.curve))
            if np.all((e[:, 0] >= x0) & (e[:, 0] <= x1) & (e[:, 1] >= y0) & (e[:, 1] <= y1)):
                inside.append(p)
        _say(report, f"bbox: kept {sum(p.curve is not None for p in inside)} of {sum(p.curve is not None for p in pieces)} pieces")
        pieces = inside
    found = sorted({t for p in pieces for t in p.tags if t})
    if getattr(drawing, "unitless", False):
        _say(report, f"the drawing declares no units ($INSUNITS): taken as {drawing.units}")

    def select(role: str, where: str):
        chosen = [p for p in pieces if keys[role] in p.tags]
        bad = [p for p in chosen if p.curve is None]
        if bad:
            raise CaseError(where, f"unsupported entity {bad[0].source}; use LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE, SPLINE or ELLIPSE (paths, lines, polylines, polygons, circles in SVG)")
        return chosen

    has_target = any(keys["target"] in p.tags for p in pieces)
    curves = [p for p in pieces if p.curve is not None]
    if not curves:
        raise CaseError(str(drawing.path), "the drawing has no curves" + (" inside the bbox" if bbox is not None else ""))
    ends = np.concatenate([np.vstack(curve_ends(p.curve)) for p in curves])
    diag = float(np.hypot(*np.ptp(ends, axis=0))) or 1.0
    tol = join_tol if join_tol is not None else 1e-6 * diag
    chord = chordal_error or 1e-4 * diag
    what = "layer" if drawing.path.suffix.lower() == ".dxf" else "id/class"

    if split is not None:
        if any(keys["contour"] in p.tags for p in pieces):
            chosen, where = select("contour", f"{what} {roles['contour']}"), f"{what} {roles['contour']}"
        else:
            where = "contour"
            chosen = [p for p in pieces if keys["target"] not in p.tags]
            bad = [p for p in chosen if p.curve is None]
            if bad:
                raise CaseError(where, f"unsupported entity {bad[0].source}; restrict the contour with --layers contour=NAME or --bbox")
        path, rep = one_chain(chosen, where, tol, snap, close_gap, closed=True)
        for line in rep.lines(where):
            _say(report, line)
        ring = curve_points(path.curve, chord)[:-1]
        if lower_side not in SIDES:
            raise CaseError("--lower-side", f"unknown side {lower_side!r}; use one of {', '.join(SIDES)}")
        pa, pb = (np.asarray(p, dtype=np.float64).reshape(2) for p in split)
        ring, ia = _nearest_on_ring(ring, pa)
        ring = np.roll(ring, -ia, axis=0)
        ring, ib = _nearest_on_ring(ring, pb)
        if ib == 0:
            raise CaseError("--split", f"A {fmt_point(pa)} and B {fmt_point(pb)} fall on the same contour point")
        forward = ring[: ib + 1]
        backward = np.vstack((ring[ib:], ring[:1]))[::-1]
        ccw = _signed_area(ring) > 0
        lens = [float(np.hypot(*np.diff(w, axis=0).T).sum()) for w in (forward, backward)]
        pick = {"shorter": int(lens[1] < lens[0]), "longer": int(lens[1] >= lens[0]),
                "ccw": 0 if ccw else 1, "cw": 1 if ccw else 0}[lower_side]
        lower_pts = (forward, backward)[pick]
        upper_pts = (backward, forward)[pick][::-1]
        lower, upper = Polyline(lower_pts), Polyline(upper_pts)
        _say(report, f"{where}: A {fmt_point(lower_pts[0])}, B {fmt_point(lower_pts[-1])}; lower {len(lower_pts)} points "
                     f"(length {lens[pick]:.6g}), upper {len(upper_pts)} points")
    else:
        missing = [roles[r] for r in ("lower", "upper") if not any(keys[r] in p.tags for p in pieces)]
        if missing:
            raise CaseError(
                str(drawing.path),
                f"{what} {' and '.join(repr(m) for m in missing)} not found (the drawing has: {', '.join(found) or 'none'}); "
                "name them with --layers lower=NAME,upper=NAME, or give --split XA,YA XB,YB for one closed contour",
            )
        lp, rep = one_chain(select("lower", f"{what} {roles['lower']}"), f"{what} {roles['lower']}", tol, snap, close_gap, closed=False)
        for line in rep.lines(f"{what} {roles['lower']}"):
            _say(report, line)
        up, rep = one_chain(select("upper", f"{what} {roles['upper']}"), f"{what} {roles['upper']}", tol, snap, close_gap, closed=False)
        for line in rep.lines(f"{what} {roles['upper']}"):
            _say(report, line)
        lower, upper = lp.curve, up.curve

        def fit_upper(lo: Curve, upc: Curve) -> tuple[Curve, float]:
            a, b = curve_ends(lo)
            s, e = curve_ends(upc)
            same = np.hypot(*(s - b)) + np.hypot(*(e - a))
            swap = np.hypot(*(e - b)) + np.hypot(*(s - a))
            return (upc, same) if same <= swap else (reverse_curve(upc), swap)

        upper, gap = fit_upper(lower, upper)
        if gap > max(2 * tol, 2 * snap):
            a, b = curve_ends(lower)
            s, e = curve_ends(upper)
            where_gap = a if np.hypot(*(e - a)) > np.hypot(*(s - b)) else b
            raise CaseError(
                f"{what} {roles['upper']}",
                f"does not meet the ends of {what} {roles['lower']}: a gap of {gap:.4g} near {fmt_point(where_gap)}; "
                "lower and upper must together make one closed contour",
            )
        hint = meta.get("lower_start")
        if hint is not None:
            a, b = curve_ends(lower)
            h = np.asarray(hint, dtype=np.float64)
            flip = np.hypot(*(b - h)) < np.hypot(*(a - h))
        else:
            ring = np.vstack((curve_points(lower, chord), curve_points(upper, chord)[1:-1]))
            flip = _signed_area(ring) < 0
        if flip:
            lower = reverse_curve(lower)
            upper = reverse_curve(upper)
        a, b = curve_ends(lower)
        upper = pin_ends(upper, b, a, diag)

    a, b = curve_ends(lower)
    if simplify:
        before = _count(lower) + _count(upper)
        lower, upper = _simplify(lower, simplify), _simplify(upper, simplify)
        _say(report, f"simplified within {simplify:g}: {before} -> {_count(lower) + _count(upper)} points "
                     f"(lower {_count(lower)}, upper {_count(upper)})")

    if has_target and target_arc is None:
        tp, rep = one_chain(select("target", f"{what} {roles['target']}"), f"{what} {roles['target']}", tol, snap, close_gap, closed=False)
        tgt = _orient_target(tp.curve, a, b, meta.get("target_start"))
    elif target_arc is not None:
        inner = np.vstack((curve_points(upper, chord), curve_points(lower, chord)))
        u = b - a
        side = 1.0 if (u[0] * (inner[:, 1].mean() - a[1]) - u[1] * (inner[:, 0].mean() - a[0])) >= 0 else -1.0
        tgt = make_target_arc(a, b, lower.length, float(target_arc), side)
        _say(report, f"target: arc of length {lower.length:.6g}, sagitta {target_arc:g}")
    elif target is not None:
        tgt = target
    else:
        raise CaseError(
            str(drawing.path),
            f"no target: draw it on {what} {roles['target']!r}, give --target-arc SAGITTA, or a target in the case JSON",
        )

    if law is None:
        if "law" not in meta:
            raise CaseError("law", "the drawing gives no law; give --area-ratio R (final area = R x initial area)")
        law = law_from_json(meta["law"])
    options = dict(meta.get("options") or {})
    case_units = drawing.units
    if units and units != case_units:
        if units not in MM_PER_UNIT or case_units not in MM_PER_UNIT:
            raise CaseError("--units", f"cannot convert {case_units!r} to {units!r}; use one of {', '.join(MM_PER_UNIT)}")
        k = MM_PER_UNIT[case_units] / MM_PER_UNIT[units]
        lower, upper, tgt = (transform_curve(c, k * np.eye(2)) for c in (lower, upper, tgt))
        for key in ("chordal_error", "element_size"):
            if key in options:
                options[key] *= k
        _say(report, f"units: {case_units} -> {units} (x {k:g})")
        case_units = units
        chordal_error = chordal_error * k if chordal_error else None
    if chordal_error:
        options["chordal_error"] = float(chordal_error)
    return Case(lower=lower, upper=upper, target=tgt, law=law,
                name=name or meta.get("name") or drawing.path.stem, units=case_units, options=options)


# --------------------------------------------------------------------------
# Case JSON that names a drawing


def read_drawing_file(path, chordal_error=None):
    """The pieces of a DXF or SVG file, by extension."""
    path = Path(path)
    ext = path.suffix.lower()
    if ext == ".dxf":
        from .dxf import read_drawing
    elif ext == ".svg":
        from .svg import read_drawing
    else:
        raise CaseError(str(path), f"unknown drawing format {ext!r}; use .dxf or .svg")
    return read_drawing(path, chordal_error)


def _drawing_options(d: dict, field: str) -> dict:
    opts = {}
    allowed = {"layers", "split", "lower_side", "target_arc", "bbox", "snap", "close_gap", "join_tol", "simplify", "units"}
    for key, value in d.items():
        if key == "file":
            continue
        if key not in allowed:
            raise CaseError(f"{field}.{key}", f"unknown key; use file, {', '.join(sorted(allowed))}")
        opts[key] = value
    return opts


def read_json_case(path, **options) -> Case:
    """Read a case JSON file; one with a ``"drawing"`` key takes its curves from a DXF or SVG.

    ``"drawing": {"file": "profile.dxf", "layers": {"lower": "BASE"}, ...}``
    (file relative to the JSON's folder; the other keys are the options of
    :func:`case_from_drawing`). Curves given in the JSON (``lower``,
    ``upper``, ``target``) take precedence over the drawing's; ``law``,
    ``name``, ``units`` and ``options`` are read as usual. Options given
    here (the command line's) override the JSON's ``drawing`` keys.
    """
    from .json import read_case as read_plain

    path = Path(path)
    data = read_json(path)
    if not isinstance(data, dict) or "drawing" not in data:
        return read_plain(path)
    d = data["drawing"]
    if not isinstance(d, dict) or not isinstance(d.get("file"), str):
        raise CaseError("drawing.file", "expected {\"file\": \"profile.dxf\", ...} naming a DXF or SVG file")
    opts = _drawing_options(d, "drawing")
    opts.update({k: v for k, v in options.items() if v is not None and k != "report"})
    if "law" in data and options.get("law") is None:
        opts["law"] = law_from_json(data["law"])
    if "target" in data:
        opts["target"] = curve_from_json(data["target"], "target")
    chordal = (data.get("options") or {}).get("chordal_error")
    drawing = read_drawing_file(path.parent / d["file"], opts.get("chordal_error") or chordal)
    case = case_from_drawing(drawing, report=options.get("report"), **{k: v for k, v in opts.items() if k != "report"})
    merged = {"format": data.get("format", "section-case/1"), "lower": case.lower.to_json(), "upper": case.upper.to_json(),
              "target": case.target.to_json(), "law": case.law.to_json(), "name": data.get("name", case.name),
              "units": data.get("units", case.units), "options": {**case.options.to_json(), **(data.get("options") or {})}}
    for key in ("lower", "upper"):
        if key in data:
            merged[key] = data[key]
    return case_from_dict(merged)


# --------------------------------------------------------------------------
# Command-line options


def _point(text: str):
    try:
        x, y = (float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected X,Y, got {text!r}") from None
    return (x, y)


def _box(text: str):
    try:
        v = tuple(float(t) for t in text.split(","))
    except ValueError:
        v = ()
    if len(v) != 4 or v[0] >= v[2] or v[1] >= v[3]:
        raise argparse.ArgumentTypeError(f"expected XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX, got {text!r}")
    return v


def _roles(text: str):
    out = {}
    for item in text.split(","):
        role, sep, name = item.partition("=")
        if not sep or role.strip() not in ROLES or not name.strip():
            raise argparse.ArgumentTypeError(f"expected ROLE=NAME[,ROLE=NAME...] with ROLE in {', '.join(ROLES)}, got {item!r}")
        out[role.strip()] = name.strip()
    return out


def add_input_args(parser) -> None:
    """Add the options for reading DXF and SVG drawings to an argparse parser.

    Coordinates such as ``-19.6,0`` are taken as values, not options (argparse
    alone only knows plain negative numbers).
    """
    import re

    parser._negative_number_matcher = re.compile(r"^-\.?\d[\d.,eE+-]*$")
    g = parser.add_argument_group("drawing input (DXF, SVG; lengths in drawing units)")
    g.add_argument("--layers", type=_roles, metavar="ROLE=NAME,...",
                   help="layer (DXF) or id/class (SVG) of each role: lower, upper, target, contour "
                        "(default LOWER, UPPER, TARGET, CONTOUR)")
    g.add_argument("--split", type=_point, nargs=2, metavar=("XA,YA", "XB,YB"),
                   help="one closed contour: the lower curve runs between the contour points nearest these")
    g.add_argument("--lower-side", choices=SIDES, default="shorter",
                   help="with --split, which way round from A to B is the lower curve (default shorter)")
    g.add_argument("--target-arc", type=float, metavar="SAGITTA",
                   help="target: an arc as long as the lower curve, tangent to AB at its midpoint; "
                        "SAGITTA > 0 bends its ends towards the section")
    g.add_argument("--bbox", type=_box, metavar="XMIN,YMIN,XMAX,YMAX", help="keep only the pieces inside this box")
    g.add_argument("--snap", type=float, metavar="D", help="snap free ends closer than D together (reported)")
    g.add_argument("--close-gap", type=float, metavar="MAXLEN",
                   help="close gaps up to MAXLEN with a straight piece (reported)")
    g.add_argument("--join-tol", type=float, metavar="D", help="ends closer than D are one point (default 1e-6 of the drawing)")
    g.add_argument("--simplify", type=float, metavar="TOL", help="simplify polylines within TOL (Douglas-Peucker)")
    g.add_argument("--chordal-error", type=float, metavar="TOL", help="chordal error of polylines made from curves")
    g.add_argument("--units", metavar="UNIT", help="convert the case to these units (mm, cm, m, in...)")


def input_options(args, report: list | None = None) -> dict:
    """Reader options from parsed arguments (see :func:`add_input_args`); ``--area-ratio`` gives the law."""
    opts = {"report": report}
    for key in ("layers", "split", "lower_side", "target_arc", "bbox", "snap", "close_gap", "join_tol", "simplify",
                "chordal_error", "units"):
        value = getattr(args, key, None)
        if value is not None:
            opts[key] = value
    for key in ("snap", "close_gap", "join_tol", "simplify", "chordal_error"):
        if key in opts and opts[key] < 0:
            raise CaseError(f"--{key.replace('_', '-')}", f"must be >= 0, got {opts[key]}")
    if getattr(args, "lower_side", None) == "shorter":
        opts.pop("lower_side")
    if getattr(args, "area_ratio", None) is not None:
        opts["law"] = AreaRatio(args.area_ratio)
    return opts
