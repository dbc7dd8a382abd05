"""Images of points through a deformed finite-element mesh, by its shape functions.

A point X of the initial section is located in the initial mesh (the element
whose local coordinates put it deepest inside, so a point a hair outside a
boundary chord, on the exact curve, takes the boundary element and is
extrapolated a hair), then mapped with the same element's shape functions
to the deformed nodes: x = Σ N_i(ξ) x_i. Initial elements have straight
sides and mid-edge nodes at the middles (see :mod:`sectiondeform.external.mesh`),
so their map is affine (triangles) or bilinear (quads).
"""

from __future__ import annotations

import numpy as np

__all__ = ["locate", "map_points", "shape_functions"]


def shape_functions(kind: str, xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Shape functions at local coordinates, ``(k, nodes)``, in Abaqus node order.

    Triangles: ξ, η are the barycentric coordinates of corners 2 and 3
    (corner 1 has 1 − ξ − η). Quads: ξ, η in [−1, 1].

    Examples
    --------
    >>> (shape_functions("triangle6", np.array([0.5]), np.array([0.0])).round(12) + 0.0).tolist()
    [[0.0, 0.0, 0.0, 1.0, 0.0, 0.0]]
    """
    if kind.startswith("triangle"):
        lam = np.stack((1.0 - xi - eta, xi, eta), axis=1)
        if kind == "triangle":
            return lam
        l1, l2, l3 = lam.T
        return np.column_stack((l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1),
                                4 * l1 * l2, 4 * l2 * l3, 4 * l3 * l1))
    sx, sy = np.array([-1.0, 1.0, 1.0, -1.0]), np.array([-1.0, -1.0, 1.0, 1.0])
    a, b = xi[:, None], eta[:, None]
    if kind == "quad":
        return 0.25 * (1 + sx * a) * (1 + sy * b)
    corner = 0.25 * (1 + sx * a) * (1 + sy * b) * (sx * a + sy * b - 1)
    mx, my = np.array([0.0, 1.0, 0.0, -1.0]), np.array([-1.0, 0.0, 1.0, 0.0])
    mid = np.where(mx == 0, 0.5 * (1 - a * a) * (1 + my * b), 0.5 * (1 + mx * a) * (1 - b * b))
    return np.concatenate((corner, mid), axis=1)


def _bary(points: np.ndarray, tri: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Local (ξ, η) of each X in each straight triangle, ``(m, M, 2)``."""
    p0, p1, p2 = (points[tri[:, k]] for k in range(3))
    d1, d2 = p1 - p0, p2 - p0
    det = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    r = X[:, None, :] - p0[None]
    xi = (r[..., 0] * d2[:, 1] - r[..., 1] * d2[:, 0]) / det
    eta = (d1[:, 0] * r[..., 1] - d1[:, 1] * r[..., 0]) / det
    return np.stack((xi, eta), axis=2)


def _bilinear_inverse(corners: np.ndarray, X: np.ndarray, iterations: int = 20) -> np.ndarray:
    """(ξ, η) of X in bilinear quads with the given corners ``(k, 4, 2)``, Newton from the centre."""
    sx, sy = np.array([-1.0, 1.0, 1.0, -1.0]), np.array([-1.0, -1.0, 1.0, 1.0])
    q = np.zeros((len(X), 2))
    for _ in range(iterations):
        a, b = q[:, :1], q[:, 1:]
        n = 0.25 * (1 + sx * a) * (1 + sy * b)
        dna, dnb = 0.25 * sx * (1 + sy * b), 0.25 * sy * (1 + sx * a)
        f = np.einsum("kn,knd->kd", n, corners) - X
        jac = np.stack((np.einsum("kn,knd->kd", dna, corners), np.einsum("kn,knd->kd", dnb, corners)), axis=2)
        step = np.linalg.solve(jac, f[..., None])[..., 0]
        q -= step
        if np.abs(step).max() < 1e-14:
            break
    return q


def locate(points: np.ndarray, cells: np.ndarray, kind: str, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Element and local coordinates of each point in an initial (straight-sided) mesh.

    Parameters
    ----------
    points : (N, 2) float64 ndarray
    cells : (M, k) int64 ndarray
    kind : str
        ``"triangle"``, ``"triangle6"``, ``"quad"`` or ``"quad8"``.
    X : (m, 2) float64 ndarray

    Returns
    -------
    element : (m,) int64 ndarray
    local : (m, 2) float64 ndarray
        (ξ, η) as :func:`shape_functions` takes them.
    """
    X = np.asarray(X, dtype=np.float64)
    if kind.startswith("triangle"):
        tri, owner = cells[:, :3], np.arange(len(cells))
    else:  # each quad as its two triangles, to choose the element
        tri = np.concatenate((cells[:, [0, 1, 2]], cells[:, [0, 2, 3]]))
        owner = np.concatenate((np.arange(len(cells)), np.arange(len(cells))))
    bc = _bary(points, tri, X)
    depth = np.minimum(np.minimum(bc[..., 0], bc[..., 1]), 1.0 - bc[..., 0] - bc[..., 1])
    best = np.argmax(depth, axis=1)
    element = owner[best]
    if kind.startswith("triangle"):
        return element, bc[np.arange(len(X)), best]
    return element, _bilinear_inverse(points[cells[element, :4]], X)


def map_points(initial: np.ndarray, deformed: np.ndarray, cells: np.ndarray, kind: str, X: np.ndarray) -> np.ndarray:
    """Images of initial points X through the deformed mesh, ``(m, 2)``, units."""
    element, local = locate(initial, cells, kind, X)
    n = shape_functions(kind, local[:, 0], local[:, 1])
    return np.einsum("kn,knd->kd", n, deformed[cells[element]])
