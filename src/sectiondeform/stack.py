"""The bodies' sections as they rest on each other: what every model prepares from.

:class:`Stack` makes every body of a :class:`~sectiondeform.problem.Problem`
a section (:func:`~sectiondeform.section.build_section`), from the top of
the stack down, and gives each lower node of a body its source: the
support (at its arc-length fraction on the support) or the upper curve of
one of the body's foundations. The nodes resting on a foundation are
inserted into the foundation's upper polyline as characteristic points, and
the foundation's own upper points lying strictly inside such a run of nodes
are taken out of it, before the foundation's section is built: on a shared
piece both bodies then have exactly the same points. A problem of one body
on the support is one section, its lower nodes all on the support.

Everything a placement needs besides the target (which lower node comes
from where, the upper bookkeeping, the contour's positions of the points
taken out) is worked out here, once.
"""

from __future__ import annotations

import numpy as np
import shapely

from .curves import Curve, Polyline, _unique
from .errors import CaseError, MeshError, SectionDeformError
from .laws import AreaRatio, VolumeRatio
from .pappus import signed_distance
from .section import Section, build_section, densified

__all__ = ["Stack", "StackedBody", "Target", "SUPPORT", "renamed", "net_quantity"]

SUPPORT = -1
"""Source of a lower node resting on the support."""


def renamed(exc: SectionDeformError, label: str) -> SectionDeformError:
    """``exc`` with its message prefixed by the body it is about (``label``; unchanged when empty)."""
    if not label:
        return exc
    if isinstance(exc, CaseError):
        return CaseError(f"{label}: {exc.field}" if exc.field else label, exc.problem)
    return type(exc)(f"{label}: {exc}")


def _cumulative(points: np.ndarray) -> np.ndarray:
    return np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))))


def net_quantity(outer: float, holes) -> float:
    """A body's signed quantity: its contour's ``outer`` less the magnitude of each of its ``holes``' (any sign).

    Examples
    --------
    >>> net_quantity(-10.0, [2.0, -3.0])
    -5.0
    """
    return float(outer - np.sign(outer) * sum(abs(h) for h in holes))


class StackedBody:
    """One body of a :class:`Stack`: its section, node sources and upper bookkeeping."""

    def __init__(self, section, original_upper):
        self.section = section
        self.original_upper = original_upper  # (m0, 2) the case's characteristic points
        self.kept = np.array(section.characteristic_index)  # index in section.upper of each original point, -1 if taken out
        self.taken = []  # (original index, resting body, node index, t) of the points taken out
        self.source = np.full(len(section.lower), SUPPORT)  # SUPPORT or a foundation body per lower node
        self.where = np.zeros(len(section.lower))  # support fraction, or index in the foundation's upper
        self.contour_order = None


class Stack:
    """Every body of a problem as a section, with its lower nodes' sources.

    Parameters
    ----------
    problem : Problem
    element_size : float, optional
        Element size of every body's section, units; overrides the case's.

    Attributes
    ----------
    problem : Problem
    layout : Layout
    bodies : list of StackedBody
        In the problem's order.
    fixed_parts : tuple of dict
        Per body, what its results share whatever the target.
    fractions : (k,) float64 ndarray
        The support's arc-length fractions at which the target is sampled
        (every lower node resting on the support, sorted, once each).

    Raises
    ------
    GeometryError, MeshError
        Naming the body whose section cannot be built.
    """

    def __init__(self, problem, element_size: float | None = None):
        self.problem = problem
        self.layout = problem.layout
        n = len(problem.bodies)
        self.bodies: list[StackedBody | None] = [None] * n
        self._initial: dict = {}
        for b in reversed(self.layout.order):
            self.bodies[b] = self._build(b, element_size)
        self.fixed_parts = tuple(self._fixed_parts(b) for b in range(n))
        self.fractions = _unique(np.concatenate([f["support_fractions"] for f in self.fixed_parts]))
        for f in self.fixed_parts:
            f["support_index"] = np.searchsorted(self.fractions, f["support_fractions"])

    def initial_quantity(self, b: int, law) -> float:
        """``law``'s quantity of body ``b``'s curves, exactly (:meth:`~sectiondeform.laws.Law.curve_quantity`), signed.

        The quantity of the case's own curves, not of their polygon: a law
        met to 1e-9 on the deformed contour is met against the curves given;
        the body's holes taken out (:func:`net_quantity`). Kept per law (a
        slider asks many ratios of one law: a bounded store).
        """
        key = (b, law.measure, getattr(law, "axis", None))
        try:
            return self._initial[key]
        except KeyError:
            body = self.problem.bodies[b]
            value = self._initial[key] = net_quantity(law.curve_quantity((body.lower, body.upper)),
                                                      [law.curve_quantity((h,)) for h in body.holes])
            return value

    @property
    def sections(self) -> list[Section]:
        """Each body's section, in the problem's order."""
        return [b.section for b in self.bodies]

    @property
    def support_length(self) -> float:
        """Length of the support, units."""
        return self.problem.support.length

    def _section(self, b: int, upper: Curve | None, element_size, dense: bool = True, shared=None):
        """Body ``b``'s section; ``dense``: with points between its upper characteristic points (:func:`densified`)."""
        try:
            section = build_section(self.problem.body_case(b, upper), element_size)
            if dense and upper is not None and len(section.upper) != len(upper.vertices):  # pragma: no cover
                raise MeshError(f"{self.problem.label(b)}: its upper polyline with the resting nodes lost points")
            return densified(section, shared) if dense else section
        except SectionDeformError as exc:
            raise renamed(exc, self.problem.label(b)) from None

    def _build(self, b: int, element_size) -> StackedBody:
        """Body ``b``'s section, with the lower nodes of the bodies resting on it in its upper polyline."""
        lay = self.layout
        resting = lay.resting_on(b)
        base = self._section(b, None, element_size, dense=not resting)
        original = np.array(base.upper[base.characteristic_index])
        if not resting:
            body = StackedBody(base, original)
        else:
            body = self._with_resting(b, original, resting, element_size)
        self._sources(b, body)
        return body

    def _with_resting(self, b: int, original: np.ndarray, resting, element_size) -> StackedBody:
        tol = self.layout.tolerance
        line = shapely.LineString(original)
        params = _cumulative(original)
        m = len(original)
        taken = np.zeros(m, dtype=bool)
        taken_by = {}
        inserts = []  # (param, point, resting body, node index)
        for r in resting:
            rb = self.bodies[r]
            idx = np.flatnonzero(rb.source == b)
            if not len(idx):
                continue
            pts = rb.section.lower[idx]
            par = shapely.line_locate_point(line, shapely.points(pts))
            inserts += [(float(p), pts[k], r, int(i)) for k, (p, i) in enumerate(zip(par, idx))]
            for run in np.split(np.arange(len(idx)), np.flatnonzero(np.diff(idx) != 1) + 1):
                lo, hi = par[run].min(), par[run].max()
                inside = (params > lo) & (params < hi)
                inside[0] = inside[-1] = False
                for k in np.flatnonzero(inside & ~taken):
                    taken_by[int(k)] = (r, idx[run])
                taken |= inside
        # Merge the kept points and the inserted nodes along the original upper curve.
        entries = [(params[k], 0 if k < m - 1 else 2, original[k], ("kept", int(k))) for k in range(m) if not taken[k]]
        entries += [(p, 1, pt, ("node", r, i)) for p, pt, r, i in inserts]
        entries.sort(key=lambda e: (e[0], e[1]))
        points, point_params, kept_index, node_index = [], [], {}, {}
        for p, _, pt, what in entries:
            if points and np.hypot(*(pt - points[-1])) <= tol:
                j = len(points) - 1
                if what[0] == "kept":  # a point of the case's own upper curve keeps its place
                    points[-1] = pt
            else:
                points.append(np.asarray(pt, dtype=float))
                point_params.append(p)
                j = len(points) - 1
            if what[0] == "kept":
                kept_index[what[1]] = j
            else:
                node_index[(what[1], what[2])] = j
        upper = np.array(points)
        # A segment between two consecutive nodes of one resting body is shared: no points put in it.
        shared = np.zeros(len(upper) - 1, dtype=bool)
        for (r, i), j in node_index.items():
            k = node_index.get((r, i + 1))
            if k is not None and abs(k - j) == 1:
                shared[min(j, k)] = True
        section = self._section(b, Polyline(upper), element_size, shared=shared)
        ch = section.characteristic_index
        body = StackedBody(section, original)
        body.kept = np.array([ch[kept_index[k]] if k in kept_index else -1 for k in range(m)])
        for (r, i), j in node_index.items():
            self.bodies[r].where[i] = ch[j]
        # The points taken out: their place on the resting body's lower polyline (segment, fraction).
        for k, (r, run) in sorted(taken_by.items()):
            nodes = self.bodies[r].section.lower[run]
            along = float(shapely.line_locate_point(shapely.LineString(nodes), shapely.Point(original[k])))
            cum = _cumulative(nodes)
            s = int(np.clip(np.searchsorted(cum, along, side="right") - 1, 0, len(nodes) - 2))
            t = float(np.clip((along - cum[s]) / (cum[s + 1] - cum[s]), 0.0, 1.0))
            body.taken.append((k, r, int(run[s]), t))
        # Contour order: the prepared upper points and the taken-out ones, along the original upper.
        dense_params = np.interp(np.arange(len(section.upper)), ch, point_params)
        all_params = np.concatenate((dense_params, params[[k for k, *_ in body.taken]]))
        body.contour_order = np.argsort(all_params, kind="stable")
        return body

    def _sources(self, b: int, body: StackedBody) -> None:
        """Classify body ``b``'s lower nodes: on the support (with their fraction) or on a foundation."""
        lay = self.layout
        a = self.problem
        low = body.section.lower
        support = lay.fine["support"]
        on_support = shapely.distance(shapely.points(low), shapely.LineString(support)) <= lay.tolerance
        found = lay.foundations[b]
        if found:
            d = np.stack([shapely.distance(shapely.points(low), shapely.LineString(lay.fine["uppers"][j])) for j in found])
            nearest = np.asarray(found)[np.argmin(d, axis=0)]
            body.source = np.where(on_support, SUPPORT, nearest)
        else:
            body.source = np.full(len(low), SUPPORT)
        sup = body.source == SUPPORT
        if a.bodies[b].lower.to_json() == a.support.to_json():
            body.where[sup] = body.section.fractions[sup]
        else:
            line = shapely.LineString(support)
            body.where[sup] = shapely.line_locate_point(line, shapely.points(low[sup])) / line.length

    def _fixed_parts(self, b: int) -> dict:
        """What body ``b``'s results share whatever the target: its initial curves, contour, initial volume, points taken out."""
        a = self.problem
        body = self.bodies[b]
        sec = body.section
        initial_upper = np.array(sec.upper)
        if body.contour_order is not None:
            initial_taken = body.original_upper[[k for k, *_ in body.taken]].reshape(-1, 2)
            initial_upper = np.concatenate((initial_upper, initial_taken))[body.contour_order]
        taken = np.array([row for row in body.taken], dtype=np.float64).reshape(-1, 4)
        initial_contour = np.concatenate((sec.lower, initial_upper[1:-1]))
        side = None
        if a.revolution is not None:
            before = signed_distance(initial_contour, a.revolution.axis)
            side = float(np.sign(before[np.argmax(np.abs(before))]))
        # Where the points taken out sit in the contour, and the last point before each that is not one
        # (the contour is the prepared polygon with these points inserted: see _sliver).
        inserted = np.zeros(0, dtype=np.int64)
        anchor = np.zeros(0, dtype=np.int64)
        if body.contour_order is not None and len(body.taken):
            if (body.contour_order[[0, -1]] >= len(sec.upper)).any():  # pragma: no cover - taken points lie inside runs
                raise MeshError(f"{a.label(b)}: a point taken out of its upper polyline falls at an end of it")
            is_taken = body.contour_order[1:-1] >= len(sec.upper)
            inserted = len(sec.lower) + np.flatnonzero(is_taken)
            own = np.concatenate((np.arange(len(sec.lower)), len(sec.lower) + np.flatnonzero(~is_taken)))
            anchor = own[np.searchsorted(own, inserted) - 1]
        sup = body.source == SUPPORT
        on = tuple((j, np.flatnonzero(body.source == j), body.where[body.source == j].astype(np.int64))
                   for j in self.layout.foundations[b])
        kept = np.flatnonzero(body.kept >= 0)
        rs, i = taken[:, 1].astype(np.int64), taken[:, 2].astype(np.int64)
        groups = tuple((int(r), np.flatnonzero(rs == r), i[rs == r], taken[rs == r, 3:]) for r in _unique(rs))
        return {
            "support_nodes": np.flatnonzero(sup), "support_fractions": body.where[sup].copy(), "on_foundations": on,
            "kept": kept, "kept_index": body.kept[kept], "taken_groups": groups,
            "initial_lower": np.array(sec.lower),
            "initial_contour": initial_contour,
            "area_initial": abs(self.initial_quantity(b, AreaRatio(1.0))),
            "volume_initial": abs(self.initial_quantity(b, VolumeRatio(1.0, a.revolution.axis))) if a.revolution is not None else None,
            "axis_side": side,
            "taken_k": taken[:, 0].astype(np.int64),
            "inserted": inserted, "anchor": anchor,
        }

    def upper_images(self, b: int, lowers, images) -> tuple[np.ndarray, np.ndarray]:
        """Images of the case's upper points of body ``b``, and of the points taken out of it."""
        fixed = self.fixed_parts[b]
        up = np.empty_like(self.bodies[b].original_upper)
        up[fixed["kept"]] = images[b][fixed["kept_index"]]
        taken = np.empty((len(fixed["taken_k"]), 2))
        for r, rows, i, t in fixed["taken_groups"]:
            low = lowers[r]
            taken[rows] = (1.0 - t) * low[i] + t * low[i + 1]
        up[fixed["taken_k"]] = taken
        return up, taken


class Target:
    """Where the support goes: sampled at the stack's fractions, and the curve itself when known.

    Parameters
    ----------
    fractions : (k,) float64 ndarray
        The stack's support fractions (:attr:`Stack.fractions`).
    nodes : (k, 2) float64 ndarray
        The target at ``fractions``, units.
    curve : Curve, optional
        The target curve; without it (the drag fast path) the target between
        two nodes is their chord.
    """

    def __init__(self, fractions: np.ndarray, nodes: np.ndarray, curve: Curve | None = None):
        self.fractions = fractions
        self.nodes = nodes
        self.curve = curve

    def at_fractions(self, s: np.ndarray) -> np.ndarray:
        """The target at the support's arc-length fractions ``s``, ``(len(s), 2)``."""
        if self.curve is not None:
            return self.curve.at_fractions(s)
        return np.column_stack((np.interp(s, self.fractions, self.nodes[:, 0]), np.interp(s, self.fractions, self.nodes[:, 1])))
