"""SVG drawings: read a section from ids and classes, write cases and deformed sections.

Reading
-------
Shapes (``path``, ``line``, ``polyline``, ``polygon``, ``rect``,
``circle``, ``ellipse``) are tagged with their ``id``, their classes and
those of their parent groups, so ``<path id="lower">``,
``<g class="upper">...</g>`` or ``<path class="target profile">`` all
work; a path of several segments gives several pieces, chained by
:mod:`.drawing` like DXF pieces. Path segments become exact curves:

- lines: polylines;
- quadratic and cubic Béziers: B-splines of degree 2 and 3 with knots
  ``[0]*(k+1) + [1]*(k+1)`` (a Bézier *is* that B-spline);
- circular arcs (rx = ry): arcs; elliptical ones: polylines within the
  chordal error.

Transforms (``transform`` attributes) are applied; circular arcs stay
arcs under similarities. Document units are honoured: with
``width="100mm"`` and ``viewBox="0 0 200 100"`` one user unit is 0.5 mm;
without physical sizes a user unit is a CSS pixel (1/96 in). The case is
in mm (or in the units a file written by :func:`write_case` records), with
the y axis flipped to point up; the viewBox origin is not subtracted, so
user coordinates map to case coordinates by scale alone.

Writing
-------
:func:`write_case` writes one ``<path>`` per layer of the problem's
dialect (:mod:`.layers`; ``lower``, ``upper``, ``target`` for the paper's
one body), arcs as ``A``, cubic and quadratic B-splines as Bézier segments,
others flattened within the chordal error, one user unit = one case unit,
plus the case data in the root's ``data-sectiondeform`` attribute; a
body's holes are one path ``BODY-<name>-HOLE``, a subpath per hole.
:func:`write_result` writes one group per layer of the result (the holes
on ``INITIAL-<name>-HOLE`` and ``DEFORMED-<name>-HOLE``). Holes are read
from ``BODY-<name>-HOLE``, or found inside a body's contour (:mod:`.holes`).
"""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from ..curves import DEFAULT_CHORDAL_FRACTION, Arc, BSpline, Curve, Polyline
from ..errors import CaseError, require
from ..limits import MAX_CURVE_POINTS, bounded, flattening_points
from .chaining import fmt_point
from .files import atomic_write
from .layers import case_layers, case_meta, check_case, check_layer_names, read_meta, result_layers, tolerance
from .pieces import Drawing, Piece, checked_coordinates
from .units import CSS_UNITS, MM_PER_UNIT, mm_per_unit

__all__ = ["read_drawing", "read_case", "write_case", "write_result"]

SVG_NS = "http://www.w3.org/2000/svg"
META_ATTR = "data-sectiondeform"
SHAPES = {"path", "line", "polyline", "polygon", "rect", "circle", "ellipse"}
SKIP = {"defs", "clipPath", "mask", "symbol", "marker", "pattern", "title", "desc", "metadata", "style", "text",
        "linearGradient", "radialGradient", "filter", "script", "tspan", "namedview"}
CONTAINERS = {"svg", "g", "a", "switch"}


def _refusal(message: str) -> CaseError:
    """A :class:`CaseError` whose message already names the element (for :func:`~sectiondeform.limits.bounded`)."""
    return CaseError("", message)


def _flatten_fix(what: str, tol: float) -> str:
    """The end of the message refusing to flatten ``what`` within ``tol``: why, and what to change."""
    return (f"{what} flattened within the chordal error {tol:.3g} (user units) would need them; give a larger "
            "--chordal-error (its default is 1e-4 of the viewBox's diagonal), or check the viewBox")


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_LIST_TOKEN = re.compile(rf"[\s,]*({_NUMBER})")
_PATH_TOKEN = re.compile(rf"[\s,]*(?:[MmZzLlHhVvCcSsQqTtAa]|{_NUMBER})")
_TRANSFORM = re.compile(rf"\s*(?:(?:matrix|translate|scale|rotate|skewX|skewY)\s*\(\s*(?:{_NUMBER}(?:[\s,]*{_NUMBER})*)?\s*\)[\s,]*)*")
_SVG_ERRORS = (ValueError, IndexError, TypeError, ArithmeticError)  # what svgelements raises on text it cannot use


def _length_mm(text: str | None) -> float | None:
    """A CSS length in mm, or None for a missing, relative or unreadable one."""
    if not text:
        return None
    m = re.fullmatch(rf"\s*({_NUMBER})\s*([a-zA-Z%]*)\s*", text)
    if not m or m.group(2) == "%":
        return None
    unit = m.group(2).lower() or "px"
    if unit not in CSS_UNITS:
        return None
    value = float(m.group(1)) * CSS_UNITS[unit]
    return value if math.isfinite(value) and value > 0 else None


def _scan(text: str, token: re.Pattern) -> tuple[list[str], int | None]:
    """The tokens of ``text`` and the position of the first character that is none (None if all are)."""
    out, pos = [], 0
    while pos < len(text):
        m = token.match(text, pos)
        if m is None or m.end() == pos:
            rest = text[pos:].lstrip(" \t\r\n,")
            return out, None if not rest else len(text) - len(rest)
        out.append(m.group(m.lastindex or 0).strip(" \t\r\n,"))
        pos = m.end()
    return out, None


def _bad_at(text: str, at: int) -> str:
    return f"cannot read {text[at:at + 12]!r} at character {at}"


def _floats(text: str | None, where: str = "svg") -> list[float]:
    """The finite numbers of a list attribute (``points``, ``viewBox``); anything else is an error naming ``where``."""
    tokens, bad = _scan(text or "", _LIST_TOKEN)
    if bad is not None:
        raise CaseError(where, f"{_bad_at(text, bad)}: expected numbers separated by spaces or commas")
    values = [float(v) for v in tokens]
    for v in values:
        if not math.isfinite(v):
            raise CaseError(where, f"{v} is not a finite number; correct the drawing")
    return values


def _number(el, key: str, where: str) -> float:
    """A finite number attribute (0 when absent), else a one-line error naming the element and the attribute."""
    text = el.get(key)
    if text is None:
        return 0.0
    m = re.fullmatch(rf"\s*({_NUMBER})\s*(?:px)?\s*", text)
    value = float(m.group(1)) if m else math.nan
    if not math.isfinite(value):
        raise CaseError(f"{where} {key}", f"{text!r} is not a finite number; write it in user units, e.g. {key}=\"10\"")
    return value


def _transform(svgelements, text: str, where: str):
    """The matrix of a ``transform`` attribute, checked: every function known, every number finite."""
    if not _TRANSFORM.fullmatch(text):
        raise CaseError(f"{where} transform", f"{text[:40]!r} is not an SVG transform of finite numbers "
                                              "(matrix, translate, scale, rotate, skewX, skewY)")
    try:
        matrix = svgelements.Matrix(text)
    except _SVG_ERRORS as exc:
        raise CaseError(f"{where} transform", f"{text[:40]!r}: {exc or 'wrong number of values'}") from None
    values = (matrix.a, matrix.b, matrix.c, matrix.d, matrix.e, matrix.f)
    if not all(math.isfinite(v) for v in values):
        raise CaseError(f"{where} transform", f"{text[:40]!r} gives a matrix that is not finite")
    return matrix


def _document_scale(root) -> tuple[float, float]:
    """Millimetres per user unit along x and y."""
    vb = _floats(root.get("viewBox"))
    w, h = _length_mm(root.get("width")), _length_mm(root.get("height"))
    px = CSS_UNITS["px"]
    if len(vb) == 4 and vb[2] > 0 and vb[3] > 0:
        sx = w / vb[2] if w else (h / vb[3] if h else px)
        sy = h / vb[3] if h else sx
        return sx, sy
    return px, px


def _bezier(points) -> BSpline:
    k = len(points) - 1
    return BSpline(k, np.array(points, dtype=np.float64), np.array([0.0] * (k + 1) + [1.0] * (k + 1)))


def _arc_curve(seg, tol: float, where: str) -> Curve:
    start = np.array([seg.start.x, seg.start.y])
    end = np.array([seg.end.x, seg.end.y])
    rx, ry = float(seg.rx), float(seg.ry)
    if abs(rx - ry) <= 1e-9 * max(rx, ry):
        c = np.array([seg.center.x, seg.center.y])
        a0 = math.degrees(math.atan2(start[1] - c[1], start[0] - c[0]))
        return Arc(c, 0.5 * (rx + ry), a0, a0 + math.degrees(seg.sweep))
    r = max(float(seg.rx), float(seg.ry))
    n = bounded(max(4, 2 * math.ceil(flattening_points(r, seg.sweep, tol) / 2)), MAX_CURVE_POINTS, "points",
                _flatten_fix("an elliptical arc", tol), _refusal, where)
    pts = np.array([[p.x, p.y] for p in (seg.point(t) for t in np.linspace(0.0, 1.0, n + 1))])
    pts[0], pts[-1] = start, end
    return Polyline(pts)


def _path_segments(svgelements, d: str, where: str) -> list:
    """The segments of a path's ``d``, checked: only path commands and finite numbers, all of them read."""
    tokens, bad = _scan(d, _PATH_TOKEN)
    if bad is not None:
        raise CaseError(f"{where} d", f"{_bad_at(d, bad)}: expected path commands and numbers")
    if not all(math.isfinite(float(t)) for t in tokens if t not in "MmZzLlHhVvCcSsQqTtAa"):
        raise CaseError(f"{where} d", "a number is not finite (too large for a float); correct the drawing")
    try:
        return list(svgelements.Path(d))
    except _SVG_ERRORS as exc:
        raise CaseError(f"{where} d", f"not valid path data ({type(exc).__name__}{': ' if str(exc) else ''}{exc})") from None


def _path_curves(d: str, tol: float, where: str = "path") -> list[Curve]:
    svgelements = require("svgelements", "cad", "reading SVG")
    out: list[Curve] = []
    for seg in _path_segments(svgelements, d, where):
        name = type(seg).__name__
        if name == "Move" or seg.start is None:
            continue
        p0 = (seg.start.x, seg.start.y)
        p1 = (seg.end.x, seg.end.y)
        if name in ("Line", "Close"):
            if p0 != p1:
                out.append(Polyline(np.array([p0, p1])))
        elif name == "QuadraticBezier":
            out.append(_bezier([p0, (seg.control.x, seg.control.y), p1]))
        elif name == "CubicBezier":
            out.append(_bezier([p0, (seg.control1.x, seg.control1.y), (seg.control2.x, seg.control2.y), p1]))
        elif name == "Arc":
            if p0 != p1:
                out.append(_arc_curve(seg, tol, where))
        else:  # pragma: no cover - svgelements yields only the kinds above
            raise CaseError("svg path", f"unsupported path segment {name}")
    return out


def _shape_curves(el, name: str, tol: float, where: str = "svg") -> list[Curve]:
    g = el.get

    def num(key):
        return _number(el, key, where)

    if name == "path":
        return _path_curves(g("d", ""), tol, where)
    if name == "line":
        p = np.array([[num("x1"), num("y1")], [num("x2"), num("y2")]])
        return [Polyline(p)]
    if name in ("polyline", "polygon"):
        values = _floats(g("points"), f"{where} points")
        if len(values) % 2:
            raise CaseError(f"{where} points", f"{len(values)} numbers: give x and y of each point")
        v = np.array(values, dtype=np.float64).reshape(-1, 2)
        if name == "polygon" and len(v):
            v = np.vstack((v, v[:1]))
        return [Polyline(v)] if len(v) >= 2 else []
    if name == "rect":
        x, y, w, h = (num(k) for k in ("x", "y", "width", "height"))
        return [Polyline(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h], [x, y]]))]
    if name == "circle":
        return [Arc(np.array([num("cx"), num("cy")]), num("r"), 0.0, 360.0)]
    if name == "ellipse":
        cx, cy, rx, ry = (num(k) for k in ("cx", "cy", "rx", "ry"))
        if rx == ry:
            return [Arc(np.array([cx, cy]), rx, 0.0, 360.0)]
        count = flattening_points(max(rx, ry), 2 * math.pi, tol)
        n = int(max(16, bounded(count, MAX_CURVE_POINTS, "points", _flatten_fix("the ellipse", tol), _refusal, where)))
        t = np.linspace(0, 2 * math.pi, n + 1)
        pts = np.column_stack((cx + rx * np.cos(t), cy + ry * np.sin(t)))
        pts[-1] = pts[0]
        return [Polyline(pts)]
    return []


def read_drawing(path, chordal_error: float | None = None):
    """Read the shapes of an SVG file as pieces, in mm (or the units it records), y up.

    Parameters
    ----------
    path : str or Path
    chordal_error : float, optional
        Chordal error of elliptical arcs flattened to polylines, in case
        units; default 1e-4 of the document's size.

    Returns
    -------
    Drawing

    Raises
    ------
    CaseError
        Unreadable file, a zero-length piece, an unsupported element,
        corrupt stored case data.
    """
    svgelements = require("svgelements", "cad", "reading SVG")
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except OSError as exc:
        raise CaseError(str(path), f"cannot read the SVG file ({exc.strerror})") from None
    except ET.ParseError as exc:
        raise CaseError(str(path), f"not a valid SVG file ({exc})") from None
    meta = read_meta(root.get(META_ATTR), f"{path} (attribute {META_ATTR})")
    vb = _floats(root.get("viewBox"), f"{path} viewBox")
    if vb and (len(vb) != 4 or not (vb[2] > 0 and vb[3] > 0)):
        raise CaseError(f"{path} viewBox", f"{root.get('viewBox')!r}: give four numbers, x y width height, "
                                           "with a positive width and height")
    sx, sy = _document_scale(root)
    units = meta.get("units", "mm")
    k = 1.0 / mm_per_unit(units, f"{path} (attribute {META_ATTR}, units)")
    doc = np.array([[sx * k, 0.0], [0.0, -sy * k]])  # user units -> case units, y up
    size = math.hypot(vb[2], vb[3]) * sx * k if len(vb) == 4 else 100.0
    tol = chordal_error or DEFAULT_CHORDAL_FRACTION * size
    pieces: list[Piece] = []
    labels: dict[str, str] = {}
    count = 0

    def visit(el, matrix, tags):
        nonlocal count
        name = _local(el.tag)
        if name in SKIP:
            return
        own = set(tags)
        where = f"<{name}>" + (f" id={el.get('id')!r}" if el.get("id") else "")
        names = ([el.get("id")] if el.get("id") else []) + (el.get("class") or "").split()
        for n in names:
            labels.setdefault(n.upper(), n)
        own.update(n.upper() for n in names)
        if el.get("transform"):
            matrix = _transform(svgelements, el.get("transform"), where) * matrix
        if name in CONTAINERS:
            for child in el:
                visit(child, matrix, frozenset(own))
            return
        count += 1
        source = f"<{name}> #{count}" + (f" id={el.get('id')!r}" if el.get("id") else "")
        if name not in SHAPES:
            pieces.append(Piece(None, frozenset(own), source))
            return
        m = np.array([[matrix.a, matrix.c], [matrix.b, matrix.d]])
        full = doc @ m
        offset = doc @ np.array([matrix.e, matrix.f])
        scale = float(np.abs(full).max())
        if not (math.isfinite(scale) and scale > 0 and np.isfinite(offset).all()):
            raise CaseError(source, "its transform and the document's units give a scale that is not finite "
                                    "and positive; correct the transform, width, height or viewBox")
        curves = _shape_curves(el, name, tol / scale, source)
        if not curves:
            raise CaseError(source, "has zero length; delete it")
        for c in curves:
            c = checked_coordinates(c.transformed(full, offset, tol), source)
            if not c.length > 0:
                raise CaseError(source, f"zero-length piece at {fmt_point(c.at_fractions(np.array([0.0]))[0])}; delete it")
            pieces.append(Piece(c, frozenset(own), source))

    for child in root:
        visit(child, svgelements.Matrix(), frozenset())
    return Drawing(pieces, units, 1.0 / k, meta, path, labels=labels)


def read_case(path, **options):
    """Read a case from an SVG drawing; see :func:`sectiondeform.io.drawing.case_from_drawing`."""
    from .drawing import case_from_drawing

    return case_from_drawing(read_drawing(path, options.get("chordal_error")), **options)


# --------------------------------------------------------------------------
# Writing


def _num(v: float) -> str:
    return repr(float(v))


def _pt(p) -> str:
    return f"{_num(p[0])},{_num(-p[1])}"


def _polyline_d(curve: Polyline, tol: float) -> list[str]:
    return ["L" + " ".join(_pt(v) for v in curve.vertices[1:])]


def _arc_d(curve: Arc, tol: float) -> list[str]:
    sweep = curve.end_deg - curve.start_deg
    n = 2 if abs(sweep) >= 180.0 else 1
    ends = curve.at_fractions(np.linspace(0.0, 1.0, n + 1)[1:])
    flag = 0 if sweep > 0 else 1  # y flipped: counter-clockwise becomes the negative-angle direction
    r = _num(curve.radius)
    return [f"A{r},{r} 0 0 {flag} {_pt(e)}" for e in ends]


def _bspline_d(curve: BSpline, tol: float) -> list[str]:
    if curve.degree not in (2, 3):
        return _flat_d(curve, tol)
    from scipy.interpolate import BSpline as SciPy

    k, t, c = curve.degree, curve.knots, curve.control_points
    spl = SciPy(t, c, k)
    for a in np.unique(t[k:-k])[1:-1]:  # raise every inner knot to multiplicity k: Bézier pieces
        have = int(np.sum(t == a))
        if have < k:
            spl = spl.insert_knot(a, k - have) if hasattr(spl, "insert_knot") else _insert(spl, a, k - have)
        t = spl.t
    cp = spl.c[: len(spl.t) - k - 1]
    letter = "C" if k == 3 else "Q"
    return [letter + " ".join(_pt(p) for p in cp[i + 1 : i + k + 1]) for i in range(0, len(cp) - 1, k)]


def _flat_d(curve: Curve, tol: float) -> list[str]:
    pts = curve.characteristic_points(tol)
    return ["L" + " ".join(_pt(v) for v in pts[1:])]


# Curve kind -> its native path segments; any other kind is flattened within the chordal error.
_NATIVE = {"polyline": _polyline_d, "arc": _arc_d, "bspline": _bspline_d}


def _curve_d(curve: Curve, tol: float) -> str:
    """SVG path data for a curve in case coordinates (y flipped)."""
    out = ["M" + _pt(curve.ends[0])]
    for part in curve.parts():
        out.extend(_NATIVE.get(part.kind, _flat_d)(part, tol))
    return " ".join(out)


def _insert(spl, x: float, m: int):  # pragma: no cover - scipy < 1.13
    from scipy.interpolate import BSpline as SciPy
    from scipy.interpolate import insert

    t, c, k = insert(x, (spl.t, [spl.c[:, 0], spl.c[:, 1]], spl.k), m)
    c = np.column_stack(c)
    return SciPy(t, c, k)


def _svg(bounds: np.ndarray, units: str, body: list[str], meta: dict | None = None) -> str:
    lo, hi = bounds.min(axis=0), bounds.max(axis=0)
    pad = 0.05 * float(max(hi - lo)) or 1.0
    x0, y0 = float(lo[0] - pad), float(-hi[1] - pad)
    w, h = float(hi[0] - lo[0] + 2 * pad), float(hi[1] - lo[1] + 2 * pad)
    css = units.lower() in CSS_UNITS
    scale = 1.0 if css else MM_PER_UNIT.get(units, 1.0)
    unit = units if css else "mm"
    attrs = (f'xmlns="{SVG_NS}" width="{w * scale!r}{unit}" height="{h * scale!r}{unit}" '
             f'viewBox="{x0!r} {y0!r} {w!r} {h!r}"')
    if meta is not None:
        attrs += f" {META_ATTR}={quoteattr(json.dumps(meta, separators=(',', ':')))}"
    stroke = 0.003 * max(w, h)
    style = f"<style>path{{fill:none;stroke-width:{stroke:.6g};stroke-linejoin:round}}</style>"
    return f'<?xml version="1.0" encoding="UTF-8"?>\n<svg {attrs}>\n{style}\n' + "\n".join(body) + "\n</svg>\n"


def write_case(path, case) -> None:
    """Write a case as an SVG drawing, atomically: one path per layer of its dialect, ids as the DXF layers.

    Parameters
    ----------
    path : str or Path
    case : Problem
        Paths ``lower``, ``upper``, ``target`` for ``section-case/1``;
        ``SUPPORT``, ``TARGET``, ``BODY-<name>-LOWER``, ``-UPPER`` (and
        ``AXIS``) for ``section-case/2`` (:func:`sectiondeform.io.layers.case_layers`).
    """
    check_layer_names(case, dxf=False)
    tol = tolerance(case)
    body, pts = [], []
    for layer in case_layers(case):
        curves = layer.data if layer.kind == "curves" else (layer.data,)
        if layer.name != "AXIS":
            pts += [c.discretise(tol)[0] for c in curves]
        d = " ".join(_curve_d(c, tol) for c in curves)
        body.append(f'<path id={quoteattr(layer.svg)} stroke="{layer.svg_color}" d="{d}"/>')
    text = _svg(np.concatenate(pts), case.units, body, case_meta(case))
    atomic_write(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))


def _poly_d(points: np.ndarray, close: bool) -> str:
    return "M" + " L".join(_pt(p) for p in points) + (" Z" if close else "")


def _layer_d(layer) -> str:
    if layer.kind == "mesh":
        corners = {"quad": 4, "triangle": 3, "triangle6": 3}[layer.data.kind]
        return " ".join(_poly_d(layer.data.points[c[:corners]], True) for c in layer.data.cells)
    if layer.kind == "rings":
        return " ".join(_poly_d(np.asarray(r), True) for r in layer.data)
    return _poly_d(np.asarray(layer.data), layer.kind == "closed")


def write_result(path, result, case=None) -> None:
    """Write a deformed problem as SVG, atomically: one group per layer, ids as in :func:`sectiondeform.io.layers.result_layers`.

    Parameters
    ----------
    path : str or Path
    result : Result
        A ``section-result/1`` result gives the groups ``mesh-initial``,
        ``initial``, ``mesh-final``, ``target``, ``deformed``; a
        ``section-result/2`` one the DXF writer's layers, per body.
    case : Problem, optional
        The problem deformed: a ``section-result/2`` drawing draws its
        support and target too.
    """
    check_case(result, case)
    check_layer_names(result, dxf=False)
    body, pts = [], []
    for layer in result_layers(result, case):
        if layer.kind == "rings":
            pts += [np.asarray(r) for r in layer.data]
        elif layer.kind != "mesh":
            pts.append(np.asarray(layer.data))
        body.append(f'<g id={quoteattr(layer.svg)} stroke="{layer.svg_color}"><path d="{_layer_d(layer)}"/></g>')
    meta = {"units": result.units, "name": result.name, "format": result.dialect}
    text = _svg(np.concatenate(pts), result.units, body, meta)
    atomic_write(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))
