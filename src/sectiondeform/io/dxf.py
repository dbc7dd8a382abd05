"""DXF drawings: read a section from layers, write cases and deformed sections.

Reading (:func:`read_drawing`, :func:`read_case`)
-------------------------------------------------
Every entity of the model space becomes a :class:`~.pieces.Piece` tagged
with its layer name:

=============  ==========================================================
LINE           a two-point polyline
ARC, CIRCLE    a circular arc (a CIRCLE is a closed 360° arc)
LWPOLYLINE,    straight runs become polylines, bulged segments arcs
POLYLINE (2D)  (bulge = tan(θ/4), positive counter-clockwise); the
               closing segment of a closed polyline is included
SPLINE         a clamped non-rational spline is kept exactly (degree,
               control points, knots); a rational one (unequal weights,
               e.g. an exact conic) or an unclamped one cannot be a case
               B-spline, and becomes a polyline within the chordal error
ELLIPSE        a polyline within the chordal error
=============  ==========================================================

Entities in an extrusion direction (0, 0, -1) are mirrored into the world
frame. Annotation (TEXT, MTEXT, DIMENSION, POINT, HATCH...) is ignored;
any other entity on a layer in use is an error. ``$INSUNITS`` gives the
units (unitless or missing: mm). How pieces become a case is
:mod:`sectiondeform.io.drawing`'s job.

Writing
-------
:func:`write_case` puts a problem's curves on the layers of its dialect
(:mod:`.layers`: LOWER, UPPER, TARGET for the paper's one body; SUPPORT,
TARGET, BODY-<name>-LOWER, -UPPER, -HOLE and AXIS otherwise) as native entities
(polylines as LWPOLYLINE, arcs as ARC or CIRCLE, B-splines as SPLINE with
their knots), and the laws, name, options and start points in the header
custom property ``sectiondeform``, so DXF -> case -> DXF loses nothing.
:func:`write_result` writes the result's layers: deformed and initial
curves as LWPOLYLINEs (the deformed ones as SPLINEs fitted within the
chordal error with ``spline=True``), the holes as closed LWPOLYLINEs on
INITIAL-<name>-HOLE and DEFORMED-<name>-HOLE, and each mesh as one closed
LWPOLYLINE per element, in element order. Holes are read from
BODY-<name>-HOLE, or found inside a body's contour (:mod:`.holes`).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..curves import DEFAULT_CHORDAL_FRACTION, Arc, BSpline, Curve, Polyline
from ..errors import CaseError, SectionDeformError, require
from ..limits import MAX_CURVE_POINTS, bounded, flattening_points
from .chaining import fmt_point
from .files import atomic_write
from .layers import Layer, case_layers, case_meta, check_case, check_layer_names, read_meta, result_layers, tolerance
from .pieces import Drawing, Piece, checked_coordinates
from .units import DXF_UNITS, MM_PER_UNIT

__all__ = ["read_drawing", "read_case", "write_case", "write_result", "fit_spline"]

INSUNITS = {name: code for code, name in DXF_UNITS.items()}
IGNORED = {"TEXT", "MTEXT", "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION", "POINT", "HATCH",
           "LEADER", "MULTILEADER", "MLEADER", "ATTDEF", "TOLERANCE", "IMAGE", "WIPEOUT", "VIEWPORT"}
META_KEY = "sectiondeform"
MIRROR_X = np.array([[-1.0, 0.0], [0.0, 1.0]])
# What ezdxf's reader raises on a damaged file besides its own errors: a value that is not a number,
# a file that ends inside a section (StopIteration), a tag or a handle that is missing.
_CORRUPT = (ValueError, StopIteration, EOFError, IndexError, KeyError, TypeError, UnicodeError, ArithmeticError)


def _refusal(message: str) -> CaseError:
    """A :class:`CaseError` whose message already names the entity (for :func:`~sectiondeform.limits.bounded`)."""
    return CaseError("", message)


def _reason(exc: BaseException) -> str:
    """One short line saying what the DXF reader found wrong."""
    if isinstance(exc, StopIteration):
        return "the file ends too early"
    text = " ".join(str(exc).split())[:120]
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _flat(p) -> np.ndarray:
    return np.array([float(p[0]), float(p[1])])


def _bulge_arc(p: np.ndarray, q: np.ndarray, bulge: float) -> Arc:
    """The arc from ``p`` to ``q`` of a polyline segment with ``bulge`` = tan(θ/4)."""
    chord = q - p
    c = math.hypot(*chord)
    d = 0.5 * c * (1.0 - bulge * bulge) / (2.0 * bulge)  # midpoint -> centre, along the left normal
    normal = np.array([-chord[1], chord[0]]) / c
    center = 0.5 * (p + q) + d * normal
    radius = math.hypot(*(p - center))
    a0 = math.degrees(math.atan2(p[1] - center[1], p[0] - center[0]))
    return Arc(center, radius, a0, a0 + math.degrees(4.0 * math.atan(bulge)))


def _polyline_pieces(points: np.ndarray, bulges: np.ndarray, closed: bool) -> list[Curve]:
    """Curves of a (LW)POLYLINE: ``(N, 2)`` vertices, ``(N,)`` bulges."""
    if closed:
        points = np.vstack((points, points[:1]))
    out: list[Curve] = []
    run = [points[0]]
    for i in range(len(points) - 1):
        p, q, b = points[i], points[i + 1], float(bulges[i])
        if np.array_equal(p, q):
            continue
        if b == 0.0:
            run.append(q)
            continue
        if len(run) > 1:
            out.append(Polyline(np.array(run)))
        out.append(_bulge_arc(p, q, b))
        run = [q]
    if len(run) > 1:
        out.append(Polyline(np.array(run)))
    return out


def _entity_curves(e, tol: float) -> list[Curve] | None:
    """Curves of one entity, in the world XY plane; None if not a curve entity."""
    kind = e.dxftype()
    mirror = False
    if e.dxf.hasattr("extrusion"):
        z = tuple(e.dxf.extrusion)
        if abs(z[0]) > 1e-12 or abs(z[1]) > 1e-12:
            raise CaseError(f"layer {e.dxf.layer}", f"{kind} (handle {e.dxf.handle}) is not in the XY plane")
        mirror = z[2] < 0 and kind in ("ARC", "CIRCLE", "LWPOLYLINE", "POLYLINE", "ELLIPSE")
    if kind == "LINE":
        curves = [Polyline(np.vstack((_flat(e.dxf.start), _flat(e.dxf.end))))]
    elif kind == "ARC":
        a0, a1 = float(e.dxf.start_angle), float(e.dxf.end_angle)
        while a1 <= a0:
            a1 += 360.0
        curves = [Arc(_flat(e.dxf.center), float(e.dxf.radius), a0, a1)]
    elif kind == "CIRCLE":
        curves = [Arc(_flat(e.dxf.center), float(e.dxf.radius), 0.0, 360.0)]
    elif kind == "LWPOLYLINE":
        xyb = np.array(list(e.get_points("xyb")), dtype=np.float64).reshape(-1, 3)
        curves = _polyline_pieces(xyb[:, :2], xyb[:, 2], e.closed)
    elif kind == "POLYLINE":
        if not (e.is_2d_polyline or e.is_3d_polyline):
            return None
        pts = np.array([_flat(v.dxf.location) for v in e.vertices]).reshape(-1, 2)
        bul = np.array([float(v.dxf.bulge) if e.is_2d_polyline else 0.0 for v in e.vertices])
        curves = _polyline_pieces(pts, bul, e.is_closed)
    elif kind == "SPLINE":
        ct = e.construction_tool()
        cps = np.array([_flat(p) for p in ct.control_points])
        knots = np.array(ct.knots(), dtype=np.float64)
        w = np.array(ct.weights(), dtype=np.float64)
        rational = len(w) and np.ptp(w) > 1e-12 * np.abs(w).max()
        if ct.is_clamped and not rational:
            curves = [BSpline(int(ct.degree), cps, (knots - knots[0]) / (knots[-1] - knots[0]))]
        else:
            curves = [Polyline(np.array([_flat(p) for p in ct.flattening(tol, segments=8)]))]
    elif kind == "ELLIPSE":
        major = math.hypot(*_flat(e.dxf.major_axis))
        sweep = (float(e.dxf.end_param) - float(e.dxf.start_param)) % (2 * math.pi) or 2 * math.pi
        bounded(flattening_points(major, sweep, tol), MAX_CURVE_POINTS, "points", f"the ellipse flattened within the "
                f"chordal error {tol:.3g} would need them; give a larger --chordal-error", _refusal,
                f"layer {e.dxf.layer}: ELLIPSE (handle {e.dxf.handle})")
        curves = [Polyline(np.array([_flat(p) for p in e.flattening(tol, segments=8)]))]
    else:
        return None
    if mirror:
        curves = [c.transformed(MIRROR_X, tol=tol) for c in curves]
    return curves


def _extent(msp) -> float:
    """Diagonal of the drawing's extents, for default tolerances (1 for an empty drawing)."""
    from ezdxf import bbox

    box = bbox.extents(msp, fast=True)
    if box.has_data:
        return float(math.hypot(box.size.x, box.size.y)) or 1.0
    return 1.0


def read_drawing(path, chordal_error: float | None = None) -> Drawing:
    """Read the curve pieces of a DXF file's model space.

    Parameters
    ----------
    path : str or Path
    chordal_error : float, optional
        Chordal error of the polylines standing for rational splines and
        ellipses, drawing units; default 1e-4 of the drawing's diagonal.

    Returns
    -------
    Drawing

    Raises
    ------
    CaseError
        Unreadable file; an unsupported entity (naming its layer, type and
        handle); a zero-length piece (naming where it is).
    """
    ezdxf = require("ezdxf", "cad", "reading DXF")
    path = Path(path)
    try:
        doc = ezdxf.readfile(str(path))
    except OSError as exc:
        raise CaseError(str(path), f"cannot read the DXF file ({exc})") from None
    except ezdxf.DXFStructureError as exc:
        raise CaseError(str(path), f"not a valid DXF file ({exc})") from None
    except (ezdxf.DXFError, *_CORRUPT) as exc:
        raise CaseError(str(path), f"not a valid DXF file ({_reason(exc)}); export it again from the CAD program") from None
    msp = doc.modelspace()
    tol = chordal_error or DEFAULT_CHORDAL_FRACTION * _extent(msp)
    # ezdxf fills a missing header with defaults ($INSUNITS 6, metres): look in the file itself.
    with open(path, "rb") as fh:
        declared = b"$INSUNITS" in fh.read(4_000_000)
    code = int(doc.header.get("$INSUNITS", 0) or 0) if declared else 0
    units = DXF_UNITS.get(code, "mm")
    mm = MM_PER_UNIT[units]
    meta = {}
    if doc.header.custom_vars.has_tag(META_KEY):
        meta = read_meta(doc.header.custom_vars.get(META_KEY), f"{path} (header property {META_KEY})")
    pieces, ignored, labels = [], [], {}
    for i, e in enumerate(msp):
        kind = e.dxftype()
        layer = e.dxf.layer
        labels.setdefault(layer.upper(), layer)
        source = f"{kind} #{i} (handle {e.dxf.handle}, layer {layer})"
        if kind in IGNORED:
            ignored.append(source)
            continue
        try:
            curves = _entity_curves(e, tol)
        except SectionDeformError:
            raise
        except (ezdxf.DXFError, *_CORRUPT) as exc:
            raise CaseError(f"layer {layer}", f"{source} cannot be read ({_reason(exc)}); draw it again") from None
        tags = frozenset({layer.upper()})
        if curves is None:
            pieces.append(Piece(None, tags, source))  # unsupported: an error if its layer is used
            continue
        if not curves:
            at = _flat(e.dxf.start) if kind == "LINE" else None
            raise CaseError(f"layer {layer}", f"zero-length {source}" + (f" at {fmt_point(at)}" if at is not None else "") + "; delete it")
        for c in curves:
            checked_coordinates(c, f"layer {layer}: {source}")
            if not c.length > 0:
                raise CaseError(f"layer {layer}", f"zero-length {source} at {fmt_point(c.at_fractions(np.array([0.0]))[0])}; delete it")
            pieces.append(Piece(c, tags, source))
    return Drawing(pieces, units, mm, meta, path, ignored, unitless=code not in DXF_UNITS, labels=labels)


def read_case(path, **options):
    """Read a case from a DXF drawing; see :func:`sectiondeform.io.drawing.case_from_drawing`."""
    from .drawing import case_from_drawing

    return case_from_drawing(read_drawing(path, options.get("chordal_error")), **options)


# --------------------------------------------------------------------------
# Writing


def _new_doc(units: str):
    ezdxf = require("ezdxf", "cad", "writing DXF")
    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = INSUNITS.get(units, 0)
    doc.header["$MEASUREMENT"] = 1
    return doc


def _layer(doc, name: str, color: int) -> None:
    if name not in doc.layers:
        doc.layers.add(name, color=color)


def _add_polyline(msp, curve: Polyline, attribs: dict) -> None:
    msp.add_lwpolyline(curve.vertices.tolist(), format="xy", dxfattribs=attribs)


def _add_arc(msp, curve: Arc, attribs: dict) -> None:
    a0, a1 = sorted((float(curve.start_deg), float(curve.end_deg)))
    if abs(a1 - a0) >= 360.0:
        msp.add_circle(curve.center.tolist(), float(curve.radius), dxfattribs=attribs)
    else:
        msp.add_arc(curve.center.tolist(), float(curve.radius), a0, a1, dxfattribs=attribs)


def _add_bspline(msp, curve: BSpline, attribs: dict) -> None:
    msp.add_open_spline(curve.control_points.tolist(), degree=int(curve.degree),
                        knots=_dxf_knots(curve.knots).tolist(), dxfattribs=attribs)


# Curve kind -> its native DXF entity; any other kind is written as a polyline.
_NATIVE = {"polyline": _add_polyline, "arc": _add_arc, "bspline": _add_bspline}


def _add_curve(msp, curve: Curve, layer: str, tol: float) -> None:
    """Add a curve as native entities; a kind without one as an LWPOLYLINE within ``tol``."""
    attribs = {"layer": layer}
    for part in curve.parts():
        add = _NATIVE.get(part.kind)
        if add is None:
            msp.add_lwpolyline(part.characteristic_points(tol).tolist(), format="xy", dxfattribs=attribs)
        else:
            add(msp, part, attribs)


def _dxf_knots(t: np.ndarray) -> np.ndarray:
    """Knots mapped onto [0, number of spans], whole numbers snapped exact.

    ezdxf writes knots with 10 decimals; uniform knots written as whole
    numbers survive exactly, and the reader maps them back onto [0, 1].
    """
    spans = max(len(np.unique(t)) - 1, 1)
    u = (t - t[0]) / (t[-1] - t[0]) * spans
    whole = np.round(u)
    return np.where(np.abs(u - whole) < 1e-9, whole, u)


def write_case(path, case) -> None:
    """Write a case as a DXF drawing, atomically: its curves as native entities on the layers of its dialect.

    Parameters
    ----------
    path : str or Path
    case : Problem
        Layers LOWER, UPPER, TARGET for ``section-case/1``; SUPPORT, TARGET,
        BODY-<name>-LOWER, -UPPER (-HOLE, AXIS) for ``section-case/2``
        (:func:`sectiondeform.io.layers.case_layers`).

    Raises
    ------
    CaseError
        A body name that cannot be part of a DXF layer name.
    """
    check_layer_names(case, dxf=True)
    doc = _new_doc(case.units)
    msp = doc.modelspace()
    tol = tolerance(case)
    for layer in case_layers(case):
        _layer(doc, layer.name, layer.dxf_color)
        for curve in (layer.data if layer.kind == "curves" else (layer.data,)):
            _add_curve(msp, curve, layer.name, tol)
    doc.header.custom_vars.append(META_KEY, json.dumps(case_meta(case), separators=(",", ":")))
    atomic_write(path, lambda tmp: doc.saveas(str(tmp)))


def fit_spline(points: np.ndarray, tol: float):
    """A clamped cubic B-spline within ``tol`` of every point of a polyline.

    Parameters
    ----------
    points : (N, 2) float64 ndarray
        N >= 2, units.
    tol : float
        Largest distance allowed from a point to the spline at its
        chord-length parameter, units.

    Returns
    -------
    control_points : (K, 2) float64 ndarray
    knots : (K + degree + 1,) float64 ndarray
    degree : int

    Examples
    --------
    >>> t = np.linspace(0, np.pi, 50)
    >>> cp, knots, k = fit_spline(np.column_stack((np.cos(t), np.sin(t))), 1e-3)
    >>> k, len(cp) < 50
    (3, True)
    """
    from scipy.interpolate import splev, splprep

    pts = np.asarray(points, dtype=np.float64)
    keep = np.concatenate(([True], np.hypot(*np.diff(pts, axis=0).T) > 0))
    pts = pts[keep]
    k = min(3, len(pts) - 1)
    u = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))))
    u /= u[-1]
    s = len(pts) * (0.25 * tol) ** 2
    for attempt in range(10):
        smooth = s / 4**attempt if attempt < 9 else 0.0
        tck, _ = splprep(pts.T, u=u, k=k, s=smooth)
        err = np.hypot(*(np.array(splev(u, tck)).T - pts).T).max()
        if err <= tol:
            break
    t, c, k = tck
    n = len(t) - k - 1
    return np.column_stack((c[0][:n], c[1][:n])), np.asarray(t, dtype=np.float64), int(k)


def _add_points(msp, pts: np.ndarray, layer: str, closed: bool) -> None:
    msp.add_lwpolyline(np.asarray(pts).tolist(), format="xy", close=closed, dxfattribs={"layer": layer})


def _add_mesh(msp, mesh, layer: str) -> None:
    corners = {"quad": 4, "triangle": 3, "triangle6": 3}[mesh.kind]
    pts = mesh.points
    for cell in mesh.cells:
        _add_points(msp, pts[cell[:corners]], layer, True)


def _add_layer(msp, layer: Layer, spline_tol: float | None) -> None:
    """One layer of a result; its deformed curves as fitted SPLINEs when ``spline_tol`` is given."""
    if layer.kind == "mesh":
        _add_mesh(msp, layer.data, layer.name)
    elif layer.kind == "rings":
        for ring in layer.data:
            _add_points(msp, ring, layer.name, True)
    elif spline_tol is not None and layer.splines:
        for part in layer.splines:
            cp, knots, k = fit_spline(part, spline_tol)
            msp.add_open_spline(cp.tolist(), degree=k, knots=knots.tolist(), dxfattribs={"layer": layer.name})
    else:
        _add_points(msp, layer.data, layer.name, layer.kind == "closed")


def write_result(path, result, spline: bool = False, chordal_error: float | None = None, case=None) -> None:
    """Write a deformed problem as a DXF drawing, atomically.

    Layers (:func:`sectiondeform.io.layers.result_layers`): for a
    ``section-result/1`` result DEFORMED (the deformed section), INITIAL
    (the section before), TARGET (the deformed lower curve, on the target),
    MESH_INITIAL and MESH_FINAL (one closed LWPOLYLINE per element, in
    element order); for a ``section-result/2`` one, per body
    DEFORMED-<name>-LOWER/-UPPER, INITIAL-<name>-LOWER/-UPPER,
    MESH-INITIAL-<name> and MESH-FINAL-<name>, and for a body with holes
    INITIAL-<name>-HOLE and DEFORMED-<name>-HOLE (one closed LWPOLYLINE per
    hole, never a spline).

    Parameters
    ----------
    path : str or Path
    result : Result
    spline : bool
        Write the deformed curves as SPLINEs fitted within ``chordal_error``
        (the one-body section as two, lower then upper) instead of polylines.
    chordal_error : float, optional
        Units; default 1e-4 of the deformed bodies' diagonal.
    case : Problem, optional
        The problem deformed: a ``section-result/2`` drawing draws its
        SUPPORT and TARGET too.

    Raises
    ------
    CaseError
        A case whose bodies are not the result's; a body name that cannot
        be part of a DXF layer name.
    """
    check_case(result, case)
    check_layer_names(result, dxf=True)
    spline_tol = None
    if spline:
        contours = np.concatenate([b.contour for b in result.bodies])
        spline_tol = chordal_error or DEFAULT_CHORDAL_FRACTION * float(np.hypot(*np.ptp(contours, axis=0)))
    doc = _new_doc(result.units)
    msp = doc.modelspace()
    for layer in result_layers(result, case):
        _layer(doc, layer.name, layer.dxf_color)
        _add_layer(msp, layer, spline_tol)
    atomic_write(path, lambda tmp: doc.saveas(str(tmp)))
