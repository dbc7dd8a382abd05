"""The bodies of a ``section-case/2`` drawing: found on their layers or as contours resting on each other.

A drawing holds a ``section-case/2`` problem when it stores a ``section-case/2`` case or has a
``SUPPORT`` layer or a layer whose name starts with ``BODY-`` (DXF layer
names; SVG ids or classes, of the element or of a parent group; matched
without regard to case):

==========================  ==================================================
``SUPPORT``                 the curve the bodies rest on, one open chain
``TARGET``                  where the support goes (or ``target_arc=S``, an arc
                            as long as the support; the layer may be renamed
                            with ``layers={"target": NAME}``)
``BODY-<name>-LOWER``,      a body's lower and upper curves, chained and fitted
``BODY-<name>-UPPER``       exactly as a one-body drawing's LOWER and UPPER
``BODY-<name>``             a body as one closed contour; its lower curve is
                            the stretch of the contour lying on the support or
                            on the upper curves of bodies already found (closed
                            contours inside it are its holes)
``BODY-<name>-HOLE``        optional: the body's holes, closed contours inside
                            it (:mod:`.holes`; so are the closed contours of a
                            layer the case does not read lying inside a body)
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
(:func:`sectiondeform.layout.layout`).
"""

from __future__ import annotations

import difflib
import math
from dataclasses import replace

import numpy as np

from ..curves import Arc, Chain, Curve, Polyline
from ..errors import CaseError
from ..layout import CONTACT_FRACTION
from ..problem import Revolution
from .case import revolution_from_json
from .chaining import fmt_point
from .holes import closed_loops, loops_beside, outer_and_holes
from .layers import AXIS, BODY, HOLE_SUFFIX, ONE_BODY_LAYERS, RIGID, ROLE_SUFFIXES, SUPPORT
from .outline import Context, curves_from_layers, say
from .pieces import merge_runs

__all__ = ["bodies_from_drawing", "revolution_from_drawing", "check_options", "stored_bodies", "unused_body_pieces",
           "NOT_FOR_BODIES"]

# Drawing options that mean nothing for a section-case/2 drawing, and why.
NOT_FOR_BODIES = {
    "split": "each body is its own layer, BODY-<name> (a closed contour) or BODY-<name>-LOWER and -UPPER",
    "split_tol": "each body is its own layer, BODY-<name> (a closed contour) or BODY-<name>-LOWER and -UPPER",
    "lower_side": "a body's lower curve is the stretch of its contour lying on the support or on other bodies",
}
SAMPLES = 1024
"""A contour is sampled at least this finely (fraction of the drawing's diagonal) when its lower curve is sought."""


def _body_tags(pieces, known: dict) -> dict:
    """Body name (upper-cased) -> role (``lower``, ``upper``, ``hole``, ``contour``) -> pieces.

    ``known`` maps the upper-cased names the drawing stores to their spelling;
    a tag is first matched against those, then read as ``BODY-<name>-LOWER``,
    ``-UPPER``, ``-HOLE``, or ``BODY-<name>``.
    """
    found: dict[str, dict[str, list]] = {}
    for p in pieces:
        roles = []
        for t in p.tags:
            if not t.startswith(BODY) or len(t) == len(BODY):
                continue
            rest = t[len(BODY):]
            role = None
            for suffix in (*ROLE_SUFFIXES, HOLE_SUFFIX):
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
    say(report, f"{where}: the lower curve ends inside a {part.kind}; that piece became a polyline within {chord:.3g}")
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


def check_options(o) -> None:
    """Refuse the drawing options that mean nothing for a ``section-case/2`` drawing, saying why."""
    for key, why in NOT_FOR_BODIES.items():
        value = getattr(o, key)
        if value is not None and not (key == "lower_side" and value == "shorter"):
            raise CaseError(key, f"applies to a one-body drawing, not to one of several bodies; {why}")
    if o.layers is not None:
        other = [r for r in o.layers if r != "target"]
        if other:
            raise CaseError("layers", f"a drawing of bodies takes only the target's layer ({other[0]!r} given); its other "
                                      "layers are SUPPORT, BODY-<name>-LOWER, BODY-<name>-UPPER or BODY-<name>")


def stored_bodies(meta: dict) -> dict:
    """The bodies' case data a drawing stores, by upper-cased name."""
    return {b["name"].upper(): b for b in meta.get("bodies") or [] if isinstance(b, dict) and isinstance(b.get("name"), str)}


def bodies_from_drawing(pieces, ctx: Context, drawing, meta: dict, report=None) -> tuple[Curve, list]:
    """The support and the bodies' curves of a ``section-case/2`` drawing (see the module docstring).

    Parameters
    ----------
    pieces : list of Piece
    ctx : Context
        Roles ``support``, ``target`` and ``axis``.
    drawing : Drawing
    meta : dict
        The case data the drawing stores (bodies' names, start points...).
    report : list, optional
        Lines saying what was done are appended.

    Returns
    -------
    support : Curve
        Oriented so that the bodies lie on its left.
    bodies : list of (str, Curve, Curve)
        Each body's name, lower and upper curves, in the stored order, then the drawing's.
    holes : dict
        Body name -> list of :class:`~.holes.Loop`, the holes drawn on the
        body's own layers (``BODY-<name>-HOLE``, or inside its contour on
        ``BODY-<name>``), not yet checked against the body.

    Raises
    ------
    CaseError
        One line naming the layer and what to fix: no SUPPORT, a body with
        no lower curve found, a lower layer without its upper, a body given
        twice, a stored body with no layer...
    """
    stored = stored_bodies(meta)
    known = {n: b["name"] for n, b in stored.items()}
    tags = sorted({t for p in pieces for t in p.tags if t})
    one_body = [t for t in ONE_BODY_LAYERS if t in tags]
    if one_body:
        raise CaseError(f"{ctx.what} {drawing.labels.get(one_body[0], one_body[0])}", "a one-body layer in a drawing of "
                        "bodies; put each body on BODY-<name>-LOWER and BODY-<name>-UPPER, or on BODY-<name> as a closed contour")
    if not ctx.has(pieces, "support"):
        raise CaseError(str(drawing.path), f"no {ctx.what} SUPPORT{_hint(SUPPORT, tags)}: draw the curve the bodies rest on "
                        f"there (the drawing has: {', '.join(tags) or 'none'})")
    support = ctx.chain(ctx.select(pieces, "support"), ctx.where("support"), False, report)
    found = _body_tags(pieces, known)
    _check_tags(found, known, tags, ctx, drawing)
    first_piece = {n: min(pieces.index(p) for ps in found[n].values() for p in ps) for n in found}
    order = [n for n in known if n in found] + sorted((n for n in found if n not in known), key=first_piece.get)
    names = {n: _spelled(n, found, known, drawing.labels) for n in order}
    curves_of, contours, holes = _drawn(found, order, names, ctx, stored, drawing.path, report)
    _rest(support, curves_of, contours, order, names, ctx, meta, report)
    support = _orient_support(support, [curves_of[n] for n in order], meta.get("support_start"))
    return support, [(names[n], *curves_of[n]) for n in order], {names[n]: h for n, h in holes.items()}


def _check_tags(found: dict, known: dict, tags, ctx: Context, drawing) -> None:
    """Refuse a drawing without bodies, a misspelt suffix, a stored body not drawn."""
    what = ctx.what
    if not found:
        raise CaseError(str(drawing.path), f"no body: put each on {what} BODY-<name>-LOWER and BODY-<name>-UPPER, or on "
                        f"BODY-<name> as a closed contour (the drawing has: {', '.join(tags)})")
    for tag in tags:  # a misspelt role suffix would silently become a body of its own
        rest = tag[len(BODY):] if tag.startswith(BODY) else None
        if rest and "-" in rest:
            stem, suffix = rest.rsplit("-", 1)
            missing = [r.upper() for r in ("lower", "upper") if r not in found.get(stem, {})] or ["LOWER", "UPPER"]
            close = difflib.get_close_matches(suffix, ["LOWER", "UPPER"], n=1, cutoff=0.6)
            if close and suffix not in ("LOWER", "UPPER", HOLE_SUFFIX[1:]) and stem in found and rest not in known:
                text = drawing.labels.get(tag, tag)
                raise CaseError(f"{what} {text}", f"matches no layer of the convention; did you mean "
                                                  f"{text[: len(text) - len(suffix)]}{missing[0] if len(missing) == 1 else close[0]}?")
    for upper_name in [n for n in known if n not in found]:
        raise CaseError(str(drawing.path), f"body {known[upper_name]!r} of the case has no {what} "
                        f"BODY-{known[upper_name]}-LOWER/-UPPER nor BODY-{known[upper_name]}; draw it or remove it")


def unused_body_pieces(pieces, ctx: Context) -> list:
    """The pieces of a drawing of bodies that no curve of the problem comes from.

    Those on no layer of the convention (``SUPPORT``, ``AXIS``, ``BODY-...``,
    the target's), and the target's when ``target_arc`` replaces it.
    """
    used = {SUPPORT, AXIS}
    if ctx.has(pieces, "target") and ctx.options.target_arc is None:
        used.add(ctx.roles["target"].upper())
    return [p for p in pieces if not any(t in used or (t.startswith(BODY) and len(t) > len(BODY))
                                         or (t.startswith(RIGID) and len(t) > len(RIGID)) for t in p.tags)]


def rigid_from_drawing(pieces, ctx: Context, drawing, meta: dict, report=None) -> tuple:
    """The rigid parts of a drawing: each ``RIGID-<name>`` layer chained into a closed contour.

    The travel and friction are the stored case data's (``meta["rigid"]``,
    by name), else none and 0.

    Returns
    -------
    tuple of Rigid
        In the stored order, then the drawing's.
    """
    from ..problem import Rigid

    stored = {r["name"].upper(): r for r in meta.get("rigid") or [] if isinstance(r, dict) and isinstance(r.get("name"), str)}
    tags = [t for p in pieces for t in p.tags if t.startswith(RIGID) and len(t) > len(RIGID)]
    order = [n for n in stored if f"{RIGID}{n}" in tags] + sorted(dict.fromkeys(t[len(RIGID):] for t in tags
                                                                          if t[len(RIGID):] not in stored))
    out = []
    for n in order:
        where = f"{ctx.what} {drawing.labels.get(RIGID + n, RIGID + n)}"
        contour = ctx.chain([p for p in pieces if RIGID + n in p.tags], where, True, report)
        data = stored.get(n, {})
        out.append(Rigid(data.get("name", drawing.labels.get(RIGID + n, RIGID + n)[len(RIGID):]), contour,
                         tuple(data.get("travel", (0.0, 0.0))), data.get("friction", 0.0)))
    return tuple(out)


def _spelled(n: str, found: dict, known: dict, labels: dict) -> str:
    """A body's name as the case or the drawing spells it (tags are upper-cased)."""
    if n in known:
        return known[n]
    for role in ("contour", "lower", "upper", "hole"):
        tag = f"{BODY}{n}" + ("" if role == "contour" else f"-{role.upper()}")
        if role in found[n] and tag in labels:
            text = labels[tag]
            return text[len(BODY):len(text) - (0 if role == "contour" else len(role) + 1)]
    return n


def _drawn(found: dict, order, names: dict, ctx: Context, stored: dict, path, report) -> tuple[dict, dict]:
    """The bodies drawn on their -LOWER and -UPPER layers (their curves), those drawn as contours (their rings), their holes."""
    what = ctx.what
    curves_of: dict[str, tuple] = {}
    contours: dict[str, Curve] = {}
    holes: dict[str, list] = {}
    for n in order:
        roles = dict(found[n])
        lay = lambda r, n=n: f"{BODY}{names[n]}" + ("" if r == "contour" else f"-{r.upper()}")  # noqa: E731
        if "hole" in roles:
            hole_pieces = roles.pop("hole")
            if not roles:
                raise CaseError(f"{what} {lay('hole')}", f"holes of body {names[n]!r}, which is not drawn; draw it on "
                                f"{lay('contour')} (a closed contour) or on {lay('lower')} and {lay('upper')}")
            holes[n] = closed_loops(_checked(hole_pieces, f"{what} {lay('hole')}"), f"{what} {lay('hole')}", ctx, report)
        if "contour" in roles and ("lower" in roles or "upper" in roles):
            raise CaseError(f"{what} {lay('contour')}", f"body {names[n]!r} is also drawn on {lay('lower' if 'lower' in roles else 'upper')}; "
                            "give a body either as one closed contour or as its lower and upper curves")
        if "contour" in roles:
            where = f"{what} {lay('contour')}"
            split = outer_and_holes(_checked(roles["contour"], where), where, ctx, report)
            if split is not None:
                holes[n] = split[1] + holes.get(n, [])
            ring = split[0] if split is not None else ctx.chain(roles["contour"], where, True, report)
            contours[n] = _oriented_ccw(ring)
            continue
        for r in ("lower", "upper"):
            if r not in roles:
                other = "upper" if r == "lower" else "lower"
                raise CaseError(f"{what} {lay(r)}", f"not found, though {lay(other)} is there; draw body {names[n]!r}'s "
                                f"{r} curve on it, or the whole body as a closed contour on {lay('contour')}")
        for r in ("lower", "upper"):  # a hole drawn beside the body's curve, on its layer
            roles[r], beside = loops_beside(_checked(roles[r], f"{what} {lay(r)}"), f"{what} {lay(r)}", ctx)
            holes[n] = holes.get(n, []) + beside
        body_ctx = replace(ctx, roles={"lower": lay("lower"), "upper": lay("upper")})
        hint = {"lower_start": stored[n]["lower_start"]} if "lower_start" in stored.get(n, {}) else {}
        curves_of[n] = curves_from_layers(_checked(roles["lower"] + roles["upper"], f"{what} {lay('lower')}"), body_ctx,
                                          hint, path, report)
    return curves_of, contours, holes


def _rest(support: Curve, curves_of: dict, contours: dict, order, names: dict, ctx: Context, meta: dict, report) -> None:
    """Find the lower curves of the bodies drawn as contours, from the support up; add them to ``curves_of``."""
    o, diag = ctx.options, ctx.diag
    fine = 0.25 * (_meta_contact(meta, o) or CONTACT_FRACTION * diag)
    tol = _meta_contact(meta, o) or CONTACT_FRACTION * _extent(support, curves_of, contours)
    foundations = [support.discretise(fine)[0]] + [c[1].discretise(fine)[0] for c in curves_of.values()]
    samples = {n: _subdivided(r.discretise(fine)[0], diag / SAMPLES) for n, r in contours.items()}
    waiting = [n for n in order if n in contours]
    while waiting:
        for n in waiting:
            where = f"{ctx.what} {BODY}{names[n]}"
            run, gap, at = _contact_run(samples[n], foundations, tol, where)
            if run is not None:
                lower, upper = _split_contour(contours[n], run, samples[n], diag, ctx.chord, report, where)
                curves_of[n] = (lower, upper)
                foundations.append(upper.discretise(fine)[0])
                say(report, f"{where}: lower curve from {fmt_point(lower.ends[0])} to {fmt_point(lower.ends[1])} "
                            f"(length {lower.length:.6g})")
                waiting.remove(n)
                break
        else:
            n = waiting[0]
            where = f"{ctx.what} {BODY}{names[n]}"
            _, gap, at = _contact_run(samples[n], foundations, tol, where)
            raise CaseError(where, f"no lower curve found: no stretch of the contour lies on the support "
                            f"or on another body (nearest gap {gap:.4g} at {fmt_point(at)}, contact tolerance {tol:.3g}); "
                            f"draw the body resting on one, or give its curves on {BODY}{names[n]}-LOWER and -UPPER")


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


def revolution_from_drawing(pieces, ctx, meta: dict, report) -> Revolution | None:
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
        say(report, f"revolution axis through {fmt_point(p)} and {fmt_point(q)}")
        return Revolution((tuple(p.tolist()), tuple(q.tolist())))
    if "revolution" in meta:
        return revolution_from_json(meta["revolution"])
    return None

