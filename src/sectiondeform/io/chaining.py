"""Order the pieces of a drawing into chains by their end points.

CAD drawings give a curve as pieces in any order and direction: thousands
of short LINEs from a scanner, or a few arcs and splines drawn by hand.
:func:`connect` joins them into chains:

1. every end point is matched with the others within ``tol`` (a KD-tree,
   so tens of thousands of pieces take milliseconds); pieces shorter than
   ``tol`` are dropped as collapsed, exact duplicates (same ends, same
   middle) are dropped, and both are counted;
2. a point where more than two pieces meet is a *branch*: an error naming
   the place and the pieces;
3. free ends closer than ``snap`` are snapped together, nearest first, and
   gaps up to ``close_gap`` are closed with a straight piece; both are
   reported, neither happens unless asked;
4. the pieces are walked from free end to free end (open chains), then
   around the loops that remain (closed chains), each piece turned to run
   the walking way.

:func:`one_chain` asks for exactly one chain and says where the gap is
when there are several.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..curves import Chain, Curve, Polyline
from ..errors import CaseError
from .pieces import Piece, merge_runs

__all__ = ["ChainReport", "Path", "connect", "one_chain", "fmt_point", "unused_summary"]


def fmt_point(p) -> str:
    """``(x, y)`` with 6 significant digits, for messages."""
    return f"({p[0]:.6g}, {p[1]:.6g})"


@dataclass
class ChainReport:
    """What :func:`connect` did to the pieces of one selection.

    Attributes
    ----------
    pieces : int
        Pieces given.
    duplicates : int
        Exact duplicates dropped.
    collapsed : int
        Pieces shorter than the join tolerance dropped.
    snapped : list of (x, y, gap)
        Free ends snapped together: where, and the gap closed (units).
    closed : list of ((x0, y0), (x1, y1), length)
        Gaps closed with a straight piece.
    """

    pieces: int = 0
    duplicates: int = 0
    collapsed: int = 0
    snapped: list = field(default_factory=list)
    closed: list = field(default_factory=list)

    def lines(self, where: str) -> list[str]:
        """Human-readable lines, one per fact worth knowing."""
        out = [f"{where}: {self.pieces} pieces"]
        if self.duplicates:
            out.append(f"{where}: dropped {self.duplicates} duplicate pieces")
        if self.collapsed:
            out.append(f"{where}: dropped {self.collapsed} pieces shorter than the join tolerance")
        if self.snapped:
            gaps = [g for _, _, g in self.snapped]
            out.append(
                f"{where}: snapped {len(gaps)} gaps (largest {max(gaps):.4g} at "
                f"{fmt_point(self.snapped[int(np.argmax(gaps))][:2])})"
            )
        for p, q, length in self.closed:
            out.append(f"{where}: closed a gap of {length:.4g} from {fmt_point(p)} to {fmt_point(q)} with a straight piece")
        return out


@dataclass(frozen=True, eq=False)
class Path:
    """One chain of pieces.

    Attributes
    ----------
    curve : Curve
        The pieces in walking order, consecutive polylines merged; a
        :class:`~sectiondeform.curves.Chain` when more than one remains.
    closed : bool
        Whether it ends where it starts.
    sources : tuple of str
        The pieces' sources, in walking order.
    """

    curve: Curve
    closed: bool
    sources: tuple

    @property
    def ends(self) -> tuple[np.ndarray, np.ndarray]:
        """First and last point, ``(2,)`` each."""
        return self.curve.ends


def _greedy_pairs(points: np.ndarray, radius: float, forbid) -> list[tuple[int, int, float]]:
    """Pairs of rows of ``points`` within ``radius``, nearest first, each row once."""
    from scipy.spatial import (
        cKDTree,  # imported here: start-up time of the command line
    )

    if len(points) < 2 or radius <= 0:
        return []
    pairs = cKDTree(points).query_pairs(radius, output_type="ndarray")
    if not len(pairs):
        return []
    d = np.hypot(*(points[pairs[:, 0]] - points[pairs[:, 1]]).T)
    used = np.zeros(len(points), dtype=bool)
    out = []
    for k in np.argsort(d, kind="stable"):
        i, j = pairs[k]
        if used[i] or used[j] or forbid(i, j):
            continue
        used[i] = used[j] = True
        out.append((int(i), int(j), float(d[k])))
    return out


def connect(pieces: list[Piece], where: str, tol: float, snap: float = 0.0, close_gap: float = 0.0):
    """Join pieces into chains by their end points.

    Parameters
    ----------
    pieces : list of Piece
        In any order and direction.
    where : str
        What the pieces are (``"layer LOWER"``), for messages.
    tol : float
        End points closer than this are the same point, units.
    snap : float
        Free ends closer than this are snapped together (reported), units.
    close_gap : float
        Free ends closer than this, after snapping, are joined by a
        straight piece (reported), units.

    Returns
    -------
    paths : list of Path
        Open chains first, then closed ones.
    report : ChainReport

    Raises
    ------
    CaseError
        At a branch (three or more pieces meeting), naming the place.

    Examples
    --------
    >>> ps = [Piece(Polyline(v), frozenset(), f"LINE #{i}") for i, v in
    ...       enumerate([[[1, 0], [2, 0]], [[1, 0], [0, 0]], [[2, 0], [2, 1]]])]
    >>> paths, report = connect(ps, "layer 0", 1e-9)
    >>> len(paths), paths[0].curve.vertices.tolist()
    (1, [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 1.0]])
    """
    from scipy.sparse import (
        coo_matrix,  # imported here: start-up time of the command line
    )
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    report = ChainReport(pieces=len(pieces))
    if not pieces:
        return [], report
    ends = [p.curve.ends for p in pieces]
    starts = np.array([e[0] for e in ends], dtype=np.float64)
    stops = np.array([e[1] for e in ends], dtype=np.float64)
    m = len(pieces)
    pts = np.vstack((starts, stops))  # endpoint e: piece e % m, side e // m

    pairs = cKDTree(pts).query_pairs(tol, output_type="ndarray") if tol > 0 else np.empty((0, 2), int)
    exact = np.flatnonzero(np.all(pts[:m] == pts[m:], axis=1))
    rows = np.concatenate((pairs[:, 0], exact))
    cols = np.concatenate((pairs[:, 1], exact + m))
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(2 * m, 2 * m))
    _, node = connected_components(graph, directed=False)

    keep = np.ones(m, dtype=bool)
    # Collapsed pieces: both ends at one node, and shorter than the tolerance.
    loop = np.flatnonzero(node[:m] == node[m:])
    for k in loop:
        if pieces[k].curve.length <= 2 * tol:
            keep[k] = False
            report.collapsed += 1
    # Duplicates: same pair of nodes and the same middle point.
    key = np.sort(np.column_stack((node[:m], node[m:])), axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    same = np.all(key[order[1:]] == key[order[:-1]], axis=1)
    if same.any():
        groups: dict[tuple, list[int]] = {}
        for a, b in zip(order[:-1][same], order[1:][same]):
            g = groups.setdefault(tuple(key[a]), [int(a)])
            if int(b) not in g:
                g.append(int(b))
        for members in groups.values():
            mids = [pieces[k].curve.at_fractions(np.array([0.5]))[0] for k in members]
            for i in range(1, len(members)):
                if not keep[members[i]]:
                    continue
                for j in range(i):
                    if keep[members[j]] and np.hypot(*(mids[i] - mids[j])) <= tol:
                        keep[members[i]] = False
                        report.duplicates += 1
                        break

    alive = np.concatenate((keep, keep))
    n_nodes = int(node.max()) + 1

    def degrees():
        return np.bincount(node[alive], minlength=n_nodes)

    deg = degrees()
    branch = np.flatnonzero(deg > 2)
    if len(branch):
        b = branch[0]
        at = np.flatnonzero((node == b) & alive)
        names = ", ".join(pieces[e % m].source for e in at[:4])
        raise CaseError(
            where,
            f"branch at {fmt_point(pts[at[0]])}: {int(deg[b])} pieces meet there ({names}); "
            "a curve must be one chain without forks (remove overlapping or stray pieces)",
        )

    def free_endpoints():
        d = degrees()
        return np.flatnonzero(alive & (d[node] == 1))

    if snap > 0:
        free = free_endpoints()
        fp = pts[free]
        for i, j, gap in _greedy_pairs(fp, snap, lambda i, j: free[i] % m == free[j] % m):
            a, b = free[i], free[j]
            node[node == node[b]] = node[a]
            report.snapped.append((*(0.5 * (fp[i] + fp[j])).tolist(), gap))

    if close_gap > 0:
        free = free_endpoints()
        fp = pts[free]
        matches = _greedy_pairs(fp, close_gap, lambda i, j: free[i] % m == free[j] % m)
        if matches:
            # Closures are new straight pieces whose ends sit at the free ends' nodes.
            extra = [
                Piece(Polyline(np.vstack((fp[i], fp[j]))), frozenset(), f"gap closure {fmt_point(fp[i])}-{fmt_point(fp[j])}")
                for i, j, _ in matches
            ]
            report.closed.extend((fp[i].tolist(), fp[j].tolist(), gap) for i, j, gap in matches)
            k = len(extra)
            s_node = np.array([node[free[i]] for i, _, _ in matches])
            t_node = np.array([node[free[j]] for _, j, _ in matches])
            pts = np.vstack((pts[:m], fp[[i for i, _, _ in matches]], pts[m:], fp[[j for _, j, _ in matches]]))
            node = np.concatenate((node[:m], s_node, node[m:], t_node))
            keep = np.concatenate((keep, np.ones(k, dtype=bool)))
            pieces = list(pieces) + extra
            m += k
            alive = np.concatenate((keep, keep))

    # Pair the two endpoints at each node (degree <= 2 everywhere now).
    idx = np.flatnonzero(alive)
    srt = idx[np.argsort(node[idx], kind="stable")]
    partner = np.full(2 * m, -1)
    twin = node[srt[1:]] == node[srt[:-1]]
    partner[srt[:-1][twin]] = srt[1:][twin]
    partner[srt[1:][twin]] = srt[:-1][twin]

    visited = ~keep.copy()
    paths: list[Path] = []

    def walk(e0: int) -> tuple[list[int], bool]:
        seq, cur = [], e0
        while True:
            k = cur % m
            if visited[k]:
                return seq, True
            visited[k] = True
            seq.append(cur)
            nxt = partner[(cur + m) % (2 * m)]
            if nxt < 0:
                return seq, False
            cur = nxt

    for e in idx:
        if partner[e] < 0 and not visited[e % m]:
            seq, _ = walk(int(e))
            paths.append(_assemble(pieces, seq, m, closed=False))
    for k in np.flatnonzero(~visited):
        if visited[k]:
            continue
        seq, _ = walk(int(k))
        paths.append(_assemble(pieces, seq, m, closed=True))
    return paths, report


def _fit_ends(curves: list[Curve], closed: bool, scale: float) -> list[Curve]:
    """Make each curve start exactly where the one before ends.

    The next curve's start is moved if its kind can move an end alone
    (polyline vertex, spline control point), else the previous curve's end;
    between two arcs a visible gap is bridged with a straight piece.
    """
    out = [curves[0]]
    for c in curves[1:] + ([None] if closed and len(curves) > 1 else []):
        prev = out[-1]
        nxt = c if c is not None else out[0]
        p_end, n_start = prev.ends[1], nxt.ends[0]
        fixed = None
        if np.array_equal(p_end, n_start):
            fixed = nxt
        elif (moved := nxt.with_end_moved(False, p_end)) is not None:
            fixed = moved
        elif (moved := prev.with_end_moved(True, n_start)) is not None:
            out[-1] = moved
            fixed = nxt
        else:  # two arcs: bridge a visible gap with a straight piece
            if np.hypot(*(p_end - n_start)) > 1e-9 * scale:
                out.append(Polyline(np.vstack((p_end, n_start))))
            fixed = nxt
        if c is None:
            out[0] = fixed
        else:
            out.append(fixed)
    return out


def _assemble(pieces: list[Piece], seq: list[int], m: int, closed: bool) -> Path:
    curves = []
    for e in seq:
        c = pieces[e % m].curve
        curves.append(c.reversed() if e >= m else c)
    pts = np.concatenate([np.vstack(c.ends) for c in curves])
    scale = float(np.hypot(*np.ptp(pts, axis=0))) or 1.0
    curves = merge_runs(_fit_ends(curves, closed, scale))
    curve = curves[0] if len(curves) == 1 else Chain(tuple(curves))
    return Path(curve, closed, tuple(pieces[e % m].source for e in seq))


def one_chain(pieces: list[Piece], where: str, tol: float, snap: float = 0.0, close_gap: float = 0.0,
              closed: bool | None = None):
    """Join pieces into exactly one chain.

    Parameters
    ----------
    pieces, where, tol, snap, close_gap
        As for :func:`connect`.
    closed : bool, optional
        Require a closed (True) or an open (False) chain.

    Returns
    -------
    path : Path
    report : ChainReport

    Raises
    ------
    CaseError
        No pieces; a branch; several chains (naming the nearest gap between
        them and the options that would close it); a chain open or closed
        against ``closed``.
    """
    if not pieces:
        raise CaseError(where, "has no curve pieces")
    paths, report = connect(pieces, where, tol, snap, close_gap)
    if not paths:
        raise CaseError(where, f"every piece is shorter than twice the join tolerance {tol:.3g} (by default 1e-6 of "
                               "the drawing's diagonal, which a far stray piece makes large): give a smaller join_tol "
                               "or delete the stray pieces")
    if len(paths) > 1:
        opened = [p for p in paths if not p.closed]
        if len(opened) >= 2:
            ends = np.array([e for p in opened for e in p.ends])
            owner = np.repeat(np.arange(len(opened)), 2)
            d = np.hypot(*(ends[:, None, :] - ends[None, :, :]).transpose(2, 0, 1))
            d[owner[:, None] == owner[None, :]] = np.inf
            i, j = np.unravel_index(int(np.argmin(d)), d.shape)
            raise CaseError(
                where,
                f"the pieces form {len(paths)} separate chains, not one; the nearest gap is "
                f"{d[i, j]:.4g} between {fmt_point(ends[i])} and {fmt_point(ends[j])}; join them in the "
                f"drawing, or allow it with option snap at {d[i, j] * 1.01:.3g} (move the ends together) or "
                f"option close_gap at {d[i, j] * 1.01:.3g} (add a straight piece)",
            )
        raise CaseError(where, f"the pieces form {len(paths)} separate chains ({sum(p.closed for p in paths)} closed), not one")
    path = paths[0]
    if closed is True and not path.closed:
        a, b = path.ends
        gap = float(np.hypot(*(a - b)))
        raise CaseError(
            where,
            f"the contour is not closed: a gap of {gap:.4g} between {fmt_point(a)} and {fmt_point(b)}; "
            f"close it in the drawing or with option close_gap at {gap * 1.01:.3g}",
        )
    if closed is False and path.closed:
        raise CaseError(where, "is a closed loop; an open curve is expected here")
    return path, report


def unused_summary(pieces, annotation, labels: dict, what: str) -> str | None:
    """One line saying which entities a case does not use: how many, on which layers (ids/classes); None if all are.

    Parameters
    ----------
    pieces : sequence of Piece
        The pieces no curve of the case was built from.
    annotation : sequence of str
        Entities the reader skipped (DXF text, dimensions...), as their sources
        ``"TEXT #3 (handle 2F, layer NOTES)"``.
    labels : dict
        Upper-cased tag -> its spelling in the file.
    what : str
        ``"layer"`` or ``"id/class"``.

    Examples
    --------
    >>> ps = [Piece(Polyline([[0, 0], [1, 0]]), frozenset({"HOLE"}), "CIRCLE #4")] * 2
    >>> unused_summary(ps, ["TEXT #5 (handle 31, layer NOTES)"], {"HOLE": "Hole"}, "layer")
    'ignored: 3 entities not used by the case: 2 on layer Hole, 1 on layer NOTES (annotation: TEXT)'
    """
    counts: dict[str, int] = {}
    for p in pieces:
        name = "/".join(sorted(labels.get(t, t) for t in p.tags)) if p.tags else None
        key = f"on {what} {name}" if name else f"without {'a layer' if what == 'layer' else 'an id or class'}"
        counts[key] = counts.get(key, 0) + 1
    kinds = []
    for source in annotation:
        kind, _, rest = source.partition(" #")
        layer = rest.rsplit("layer ", 1)[-1].rstrip(")") if "layer " in rest else None
        key = f"on {what} {layer}" if layer else "in the drawing"
        counts[key] = counts.get(key, 0) + 1
        if kind not in kinds:
            kinds.append(kind)
    total = len(pieces) + len(annotation)
    if not total:
        return None
    where = ", ".join(f"{n} {key}" for key, n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])))
    note = f" (annotation: {', '.join(kinds)})" if kinds else ""
    return f"ignored: {total} {'entity' if total == 1 else 'entities'} not used by the case: {where}{note}"
