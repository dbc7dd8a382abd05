"""The finite-element mesh of a case for an external solver: corners, mid-edge nodes, quads.

The corners come from the project's reference mesher
(:func:`~sectiondeform.reference.mesh.triangulate`: one conforming mesh of
the bodies' union, quality triangles whose vertices include the upper
curves' characteristic points, thinned to a third of the element size, and
the support's nodes with their arc-length fractions). From them:

* triangles (``CPE3``) are used as they are; six-node triangles (``CPE6``)
  get a node at the middle of every edge;
* quadrilaterals (``CPE4``) split each triangle into three, through the
  middles of its edges and its centroid; eight-node quadrilaterals
  (``CPE8``) then get a node at the middle of every quad edge.

A node added on a lower edge gets the mean of its two ends' fractions (the
same linear rule as the reference's mid-edge nodes), so every node of the
lower curve carries the fraction at which it goes onto the target.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..errors import MeshError
from ..limits import MAX_DECK_TRIANGLES, bounded, triangles_needed

__all__ = ["FeMesh", "add_mid_nodes", "check_deck_size", "element_areas", "fe_mesh", "split_into_quads"]

#: meshio's name of each (family, nodes) mesh kind.
KINDS = {("triangle", 3): "triangle", ("triangle", 6): "triangle6", ("quad", 4): "quad", ("quad", 8): "quad8"}


@dataclass(frozen=True, eq=False)
class FeMesh:
    """A mesh ready for a deck.

    Attributes
    ----------
    points : (N, 2) float64 ndarray
        Node coordinates, units.
    cells : (M, k) int64 ndarray
        Node indices of each element, corners counter-clockwise then the
        middles of edges corner 1-2, 2-3, ... (Abaqus order).
    kind : str
        ``"triangle"``, ``"triangle6"``, ``"quad"`` or ``"quad8"``.
    lower_nodes : (n_l,) int64 ndarray
        Nodes on the support, by increasing fraction (A to B).
    lower_fractions : (n_l,) float64 ndarray
        Arc-length fraction of each of ``lower_nodes`` on the support.
    upper_nodes : (m',) int64 ndarray
        Nodes of the upper curves' characteristic points kept as mesh
        nodes (:func:`~sectiondeform.reference.mesh.thin_polyline`), body
        by body, each B to A.
    hole_nodes : (h,) int64 ndarray
        Nodes of the bodies' holes' points (free faces, not loaded), body
        by body, hole by hole.
    """

    points: np.ndarray
    cells: np.ndarray
    kind: str
    lower_nodes: np.ndarray
    lower_fractions: np.ndarray
    upper_nodes: np.ndarray
    hole_nodes: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, dtype=np.int64))

    @property
    def corners(self) -> int:
        """Corner nodes per element (3 or 4)."""
        return 3 if self.kind.startswith("triangle") else 4


def _edges(cells: np.ndarray) -> np.ndarray:
    """Edges corner k to corner k + 1 of each cell, ``(M, c, 2)``."""
    return np.stack((cells, np.roll(cells, -1, axis=1)), axis=2)


def add_mid_nodes(points, cells, lower_nodes, lower_fractions):
    """Add a node at the middle of every edge of a corner-only mesh.

    Parameters
    ----------
    points : (N, 2) float64 ndarray
    cells : (M, c) int64 ndarray
        Corners, counter-clockwise.
    lower_nodes : (n_l,) int64 ndarray
    lower_fractions : (n_l,) float64 ndarray

    Returns
    -------
    points : (N + E, 2) float64 ndarray
        The input points, then one per edge.
    cells : (M, 2c) int64 ndarray
        Corners, then the middle of edge k -> k + 1 for each k.
    lower_nodes, lower_fractions : ndarray
        With the middles of the lower boundary edges, sorted by fraction.

    Examples
    --------
    >>> p, c, ln, lf = add_mid_nodes(np.array([[0.0, 0], [2, 0], [0, 2]]), np.array([[0, 1, 2]]),
    ...                              np.array([0, 1]), np.array([0.0, 1.0]))
    >>> p[c[0, 3:]].tolist(), ln.tolist(), lf.tolist()
    ([[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], [0, 3, 1], [0.0, 0.5, 1.0])
    """
    e = _edges(cells).reshape(-1, 2)
    key = np.sort(e, axis=1)
    uniq, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    mids = 0.5 * (points[uniq[:, 0]] + points[uniq[:, 1]])
    n = len(points)
    new_cells = np.concatenate((cells, n + inverse.reshape(cells.shape)), axis=1)
    frac = np.full(n, np.nan)
    frac[lower_nodes] = lower_fractions
    f0, f1 = frac[uniq[:, 0]], frac[uniq[:, 1]]
    on_lower = (counts == 1) & np.isfinite(f0) & np.isfinite(f1)
    nodes = np.concatenate((lower_nodes, n + np.flatnonzero(on_lower)))
    fractions = np.concatenate((lower_fractions, 0.5 * (f0 + f1)[on_lower]))
    order = np.argsort(fractions, kind="stable")
    return np.concatenate((points, mids)), new_cells, nodes[order], fractions[order]


def split_into_quads(points, triangles, lower_nodes, lower_fractions):
    """Split each triangle into three quadrilaterals through its edge middles and centroid.

    Returns
    -------
    points : (N', 2) float64 ndarray
    quads : (3M, 4) int64 ndarray
        Counter-clockwise.
    lower_nodes, lower_fractions : ndarray
    """
    p6, c6, nodes, fractions = add_mid_nodes(points, triangles, lower_nodes, lower_fractions)
    g = len(p6) + np.arange(len(triangles))
    centroids = points[triangles].mean(axis=1)
    a, b, c, mab, mbc, mca = c6.T
    quads = np.concatenate((
        np.column_stack((a, mab, g, mca)),
        np.column_stack((b, mbc, g, mab)),
        np.column_stack((c, mca, g, mbc)),
    ))
    return np.concatenate((p6, centroids)), quads, nodes, fractions


def element_areas(points: np.ndarray, cells: np.ndarray, corners: int) -> np.ndarray:
    """Exact signed area of each (isoparametric) element, ``(M,)``, units².

    Green's theorem on the element's boundary: the polygon through its
    nodes, plus, for a quadratic edge a-m-b, one third of the triangle
    (a, m, b) (Archimedes: a parabolic segment is 4/3 of that triangle),
    about each element's first node so that it stays exact far from the origin.
    """
    if cells.shape[1] == corners:
        ring = points[cells]
        bulge = 0.0
    else:
        c, m = cells[:, :corners], cells[:, corners:]
        ring = points[np.stack((c, m), axis=2).reshape(len(cells), -1)]
        a, mid, b = points[c], points[m], points[np.roll(c, -1, axis=1)]
        d1, d2 = mid - a, b - a
        bulge = 0.5 * (d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0])
        bulge = np.sum(bulge, axis=1) / 3.0
    ring = ring - ring[:, :1]  # about each element's first node: far from the origin, no cancellation
    x, y = ring[..., 0], ring[..., 1]
    poly = 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)
    return poly + bulge


def check_deck_size(sections, sizes) -> float:
    """The triangles the sections need at their element sizes, or a :class:`MeshError` naming them and the bound.

    Checked before anything is meshed or split (:data:`~sectiondeform.limits.MAX_DECK_TRIANGLES`), over
    every body: a lower estimate from each body's area and outline (:func:`~sectiondeform.limits.triangles_needed`).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> unit = SimpleNamespace(upper=np.array([[1.0, 0], [1, 1], [0, 1], [0, 0]]), lower_length=1.0, area=1.0)
    >>> round(check_deck_size([unit, unit], [0.5, 0.5]))
    34
    >>> check_deck_size([unit], [1e-6])
    Traceback (most recent call last):
    ...
    sectiondeform.errors.MeshError: solver mesh: 2309405076759 triangles needed, more than the bound 500000; raise --mesh-size (a fraction of the section's mean thickness)
    """
    count = 0.0
    for section, size in zip(sections, sizes):
        upper = np.asarray(section.upper, dtype=np.float64)
        perimeter = section.lower_length + float(np.hypot(*np.diff(upper, axis=0).T).sum())
        count += triangles_needed(section.area, perimeter, size)
    return bounded(count, MAX_DECK_TRIANGLES, "triangles",
                   "raise --mesh-size (a fraction of the section's mean thickness)", MeshError, "solver mesh")


def fe_mesh(problem, mesh_size: float, family: str, nodes: int) -> tuple[FeMesh, np.ndarray]:
    """Mesh a problem's bodies for a solver deck: one conforming mesh, each element with its body.

    Parameters
    ----------
    problem : Problem
        One body or several.
    mesh_size : float
        Triangle size over each body's mesh scale (quads are about half).
    family : str
        ``"triangle"`` or ``"quad"``.
    nodes : int
        Nodes per element: 3 or 6 for triangles, 4 or 8 for quads.

    Returns
    -------
    mesh : FeMesh
    body : (M,) int64 ndarray
        The body of each element.

    Raises
    ------
    MeshError
        If the bodies need more than :data:`~sectiondeform.limits.MAX_DECK_TRIANGLES`
        triangles at this size (estimated before anything is meshed), or Triangle fails.
    """
    from ..reference.mesh import triangulate
    from ..section import build_section

    sections = [build_section(problem.body_case(b)) for b in range(len(problem.bodies))]
    check_deck_size(sections, [mesh_size * s.mesh_scale for s in sections])
    # Upper points about size / 3 apart (the rest are mapped by the shape functions),
    # so a finely discretised curve does not flood the mesh with elements.
    tri = triangulate(problem, mesh_size, sections, thin=True)
    p, c, body = np.asarray(tri.points), np.asarray(tri.triangles), np.asarray(tri.body)
    ln, lf = np.asarray(tri.lower_nodes), np.asarray(tri.lower_fractions)
    if family == "quad":
        p, c, ln, lf = split_into_quads(p, c, ln, lf)
        body = np.tile(body, 3)
    if nodes in (6, 8):
        p, c, ln, lf = add_mid_nodes(p, c, ln, lf)
    upper = np.concatenate(tri.upper_nodes)
    holes = [h for hb in tri.hole_nodes for h in hb]  # corners: the first nodes of every kind of mesh
    out = FeMesh(points=p, cells=c.astype(np.int64), kind=KINDS[(family, nodes)], lower_nodes=ln.astype(np.int64),
                 lower_fractions=lf, upper_nodes=upper[np.sort(np.unique(upper, return_index=True)[1])],
                 hole_nodes=np.concatenate(holes).astype(np.int64) if holes else np.zeros(0, dtype=np.int64))
    body = body.astype(np.int64)
    for arr in (out.points, out.cells, out.lower_nodes, out.lower_fractions, out.upper_nodes, out.hole_nodes, body):
        arr.setflags(write=False)
    return out, body
