"""One conforming mesh of several bonded bodies (``section-case/2``) for a solver deck.

Each body's outline is its section's polyline (lower nodes, then its upper
characteristic points thinned as for one body, see
:func:`~sectiondeform.external.mesh.thin_polyline`), every segment split to
the body's element size. The outlines are merged into one planar straight
line graph: points of different bodies closer than the contact tolerance
become one node, and a node of one outline lying on another's segment is
inserted into that segment, so a piece shared by two bodies is one chain of
segments with the same nodes on both sides (the bodies are bonded there).
Shewchuk's Triangle (the ``[fem]`` extra, as the project's reference mesh)
meshes it with quality triangles (30°), one region per body with that
body's area bound; each triangle carries its body.

The support's nodes are the nodes on the support's polyline; each gets the
arc-length fraction of its place along it, the rule by which it goes onto
the target. Six-node triangles and quads are made from the triangles as for
one body (:func:`~sectiondeform.external.mesh.add_mid_nodes`,
:func:`~sectiondeform.external.mesh.split_into_quads`), a mid-edge node of
the support taking the mean fraction of its edge.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.spatial import cKDTree

from ..errors import MeshError, require
from .mesh import KINDS, FeMesh, add_mid_nodes, split_into_quads, thin_polyline

__all__ = ["assembly_mesh", "split_ring"]

MIN_ANGLE_DEG = 30.0


def split_ring(ring: np.ndarray, size: float) -> np.ndarray:
    """A closed polyline with every segment longer than ``size`` split evenly, ``(k, 2)``.

    Examples
    --------
    >>> split_ring(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0]]), 1.0).shape
    (6, 2)
    """
    closed = np.concatenate((ring, ring[:1]))
    out = []
    for a, b in zip(closed[:-1], closed[1:]):
        k = max(1, math.ceil(np.hypot(*(b - a)) / size - 1e-9))
        t = np.arange(k)[:, None] / k
        out.append(a + t * (b - a))
    return np.concatenate(out)


def _merge(points: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Unique points (first of each cluster within ``tol``) and the index of each input point among them."""
    pairs = cKDTree(points).query_pairs(tol, output_type="ndarray")
    parent = np.arange(len(points))
    for i, j in sorted(map(tuple, pairs)):  # union towards the smaller index
        ri, rj = parent[i], parent[j]
        while parent[ri] != ri:
            ri = parent[ri]
        while parent[rj] != rj:
            rj = parent[rj]
        parent[max(ri, rj)] = min(ri, rj)
    for k in range(len(points)):
        r = k
        while parent[r] != r:
            r = parent[r]
        parent[k] = r
    roots, index = np.unique(parent, return_inverse=True)
    return points[roots], index.ravel()


def _augmented(ring_ids: np.ndarray, points: np.ndarray, tol: float) -> np.ndarray:
    """A ring's node ids with every other node lying on one of its segments inserted in order."""
    ring = points[ring_ids]
    line = shapely.LineString(np.concatenate((ring, ring[:1])))
    others = np.setdiff1d(np.arange(len(points)), ring_ids)
    if len(others) == 0:
        return ring_ids
    near = others[shapely.distance(shapely.points(points[others]), line) <= tol]
    if len(near) == 0:
        return ring_ids
    own = shapely.line_locate_point(line, shapely.points(ring))
    own[0] = 0.0
    at = shapely.line_locate_point(line, shapely.points(points[near]))
    order = np.argsort(np.concatenate((own, at)), kind="stable")
    return np.concatenate((ring_ids, near))[order]


def assembly_mesh(rings, sizes, support: np.ndarray, tol: float, family: str, nodes: int):
    """Mesh bonded bodies into one conforming mesh.

    Parameters
    ----------
    rings : sequence of (k_b, 2) float64 ndarray
        Each body's outline, a closed polyline (last point not repeated), units.
    sizes : sequence of float
        Each body's element size h, units.
    support : (n_s, 2) float64 ndarray
        The support's polyline, A to B.
    tol : float
        Contact tolerance: points closer than this are one node.
    family : str
        ``"triangle"`` or ``"quad"``.
    nodes : int
        Nodes per element (3, 6, 4 or 8).

    Returns
    -------
    mesh : FeMesh
        ``lower_nodes`` / ``lower_fractions`` are the support's nodes and
        their fractions; ``upper_nodes`` is empty (upper points are mapped).
    body : (M,) int64 ndarray
        The body of each element.

    Raises
    ------
    MeshError
        If Triangle fails or the mesh does not cover the bodies.
    """
    tr = require("triangle", "fem", "the solver deck's mesh")
    split = [split_ring(np.asarray(r, dtype=np.float64), h) for r, h in zip(rings, sizes)]
    points, index = _merge(np.concatenate(split), tol)
    starts = np.cumsum([0] + [len(r) for r in split])
    ids = [index[starts[b]:starts[b + 1]] for b in range(len(split))]
    ids = [_augmented(np.asarray([k for i, k in enumerate(r) if i == 0 or k != r[i - 1]]), points, tol) for r in ids]
    seg = np.concatenate([np.column_stack((r, np.roll(r, -1))) for r in ids])
    seg = np.unique(np.sort(seg[seg[:, 0] != seg[:, 1]], axis=1), axis=0)
    regions = []
    for b, r in enumerate(ids):
        inside = shapely.Polygon(points[r]).point_on_surface()
        x, y = shapely.get_coordinates(inside)[0]
        regions.append([x, y, b + 1, math.sqrt(3.0) / 4.0 * sizes[b] ** 2])
    try:
        out = tr.triangulate({"vertices": points, "segments": seg, "regions": np.asarray(regions)},
                             f"pq{MIN_ANGLE_DEG:g}AaQ")
    except Exception as exc:  # pragma: no cover - Triangle's own failures
        raise MeshError(f"solver deck mesh: Triangle failed on the assembly ({exc})") from exc
    p = np.asarray(out["vertices"], dtype=np.float64)
    tri = np.asarray(out["triangles"], dtype=np.int64)
    body = np.rint(np.asarray(out["triangle_attributes"]).ravel()).astype(np.int64) - 1
    if body.min() < 0:
        raise MeshError("solver deck mesh: part of the mesh lies in no body (an outline is not closed)")
    d1, d2 = p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]]
    cw = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] < 0
    tri[cw] = tri[cw][:, ::-1]
    area = sum(abs(shapely.Polygon(points[r]).area) for r in ids)
    d1, d2 = p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]]
    if abs(0.5 * np.sum(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) - area) > 1e-9 * area:
        raise MeshError("solver deck mesh: the triangles do not cover the bodies (do their outlines cross?)")
    line = shapely.LineString(support)
    on = np.flatnonzero(shapely.distance(shapely.points(p), line) <= tol)
    frac = shapely.line_locate_point(line, shapely.points(p[on]), normalized=True)
    order = np.argsort(frac, kind="stable")
    ln, lf = on[order], frac[order]
    if family == "quad":
        p, tri, ln, lf = split_into_quads(p, tri, ln, lf)
        body = np.tile(body, 3)
    if nodes in (6, 8):
        p, tri, ln, lf = add_mid_nodes(p, tri, ln, lf)
    mesh = FeMesh(points=p, cells=tri.astype(np.int64), kind=KINDS[(family, nodes)], lower_nodes=ln.astype(np.int64),
                  lower_fractions=np.asarray(lf, dtype=np.float64), upper_nodes=np.zeros(0, dtype=np.int64))
    for arr in (mesh.points, mesh.cells, mesh.lower_nodes, mesh.lower_fractions, mesh.upper_nodes, body):
        arr.setflags(write=False)
    return mesh, body


def body_ring(section, size: float) -> np.ndarray:
    """A body's outline for :func:`assembly_mesh`: its lower nodes, then its upper points thinned to ``size / 3``."""
    upper = np.asarray(section.upper, dtype=np.float64)
    kept = upper[thin_polyline(upper, size / 3.0)]
    return np.concatenate((np.asarray(section.lower, dtype=np.float64), kept[1:-1]))
