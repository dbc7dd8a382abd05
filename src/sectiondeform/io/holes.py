"""The holes of a drawing's bodies: closed contours inside a body's contour.

A hollow profile (a bulb seal, a door seal, a hose) is drawn as its outer
contour and, inside it, one closed contour per hole. A drawing gives a
body's holes in any of three ways (DXF layer names, SVG ids or classes,
matched without regard to case; :mod:`.layers`):

- on the body's hole layer ``BODY-<name>-HOLE`` (the layer the writers
  use): every closed contour there is a hole of body ``<name>``;
- on the body's contour layer ``BODY-<name>``, beside its outer contour:
  the contours inside the outer one; on its curve layers (``UPPER``,
  ``BODY-<name>-UPPER``, ...), beside the open curve: the closed contours;
- on a layer the case does not read (``HOLE``, ``0``, ...): a closed
  contour lying inside a body's contour is a hole of that body. The paper's
  one body on ``LOWER`` and ``UPPER`` takes its holes this way, and is then
  read as a ``section-case/2`` problem (the dialect that holds holes).

Every hole is checked as a case's holes are
(:func:`sectiondeform.layout.check_holes`): a simple closed curve strictly
inside its body, apart from its contour and from its other holes. A closed
contour that crosses or touches a body's contour, or an open curve on a
hole layer, is refused in one line naming the layer and the entity. The
holes read are reported, per body (``read 2 holes in body 'seal'``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..curves import Curve
from ..errors import CaseError
from ..layout import CONTACT_FRACTION, check_holes
from .chaining import connect, fmt_point
from .outline import Context, say

__all__ = ["Loop", "closed_loops", "outer_and_holes", "loops_beside", "body_holes"]


@dataclass(frozen=True, eq=False)
class Loop:
    """A closed chain of a drawing's pieces.

    Attributes
    ----------
    curve : Curve
        Closed (its ends within the join tolerance), counter-clockwise.
    where : str
        Its layer (id/class) and first entity, for messages.
    sources : tuple of str
        The sources of its pieces.
    """

    curve: Curve
    where: str
    sources: tuple


def _polygon(curve: Curve, chord: float):
    import shapely

    poly = shapely.Polygon(curve.characteristic_points(chord))
    return poly if poly.is_valid else shapely.make_valid(poly)


def closed_loops(pieces, where: str, ctx: Context, report, strict: bool = True) -> list[Loop]:
    """The closed chains of ``pieces`` (one layer's), counter-clockwise.

    Parameters
    ----------
    pieces : list of Piece
    where : str
        Their layer (``"layer BODY-seal-HOLE"``), for messages.
    ctx : Context
    report : list or None
    strict : bool
        Refuse an open chain (a hole layer); otherwise skip it, and skip
        pieces that branch (a layer nobody reads).

    Raises
    ------
    CaseError
        With ``strict``: an open chain, naming its ends and first entity.
    """
    o = ctx.options
    try:
        paths, rep = connect(list(pieces), where, ctx.tol, o.snap, o.close_gap)
    except CaseError:
        if strict:
            raise
        return []
    if strict:
        for line in rep.lines(where):
            say(report, line)
    out = []
    for path in paths:
        if not path.closed:
            if strict:
                a, b = path.ends
                raise CaseError(where, f"{path.sources[0]} is part of an open curve from {fmt_point(a)} to {fmt_point(b)}; "
                                       "a hole is a closed contour: close it in the drawing (or with option close_gap)")
            continue
        curve = path.curve if path.curve.green() > 0 else path.curve.reversed()
        sources = tuple(dict.fromkeys(path.sources))
        more = f" and {len(sources) - 1} more" if len(sources) > 1 else ""
        out.append(Loop(curve, f"{where}: {sources[0]}{more}", sources))
    return out


def outer_and_holes(pieces, where: str, ctx: Context, report) -> tuple[Curve, list[Loop]] | None:
    """A body's contour layer holding several closed contours: the outer one and the others (its holes).

    Returns None unless the pieces form two or more chains, all closed (the
    caller then chains them as one contour, refusing what is wrong).
    """
    o = ctx.options
    paths, _ = connect(list(pieces), where, ctx.tol, o.snap, o.close_gap)
    if len(paths) < 2 or not all(p.closed for p in paths):
        return None
    loops = closed_loops(pieces, where, ctx, report)
    k = int(np.argmax([abs(loop.curve.green()) for loop in loops]))
    return loops[k].curve, loops[:k] + loops[k + 1:]


def loops_beside(pieces, where: str, ctx: Context) -> tuple[list, list[Loop]]:
    """A curve's layer holding its open chain and closed contours beside it (a hole drawn on UPPER): split them.

    Returns
    -------
    kept : list of Piece
        ``pieces`` less those of the closed contours (all of them when the
        layer holds no open chain, or no closed one, or branches: the
        caller's chaining then says what is wrong).
    loops : list of Loop
    """
    o = ctx.options
    try:
        paths, _ = connect(list(pieces), where, ctx.tol, o.snap, o.close_gap)
    except CaseError:
        return list(pieces), []
    if all(p.closed for p in paths) or not any(p.closed for p in paths):
        return list(pieces), []
    closed = {s for p in paths if p.closed for s in p.sources}
    loops = closed_loops([p for p in pieces if p.source in closed], where, ctx, None)
    return [p for p in pieces if p.source not in closed], loops


def body_holes(found: list, own: dict, unused: list, ctx: Context, labels: dict, report) -> tuple[dict, list]:
    """Each body's holes: its own (drawn on its layers) and the closed contours of unused pieces inside it.

    Parameters
    ----------
    found : list of (str, Curve, Curve)
        Each body's name, lower and upper curves.
    own : dict
        Body name -> list of :class:`Loop` drawn on the body's own layers.
    unused : list of Piece
        The pieces no curve of the case comes from.
    ctx : Context
    labels : dict
        Upper-cased tag -> its spelling in the file.
    report : list or None

    Returns
    -------
    holes : dict
        Body name -> tuple of Curve (closed, counter-clockwise), for the
        bodies that have holes.
    unused : list of Piece
        ``unused`` less the pieces that became holes.

    Raises
    ------
    CaseError
        A closed unused contour crossing or touching a body's contour.
    GeometryError
        A hole of a body's own layers outside it, touching its contour or
        another hole (:func:`sectiondeform.layout.check_holes`), naming the
        layer and entity.
    """
    import shapely

    tol = max(ctx.tol, CONTACT_FRACTION * ctx.diag)
    placed = {name: list(own.get(name, ())) for name, _, _ in found}
    groups: dict[frozenset, list] = {}
    for p in unused:
        if p.curve is not None:
            groups.setdefault(p.tags, []).append(p)
    candidates = [loop for tags, group in groups.items()
                  for loop in closed_loops(group, f"{ctx.what} {'/'.join(sorted(labels.get(t, t) for t in tags)) or '(none)'}",
                                           ctx, None, strict=False)]
    if not candidates and not any(placed.values()):
        return {}, unused
    polygons = [_polygon_of(lower, upper, 0.25 * tol) for _, lower, upper in found]
    outlines = [p.boundary for p in polygons]
    taken: set = set()
    for loop in candidates:
        poly = _polygon(loop.curve, 0.25 * tol)  # fine enough to see it touch a contour within ``tol``
        ring = poly.exterior if hasattr(poly, "exterior") else poly.boundary
        for i, (body, *_) in enumerate(found):
            d = float(shapely.distance(ring, outlines[i]))
            if d <= tol:
                p = shapely.get_coordinates(shapely.shortest_line(ring, outlines[i]))[0]
                raise CaseError(loop.where, f"a closed contour crossing or touching the contour of body {body!r} near "
                                            f"{fmt_point(p)} (gap {d:.3g}, tolerance {tol:.3g}); a hole lies strictly "
                                            "inside its body: move it inside, or off the section")
        inside = [i for i in range(len(found)) if polygons[i].contains(poly.representative_point())]
        if inside:
            placed[found[inside[0]][0]].append(loop)
            taken.update(loop.sources)
    out = {}
    for i, (body, _, _) in enumerate(found):
        loops = placed[body]
        if not loops:
            continue
        check_holes([loop.curve for loop in loops], polygons[i], tol, body, [loop.where for loop in loops])
        out[body] = tuple(loop.curve for loop in loops)
        say(report, f"read {len(loops)} hole{'s' if len(loops) > 1 else ''} in body {body!r} "
                    f"({'; '.join(loop.where for loop in loops)})")
    return out, [p for p in unused if p.source not in taken]


def _polygon_of(lower: Curve, upper: Curve, chord: float):
    import shapely

    ring = np.vstack((lower.characteristic_points(chord), upper.characteristic_points(chord)[1:-1]))
    poly = shapely.Polygon(ring)
    return poly if poly.is_valid else shapely.make_valid(poly)
