"""What CalculiX says of the rigid parts: forces from the ``.dat``, contact pressures from the ``.frd``.

* The force on each part: the total reaction ``RF`` of its nodes, printed
  to the ``.dat`` at every increment (``*NODE PRINT, NSET=R_<NAME>_NODES,
  TOTALS=ONLY``: CalculiX computes no reaction at a rigid body's reference
  node, whose forces come through multiple point constraints); the support's: the total of ``RF`` over the set ``SUPPORT``
  (``TOTALS=ONLY``). The reaction balances the bodies' push, so the force
  the bodies exert on the part is ``−RF``. CalculiX's forces of an axisymmetric model are per radian; they
  are multiplied by 2π for the whole ring, as the project reports them.
* The contact: ``CPRESS`` and ``COPEN`` of the ``CONTACT`` block
  (``*CONTACT FILE`` ``CSTR, CDIS``) at the slave nodes; each node in
  contact is given to the part whose outline (at its end) is nearest. The
  contact length is the deformed length of the bodies' free faces where the
  pressure, linear between a face's successive nodes (corner, middle,
  corner), is positive.
"""

from __future__ import annotations

import math
import re

import numpy as np

from ..fem.contact import Obstacle, PartContact
from ..models.hyperelastic_contact import HistoryStep

__all__ = ["AXISYMMETRIC_SEGMENTS", "AXISYMMETRIC_NOTE", "read_dat_forces", "contact_of_parts"]

AXISYMMETRIC_SEGMENTS = 180.0
"""CalculiX's reactions of a body of revolution times this: the whole ring (its elements span 2°)."""
AXISYMMETRIC_NOTE = ("CalculiX, body of revolution: each rigid part's ring force is the integral of CalculiX's contact "
                     "pressure; the support's force and the history are its reactions times 180 (a 2-degree segment), "
                     "which on the sleeve came 8 % below the pressure's integral")

_HEAD = re.compile(r"^\s*forces \(fx,fy,fz\) for set (\S+) and time\s+(\S+)", re.IGNORECASE)
_TOTAL = re.compile(r"^\s*total force \(fx,fy,fz\) for set (\S+) and time\s+(\S+)", re.IGNORECASE)


def read_dat_forces(text: str) -> dict:
    r"""Force blocks of a ``.dat`` file: set name (upper case) to ``[(time, (fx, fy, fz)), ...]``.

    A block of node lines is summed (one reference node); a ``total force``
    block is taken as it is.

    Examples
    --------
    >>> text = " total force (fx,fy,fz) for set R_P_NODES and time  0.5000000E+00\n\n  1.0E+00 -2.0E+00  0.0E+00\n"
    >>> read_dat_forces(text)
    {'R_P_NODES': [(0.5, (1.0, -2.0, 0.0))]}
    """
    out: dict = {}
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        head, total = _HEAD.match(lines[i]), _TOTAL.match(lines[i])
        m = head or total
        i += 1
        if not m:
            continue
        name, time = m.group(1).upper(), float(m.group(2))
        acc = np.zeros(3)
        while i < len(lines) and not lines[i].strip():
            i += 1
        while i < len(lines) and lines[i].strip() and not (_HEAD.match(lines[i]) or _TOTAL.match(lines[i])):
            parts = lines[i].split()
            try:
                vals = [float(v) for v in parts[-3:]]
            except ValueError:
                break
            acc += vals
            i += 1
        out.setdefault(name, []).append((time, tuple(float(v) for v in acc)))
    return out


def _face_nodes(cells: np.ndarray, corners: int, faces: np.ndarray) -> np.ndarray:
    """``(f, 3)`` (corner, corner, mid) or ``(f, 2)`` nodes of each face."""
    c = cells[faces[:, 0]]
    a = c[np.arange(len(c)), faces[:, 1]]
    b = c[np.arange(len(c)), (faces[:, 1] + 1) % corners]
    if cells.shape[1] == 2 * corners:
        return np.column_stack((a, b, c[np.arange(len(c)), corners + faces[:, 1]]))
    return np.column_stack((a, b))


def contact_of_parts(deck, frd, final: np.ndarray, dat: str):
    """Each part's :class:`~sectiondeform.fem.contact.PartContact`, the support's force, the history.

    Parameters
    ----------
    deck : Deck
        With rigid parts.
    frd : FrdResults
        ccx's results (the last ``CONTACT`` block).
    final : (N, 2) float64 ndarray
        The deformed nodes in the case's plane, units.
    dat : str
        The ``.dat`` text.

    Returns
    -------
    parts : tuple of PartContact
    support_force : (float, float)
    history : tuple of HistoryStep
    """
    from .contact_deck import free_faces

    m = deck.mesh
    ring = 1.0 if deck.axis is None else AXISYMMETRIC_SEGMENTS
    forces = read_dat_forces(dat)

    def to_case(v):
        v = np.asarray(v, dtype=np.float64)[:2]
        if deck.axis is not None:
            v = deck.axis.from_rz(v[None])[0] - np.asarray(deck.axis.origin)
        return -ring * v

    faces = free_faces(m.cells, m.corners, m.lower_nodes)
    fn = _face_nodes(m.cells, m.corners, faces)
    p_node = np.zeros(len(m.points))
    open_node = np.zeros(len(m.points))
    if frd.blocks.get("CONTACT"):
        _, ids, vals = frd.last("CONTACT")
        ok = ids <= len(m.points)
        p_node[ids[ok] - 1] = vals[ok, 3]
        open_node[ids[ok] - 1] = vals[ok, 0]
    # each face as a polyline through its nodes in order (corner, mid, corner), the pressure linear along each piece
    if fn.shape[1] == 3:
        fn = fn[:, [0, 2, 1]]
    s = np.linspace(0.0, 1.0, 9)
    xs = np.concatenate([(1 - s)[None, :, None] * final[fn[:, j]][:, None] + s[None, :, None] * final[fn[:, j + 1]][:, None]
                         for j in range(fn.shape[1] - 1)], axis=1)
    ps = np.concatenate([(1 - s)[None] * p_node[fn[:, j]][:, None] + s[None] * p_node[fn[:, j + 1]][:, None]
                         for j in range(fn.shape[1] - 1)], axis=1)
    mid = 0.5 * (ps[:, 1:] + ps[:, :-1])
    dl = np.hypot(*np.diff(xs, axis=1).transpose(2, 0, 1))
    xm = 0.5 * (xs[:, 1:] + xs[:, :-1])
    obstacles = [Obstacle(p.points + p.travel, (0.0, 0.0)) for p in deck.rigid]
    pts = xm.reshape(-1, 2)
    dist = np.full((len(obstacles), len(pts)), np.inf)
    normals = np.zeros((len(obstacles), len(pts), 2))
    for k, obs in enumerate(obstacles):
        idx, g, nk, _ = obs.query(pts, np.zeros(2), np.inf)
        dist[k, idx] = np.abs(g)
        normals[k, idx] = nk
    owner = np.argmin(dist, axis=0)
    on = mid.ravel() > 0
    nodes_on = np.unique(fn[p_node[fn] > 0])
    node_owner = np.zeros(len(m.points), np.int64)
    if len(nodes_on):
        nd = np.full((len(obstacles), len(nodes_on)), np.inf)
        for k, obs in enumerate(obstacles):
            idx, g, _, _ = obs.query(final[nodes_on], np.zeros(2), np.inf)
            nd[k, idx] = np.abs(g)
        node_owner[nodes_on] = np.argmin(nd, axis=0)
    parts = []
    for k, part in enumerate(deck.rigid):
        sel = on & (owner == k)
        length = float(dl.ravel()[sel].sum())
        pm = mid.ravel()[sel]
        mine = nodes_on[node_owner[nodes_on] == k]
        mine = mine[np.argsort(obstacles[k].query(final[mine], np.zeros(2), np.inf)[3], kind="stable")] \
            if len(mine) else mine
        if deck.axis is None:
            f = forces.get(f"{part.name}_NODES")
            force = to_case(f[-1][1]) if f else np.zeros(2)
        else:  # the whole ring: 2π ∫ p (−n) r dl over the contact
            r = deck.axis.to_rz(pts[sel])[:, 0]
            force = -2.0 * math.pi * ((pm * dl.ravel()[sel] * r) @ normals[k][sel])
        parts.append(PartContact(
            name=part.label, force=(float(force[0]), float(force[1])), length=length,
            pressure_max=float(p_node[mine].max(initial=0.0)),
            pressure_mean=float((pm * dl.ravel()[sel]).sum() / length) if length > 0 else 0.0,
            penetration_max=float(np.maximum(-open_node[mine], 0.0).max(initial=0.0)),
            pressure=np.column_stack((final[mine], p_node[mine])), outline=obstacles[k].ring))
    support = forces.get("SUPPORT", [])
    support_force = to_case(support[-1][1]) if support else np.zeros(2)
    times = [t for t, _ in forces.get(f"{deck.rigid[0].name}_NODES", [])]
    history = [HistoryStep(0.0, {**{p.label: (0.0, 0.0) for p in deck.rigid}, "support": (0.0, 0.0)})]
    for j, t in enumerate(times):
        step = {}
        for part in deck.rigid:
            f = forces.get(f"{part.name}_NODES", [])
            step[part.label] = tuple(float(v) for v in to_case(f[j][1])) if j < len(f) else (math.nan, math.nan)
        step["support"] = tuple(float(v) for v in to_case(support[j][1])) if j < len(support) else (math.nan, math.nan)
        history.append(HistoryStep(float(t), step))
    return tuple(parts), (float(support_force[0]), float(support_force[1])), tuple(history)
