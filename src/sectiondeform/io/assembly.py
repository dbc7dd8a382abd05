"""Assemblies (``section-case/2``) in drawings: DXF and SVG in and out, meshes out.

Reading (:func:`assembly_from_drawing`)
---------------------------------------
A drawing is an assembly when it stores a ``section-case/2`` case or has a
``SUPPORT`` layer or a layer whose name starts with ``BODY-`` (DXF layer
names; SVG ids or classes, of the element or of a parent group; matched
without regard to case):

==========================  ==================================================
``SUPPORT``                 the curve the assembly rests on, one open chain
``TARGET``                  where the support goes (or ``target_arc=S``, an arc
                            as long as the support; the layer may be renamed
                            with ``layers={"target": NAME}``)
``BODY-<name>-LOWER``,      a body's lower and upper curves, chained and fitted
``BODY-<name>-UPPER``       exactly as a one-body drawing's LOWER and UPPER
``BODY-<name>``             a body as one closed contour; its lower curve is
                            the stretch of the contour lying on the support or
                            on the upper curves of bodies already found
``AXIS``                    optional: a straight line, the axis of revolution
==========================  ==================================================

Bodies given as contours are found from the support up: the first body (in
the order the case stores, else the drawing's) whose contour has a stretch
within the contact tolerance (``options.contact_tolerance``, default 1e-6
of the drawing's diagonal) of the support or of a found body's upper curve
is found next, its lower curve being that stretch. Of two bodies side by
side on the support the first found rests on the support only, the other
one's lower curve runs up their shared side. A stretch ends at a contour vertex
or piece end when the contact does; where the contact ends inside a segment
or an arc (a body overhanging its foundation), it ends at the last sample
in contact (samples at most 1/1024 of the drawing's diagonal apart), and
that piece is cut there (an arc into two arcs; a spline becomes a polyline
within the chordal error, reported). Every
body is oriented so that it lies on the left of its lower curve (its
contour counter-clockwise), the support so that the bodies lie on its left,
the target the same general way as the support (a file written here stores
the start points and restores them exactly).

Laws and materials come from the case data a writer of this package stored
in the drawing, or ``law=`` for every body (the command line's
``--area-ratio``). Once found, the bodies are checked as any assembly is
(:func:`sectiondeform.assembly.layout`).

Writing
-------
:func:`write_case_dxf` / :func:`write_case_svg`: layers (SVG path ids)
``SUPPORT``, ``TARGET``, ``BODY-<name>-LOWER``, ``BODY-<name>-UPPER`` (and
``AXIS`` for a body of revolution), as native curves, plus the case data
(format, name, options, laws, materials, start points) in the header
property / root attribute ``sectiondeform``: case -> drawing -> case gives
the same case. :func:`write_result_dxf` / :func:`write_result_svg`: per
body the layers (SVG group ids) ``INITIAL-<name>-LOWER``,
``INITIAL-<name>-UPPER``, ``DEFORMED-<name>-LOWER``,
``DEFORMED-<name>-UPPER``, ``MESH-INITIAL-<name>``, ``MESH-FINAL-<name>``,
and ``SUPPORT`` and ``TARGET`` when the case is given. :func:`write_mesh`:
one mesh of every body, cell data ``body`` = the body's tag (its index in
the case's ``bodies`` plus 1) and ``element`` (the element's number in its
body's mesh); field data ``{name: [tag, 2]}``, which Gmsh files keep as
named physical groups (VTU and VTK files keep no field data: tag t is
``bodies[t - 1]`` of the case and of the result JSON); Abaqus files get one
element set per body, named after it. Each body keeps its own nodes (a node
on a shared piece is written once per body).
"""

from __future__ import annotations

import difflib
import json
import math
import re
from dataclasses import replace

import numpy as np

from ..assembly import CONTACT_FRACTION, Assembly, Body, Revolution, material_from_json, revolution_from_json
from ..curves import DEFAULT_CHORDAL_FRACTION, Arc, Chain, Curve, Polyline
from ..errors import CaseError
from ..laws import law_from_json
from .chaining import fmt_point
from .pieces import Drawing, merge_runs

__all__ = [
    "is_assembly_drawing", "assembly_from_drawing", "assembly_from_json_and_drawing", "convert_assembly_units", "check_layer_names",
    "write_case_dxf", "write_case_svg", "write_result_dxf", "write_result_svg", "to_meshio", "write_mesh",
    "ASSEMBLY_FORMAT", "SUPPORT", "TARGET", "AXIS", "BODY",
]

ASSEMBLY_FORMAT = "section-case/2"
SUPPORT, TARGET, AXIS, BODY = "SUPPORT", "TARGET", "AXIS", "BODY-"
ROLE_SUFFIXES = ("-LOWER", "-UPPER")
ONE_BODY_LAYERS = ("LOWER", "UPPER", "CONTOUR")
# Drawing options that mean nothing for an assembly, and why.
NOT_FOR_ASSEMBLIES = {
    "split": "each body is its own layer, BODY-<name> (a closed contour) or BODY-<name>-LOWER and -UPPER",
    "split_tol": "each body is its own layer, BODY-<name> (a closed contour) or BODY-<name>-LOWER and -UPPER",
    "lower_side": "a body's lower curve is the stretch of its contour lying on the support or on other bodies",
}
SAMPLES = 1024
"""A contour is sampled at least this finely (fraction of the drawing's diagonal) when its lower curve is sought."""
DXF_COLORS = (1, 3, 4, 6, 2, 30, 140, 200)
SVG_COLORS = ("#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2", "#bcbd22")


def _say(report, line: str) -> None:
    if report is not None:
        report.append(line)


def is_assembly_drawing(drawing: Drawing) -> bool:
    """Whether a drawing holds an assembly: stored ``section-case/2`` data, a SUPPORT or a BODY-... layer."""
    if (drawing.meta or {}).get("format") == ASSEMBLY_FORMAT:
        return True
    return any(t == SUPPORT or t.startswith(BODY) for p in drawing.pieces for t in p.tags)


# --------------------------------------------------------------------------
# Reading


def _body_tags(pieces, known: dict) -> dict:
    """Body name (upper-cased) -> role (``lower``, ``upper``, ``contour``) -> pieces.

    ``known`` maps the upper-cased names the drawing stores to their spelling;
    a tag is first matched against those, then read as ``BODY-<name>-LOWER``,
    ``-UPPER``, or ``BODY-<name>``.
    """
    found: dict[str, dict[str, list]] = {}
    for p in pieces:
        roles = []
        for t in p.tags:
            if not t.startswith(BODY) or len(t) == len(BODY):
                continue
            rest = t[len(BODY):]
            role = None
            for suffix in ROLE_SUFFIXES:
                if rest.endswith(suffix) and (rest[: -len(suffix)] in known or rest not in known) and len(rest) > len(suffix):
                    role = (rest[: -len(suffix)], suffix[1:].lower())
            roles.append(role or (rest, "contour"))
        specific = [r for r in roles if r[1] != "contour"]
        contour = [r for r in roles if r[1] == "contour"]
        # An SVG path with id BODY-x-LOWER inside a group BODY-x is x's lower curve, not part of its contour.
        contour = [r for r in contour if r[0] not in {s[0] for s in specific}]
        chosen = specific or contour
        if len({r[0] for r in chosen}) > 1 or len(chosen) > 1:
            names = ", ".join(sorted(f"{BODY}{n}" + ("" if r == "contour" else f"-{r.upper()}") for n, r in chosen))
            raise CaseError(p.source, f"carries several body names ({names}); put each piece on one body's layer only")
        if chosen:
            name, role = chosen[0]
            found.setdefault(name, {}).setdefault(role, []).append(p)
    return found


def _hint(name: str, names) -> str:
    close = difflib.get_close_matches(name, list(names), n=1)
    return f" (did you mean {close[0]}?)" if close else ""


def _oriented_ccw(ring: Curve) -> Curve:
    return ring.reversed() if ring.green() < 0 else ring


def _subdivided(points: np.ndarray, step: float) -> np.ndarray:
    """A closed polyline (first = last) with every edge cut into pieces no longer than ``step``."""
    seg = np.diff(points, axis=0)
    n = np.maximum(np.ceil(np.hypot(*seg.T) / step).astype(int), 1)
    t = np.concatenate([np.arange(k) / k for k in n])
    start = np.repeat(points[:-1], n, axis=0)
    out = start + np.repeat(seg, n, axis=0) * t[:, None]
    return np.vstack((out, points[-1:]))


def _distance(points: np.ndarray, lines: list[np.ndarray], each: bool = False) -> np.ndarray:
    """Distance of each point to the nearest of the polylines, ``(n,)``; with ``each``, of point i to polyline i."""
    import shapely

    if each:
        return shapely.distance(shapely.points(points), np.array([shapely.LineString(ln) for ln in lines], dtype=object))
    if not lines:
        return np.full(len(points), np.inf)
    geom = shapely.MultiLineString([ln for ln in lines]) if len(lines) > 1 else shapely.LineString(lines[0])
    return shapely.distance(shapely.points(points), geom)


def _contact_run(ring_pts: np.ndarray, foundations: list[np.ndarray], tol: float, where: str):
    """The stretch of a closed sampled contour lying on the foundations: (start index, end index) or None.

    An edge lies on them when both its ends and its midpoint are within
    ``tol``. Indices are into ``ring_pts`` (closed, first = last); the
    stretch may wrap around the start.
    """
    d = _distance(ring_pts, foundations)
    near = d <= tol
    mids = 0.5 * (ring_pts[1:] + ring_pts[:-1])
    on = near[1:] & near[:-1]
    if on.any():
        on[on] &= _distance(mids[on], foundations) <= tol
    n = len(on)
    if not on.any():
        return None, float(d.min()), ring_pts[int(np.argmin(d))]
    if on.all():
        raise CaseError(where, "the whole contour lies on the support or on other bodies; give the body's curves on "
                               "BODY-<name>-LOWER and BODY-<name>-UPPER")
    first_off = int(np.argmin(on))
    rolled = np.roll(on, -first_off)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], rolled.astype(np.int8), [0]))))
    runs = [((a + first_off) % n, (b + first_off) % n) for a, b in edges.reshape(-1, 2)]
    if len(runs) > 1:
        places = ", ".join(fmt_point(ring_pts[a]) for a, _ in runs[:3])
        raise CaseError(where, f"the contour touches the support or other bodies in {len(runs)} separate stretches "
                               f"(starting at {places}); a lower curve is one stretch: close the gaps in the drawing, "
                               "or give the body's curves on BODY-<name>-LOWER and BODY-<name>-UPPER")
    return runs[0], 0.0, None


def _split_part(part: Curve, point: np.ndarray, chord: float, report, where: str) -> list[Curve]:
    """``part`` cut in two at ``point`` (a point on it)."""
    if isinstance(part, Polyline):
        v = part.vertices
        seg = np.diff(v, axis=0)
        dd = np.einsum("ij,ij->i", seg, seg)
        t = np.clip(np.einsum("ij,ij->i", point - v[:-1], seg) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
        i = int(np.argmin(np.hypot(*(v[:-1] + t[:, None] * seg - point).T)))
        tiny = 1e-12 * (1.0 + float(np.abs(point).max()))
        left = np.array(v[: i + 1]) if np.hypot(*(v[i] - point)) <= tiny else np.vstack((v[: i + 1], point))
        right = np.array(v[i + 1:]) if np.hypot(*(v[i + 1] - point)) <= tiny else np.vstack((point, v[i + 1:]))
        left[-1], right[0] = point, point
        return [Polyline(left), Polyline(right)]
    if isinstance(part, Arc):
        a0, a1 = float(part.start_deg), float(part.end_deg)
        am = math.degrees(math.atan2(point[1] - part.center[1], point[0] - part.center[0]))
        lo, hi = min(a0, a1), max(a0, a1)
        am = lo + (am - lo) % 360.0
        am = min(max(am, lo), hi)
        return [Arc(part.center, part.radius, a0, am), Arc(part.center, part.radius, am, a1)]
    _say(report, f"{where}: the lower curve ends inside a {part.kind}; that piece became a polyline within {chord:.3g}")
    return _split_part(Polyline(part.characteristic_points(chord)), point, chord, report, where)


def _cut_at(parts: list[Curve], point: np.ndarray, scale: float, chord: float, report, where: str) -> tuple[list, int]:
    """``parts`` of a closed ring with a joint at ``point``; the index of the part starting there."""
    starts = np.array([p.ends[0] for p in parts])
    d = np.hypot(*(starts - point).T)
    k = int(np.argmin(d))
    if d[k] <= 1e-9 * scale:
        return parts, k
    k = int(np.argmin(_distance(point[None, :].repeat(len(parts), axis=0), [p.discretise(chord)[0] for p in parts],
                                each=True)))
    end = parts[k].ends[1]
    if np.hypot(*(end - point)) <= 1e-9 * scale:
        return parts, (k + 1) % len(parts)
    parts = parts[:k] + _split_part(parts[k], point, chord, report, where) + parts[k + 1:]
    return parts, k + 1


def _joined(parts: list[Curve]) -> Curve:
    parts = merge_runs(parts)
    return parts[0] if len(parts) == 1 else Chain(tuple(parts))


def _split_contour(ring: Curve, run, pts: np.ndarray, scale: float, chord: float, report, where: str):
    """Lower (the run, in the ring's direction) and upper curves of a counter-clockwise ring."""
    parts = list(ring.parts())
    parts, _ = _cut_at(parts, pts[run[0]], scale, chord, report, where)
    parts, _ = _cut_at(parts, pts[run[1]], scale, chord, report, where)
    starts = np.array([p.ends[0] for p in parts])
    i = int(np.argmin(np.hypot(*(starts - pts[run[0]]).T)))
    parts = parts[i:] + parts[:i]
    j = int(np.argmin(np.hypot(*(np.array([p.ends[0] for p in parts]) - pts[run[1]]).T)))
    return _joined(parts[:j]), _joined(parts[j:])


def _options_check(o) -> None:
    for key, why in NOT_FOR_ASSEMBLIES.items():
        value = getattr(o, key)
        if value is not None and not (key == "lower_side" and value == "shorter"):
            raise CaseError(key, f"applies to a one-body drawing, not to an assembly; {why}")
    if o.layers is not None:
        other = [r for r in o.layers if r != "target"]
        if other:
            raise CaseError("layers", f"an assembly drawing takes only the target's layer ({other[0]!r} given); its other "
                                      "layers are SUPPORT, BODY-<name>-LOWER, BODY-<name>-UPPER or BODY-<name>")


def assembly_from_drawing(drawing: Drawing, options, report=None) -> Assembly:
    """Build an assembly from the pieces of a drawing (see the module docstring).

    Parameters
    ----------
    drawing : Drawing
    options : DrawingOptions
        ``split``, ``split_tol``, ``lower_side`` and roles of ``layers``
        other than ``target`` are refused; ``law`` is every body's law.
    report : list, optional
        Lines saying what was done are appended.

    Returns
    -------
    Assembly

    Raises
    ------
    CaseError
        One line naming the layer and what to fix: no SUPPORT, a body with
        no lower curve found, a lower layer without its upper, a body given
        twice, a stored body with no layer, a body without a law...
    GeometryError
        From the assembly's own checks (:func:`sectiondeform.assembly.layout`).
    """
    from .drawing import _Context, _from_layers, _inside_bbox, _orient_target, make_target_arc

    o = options
    _options_check(o)
    meta = dict(drawing.meta or {})
    stored = [b for b in meta.get("bodies") or [] if isinstance(b, dict) and isinstance(b.get("name"), str)]
    known = {b["name"].upper(): b["name"] for b in stored}
    pieces = list(drawing.pieces)
    if o.bbox is not None:
        pieces = _inside_bbox(pieces, o.bbox, report)
    curves = [p for p in pieces if p.curve is not None]
    if not curves:
        raise CaseError(str(drawing.path), "the drawing has no curves" + (" inside the bbox" if o.bbox is not None else ""))
    what = "layer" if drawing.path.suffix.lower() == ".dxf" else "id/class"
    tags = sorted({t for p in pieces for t in p.tags if t})
    one_body = [t for t in ONE_BODY_LAYERS if t in tags]
    if one_body:
        raise CaseError(f"{what} {drawing.labels.get(one_body[0], one_body[0])}", "a one-body layer in an assembly drawing; "
                        "put each body on BODY-<name>-LOWER and BODY-<name>-UPPER, or on BODY-<name> as a closed contour")
    ends = np.concatenate([np.vstack(p.curve.ends) for p in curves])
    diag = float(np.hypot(*np.ptp(ends, axis=0))) or 1.0
    target_name = (o.layers or {}).get("target", TARGET)
    ctx = _Context(what=what, roles={"support": SUPPORT, "target": target_name, "axis": AXIS},
                   tol=o.join_tol if o.join_tol is not None else 1e-6 * diag,
                   chord=o.chordal_error or DEFAULT_CHORDAL_FRACTION * diag, diag=diag, options=o)
    label = lambda tag: f"{what} {drawing.labels.get(tag, tag)}"  # noqa: E731

    if not ctx.has(pieces, "support"):
        raise CaseError(str(drawing.path), f"no {what} SUPPORT{_hint(SUPPORT, tags)}: draw the curve the assembly rests on "
                        f"there (the drawing has: {', '.join(tags) or 'none'})")
    support = ctx.chain(ctx.select(pieces, "support"), ctx.where("support"), False, report)

    found = _body_tags(pieces, known)
    used = {SUPPORT, target_name.upper(), AXIS}
    others = sorted({drawing.labels.get(t, t) for p in curves for t in p.tags}
                    - {drawing.labels.get(t, t) for p in curves for t in p.tags if t in used or t.startswith(BODY)})
    if others:
        _say(report, f"ignored: the curves on {what} {', '.join(others)} (not SUPPORT, TARGET, AXIS nor BODY-...)")
    if not found:
        raise CaseError(str(drawing.path), f"no body: put each on {what} BODY-<name>-LOWER and BODY-<name>-UPPER, or on "
                        f"BODY-<name> as a closed contour (the drawing has: {', '.join(tags)})")
    for tag in tags:  # a misspelt role suffix would silently become a body of its own
        rest = tag[len(BODY):] if tag.startswith(BODY) else None
        if rest and "-" in rest:
            stem, suffix = rest.rsplit("-", 1)
            missing = [r.upper() for r in ("lower", "upper") if r not in found.get(stem, {})] or ["LOWER", "UPPER"]
            close = difflib.get_close_matches(suffix, ["LOWER", "UPPER"], n=1, cutoff=0.6)
            if close and suffix not in ("LOWER", "UPPER") and stem in found and rest not in known:
                text = drawing.labels.get(tag, tag)
                raise CaseError(label(tag), f"matches no layer of the convention; did you mean "
                                            f"{text[: len(text) - len(suffix)]}{missing[0] if len(missing) == 1 else close[0]}?")
    for upper_name in [n for n in known if n not in found]:
        raise CaseError(str(drawing.path), f"body {known[upper_name]!r} of the case has no {what} "
                        f"BODY-{known[upper_name]}-LOWER/-UPPER nor BODY-{known[upper_name]}; draw it or remove it")
    first_piece = {n: min(pieces.index(p) for ps in found[n].values() for p in ps) for n in found}
    order = [n for n in known if n in found] + sorted((n for n in found if n not in known), key=first_piece.get)

    def spelled(n: str) -> str:
        if n in known:
            return known[n]
        for role in ("contour", "lower", "upper"):
            tag = f"{BODY}{n}" + ("" if role == "contour" else f"-{role.upper()}")
            if role in found[n] and tag in drawing.labels:
                text = drawing.labels[tag]
                return text[len(BODY):len(text) - (0 if role == "contour" else len(role) + 1)]
        return n

    stored_by = {b["name"].upper(): b for b in stored}
    curves_of: dict[str, tuple] = {}
    contours: dict[str, Curve] = {}
    for n in order:
        roles = found[n]
        lay = lambda r, n=n: f"{BODY}{spelled(n)}" + ("" if r == "contour" else f"-{r.upper()}")  # noqa: E731
        if "contour" in roles and ("lower" in roles or "upper" in roles):
            raise CaseError(f"{what} {lay('contour')}", f"body {spelled(n)!r} is also drawn on {lay('lower' if 'lower' in roles else 'upper')}; "
                            "give a body either as one closed contour or as its lower and upper curves")
        if "contour" in roles:
            where = f"{what} {lay('contour')}"
            ring = ctx.chain(_checked(roles["contour"], where), where, True, report)
            contours[n] = _oriented_ccw(ring)
            continue
        for r in ("lower", "upper"):
            if r not in roles:
                other = "upper" if r == "lower" else "lower"
                raise CaseError(f"{what} {lay(r)}", f"not found, though {lay(other)} is there; draw body {spelled(n)!r}'s "
                                f"{r} curve on it, or the whole body as a closed contour on {lay('contour')}")
        body_ctx = replace(ctx, roles={"lower": lay("lower"), "upper": lay("upper")})
        hint = {"lower_start": stored_by[n]["lower_start"]} if n in stored_by and "lower_start" in stored_by[n] else {}
        curves_of[n] = _from_layers(_checked(roles["lower"] + roles["upper"], f"{what} {lay('lower')}"), body_ctx, hint,
                                    drawing.path, report)

    # Contours: found from the support up, in order.
    fine = 0.25 * (_meta_contact(meta, o) or CONTACT_FRACTION * diag)
    tol = _meta_contact(meta, o) or CONTACT_FRACTION * _extent(support, curves_of, contours)
    foundations = [support.discretise(fine)[0]] + [c[1].discretise(fine)[0] for c in curves_of.values()]
    samples = {n: _subdivided(r.discretise(fine)[0], diag / SAMPLES) for n, r in contours.items()}
    waiting = [n for n in order if n in contours]
    while waiting:
        for n in waiting:
            where = f"{what} {BODY}{spelled(n)}"
            run, gap, at = _contact_run(samples[n], foundations, tol, where)
            if run is not None:
                lower, upper = _split_contour(contours[n], run, samples[n], diag, ctx.chord, report, where)
                curves_of[n] = (lower, upper)
                foundations.append(upper.discretise(fine)[0])
                _say(report, f"{where}: lower curve from {fmt_point(lower.ends[0])} to {fmt_point(lower.ends[1])} "
                             f"(length {lower.length:.6g})")
                waiting.remove(n)
                break
        else:
            n = waiting[0]
            _, gap, at = _contact_run(samples[n], foundations, tol, f"{what} {BODY}{spelled(n)}")
            raise CaseError(f"{what} {BODY}{spelled(n)}", f"no lower curve found: no stretch of the contour lies on the support "
                            f"or on another body (nearest gap {gap:.4g} at {fmt_point(at)}, contact tolerance {tol:.3g}); "
                            f"draw the body resting on one, or give its curves on {BODY}{spelled(n)}-LOWER and -UPPER")

    if o.simplify:
        curves_of = {n: (lo.simplified(o.simplify), up.simplified(o.simplify)) for n, (lo, up) in curves_of.items()}
        _say(report, f"simplified every body within {o.simplify:g}")

    support = _orient_support(support, [curves_of[n] for n in order], meta.get("support_start"))
    a, b = support.ends
    if ctx.has(pieces, "target") and o.target_arc is None:
        target = _orient_target(ctx.chain(ctx.select(pieces, "target"), ctx.where("target"), False, None), a, b,
                                meta.get("target_start"))
    elif o.target_arc is not None:
        inner = np.concatenate([c.discretise(ctx.chord)[0] for lo, up in curves_of.values() for c in (lo, up)])
        u = b - a
        side = 1.0 if (u[0] * (inner[:, 1].mean() - a[1]) - u[1] * (inner[:, 0].mean() - a[0])) >= 0 else -1.0
        _say(report, f"target: arc of length {support.length:.6g}, sagitta {o.target_arc:g}")
        target = make_target_arc(a, b, support.length, o.target_arc, side)
    elif o.target is not None:
        target = o.target
    else:
        raise CaseError(str(drawing.path), f"no target: draw it on {ctx.where('target')!r}, or give target_arc=SAGITTA "
                        "(an arc as long as the support)")

    revolution = _revolution(pieces, ctx, meta, report)
    axis = revolution.axis if revolution is not None else None
    bodies = []
    for i, n in enumerate(order):
        name = spelled(n)
        data = stored_by.get(n, {})
        if o.law is not None:
            law = o.law
        elif "law" in data:
            law = law_from_json(data["law"], f"bodies[{i}].law", axis)
        else:
            raise CaseError("law", f"body {name!r}: the drawing stores no law; give law=AreaRatio(R) (every body), "
                                   "or the bodies' laws in a case JSON")
        material = material_from_json(data.get("material"), f"bodies[{i}].material")
        lower, upper = curves_of[n]
        bodies.append(Body(name=name, lower=lower, upper=upper, law=law, material=material))
    case_options = {**(meta.get("options") or {}), **({"chordal_error": o.chordal_error} if o.chordal_error else {})}
    assembly = Assembly(support=support, target=target, bodies=tuple(bodies),
                        name=o.name or meta.get("name") or drawing.path.stem, units=drawing.units,
                        options=case_options, revolution=revolution)
    _say(report, f"assembly: {len(bodies)} bodies ({', '.join(b.name for b in bodies)}), resting order "
                 f"{' < '.join(bodies[k].name for k in assembly.layout.order)}")
    return convert_assembly_units(assembly, o.units, report) if o.units else assembly


JSON_BODY_KEYS = ("name", "law", "material", "note")
JSON_KEYS = ("format", "name", "units", "target", "revolution", "bodies", "options", "drawing", "note")


def assembly_from_json_and_drawing(path, data: dict, opts: dict, report=None) -> Assembly:
    """An assembly whose curves are a drawing's and whose laws and materials a case JSON gives.

    ``{"format": "section-case/2", "drawing": {"file": "layup.dxf", ...},
    "bodies": [{"name": "tread", "law": {...}, "material": {...}}, ...]}``:
    the bodies are the drawing's, matched by name (without regard to case),
    in the JSON's order; ``target``, ``revolution``, ``options``, ``name``
    and ``units`` (a relabelling, as for one body) of the JSON take
    precedence over the drawing's.

    Raises
    ------
    CaseError
        A key this form does not take (curves of a body: draw them), a body
        of the JSON with no layer, or the errors of :func:`assembly_from_drawing`.
    """
    from ..case import unknown_key
    from ..curves import curve_from_json
    from .drawing import DrawingOptions, read_drawing_file

    for key in data:
        if key not in JSON_KEYS and not str(key).startswith("x-") and key != "extra":
            raise unknown_key("", key, JSON_KEYS)
    bodies = data.get("bodies", [])
    if not isinstance(bodies, list):
        raise CaseError("bodies", f"expected a list of {{\"name\", \"law\", \"material\"}}, got {bodies!r}")
    for i, b in enumerate(bodies):
        if not isinstance(b, dict) or not isinstance(b.get("name"), str):
            raise CaseError(f"bodies[{i}]", "expected {\"name\": ..., \"law\": ...}; the curves are the drawing's")
        for key in b:
            if key not in JSON_BODY_KEYS and not str(key).startswith("x-"):
                hint = "; with a drawing, a body's curves are drawn on its layers" if key in ("lower", "upper") else ""
                raise CaseError(f"bodies[{i}].{key}", f"not taken here{hint}; use {', '.join(JSON_BODY_KEYS)}")
    revolution = revolution_from_json(data["revolution"]) if "revolution" in data else None
    axis = revolution.axis if revolution is not None else None
    if "target" in data:
        opts["target"] = curve_from_json(data["target"], "target")
    chordal = (data.get("options") or {}).get("chordal_error")
    drawing = read_drawing_file(path.parent / data["drawing"]["file"], opts.get("chordal_error") or chordal)
    meta = dict(drawing.meta or {})
    stored = {b["name"].upper(): b for b in meta.get("bodies") or [] if isinstance(b, dict) and isinstance(b.get("name"), str)}
    merged = []
    for i, b in enumerate(bodies):
        entry = {**stored.pop(b["name"].upper(), {}), **{k: v for k, v in b.items() if k in ("name", "law", "material")}}
        if "law" in b:
            law_from_json(b["law"], f"bodies[{i}].law", axis)  # checked here, to name the JSON's field
        merged.append(entry)
    meta["bodies"] = merged + list(stored.values())
    meta["format"] = ASSEMBLY_FORMAT
    meta["options"] = {**(meta.get("options") or {}), **(data.get("options") or {})}
    if revolution is not None:
        meta["revolution"] = revolution.to_json()
    if "name" in data:
        meta["name"] = data["name"]
    assembly = assembly_from_drawing(replace(drawing, meta=meta), DrawingOptions.from_mapping(opts), report)
    if "units" in data and "units" not in opts:
        assembly = assembly.replace(units=data["units"])
    return assembly


def _checked(pieces, where: str):
    bad = [p for p in pieces if p.curve is None]
    if bad:
        raise CaseError(where, f"unsupported entity {bad[0].source}; use LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE, SPLINE "
                               "or ELLIPSE (paths, lines, polylines, polygons, circles in SVG)")
    return pieces


def _meta_contact(meta: dict, o) -> float | None:
    value = (meta.get("options") or {}).get("contact_tolerance")
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) and value > 0 else None


def _extent(support: Curve, curves_of: dict, contours: dict) -> float:
    s = np.linspace(0.0, 1.0, 65)
    pts = [support.at_fractions(s)] + [c.at_fractions(s) for pair in curves_of.values() for c in pair]
    pts += [r.at_fractions(s) for r in contours.values()]
    return float(np.hypot(*np.ptp(np.concatenate(pts), axis=0))) or 1.0


def _orient_support(support: Curve, bodies, hint) -> Curve:
    """The support running so that the bodies lie on its left (or from the stored start point)."""
    s, e = support.ends
    if hint is not None:
        h = np.asarray(hint, dtype=np.float64)
        return support.reversed() if np.hypot(*(e - h)) < np.hypot(*(s - h)) else support
    pts = np.concatenate([c.at_fractions(np.linspace(0.0, 1.0, 33)) for pair in bodies for c in pair])
    c = pts.mean(axis=0)
    u = e - s
    return support.reversed() if u[0] * (c[1] - s[1]) - u[1] * (c[0] - s[0]) < 0 else support


def _revolution(pieces, ctx, meta: dict, report) -> Revolution | None:
    """The axis drawn on AXIS (a straight line), else the stored one, else None."""
    if ctx.has(pieces, "axis"):
        line = ctx.chain(ctx.select(pieces, "axis"), ctx.where("axis"), False, None)
        p, q = line.ends
        off = line.discretise(ctx.chord)[0]
        u = (q - p) / (np.hypot(*(q - p)) or 1.0)
        bend = np.abs((off - p) @ np.array([-u[1], u[0]])).max()
        if bend > ctx.tol:
            raise CaseError(ctx.where("axis"), f"the axis of revolution must be a straight line; it bends {bend:.4g} away "
                                               "from its chord")
        _say(report, f"revolution axis through {fmt_point(p)} and {fmt_point(q)}")
        return Revolution((tuple(p.tolist()), tuple(q.tolist())))
    if "revolution" in meta:
        return revolution_from_json(meta["revolution"])
    return None


def convert_assembly_units(assembly: Assembly, units: str, report=None) -> Assembly:
    """The assembly in other length units: curves, axis and lengths among its options scaled."""
    from .units import mm_per_unit

    if units == assembly.units:
        return assembly
    k = mm_per_unit(assembly.units, "units") / mm_per_unit(units, "units")
    o = assembly.options
    scaled = {key: getattr(o, key) * k for key in ("chordal_error", "element_size", "contact_tolerance")
              if getattr(o, key) is not None}
    rev = assembly.revolution
    if rev is not None:
        rev = Revolution(tuple(tuple(float(v) * k for v in p) for p in rev.axis))
    bodies = tuple(replace(b, lower=b.lower.scaled(k), upper=b.upper.scaled(k)) for b in assembly.bodies)
    _say(report, f"units: {assembly.units} -> {units} (x {k:g})")
    return assembly.replace(support=assembly.support.scaled(k), target=assembly.target.scaled(k), bodies=bodies,
                            units=units, options=o.replace(**scaled) if scaled else o, revolution=rev)


# --------------------------------------------------------------------------
# Writing


_DXF_BAD = re.compile(r'[<>/\\":;?*|=`]')


def check_layer_names(assembly: Assembly, dxf: bool) -> None:
    """Refuse body names that cannot name a layer: two equal but for case; for DXF, a forbidden character.

    Raises
    ------
    CaseError
        Naming the body (``bodies[i].name``) and what to change.
    """
    seen: dict[str, int] = {}
    for i, b in enumerate(assembly.bodies):
        if b.name.upper() in seen:
            raise CaseError(f"bodies[{i}].name", f"{b.name!r} differs from bodies[{seen[b.name.upper()]}]'s name only by "
                            "case; drawings match layer names without regard to case: rename one")
        seen[b.name.upper()] = i
        if dxf and (_DXF_BAD.search(b.name) or b.name != b.name.strip()):
            raise CaseError(f"bodies[{i}].name", f"{b.name!r} cannot be part of a DXF layer name (no <>/\\\":;?*|=` "
                            "characters, no leading or trailing spaces); rename the body")


def _case_meta(assembly: Assembly) -> dict:
    meta = {"format": ASSEMBLY_FORMAT, "name": assembly.name, "units": assembly.units,
            "options": assembly.options.to_json(), "support_start": assembly.support.start.tolist(),
            "target_start": assembly.target.start.tolist(), "bodies": []}
    if assembly.revolution is not None:
        meta["revolution"] = assembly.revolution.to_json()
    for b in assembly.bodies:
        entry = {"name": b.name, "law": b.law.to_json(), "lower_start": b.lower.start.tolist()}
        if b.material != "{}":
            entry["material"] = b.material_data
        meta["bodies"].append(entry)
    return meta


def _case_layers(assembly: Assembly):
    """(layer, colour index, curve) of every curve of an assembly case."""
    out = [(SUPPORT, 8, assembly.support), (TARGET, 5, assembly.target)]
    for i, b in enumerate(assembly.bodies):
        color = DXF_COLORS[i % len(DXF_COLORS)]
        out += [(f"{BODY}{b.name}-LOWER", color, b.lower), (f"{BODY}{b.name}-UPPER", color, b.upper)]
    if assembly.revolution is not None:
        out.append((AXIS, 9, Polyline(np.array(assembly.revolution.axis, dtype=np.float64))))
    return out


def _tolerance(assembly: Assembly) -> float:
    return assembly.options.chordal_error or DEFAULT_CHORDAL_FRACTION * (assembly.size or 1.0)


def write_case_dxf(path, assembly: Assembly) -> None:
    """Write an assembly case as a DXF drawing (see the module docstring), atomically."""
    from .dxf import META_KEY, _add_curve, _layer, _new_doc
    from .json import atomic_write

    check_layer_names(assembly, dxf=True)
    doc = _new_doc(assembly.units)
    msp = doc.modelspace()
    tol = _tolerance(assembly)
    for name, color, curve in _case_layers(assembly):
        _layer(doc, name, color)
        _add_curve(msp, curve, name, tol)
    doc.header.custom_vars.append(META_KEY, json.dumps(_case_meta(assembly), separators=(",", ":")))
    atomic_write(path, lambda tmp: doc.saveas(str(tmp)))


def write_case_svg(path, assembly: Assembly) -> None:
    """Write an assembly case as an SVG drawing (path ids as the DXF layers), atomically."""
    from xml.sax.saxutils import quoteattr

    from .json import atomic_write
    from .svg import _curve_d, _svg

    check_layer_names(assembly, dxf=False)
    tol = _tolerance(assembly)
    body, pts = [], []
    colors = {SUPPORT: "#555555", TARGET: "#1f77b4", AXIS: "#999999"}
    for i, b in enumerate(assembly.bodies):
        for side in ("LOWER", "UPPER"):
            colors[f"{BODY}{b.name}-{side}"] = SVG_COLORS[i % len(SVG_COLORS)]
    for name, _, curve in _case_layers(assembly):
        if name != AXIS:
            pts.append(curve.discretise(tol)[0])
        body.append(f'<path id={quoteattr(name)} stroke="{colors[name]}" d="{_curve_d(curve, tol)}"/>')
    text = _svg(np.concatenate(pts), assembly.units, body, _case_meta(assembly))
    atomic_write(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))


def _result_layers(result, case: Assembly | None):
    """(layer, colour index, kind, points) of an assembly result: kind "open", "closed" or "mesh"."""
    out = []
    if case is not None:
        tol = _tolerance(case)
        out += [(SUPPORT, 8, "open", case.support.discretise(tol)[0]), (TARGET, 5, "open", case.target.discretise(tol)[0])]
    for i, b in enumerate(result.bodies):
        color = DXF_COLORS[i % len(DXF_COLORS)]
        out += [
            (f"MESH-INITIAL-{b.name}", 9, "mesh", b.initial_mesh),
            (f"MESH-FINAL-{b.name}", color, "mesh", b.final_mesh),
            (f"INITIAL-{b.name}-LOWER", 8, "open", b.initial_lower),
            (f"INITIAL-{b.name}-UPPER", 8, "open", b.initial_upper),
            (f"DEFORMED-{b.name}-LOWER", color, "open", b.lower),
            (f"DEFORMED-{b.name}-UPPER", color, "open", b.upper),
        ]
    return out


def _check_case(result, case) -> None:
    if case is None:
        return
    if not isinstance(case, Assembly) or [b.name for b in case.bodies] != [b.name for b in result.bodies]:
        raise CaseError("case", "is not the assembly this result was deformed from (its bodies differ); give that case")


def write_result_dxf(path, result, case: Assembly | None = None) -> None:
    """Write a deformed assembly as a DXF drawing (see the module docstring), atomically.

    Parameters
    ----------
    path : str or Path
    result : AssemblyResult
    case : Assembly, optional
        The case deformed: its support and target are drawn too.
    """
    from .dxf import _layer, _new_doc
    from .json import atomic_write

    _check_case(result, case)
    check_layer_names(result, dxf=True)
    doc = _new_doc(result.units)
    msp = doc.modelspace()
    for name, color, kind, data in _result_layers(result, case):
        _layer(doc, name, color)
        attribs = {"layer": name}
        if kind == "mesh":
            corners = {"quad": 4, "triangle": 3, "triangle6": 3}[data.kind]
            for cell in data.cells:
                msp.add_lwpolyline(data.points[cell[:corners]].tolist(), format="xy", close=True, dxfattribs=attribs)
        else:
            msp.add_lwpolyline(np.asarray(data).tolist(), format="xy", close=kind == "closed", dxfattribs=attribs)
    atomic_write(path, lambda tmp: doc.saveas(str(tmp)))


def write_result_svg(path, result, case: Assembly | None = None) -> None:
    """Write a deformed assembly as SVG: one group per DXF layer of :func:`write_result_dxf`, same ids, atomically."""
    from xml.sax.saxutils import quoteattr

    from .json import atomic_write
    from .svg import _poly_d, _svg

    _check_case(result, case)
    check_layer_names(result, dxf=False)
    palette = {8: "#777777", 9: "#bbbbbb", 5: "#1f77b4"}
    body, pts = [], []
    for name, color, kind, data in _result_layers(result, case):
        stroke = palette.get(color) or SVG_COLORS[DXF_COLORS.index(color) % len(SVG_COLORS)]
        if kind == "mesh":
            corners = {"quad": 4, "triangle": 3, "triangle6": 3}[data.kind]
            d = " ".join(_poly_d(data.points[c[:corners]], True) for c in data.cells)
        else:
            d = _poly_d(np.asarray(data), kind == "closed")
            pts.append(np.asarray(data))
        body.append(f'<g id={quoteattr(name)} stroke="{stroke}"><path d="{d}"/></g>')
    text = _svg(np.concatenate(pts), result.units, body, {"units": result.units, "name": result.name,
                                                           "format": "section-result/2"})
    atomic_write(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))


def to_meshio(result, which: str = "final"):
    """One mesh of every body of an assembly result as one :class:`meshio.Mesh`.

    Parameters
    ----------
    result : AssemblyResult
    which : str
        ``"final"`` or ``"initial"``.

    Returns
    -------
    meshio.Mesh
        Points ``(N, 3)`` (z = 0), the bodies' nodes one after the other in
        the case's order; one cell block per body; cell data ``body`` (tag
        = index in ``bodies`` + 1) and ``element`` (number in the body's
        mesh); point data ``initial``/``final`` and ``displacement`` when
        every body's two meshes have the same nodes; field data
        ``{name: [tag, 2]}``.
    """
    from ..errors import require

    meshio = require("meshio", "cad", "writing meshes")
    if which not in ("final", "initial"):
        raise CaseError("mesh", f"unknown mesh {which!r}; use final or initial")
    blocks, pts, other, tags, numbers = [], [], [], [], []
    offset = 0
    same = all(b.initial_mesh.points.shape == b.final_mesh.points.shape for b in result.bodies)
    for i, b in enumerate(result.bodies):
        mesh, twin = (b.final_mesh, b.initial_mesh) if which == "final" else (b.initial_mesh, b.final_mesh)
        blocks.append((mesh.kind, np.asarray(mesh.cells, dtype=np.int64) + offset))
        pts.append(mesh.points)
        if same:
            other.append(twin.points)
        tags.append(np.full(len(mesh.cells), i + 1, dtype=np.int64))
        numbers.append(np.arange(len(mesh.cells), dtype=np.int64))
        offset += len(mesh.points)
    xyz = lambda p: np.column_stack((p, np.zeros(len(p))))  # noqa: E731
    points = np.concatenate(pts)
    point_data = {}
    if same:
        twin = np.concatenate(other)
        point_data["initial" if which == "final" else "final"] = xyz(twin)
        point_data["displacement"] = xyz(points - twin if which == "final" else twin - points)
    field_data = {b.name: np.array([i + 1, 2], dtype=np.int64) for i, b in enumerate(result.bodies)}
    return meshio.Mesh(xyz(points), blocks, point_data=point_data, cell_data={"body": tags, "element": numbers},
                       field_data=field_data)


def _one_block_per_type(mesh, meshio):
    """The mesh with the blocks of one cell type joined (cell data joined alike; ``body`` still tags each cell).

    XDMF writes blocks of several types as one *Mixed* topology, which
    meshio 5.3 cannot read back for quadratic triangles: an assembly whose
    bodies share one element type is written as one block instead.
    """
    types = [c.type for c in mesh.cells]
    if len(set(types)) != 1 or len(types) == 1:
        return mesh
    cells = [(types[0], np.concatenate([c.data for c in mesh.cells]))]
    data = {name: [np.concatenate(blocks)] for name, blocks in mesh.cell_data.items()}
    return meshio.Mesh(mesh.points, cells, point_data=mesh.point_data, cell_data=data)


def write_mesh(path, result, which: str = "final", cell_data: dict | None = None) -> None:
    """Write one mesh of every body of an assembly result (.vtu, .vtk, .msh, .xdmf, .inp), atomically.

    Gmsh files carry ``gmsh:physical`` = the body tag, named by the field
    data; Abaqus files carry one element set per body, named after it.
    ``cell_data``: more cell data, name to one array per body (one row per
    element of its mesh); not in Abaqus files.

    Raises
    ------
    CaseError
        For an unknown extension.
    """
    from pathlib import Path

    from ..errors import require
    from .json import atomic_write
    from .meshes import FORMATS, _teach_meshio_plane_strain, writer_options

    meshio = require("meshio", "cad", "writing meshes")
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in FORMATS:
        raise CaseError(str(path), f"unknown mesh format {ext!r}; use one of {', '.join(FORMATS)}")
    fmt = FORMATS[ext]
    mesh = to_meshio(result, which)
    for name, blocks in (cell_data or {}).items() if fmt != "abaqus" else ():
        mesh.cell_data[name] = [np.asarray(v) for v in blocks]
    kwargs = writer_options(fmt)
    if fmt == "xdmf":
        mesh = _one_block_per_type(mesh, meshio)
    if fmt == "gmsh":
        mesh.cell_data["gmsh:physical"] = [t.astype(np.int32) for t in mesh.cell_data["body"]]
        mesh.cell_data["gmsh:geometrical"] = [t.astype(np.int32) for t in mesh.cell_data["body"]]
        counts = [len(b.final_mesh.points if which == "final" else b.initial_mesh.points) for b in result.bodies]
        mesh.point_data["gmsh:dim_tags"] = np.column_stack((np.full(sum(counts), 2), np.repeat(np.arange(1, len(counts) + 1), counts)))
    if fmt == "abaqus":
        sets = {}
        for i, b in enumerate(result.bodies):
            sets[re.sub(r"[^A-Za-z0-9_]", "_", b.name)] = [np.arange(len(c.data)) if k == i else np.array([], dtype=np.int64)
                                                          for k, c in enumerate(mesh.cells)]
        mesh = meshio.Mesh(mesh.points, mesh.cells, cell_sets=sets)

    def write(tmp):
        meshio.write(str(tmp), mesh, file_format=fmt, **kwargs)
        if fmt == "abaqus":
            _teach_meshio_plane_strain()
            tmp.write_text(re.sub(r"(?i)type\s*=\s*CAX4P\b", "type=CPE4", tmp.read_text()))

    atomic_write(path, write)
