r"""Contact of the bodies' free boundary with rigid parts: nodal pressures on weighted penetrations (mortar), penalty with augmented-Lagrangian updates.

The method (the segment-to-rigid mortar of Puso and Laursen, and of
Popp, Wohlmuth and Wall for quadratic elements, with the penalty and
Uzawa's augmented-Lagrangian updates of FElupe's rigid-obstacle contact and
CalculiX; the semismooth active set of Hüeber, Stadler and Wohlmuth 2008
was the other choice, but it adds multiplier unknowns and changes the
sparse pattern with the active set):

* each node ``v`` of the free boundary's quadratic edges (corners and
  mid-edge nodes) carries a pressure per reference length ``P_v``; the
  pressure along an edge is linear on each of its halves between them
  (hat functions ``ψ_v``, :data:`_PSI`);
* the penetration ``g`` (the distance to the part's outline, positive
  inside) and the part's outward normal ``n`` at the closest point are
  taken at :data:`GAUSS` Gauss points per edge (in the reference
  configuration); a node's *weighted penetration* is their average with
  its hat, ``ĝ_v = ∫ ψ_v g ds0 / D_v``, ``D_v = ∫ ψ_v ds0``;
* ``P_v = max(0, λ_v + ε_v ĝ_v)`` (the ramp rounded by :data:`SMOOTHING`);
  the energy ``Σ_v D_v (max(0, λ_v + ε ĝ_v)² − λ_v²) / (2 ε)`` gives the
  residual ``R_a = −∫ p n N_a ds0`` (``p = Σ P_v ψ_v``) and the tangent
  ``Σ_v ε_v ramp′_v / D_v a_v a_vᵀ``, ``a_v = ∫ ψ_v n N ds0`` (the
  curvature of the outline left out: a quasi-Newton tangent there);
* ``ε = PENALTY μ / h``, ``μ`` the shear modulus of the edge's body and
  ``h`` its element size; after a solve ``λ ← P`` (an Uzawa update) and
  the solve is repeated until the largest weighted penetration is at
  most :data:`PENETRATION_FRACTION` of the element size;
* a mid-edge node's hat lies within its edge's cell; a corner's spans the
  two edges meeting there, which belong to two cells: the sparse pattern
  gains those pairs of edges once (:attr:`Boundary.pair_dofs`,
  :meth:`ContactPhysics.coupling_matrices`), whatever is in contact.

Why not pointwise: a penalty at each Gauss point constrains four points
per edge where a quadratic edge has two nodes' worth of freedom; the
pressure then alternates from point to point, some points inside the
contact let go, and a plane Hertz contact came out 39 % narrow with twice
the peak. With one constraint per node the edge still lies on the part,
and what alternates from a corner to a mid-edge node is removed from the
pressure reported by projecting it on the corners' coarser hats
(:func:`_corner_pressure`); its integral, the force, is unchanged.

Coulomb friction (a part's ``friction`` μ_f > 0) is a regularised
tangential penalty at the Gauss points: each point has an anchor, the
place along the part's outline (arc length ``s_a``) it is held to; with
``d = s − s_a`` (``s`` the point's closest place on the outline) the
tangential force per reference length is

    q = −μ_f p ψ(u),   u = d / (SLIP_MEMORY δ),   δ = max(μ_f p / ε_t, SLIP_FLOOR h),
    ψ(u) = (3u − u³) / 2 for |u| ≤ 1, sign(u) beyond

(``ε_t`` = :data:`TANGENT_PENALTY` ε, :data:`SLIP_MEMORY` = 1.5): the
stick penalty ``−ε_t d`` at small slips, Coulomb's ``−μ_f p sign d``
exactly from ``|d| = 1.5 δ`` on, and between them a cubic with a
continuous slope. A stick/slip switch (``q = −ε_t d`` capped at ``μ_f p``)
makes Newton cycle where a point sits at the switch, or where a point just
touching (``p`` ≈ 0) slips back and forth about its anchor; this law has
neither. The force on the body is ``p n + q τ`` (``τ`` the outline's
tangent, ``p`` the pressure there from its nodes'); the tangent gains the
slip's ``−(∂q/∂d / ε) τ τᵀ`` at each point and the pressure's share
through ``q`` at each node (not symmetric; the pattern is the same). The anchors are history:
:meth:`ContactPhysics.commit` drags them after each converged load step so
that no point is more than 1.5 δ from its anchor (the force unchanged), so
a reversed slip turns the force round after a motion of 3 δ. With μ_f = 0
none of this is computed: the frictionless result, exactly.

For a body of revolution every integral is per radian, weighted by the
initial distance from the axis (as :mod:`~sectiondeform.fem.axisymmetric`);
the forces reported are the whole ring's, 2π times. An edge lying on the
axis is no surface of the solid and is not part of the boundary.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

__all__ = ["Boundary", "Obstacle", "ContactPhysics", "Touch", "PartContact", "free_boundary", "contact_figures", "part_forces",
           "GAUSS", "PENALTY", "PENETRATION_FRACTION", "TANGENT_PENALTY"]

GAUSS = 4
"""Gauss points per boundary edge: two on each half, where the pressure is linear (exact for cubics there)."""
PENALTY = 300.0
"""The penalty ε in units of the body's shear modulus over its element size (the augmented-Lagrangian updates make
the constraint exact whatever it is). Chosen on the factorisations of thirteen contact problems (the shared cases,
the bumper at 8 and 16 elements through, the sleeve at 8, the Hertz blocks and hemispheres, the block under a
sliding plate with and without friction; ``SMOOTHING`` 1e-2): 177 in all at 300, 196 at 1000, and at 100 the block
under a sliding plate with friction 0.3 is refused; the pointwise penalty before took 315."""
PENETRATION_FRACTION = 1e-3
"""Augmented-Lagrangian updates go on until the largest penetration is at most this fraction of the element size."""
MAX_UPDATES = 8
"""At most this many augmented-Lagrangian updates per solve."""
SMOOTHING = 1e-2
"""The ramp ``max(0, u)`` is rounded over ``|u| < SMOOTHING μ`` (a quadratic there: a band of
±``SMOOTHING / PENALTY`` h, 3e-5 h, in the weighted penetration), so Newton does not cycle on a node at the contact's edge: 177
factorisations on the problems of ``PENALTY`` at 1e-2, 178 at 1e-3, 186 at 1e-1 (and a refusal)."""
TANGENT_PENALTY = 1.0
"""The tangential (stick) penalty in units of the normal penalty ε."""
SLIP_MEMORY = 1.5
"""The slip, in units of δ = μ_f p / ε_t, from which a point slides at Coulomb's force (the stick slope is then ε_t)."""
SLIP_FLOOR = 1e-2
"""The least δ, in units of the element size: a point barely pressed (``p`` → 0) would otherwise switch between
slipping one way and the other over a vanishing slip; its stick is then softer than ``ε_t`` (its force is small)."""
SMOOTH_DEG = 15.0
"""At a vertex of a part's outline turning by less than this, the normal turns continuously (a polygon drawn for a curve)."""


def ramp(u: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The rounded ramp and its slope: ``0`` below ``-c``, ``(u + c)² / (4 c)`` within ``c``, ``u`` above.

    Examples
    --------
    >>> p, dp = ramp(np.array([-2.0, 0.0, 2.0]), np.ones(3))
    >>> p.tolist(), dp.tolist()
    ([0.0, 0.25, 2.0], [0.0, 0.5, 1.0])
    """
    mid = np.abs(u) < c
    p = np.where(u >= c, u, 0.0)
    slope = np.where(u >= c, 1.0, 0.0)
    p = np.where(mid, (u + c) ** 2 / (4.0 * c), p)
    slope = np.where(mid, (u + c) / (2.0 * c), slope)
    return p, slope

_GX, _GW = np.polynomial.legendre.leggauss(GAUSS // 2)
_S = np.concatenate((0.25 * (_GX + 1.0), 0.5 + 0.25 * (_GX + 1.0)))  # Gauss points on [0, 1/2] and [1/2, 1]
_W = np.concatenate((0.25 * _GW, 0.25 * _GW))
_N = np.stack(((1 - _S) * (1 - 2 * _S), _S * (2 * _S - 1), 4 * _S * (1 - _S)), axis=1)  # (g, 3): corner a, corner b, mid
_DN = np.stack((4 * _S - 3, 4 * _S - 1, 4 - 8 * _S), axis=1)
_PSI = np.column_stack((np.maximum(1.0 - 2.0 * _S, 0.0), np.maximum(2.0 * _S - 1.0, 0.0), 1.0 - np.abs(2.0 * _S - 1.0)))
"""(g, 3): the pressure's hat functions at the Gauss points, linear on each half of an edge (corner a, corner b, mid)."""
_GAUSS_RANGE = np.arange(GAUSS)
_EDGES = np.array([[0, 1, 3], [1, 2, 4], [2, 0, 5]])  # a cell's edges: corner, corner, mid (counter-clockwise)
_FINE_S = np.linspace(0.0, 1.0, 129)
_FINE = np.stack([np.interp(_FINE_S, _S, np.eye(GAUSS)[i]) for i in range(GAUSS)], axis=1)
"""(129, g): a quantity at the Gauss points, linear between them (constant beyond), at 129 places along an edge."""


@dataclass(frozen=True, eq=False)
class Boundary:
    """The bodies' free boundary edges: their Gauss points, and the nodes carrying the contact pressure.

    Point ``q`` lies on edge ``q // GAUSS``; a *vertex* is a node of a free
    edge (corner or mid-edge) and carries a pressure, linear on each half
    edge between nodes (hat ``ψ_v``); its constraint is the penetration
    averaged with that hat (a weighted gap, as mortar methods have for a
    rigid obstacle).

    Attributes
    ----------
    nodes : (P, 3) int64 ndarray
        The edge's nodes of each point (corner, corner, mid-edge).
    shape : (P, 3) float64 ndarray
        Their shape functions at the point.
    dshape : (P, 3) float64 ndarray
        Their derivatives along the edge's parameter.
    weight : (P,) float64 ndarray
        Gauss weight times the initial length element (times the initial
        distance from the axis for a body of revolution), units (units² per radian).
    cell : (P,) int64 ndarray
        The cell holding the edge.
    local : (P, 3) int64 ndarray
        The edge's nodes' places in that cell (0 to 5).
    penalty : (P,) float64 ndarray
        ε at the point: ``PENALTY μ / h`` of the edge's body.
    size : (P,) float64 ndarray
        The edge's body's element size h, units.
    vertex : (P, 3) int64 ndarray
        The vertices at the point's edge's nodes (corner, corner, mid-edge).
    psi : (P, 3) float64 ndarray
        Their hats at the point (two of them nonzero).
    vertex_weight : (V,) float64 ndarray
        ``D_v = Σ w ψ_v`` over the vertex's edges' points, units (units² per radian).
    vertex_penalty : (V,) float64 ndarray
        ε at the vertex: the smallest of its edges' (the softer body's where two bodies meet).
    vertex_size : (V,) float64 ndarray
        h at the vertex: its edges' weighted by ``w ψ_v``, units.
    vertex_node : (V,) int64 ndarray
        The mesh node of each vertex.
    pairs : (Q, 4) int64 ndarray
        ``[e, j, e', j']``: edges ``e`` and ``e'`` meeting at their corners ``j`` and ``j'`` (0 or 1), one row per
        vertex two free edges share: the contact's stiffness couples their nodes.
    pair_dofs : (Q, 12) int64 ndarray
        The dofs of ``e``'s three nodes, then of ``e'``'s: the sparse pattern's entries the coupling needs.
    """

    nodes: np.ndarray
    shape: np.ndarray
    dshape: np.ndarray
    weight: np.ndarray
    cell: np.ndarray
    local: np.ndarray
    penalty: np.ndarray
    size: np.ndarray
    vertex: np.ndarray
    psi: np.ndarray
    vertex_weight: np.ndarray
    vertex_penalty: np.ndarray
    vertex_size: np.ndarray
    vertex_node: np.ndarray
    pairs: np.ndarray
    pair_dofs: np.ndarray

    @property
    def edges(self) -> int:
        """The number of free edges."""
        return len(self.weight) // GAUSS

    def points(self, x: np.ndarray) -> np.ndarray:
        """The Gauss points' positions ``(P, 2)`` for node positions ``x`` ``(N, 2)``, units."""
        return (self.shape[:, :, None] * x[self.nodes]).sum(axis=1)


def _pairs(corner_vertex: np.ndarray) -> np.ndarray:
    """``[e, j, e', j']`` for every two edges meeting at a vertex (``corner_vertex``: (k, 2) vertex of each edge's corners), ``(Q, 4)``."""
    v = corner_vertex.ravel()
    order = np.argsort(v, kind="stable")
    starts = np.flatnonzero(np.r_[True, v[order][1:] != v[order][:-1]])
    counts = np.diff(np.r_[starts, len(v)])
    rows = []
    for start, count in zip(starts[counts > 1], counts[counts > 1]):
        inc = order[start:start + count]  # incidences 2 e + j
        for i in range(count):
            for k in range(i + 1, count):
                rows.append((inc[i] // 2, inc[i] % 2, inc[k] // 2, inc[k] % 2))
    return np.array(rows, dtype=np.int64).reshape(-1, 4)


def free_boundary(nodes: np.ndarray, cells: np.ndarray, body: np.ndarray, fixed_nodes: np.ndarray, mu: np.ndarray,
                  size: np.ndarray, radius=None) -> Boundary:
    """The mesh's free boundary: edges of one cell only, not bonded to the support.

    Parameters
    ----------
    nodes : (N, 2) float64 ndarray
        Initial node positions, units.
    cells : (E, 6) int64 ndarray
        Counter-clockwise ``triangle6`` cells.
    body : (E,) int64 ndarray
        The body of each cell.
    fixed_nodes : (d,) int64 ndarray
        Nodes bonded to the support; an edge whose three nodes all are is not free.
    mu : (B,) float64 ndarray
        Each body's shear modulus.
    size : (E,) float64 ndarray
        Each cell's element size, units (a graded mesh's local one).
    radius : callable, optional
        Distance from the axis of points ``(..., 2)`` for a body of revolution.

    Returns
    -------
    Boundary

    Examples
    --------
    >>> pts = np.array([[0, 0], [1, 0], [0, 1], [.5, 0], [.5, .5], [0, .5]], float)
    >>> b = free_boundary(pts, np.arange(6)[None], np.zeros(1, int), np.array([0, 1, 3]), np.ones(1), np.ones(1))
    >>> len(b.weight), round(float(b.weight.sum()), 12) == round(1 + 2 ** 0.5, 12)
    (8, True)
    >>> # A quarter of an edge at a corner, half at a mid-node; bonded nodes 0 and 1 give theirs to the mid-nodes.
    >>> b.vertex_node.tolist(), b.vertex_weight.round(4).tolist()
    ([0, 1, 2, 4, 5], [0.0, 0.0, 0.6036, 1.0607, 0.75])
    >>> b.pairs.tolist()  # the two free edges meet at node 2: the second's corner 0 and the first's corner 1
    [[0, 1, 1, 0]]
    """
    corners = cells[:, _EDGES[:, :2]].reshape(-1, 2)
    key = np.sort(corners, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    is_fixed = np.zeros(len(nodes), bool)
    is_fixed[fixed_nodes] = True
    edge_nodes = cells[:, _EDGES].reshape(-1, 3)
    free = (counts[inverse.ravel()] == 1) & ~is_fixed[edge_nodes].all(axis=1)
    k = np.flatnonzero(free)
    en = edge_nodes[k]
    cell = np.repeat(k // 3, GAUSS)
    local = np.repeat(_EDGES[k % 3], GAUSS, axis=0)
    xe = nodes[en]  # (k, 3, 2)
    pts = np.einsum("ga,kai->kgi", _N, xe)
    tang = np.einsum("ga,kai->kgi", _DN, xe)
    w = _W[None] * np.hypot(tang[..., 0], tang[..., 1])
    if radius is not None:  # an edge on the axis is no surface of the solid of revolution: dropped
        w = w * radius(pts)
        r = np.abs(radius(xe))  # (k, 3)
        on_surface = r.max(axis=1) > 1e-9 * max(float(r.max(initial=0.0)), 1e-300)
        k, en, xe, w = k[on_surface], en[on_surface], xe[on_surface], w[on_surface]
        cell = np.repeat(k // 3, GAUSS)
        local = np.repeat(_EDGES[k % 3], GAUSS, axis=0)
    w = w.ravel()
    b = body[cell]
    h = size[cell]
    penalty = PENALTY * mu[b] / h
    vnodes, vinv = np.unique(en, return_inverse=True)
    edge_vertex = vinv.reshape(-1, 3)
    vertex = np.repeat(edge_vertex, GAUSS, axis=0)
    psi = np.tile(_PSI, (len(k), 1))
    # A node bonded to the support cannot answer a pressure: its hat goes to the edge's mid-node (as mortar
    # methods modify the multipliers at the slave surface's boundary), so the pressure stays constant up to it.
    held = np.repeat(is_fixed[en[:, :2]], GAUSS, axis=0)  # (P, 2)
    psi[:, 2] += (psi[:, :2] * held).sum(axis=1)
    psi[:, :2] *= ~held
    share = (psi * w[:, None]).ravel()
    vw = np.bincount(vertex.ravel(), weights=share, minlength=len(vnodes))
    per_vertex = np.where(vw > 0, vw, 1.0)
    # A node two bodies share takes the softer one's penalty: the stiffer one's would make the soft body's
    # constraint ill-conditioned (the updates make both exact alike).
    vpen = np.full(len(vnodes), np.inf)
    np.minimum.at(vpen, vertex.ravel(), np.where(share > 0, np.repeat(penalty, 3), np.inf))
    vpen[np.isinf(vpen)] = 0.0
    vsize = np.bincount(vertex.ravel(), weights=share * np.repeat(h, 3), minlength=len(vnodes)) / per_vertex
    pairs = _pairs(edge_vertex[:, :2])
    edofs = (2 * en[:, :, None] + np.arange(2)).reshape(-1, 6)
    pair_dofs = np.concatenate((edofs[pairs[:, 0]], edofs[pairs[:, 2]]), axis=1) if len(pairs) else np.zeros((0, 12), np.int64)
    return Boundary(np.repeat(en, GAUSS, axis=0), np.tile(_N, (len(k), 1)), np.tile(_DN, (len(k), 1)), w,
                    cell, local, penalty, h, vertex, psi, vw, vpen, vsize, vnodes, pairs, pair_dofs)


class Obstacle:
    """A rigid part's closed outline as segments, with distances and normals of points.

    Parameters
    ----------
    ring : (k, 2) float64 ndarray
        The closed outline at the part's end position (first point repeated or not), units.
    travel : (2,) float64 array_like
        The part starts at ``ring - travel``.
    friction : float
        Coulomb's coefficient μ_f >= 0 between the part and the bodies.
    """

    def __init__(self, ring: np.ndarray, travel, friction: float = 0.0):
        self.friction = float(friction)
        ring = np.asarray(ring, dtype=np.float64)
        if np.allclose(ring[0], ring[-1]):
            ring = ring[:-1]
        area = 0.5 * float(np.sum(ring[:, 0] * np.roll(ring[:, 1], -1) - np.roll(ring[:, 0], -1) * ring[:, 1]))
        if area < 0:
            ring = ring[::-1]
        self.ring = ring
        self.travel = np.asarray(travel, dtype=np.float64)
        self.a = ring
        self.d = np.roll(ring, -1, axis=0) - ring
        self.len2 = np.einsum("ki,ki->k", self.d, self.d)
        length = np.sqrt(self.len2)
        self.out = np.column_stack((self.d[:, 1], -self.d[:, 0])) / length[:, None]  # outward (counter-clockwise ring)
        self.s0 = np.concatenate(([0.0], np.cumsum(length)[:-1]))
        self.perimeter = float(length.sum())
        prev = np.roll(self.out, 1, axis=0)  # the segment ending at each vertex
        mean = prev + self.out
        turn = np.degrees(np.arccos(np.clip(np.einsum("ki,ki->k", prev, self.out), -1.0, 1.0)))
        self.smooth = turn < SMOOTH_DEG  # per vertex
        self.vnormal = mean / np.maximum(np.hypot(mean[:, 0], mean[:, 1]), 1e-300)[:, None]
        self.lo, self.hi = ring.min(axis=0), ring.max(axis=0)
        self._out_prev, self._out_next = prev, np.roll(self.out, -1, axis=0)
        self._any_smooth = bool(self.smooth.any())
        self._length = length

    def moved(self, shift, travel) -> Obstacle:
        """The same part with its end ``shift`` ((2,), units) further, arriving by ``travel`` ((2,), units).

        ``moved(travel - self.travel, travel)`` is the part starting where
        this one starts and travelling ``travel`` instead;
        ``moved((0, 0), travel)`` ends where this one ends.
        """
        new = copy.copy(self)
        shift = np.asarray(shift, dtype=np.float64)
        new.ring = new.a = self.ring + shift
        new.lo, new.hi = self.lo + shift, self.hi + shift
        new.travel = np.asarray(travel, dtype=np.float64)
        return new

    def at(self, t: float) -> np.ndarray:
        """The outline's offset at load fraction ``t`` (0 start, 1 end), ``(2,)``."""
        return -(1.0 - t) * self.travel

    def query(self, x: np.ndarray, shift: np.ndarray, margin: float):
        """Signed penetration, outward normal and place along the outline of points near the part.

        Parameters
        ----------
        x : (P, 2) float64 ndarray
            Points, units.
        shift : (2,) float64 ndarray
            The outline's offset from its end position.
        margin : float
            Points farther than this outside the outline's bounding box are skipped.

        Returns
        -------
        idx : (m,) int64 ndarray
            The points looked at.
        g : (m,) float64 ndarray
            Penetration, positive inside the part, units.
        n : (m, 2) float64 ndarray
            The part's outward unit normal at the closest point.
        s : (m,) float64 ndarray
            Arc length of the closest point along the outline, units.
        """
        y = x - shift
        box = (y >= self.lo - margin) & (y <= self.hi + margin)
        idx = np.flatnonzero(box[:, 0] & box[:, 1])
        m, k = len(idx), len(self.a)
        g = np.empty(m)
        n = np.empty((m, 2))
        s = np.empty(m)
        chunk = max(1, 2_000_000 // k)
        for c0 in range(0, m, chunk):
            yy = y[idx[c0:c0 + chunk]]
            w = yy[:, None, :] - self.a  # (m, k, 2): from each segment's start
            t = np.clip((w * self.d).sum(axis=2) / self.len2, 0.0, 1.0)
            w -= t[:, :, None] * self.d  # now from each segment's closest point
            d2 = (w * w).sum(axis=2)
            j = np.argmin(d2, axis=1)
            r = np.arange(len(yy))
            tj, wj = t[r, j], w[r, j]
            dist = np.sqrt(d2[r, j])
            at0, at1 = tj <= 0.0, tj >= 1.0
            # Inside by the closest feature's pseudo-normal (Baerentzen & Aanaes 2005): the segment's
            # outward normal, or at a vertex the sum of its two segments' (the same as an even-odd count).
            pseudo = self.out[j] + at0[:, None] * self._out_prev[j] + at1[:, None] * self._out_next[j]
            inside = (wj * pseudo).sum(axis=1) < 0.0
            if self._any_smooth:
                j1 = (j + 1) % k
                n0 = np.where(self.smooth[j, None], self.vnormal[j], self.out[j])
                n1 = np.where(self.smooth[j1, None], self.vnormal[j1], self.out[j])
                normal = (1.0 - tj)[:, None] * n0 + tj[:, None] * n1
                normal /= np.hypot(normal[:, 0], normal[:, 1])[:, None]
                sharp = np.where(at0, ~self.smooth[j], ~self.smooth[j1])
            else:
                normal = self.out[j]
                sharp = True
            corner = (at0 | at1) & sharp & (dist > 1e-12 * (1.0 + np.abs(yy).max(initial=0.0)))
            if corner.any():
                v = wj[corner] / dist[corner, None]  # from the closest vertex to the point
                normal[corner] = np.where(inside[corner, None], -v, v)
            g[c0:c0 + chunk] = np.where(inside, dist, -dist)
            n[c0:c0 + chunk] = normal
            s[c0:c0 + chunk] = self.s0[j] + tj * self._length[j]
        return idx, g, n, s


class ContactPhysics:
    """A body physics with the contact terms of rigid parts added; everything else delegated.

    The solver sees the same interface (``fields``, ``residual``,
    ``element_matrices``...): the fields carry the positions, the residual
    and the element matrices gain the contact terms. The load fraction
    :attr:`t` (where the parts are) and the multipliers :attr:`lam` are this
    object's state: each solve works on its own copy.

    Parameters
    ----------
    physics : object
        The mixed problem (plane or axisymmetric).
    boundary : Boundary
    obstacles : list of Obstacle
    lam : (K, V) float64 ndarray, optional
        Multipliers per part and boundary vertex (pressure per reference length); zeros by default.
    anchor : (K, P) float64 ndarray, optional
        Friction's anchors: where along each part's outline (arc length,
        units) each point sticks; NaN where none is set (the point's own
        place then: no tangential force). NaN by default.
    """

    def __init__(self, physics, boundary: Boundary, obstacles, lam=None, anchor=None):
        object.__setattr__(self, "_inner", physics)
        object.__setattr__(self, "boundary", boundary)
        object.__setattr__(self, "obstacles", list(obstacles))
        object.__setattr__(self, "t", 1.0)
        k = len(obstacles)
        object.__setattr__(self, "lam", np.zeros((k, len(boundary.vertex_weight))) if lam is None
                           else np.array(lam, dtype=np.float64))
        object.__setattr__(self, "anchor", np.full((k, len(boundary.weight)), np.nan) if anchor is None
                           else np.array(anchor, dtype=np.float64))
        object.__setattr__(self, "_cache", [])
        object.__setattr__(self, "_memo", [])
        object.__setattr__(self, "_vectors", [])
        object.__setattr__(self, "_residual", None)
        # What every evaluation reads of the boundary: each edge's vertices and nodes, the smallest penalty,
        # the largest element size, the vertices that carry a pressure.
        object.__setattr__(self, "_fixed", (boundary.vertex[::GAUSS], boundary.nodes[::GAUSS],
                                            float(boundary.penalty.min(initial=np.inf)),
                                            float(boundary.size.max(initial=0.0)), boundary.vertex_weight > 0))

    _own = ("_inner", "boundary", "obstacles", "t", "lam", "anchor", "_cache", "_memo", "_vectors", "_fixed", "_residual")

    def __getattr__(self, name):
        return getattr(self._inner, name)

    def __setattr__(self, name, value):
        if name in self._own:
            object.__setattr__(self, name, value)
        else:
            setattr(self._inner, name, value)

    def __copy__(self):
        new = ContactPhysics(copy.copy(self._inner), self.boundary, self.obstacles, self.lam, self.anchor)
        object.__setattr__(new, "t", self.t)
        return new

    @property
    def inner(self):
        """The physics without contact."""
        return self._inner

    def positions(self, z: np.ndarray) -> np.ndarray:
        """Node positions ``(N, 2)`` of state ``z``."""
        n = self._inner.n_nodes
        return z[: 2 * n].reshape(n, 2)

    def fields(self, z: np.ndarray, lz: float):
        f = self._inner.fields(z, lz)
        if f is not None:
            object.__setattr__(self, "_cache", [*self._cache[-3:], (f, self.positions(z).copy())])
        return f

    def computed(self, f) -> bool:
        """Whether the fields ``f`` are among the last states computed here (their positions known)."""
        return f is not None and any(g is f for g, _ in self._cache)

    def _x(self, f) -> np.ndarray:
        """The positions the fields ``f`` were computed at (one of the last four states)."""
        for g, x in reversed(self._cache):
            if g is f:
                return x
        raise RuntimeError("ContactPhysics: fields of a state not computed here")

    def evaluate(self, x: np.ndarray) -> list[Touch]:
        """Per part, where it presses on the bodies at node positions ``x`` ``(N, 2)``: a :class:`Touch`.

        A node's pressure (per reference length) is ``ramp(λ_v + ε_v ĝ_v)``
        with ``ĝ_v = Σ w ψ_v g / D_v`` the penetration ``g`` of its edges'
        Gauss points averaged with its hat ``ψ_v``; a point's is the linear
        interpolation of the two nodes of its half edge.
        """
        b, (corner, edge_nodes, pen_min, size_max, carries) = self.boundary, self._fixed
        xq = b.points(x)
        margin = float(self.lam.max(initial=0.0) / pen_min + SMOOTHING / PENALTY * size_max) + 1e-9 * (1.0 + float(np.abs(xq).max()))
        xe = x[edge_nodes]  # (edges, 3, 2)
        halves = xe[:, 2:] - xe[:, :2]  # from each corner to the mid-node
        reach = margin + 2.0 * float(np.sqrt((halves * halves).sum(axis=2)).sum(axis=1).max(initial=0.0))
        out = []
        for k, obs in enumerate(self.obstacles):
            # Every point of an edge at a vertex that has a point within ``margin`` is within ``reach``.
            shift = obs.at(self.t)
            seen, g_all, n_all, s_all = obs.query(xq, shift, reach)
            near = seen[_outside_box(xq[seen] - shift, obs.lo, obs.hi) <= margin]
            if not len(near):
                out.append(_NO_TOUCH)
                continue
            candidates = np.zeros(len(carries), bool)
            candidates[b.vertex[near]] = True
            candidates &= carries  # a node bonded to the support carries no pressure
            vidx = np.flatnonzero(candidates)
            edges = np.flatnonzero(candidates[corner].any(axis=1))  # every edge of a candidate vertex: its whole hat
            pts = (edges[:, None] * GAUSS + _GAUSS_RANGE).ravel()
            at = np.searchsorted(seen, pts)  # seen is sorted and holds pts
            g, n, s = g_all[at], n_all[at], s_all[at]
            gap = _vertex_mean(b, pts, g, vidx)
            eps = b.vertex_penalty[vidx]
            vp, vslope = ramp(self.lam[k, vidx] + eps * gap, SMOOTHING / PENALTY * eps * b.vertex_size[vidx])
            full = np.zeros(len(candidates))
            full[vidx] = vp
            p = (b.psi[pts] * full[b.vertex[pts]]).sum(axis=1)
            on = np.repeat((full[corner[edges]] > 0).any(axis=1), GAUSS)  # whole edges: those with a pressed node
            out.append(Touch(pts[on], p[on], n[on], g[on], s[on], vidx, vp, gap, vslope))
        return out

    def friction(self, k: int, idx: np.ndarray, p: np.ndarray, s: np.ndarray):
        """Part ``k``'s tangential force per reference length at its contact points and its derivatives.

        Returns
        -------
        q : (m,) float64 ndarray
            Along the outline's tangent ``τ = (−n_y, n_x)``, on the body.
        dq_dd : (m,) float64 ndarray
            Its derivative in the slip ``d = s − s_a`` (at most ``ε_t`` in size, at ``d = 0``).
        dq_dp : (m,) float64 ndarray
            Its derivative in the pressure ``p``.
        d : (m,) float64 ndarray
            The slip from the anchor, units.
        """
        obs = self.obstacles[k]
        anchor = self.anchor[k, idx]
        d = np.where(np.isnan(anchor), 0.0, s - anchor)
        d = d - obs.perimeter * np.round(d / obs.perimeter)  # the shorter way round a closed outline
        limit = obs.friction * p
        delta, floor = self._slip_scale(idx, limit)
        inside = np.abs(d) < SLIP_MEMORY * delta  # |u| < 1
        u = np.where(inside, d / (SLIP_MEMORY * delta), 0.0)
        psi = np.where(inside, 0.5 * (3.0 - u * u) * u, np.sign(d))
        q = -limit * psi
        dq_dd = np.where(inside, -limit * (1.0 - u * u) / delta, 0.0)
        dq_dp = -obs.friction * np.where(inside, np.where(floor, psi, u**3), np.sign(d))
        return q, dq_dd, dq_dp, d

    def _slip_scale(self, idx: np.ndarray, limit: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``δ = max(μ_f p / ε_t, SLIP_FLOOR h)`` at the points ``idx``, and where the floor holds."""
        b = self.boundary
        floor = SLIP_FLOOR * b.size[idx]
        delta = limit / (TANGENT_PENALTY * b.penalty[idx])
        return np.maximum(delta, floor), delta <= floor

    def _state(self, f) -> tuple:
        """What an evaluation at the fields ``f`` depends on: ``(f, t, lam, anchor)`` (arrays replaced, never changed in place)."""
        return (f, self.t, self.lam, self.anchor)

    @staticmethod
    def _same(a: tuple, b: tuple) -> bool:
        """Whether two :meth:`_state` keys are the same state: the same objects, the same load fraction."""
        return a[0] is b[0] and a[2] is b[2] and a[3] is b[3] and a[1] == b[1]

    def _contact_of(self, f) -> list:
        """:meth:`evaluate` at the positions of the fields ``f``, once for the residual and the tangent alike.

        Kept for the last two fields, with the load fraction, multipliers and
        anchors it was computed under (each replaced, never changed in place).
        """
        key = self._state(f)
        for memo, out in self._memo:
            if self._same(memo, key):
                return out
        out = self.evaluate(self._x(f))
        object.__setattr__(self, "_memo", [*self._memo[-1:], (key, out)])
        return out

    def contact_residual(self, x: np.ndarray, contact: list | None = None) -> np.ndarray:
        """The contact terms of the position residual, ``(2 N,)`` (``contact``: :meth:`evaluate` at ``x``, if known)."""
        contact = self.evaluate(x) if contact is None else contact
        return self._assembled([(idx, _traction(self, k, idx, p, n, s)) for k, (idx, p, n, _, s, *_) in enumerate(contact)])

    def _assembled(self, tractions) -> np.ndarray:
        """``−∫ t N_a ds0`` at the nodes, ``(2 N,)``, from ``(idx, t)`` pairs: tractions ``(m, 2)`` at boundary points ``idx``."""
        b = self.boundary
        r = np.zeros((self._inner.n_nodes, 2))
        for idx, traction in tractions:
            force = -b.weight[idx][:, None, None] * b.shape[idx][:, :, None] * traction[:, None, :]  # (m, 3, 2)
            np.add.at(r, b.nodes[idx], force)
        return r.ravel()

    def residual_rate(self, x: np.ndarray, shifts: np.ndarray, dx: np.ndarray | None = None,
                      contact: list | None = None) -> np.ndarray:
        """The first-order change of the contact residual at ``x`` as the parts move by ``shifts`` ((K, 2), units), ``(2 N,)``.

        A point's penetration grows by ``n · shift``, so a pressed node's
        weighted one by its average and its pressure by ``ramp′ ε_v`` times
        that, along each point's ``n``; a node not pressed at ``x`` stays
        so (first order), and the tangential force is held. With ``dx``
        (``(N, 2)``, units: the nodes moved too) the penetration grows by
        ``n · (shift − dx)`` instead: the augmented-Lagrangian update that
        closes what the nodes' move left open (a preview's Uzawa step).
        ``contact``: :meth:`evaluate` at ``x``, if known.
        """
        b = self.boundary
        tractions = []
        for touch, shift in zip(self.evaluate(x) if contact is None else contact, shifts):
            idx = touch.idx
            if not len(idx):
                continue
            grow = touch.n @ np.asarray(shift, dtype=np.float64)
            if dx is not None:
                grow = grow - np.einsum("pi,pi->p", touch.n, np.einsum("pa,pai->pi", b.shape[idx], dx[b.nodes[idx]]))
            dgap = _vertex_mean(b, idx, grow, touch.vidx)
            dp = np.zeros(len(b.vertex_weight))
            dp[touch.vidx] = touch.vslope * b.vertex_penalty[touch.vidx] * dgap
            rate = np.einsum("pj,pj->p", b.psi[idx], dp[b.vertex[idx]])
            tractions.append((idx, rate[:, None] * touch.n))
        return self._assembled(tractions)

    def residual(self, f) -> np.ndarray:
        """The bodies' residual with the contact's, ``(2 N + n_pressures,)``; the last one kept (its reactions are
        read again once a solve ends on it).
        """
        key = self._state(f)
        last = self._residual
        if last is not None and self._same(last[0], key):
            return last[1].copy()
        r = self._inner.residual(f)
        n2 = 2 * self._inner.n_nodes
        r[:n2] += self.contact_residual(self._x(f), self._contact_of(f))
        object.__setattr__(self, "_residual", (key, r.copy()))
        return r

    def element_matrices(self, f) -> np.ndarray:
        """The bodies' element matrices with the contact's stiffness within each free edge added, ``(E, k, k)``.

        A node ``v`` carrying the pressure adds ``ε_v ramp′_v / D_v r_v a_vᵀ``:
        ``a_v = Σ w ψ_v n N`` over its edges' points is the derivative of its
        weighted penetration (times ``−D_v``), ``r_v = a_v + Σ w ψ_v ∂q/∂p τ N``
        where the force depends on its pressure (friction's share through
        ``q``), the curvature of the parts' outlines left out (a quasi-Newton
        tangent there). Friction's dependence on the slip is pointwise. The
        products of one edge's parts go to that edge's cell, those of two
        edges meeting at a corner to :meth:`coupling_matrices`.
        """
        ke = self._inner.element_matrices(f)
        b = self.boundary
        for k, touch in enumerate(self._contact_of(f)):
            idx = touch.idx
            if not len(idx):
                continue
            edges, a, r, c, along = self._edge_vectors(k, touch)
            cell, local = b.cell[edges * GAUSS], b.local[edges * GAUSS]  # (e,), (e, 3)
            block = np.einsum("ej,ejai,ejbl->eaibl", c[b.vertex[edges * GAUSS]], r, a)  # (e, 3, 2, 3, 2)
            if along is not None:
                w = (b.penalty[idx] * b.weight[idx])[:, None, None, None, None]
                pointwise = w * b.shape[idx][:, :, None, None, None] * b.shape[idx][:, None, :, None, None] * along[:, None, None]
                block = block + pointwise.reshape(len(edges), GAUSS, 3, 3, 2, 2).sum(axis=1).transpose(0, 1, 3, 2, 4)
            rows = (2 * local[:, :, None] + np.arange(2))[:, :, :, None, None]
            cols = (2 * local[:, :, None] + np.arange(2))[:, None, None, :, :]
            cells = np.broadcast_to(cell[:, None, None, None, None], block.shape)
            np.add.at(ke, (cells, np.broadcast_to(rows, block.shape), np.broadcast_to(cols, block.shape)), block)
        return ke

    def coupling_matrices(self, f) -> np.ndarray:
        """The contact's stiffness between two free edges meeting at a pressed corner, ``(Q, 12, 12)``.

        Row and column order of :attr:`Boundary.pair_dofs`: the first
        edge's three nodes, then the second's.
        """
        b = self.boundary
        out = np.zeros((len(b.pairs), 12, 12))
        for k, touch in enumerate(self._contact_of(f)):
            if not len(touch.idx):
                continue
            edges, a, r, c, _ = self._edge_vectors(k, touch)
            where = np.full(b.edges, -1)
            where[edges] = np.arange(len(edges))
            e1, e2 = where[b.pairs[:, 0]], where[b.pairs[:, 2]]
            q = np.flatnonzero((e1 >= 0) & (e2 >= 0))
            if not len(q):
                continue
            e1, e2, j1, j2 = e1[q], e2[q], b.pairs[q, 1], b.pairs[q, 3]
            cv = c[b.vertex[edges[e1] * GAUSS, j1]][:, None, None]
            out[q, :6, 6:] += cv * np.einsum("qai,qbl->qaibl", r[e1, j1], a[e2, j2]).reshape(len(q), 6, 6)
            out[q, 6:, :6] += cv * np.einsum("qai,qbl->qaibl", r[e2, j2], a[e1, j1]).reshape(len(q), 6, 6)
        return out

    def _edge_vectors(self, k: int, touch: Touch):
        """Part ``k``'s pressed edges and their shares of each node's ``a_v`` and ``r_v`` ``(e, 3, 3, 2)``;
        ``ε_v ramp′_v / D_v`` ``(V,)``; friction's pointwise slip stiffness ``(m, 2, 2)`` (None without friction).

        Kept for the last touches it was made for: a tangent's element and coupling matrices share them.
        """
        for done, vectors in self._vectors:
            if done is touch:
                return vectors
        vectors = self._make_edge_vectors(k, touch)
        object.__setattr__(self, "_vectors", [*self._vectors[-3:], (touch, vectors)])
        return vectors

    def _make_edge_vectors(self, k: int, touch: Touch):
        """:meth:`_edge_vectors`, computed."""
        b = self.boundary
        idx = touch.idx  # whole edges
        edges = idx[::GAUSS] // GAUSS
        wpsi = (b.weight[idx, None] * b.psi[idx]).reshape(len(edges), GAUSS, 3)
        shape = b.shape[idx].reshape(len(edges), GAUSS, 3)
        a = np.einsum("egj,ega,egi->ejai", wpsi, shape, touch.n.reshape(len(edges), GAUSS, 2))
        c = np.zeros(len(b.vertex_weight))
        c[touch.vidx] = touch.vslope * b.vertex_penalty[touch.vidx] / b.vertex_weight[touch.vidx]
        if self.obstacles[k].friction <= 0:
            return edges, a, a, c, None
        n = touch.n
        _, dq_dd, dq_dp, _ = self.friction(k, idx, touch.p, touch.s)
        tau = np.column_stack((-n[:, 1], n[:, 0]))
        r = a + np.einsum("egj,ega,egi->ejai", wpsi, shape, (dq_dp[:, None] * tau).reshape(len(edges), GAUSS, 2))
        along = (-dq_dd / b.penalty[idx])[:, None, None] * tau[:, :, None] * tau[:, None, :]
        return edges, a, r, c, along

    def commit(self, x: np.ndarray) -> None:
        """Move the friction anchors to the converged state ``x`` (the return mapping's history).

        A point in contact keeps its anchor within :data:`SLIP_MEMORY` δ
        (dragged along when it slid further); a point not in contact is
        anchored where it is.
        """
        b = self.boundary
        if not any(obs.friction > 0 for obs in self.obstacles):
            return
        xq = b.points(x)
        anchor = np.full_like(self.anchor, np.nan)
        contact = self.evaluate(x)
        for k, obs in enumerate(self.obstacles):
            if obs.friction <= 0:
                continue
            near, _, _, s_all = obs.query(xq, obs.at(self.t), 2.0 * float(b.size.max()))
            anchor[k, near] = s_all
            idx, p, s = contact[k].idx, contact[k].p, contact[k].s
            if len(idx):
                d = self.friction(k, idx, p, s)[3]
                reach = SLIP_MEMORY * self._slip_scale(idx, obs.friction * p)[0]  # q unchanged
                anchor[k, idx] = (s - np.clip(d, -reach, reach)) % obs.perimeter
        object.__setattr__(self, "anchor", anchor)

    def update(self, x: np.ndarray, contact: list | None = None) -> float:
        """Uzawa's update ``λ ← max(0, λ + ε ĝ)`` at ``x`` (``contact``: :meth:`evaluate` there, if known); the largest
        penetration relative to the element size before it.
        """
        lam = np.zeros_like(self.lam)
        contact = self.evaluate(x) if contact is None else contact
        for k, touch in enumerate(contact):
            lam[k, touch.vidx] = touch.vp
        object.__setattr__(self, "lam", lam)
        return _penetration(self.boundary, contact)

    def penetration(self, x: np.ndarray, contact: list | None = None) -> float:
        """The largest weighted penetration of a pressed vertex at ``x`` (``contact`` as :meth:`update`), relative to the
        element size.
        """
        return _penetration(self.boundary, self.evaluate(x) if contact is None else contact)


class Touch(NamedTuple):
    """Where one part presses on the bodies: its pressed boundary points and vertices.

    Attributes
    ----------
    idx : (m,) int64 ndarray
        The points of the pressed edges (those with a pressed node), whole edges in order.
    p : (m,) float64 ndarray
        Their pressure per reference length (interpolated from the nodes'; 0 on the unpressed half of an edge).
    n : (m, 2) float64 ndarray
        The part's outward normal at each point's closest place.
    g : (m,) float64 ndarray
        Each point's penetration, units.
    s : (m,) float64 ndarray
        Each point's closest place along the part's outline, units.
    vidx : (a,) int64 ndarray
        The vertices looked at (those with a point near the part).
    vp, vgap, vslope : (a,) float64 ndarray
        Their pressure per reference length (0 when not pressed), weighted
        penetration (units) and ramp slope.
    """

    idx: np.ndarray
    p: np.ndarray
    n: np.ndarray
    g: np.ndarray
    s: np.ndarray
    vidx: np.ndarray
    vp: np.ndarray
    vgap: np.ndarray
    vslope: np.ndarray


_EMPTY = np.zeros(0)
_NO_TOUCH = Touch(np.zeros(0, np.int64), _EMPTY, np.zeros((0, 2)), _EMPTY, _EMPTY, np.zeros(0, np.int64), _EMPTY,
                  _EMPTY, _EMPTY)


def _outside_box(y: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """How far each point ``(m, 2)`` lies outside the box ``[lo, hi]`` along either axis (0 inside), ``(m,)``."""
    return np.maximum(np.maximum(lo - y, y - hi), 0.0).max(axis=1, initial=0.0)


def _vertex_mean(b: Boundary, idx: np.ndarray, values: np.ndarray, vidx: np.ndarray) -> np.ndarray:
    """``Σ w ψ_v value / D_v`` at the vertices ``vidx`` of the point values ``values`` at points ``idx``."""
    share = b.psi[idx] * (b.weight[idx] * values)[:, None]
    total = np.bincount(b.vertex[idx].ravel(), weights=share.ravel(), minlength=len(b.vertex_weight))
    return total[vidx] / b.vertex_weight[vidx]


def _penetration(b: Boundary, contact: list) -> float:
    """The largest weighted penetration of a pressed vertex, relative to its element size."""
    worst = 0.0
    for touch in contact:
        on = touch.vp > 0
        if on.any():
            worst = max(worst, float((np.maximum(touch.vgap[on], 0.0) / b.vertex_size[touch.vidx[on]]).max()))
    return worst


@dataclass(frozen=True, eq=False)
class PartContact:
    """What one rigid part feels: the force on it and its contact figures.

    Attributes
    ----------
    name : str
    force : (float, float)
        The force the bodies exert on the part: per unit length for a plane
        section, the whole ring's for a body of revolution (units of the
        moduli times units², or per units).
    length : float
        The contact's length along the part's outline in the section's plane, units.
    pressure_max, pressure_mean : float
        The largest and the mean contact pressure (true, per deformed area), units of the moduli.
    penetration_max : float
        The largest penetration left, units.
    pressure : (m, 3) float64 ndarray
        ``[x, y, p]`` at the pressed boundary vertices (the corner nodes carrying the pressure), in order along
        the part's outline.
    outline : (k, 2) float64 ndarray
        The part's outline where it is (for figures; not written to JSON).
    """

    name: str
    force: tuple
    length: float
    pressure_max: float
    pressure_mean: float
    penetration_max: float
    pressure: np.ndarray
    outline: np.ndarray = None

    def to_json(self) -> dict:
        """The result's ``rigid[]`` object."""
        return {"name": self.name, "force": [float(v) for v in self.force],
                "contact": {"length": self.length, "pressure_max": self.pressure_max, "pressure_mean": self.pressure_mean,
                            "penetration_max": self.penetration_max, "pressure": self.pressure.tolist()}}


def _traction(physics: ContactPhysics, k: int, idx, p, n, s) -> np.ndarray:
    """Part ``k``'s traction on the body at its contact points ``(m, 2)``: the pressure along ``n``, friction along the outline."""
    traction = p[:, None] * n
    if physics.obstacles[k].friction > 0 and len(idx):
        q = physics.friction(k, idx, p, s)[0]
        traction = traction + q[:, None] * np.column_stack((-n[:, 1], n[:, 0]))
    return traction


def part_forces(physics: ContactPhysics, contact: list, ring: float = 1.0) -> list[tuple[float, float]]:
    """Each part's force ``(fx, fy)`` from its contact (:meth:`ContactPhysics.evaluate`), as :func:`contact_figures`."""
    b = physics.boundary
    out = []
    for k, (idx, p, n, _, s, *_) in enumerate(contact):
        force = -ring * b.weight[idx] @ _traction(physics, k, idx, p, n, s) if len(idx) else np.zeros(2)
        out.append((float(force[0]), float(force[1])))
    return out


def contact_figures(physics: ContactPhysics, x: np.ndarray, names, ring: float = 1.0, radius=None,
                    contact: list | None = None) -> list[PartContact]:
    """Each part's force and contact figures at positions ``x`` (``contact``: :meth:`ContactPhysics.evaluate` there, if known).

    Parameters
    ----------
    physics : ContactPhysics
    x : (N, 2) float64 ndarray
        Node positions, units.
    names : sequence of str
        The parts' names.
    ring : float
        The factor from the integrals to the forces: 1 for a plane section, 2π for a body of revolution.
    radius : callable, optional
        Distance from the axis, for the true pressure of a body of revolution.

    Returns
    -------
    list of PartContact
    """
    b = physics.boundary
    contact = physics.evaluate(x) if contact is None else contact
    out = []
    for name, obs, force, touch in zip(names, physics.obstacles, part_forces(physics, contact, ring), contact):
        idx = touch.idx
        xe = x[b.nodes[idx]]
        xq = np.einsum("pa,pai->pi", b.shape[idx], xe)
        tang = np.einsum("pa,pai->pi", b.dshape[idx], xe)
        dl = _W[idx % GAUSS] * np.hypot(tang[:, 0], tang[:, 1])  # the current length of each point's share
        cur = dl * (radius(xq) if radius is not None else 1.0)
        vidx, true = _corner_pressure(b, idx, touch.p, cur)
        at = x[b.vertex_node[vidx]]
        order = np.argsort(obs.query(at, obs.at(physics.t), np.inf)[3], kind="stable")
        length = _contact_length(b, touch, dl)
        area = float((touch.p * b.weight[idx] * dl / np.where(cur > 0, cur, np.inf)).sum())  # ∫ p dl, current
        mean = area / length if length > 0 else 0.0
        out.append(PartContact(
            name=name, force=force, length=length,
            # a contact narrower than the corners' hats has its projection spread over them: the peak is then
            # at least the mean over the contact's own length
            pressure_max=max(float(true.max(initial=0.0)), mean),
            pressure_mean=mean,
            penetration_max=float(np.maximum(touch.g, 0.0).max(initial=0.0)),
            pressure=np.column_stack((at, true))[order],
            outline=obs.ring + obs.at(physics.t),
        ))
    return out


def _corner_pressure(b: Boundary, idx: np.ndarray, p: np.ndarray, cur: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pressure at the edges' corners: its projection on the functions linear along each edge, true (per current length).

    The pressure carried by every node of a quadratic edge oscillates from
    node to node (the price of constraining every node: it keeps the
    quadratic edge on the part); its L2 projection on the coarser hats of
    the corners, ``∫ φ_v p ds0 / ∫ φ_v ds0``, removes that and keeps its
    integral. Converted to the true pressure with the current length
    (``cur``: each point's current share, times its distance from the axis
    for a body of revolution) as ``∫ φ_v p ds0 / ∫ φ_v ds``.

    Returns
    -------
    vidx : (c,) int64 ndarray
        The corners with a positive pressure.
    true : (c,) float64 ndarray
        Their pressure, units of the moduli.
    """
    hat = np.column_stack((1.0 - _S, _S))  # (g, 2): corner a, corner b
    corners = b.vertex[idx][:, :2]
    share = np.tile(hat, (len(idx) // GAUSS, 1))
    n = len(b.vertex_weight)
    load = np.bincount(corners.ravel(), weights=(share * (b.weight[idx] * p)[:, None]).ravel(), minlength=n)
    now = np.bincount(corners.ravel(), weights=(share * cur[:, None]).ravel(), minlength=n)
    vidx = np.flatnonzero(load > 0)
    return vidx, load[vidx] / now[vidx]


def _contact_length(b: Boundary, touch: Touch, dl: np.ndarray) -> float:
    """The pressed length along the bodies' outline, units (``dl``: the current length of each pressed point's share).

    The outline is cut at the nodes carrying the pressure into segments
    (half edges). A segment with both ends pressed counts whole. On a
    segment from a pressed node to one not pressed, the contact runs from
    the pressed node until the body leaves the part: to the last place
    where the penetration, linear between the edge's Gauss points, is
    above ``−PENETRATION_FRACTION h`` (the contact's own tolerance; within a
    contact the pointwise penetration wavers about 0 by more than that, so
    the last such place, not the first one below it).
    """
    if not len(touch.idx):
        return 0.0
    pv = np.zeros(len(b.vertex_weight))
    pv[touch.vidx] = touch.vp
    edges = touch.idx[::GAUSS] // GAUSS
    first = np.where(_S < 0.5, 1.0, np.where(_S == 0.5, 0.5, 0.0))
    shares = dl.reshape(len(edges), GAUSS)
    nodes = b.vertex[edges * GAUSS]  # (e, 3): corner a, corner b, mid
    pressed = pv[nodes] > 0
    halves = np.stack((shares @ first, shares @ (1.0 - first)), axis=1)  # (e, 2): a-m, m-b
    whole = np.stack((pressed[:, 0] & pressed[:, 2], pressed[:, 2] & pressed[:, 1]), axis=1)
    total = float(halves[whole].sum())
    ends = np.stack((pressed[:, 0] != pressed[:, 2], pressed[:, 2] != pressed[:, 1]), axis=1)
    if not ends.any():
        return total
    gap = (touch.g.reshape(len(edges), GAUSS) @ _FINE.T) / b.size[touch.idx[::GAUSS], None]  # (e, F) along the edge
    for e, half in zip(*np.nonzero(ends)):
        grid = _FINE_S <= 0.5 if half == 0 else _FINE_S >= 0.5
        run = gap[e, grid]  # from node a (or the mid-node) to the mid-node (or node b)
        outward = pressed[e, 0] if half == 0 else pressed[e, 2]  # the pressed node is the segment's start
        run = run if outward else run[::-1]
        on = np.flatnonzero(run >= -PENETRATION_FRACTION)
        total += float(halves[e, half] * (on[-1] / (len(run) - 1) if len(on) else 0.0))
    return total


def ring_factor(plane: bool) -> float:
    """1 for a plane section, 2π for a body of revolution (integrals per radian)."""
    return 1.0 if plane else 2.0 * math.pi
