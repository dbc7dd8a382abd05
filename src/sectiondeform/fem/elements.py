r"""The Taylor-Hood triangle: quadratic displacement (P2), linear pressure (P1).

Reference triangle with corners (0, 0), (1, 0), (0, 1) and area coordinates
``L0 = 1 - xi - eta``, ``L1 = xi``, ``L2 = eta``. Node order (meshio's
``triangle6``)::

    2
    | \
    5   4
    |     \
    0---3---1

Corner shape functions ``Li (2 Li - 1)``, mid-edge ``4 Li Lj``; the pressure
uses the three corner functions ``Li``. The pair is inf-sup stable, so the
element does not lock as the bulk modulus grows (a pure P2 displacement
element would, at bulk/shear 1000). The geometry is isoparametric: mid-edge
nodes on a curved boundary sit on the curve.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["QUAD_POINTS", "QUAD_WEIGHTS", "p2_values", "p2_gradients", "p1_values", "Geometry", "geometry"]

# Strang-Fix / Dunavant 6-point rule, exact for degree 4 (weights sum to 1/2).
_A, _B = 0.445948490915965, 0.091576213509771
_WA, _WB = 0.223381589678011 / 2.0, 0.109951743655322 / 2.0
QUAD_POINTS = np.array(
    [[_A, _A], [1 - 2 * _A, _A], [_A, 1 - 2 * _A], [_B, _B], [1 - 2 * _B, _B], [_B, 1 - 2 * _B]]
)
QUAD_WEIGHTS = np.array([_WA, _WA, _WA, _WB, _WB, _WB])


def p2_values(local: np.ndarray) -> np.ndarray:
    """P2 shape functions at local points.

    Parameters
    ----------
    local : (q, 2) float64 ndarray
        Reference coordinates (xi, eta).

    Returns
    -------
    (q, 6) float64 ndarray

    Examples
    --------
    >>> (p2_values(np.array([[0.5, 0.0]])).round(12) + 0.0).tolist()
    [[0.0, 0.0, 0.0, 1.0, 0.0, 0.0]]
    """
    xi, eta = local[:, 0], local[:, 1]
    l0, l1, l2 = 1.0 - xi - eta, xi, eta
    return np.stack(
        (l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), 4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0), axis=1
    )


def p2_gradients(local: np.ndarray) -> np.ndarray:
    """Gradients of the P2 shape functions in reference coordinates, ``(q, 6, 2)``."""
    xi, eta = local[:, 0], local[:, 1]
    l0, l1, l2 = 1.0 - xi - eta, xi, eta
    dl = np.array([[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])  # dLi/d(xi, eta)
    q = len(local)
    g = np.empty((q, 6, 2))
    for i, li in enumerate((l0, l1, l2)):
        g[:, i] = (4 * li - 1)[:, None] * dl[i]
    for k, (i, j) in enumerate(((0, 1), (1, 2), (2, 0))):
        li, lj = (l0, l1, l2)[i], (l0, l1, l2)[j]
        g[:, 3 + k] = 4 * (lj[:, None] * dl[i] + li[:, None] * dl[j])
    return g


def p1_values(local: np.ndarray) -> np.ndarray:
    """Linear (corner) shape functions at local points, ``(q, 3)``."""
    xi, eta = local[:, 0], local[:, 1]
    return np.stack((1.0 - xi - eta, xi, eta), axis=1)


@dataclass(frozen=True, eq=False)
class Geometry:
    """Element geometry at the quadrature points, computed once per mesh.

    Attributes
    ----------
    grad : (E, q, 6, 2) float64 ndarray
        Gradients of the P2 shape functions with respect to the initial
        coordinates, 1/units.
    weight : (E, q) float64 ndarray
        Quadrature weight times the Jacobian determinant, units².
    pvalues : (q, 3) float64 ndarray
        Pressure (P1) shape functions at the quadrature points.
    detj_ratio : (E,) float64 ndarray
        Smallest Jacobian determinant of each element over its quadrature
        points relative to its straight-sided value (1 when straight).
    """

    grad: np.ndarray
    weight: np.ndarray
    pvalues: np.ndarray
    detj_ratio: np.ndarray


def geometry(nodes: np.ndarray, cells: np.ndarray) -> Geometry:
    """Isoparametric geometry of P2 triangles.

    Parameters
    ----------
    nodes : (N, 2) float64 ndarray
        Node coordinates, units.
    cells : (E, 6) int64 ndarray
        Counter-clockwise ``triangle6`` cells.

    Returns
    -------
    Geometry

    Examples
    --------
    >>> pts = np.array([[0, 0], [1, 0], [0, 1], [.5, 0], [.5, .5], [0, .5]], float)
    >>> g = geometry(pts, np.arange(6)[None])
    >>> round(float(g.weight.sum()), 12)
    0.5
    """
    dref = p2_gradients(QUAD_POINTS)  # (q, 6, 2)
    xe = nodes[cells]  # (E, 6, 2)
    jac = np.einsum("eai,qaj->eqij", xe, dref)  # dX_i / dxi_j
    det = jac[..., 0, 0] * jac[..., 1, 1] - jac[..., 0, 1] * jac[..., 1, 0]
    inv = np.empty_like(jac)
    inv[..., 0, 0], inv[..., 1, 1] = jac[..., 1, 1] / det, jac[..., 0, 0] / det
    inv[..., 0, 1], inv[..., 1, 0] = -jac[..., 0, 1] / det, -jac[..., 1, 0] / det
    grad = np.einsum("qaj,eqji->eqai", dref, inv)
    c = xe[:, :3]
    straight = (c[:, 1, 0] - c[:, 0, 0]) * (c[:, 2, 1] - c[:, 0, 1]) - (c[:, 2, 0] - c[:, 0, 0]) * (c[:, 1, 1] - c[:, 0, 1])
    return Geometry(grad, det * QUAD_WEIGHTS[None], p1_values(QUAD_POINTS), (det / straight[:, None]).min(axis=1))
