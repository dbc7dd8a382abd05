"""Vectorised assembly of the mixed neo-Hookean problem, generalised plane strain.

Per unit reference area and unit length out of plane, with shear modulus 1
(the shape does not depend on it: only displacements are prescribed) and
``lam`` the first Lame constant (bulk/shear - 2/3)::

    F3 = [[F, 0], [0, lz]],   J = lz det F
    psi(F, p) = (|F|^2 + lz^2 - 3) / 2 - ln J + p ln J - p^2 / (2 lam)

the compressible neo-Hookean energy ``(I1 - 3)/2 - ln J + lam (ln J)^2 / 2``
with its volumetric part written through an independent pressure ``p``
(stationarity in p gives p = lam ln J). The out-of-plane stretch ``lz`` is
given (1 / area ratio). With ``g_a = F^-T grad N_a`` (spatial gradients)::

    R_x[a, i] = sum_q w (F grad N_a + (p - 1) g_a)_i
    R_p[b]    = sum_q w M_b (ln J - p / lam)
    K_xx[a i, b k] = sum_q w (delta_ik grad N_a . grad N_b - (p - 1) g_ak g_bi)
    K_xp[a i, b]   = sum_q w g_ai M_b,      K_pp = -sum_q w M_a M_b / lam

Every quantity is computed for all elements and quadrature points at once
(arrays ``(E, q, ...)``); element matrices go into a fixed sparse pattern by
one ``bincount``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .elements import Geometry

__all__ = ["MixedNeoHooke", "Fields", "Pattern"]


@dataclass(frozen=True, eq=False)
class Fields:
    """Kinematics at the quadrature points for one state.

    Attributes
    ----------
    F : (E, q, 2, 2) float64 ndarray
        In-plane deformation gradient.
    g : (E, q, 6, 2) float64 ndarray
        Spatial gradients of the shape functions, ``grad N F^-1``.
    lnj : (E, q) float64 ndarray
        ln J with J = lz det F.
    p : (E, q) float64 ndarray
        Pressure at the quadrature points (units of the shear modulus).
    """

    F: np.ndarray
    g: np.ndarray
    lnj: np.ndarray
    p: np.ndarray


class MixedNeoHooke:
    """Residual and tangent of the Taylor-Hood neo-Hookean problem on one mesh.

    Parameters
    ----------
    cells : (E, 6) int64 ndarray
        P2 cells; their first three nodes are the pressure nodes.
    n_nodes : int
        Number of displacement nodes N.
    geom : Geometry
        Shape-function gradients and weights at the quadrature points.
    lam : float
        First Lame constant over the shear modulus.

    Notes
    -----
    The unknown vector is ``z = [x (2 N, node-major), p (n_vertices)]`` with
    ``x`` the deformed node positions; the element dofs are
    ``(x0, y0, ..., x5, y5, p0, p1, p2)``.
    """

    def __init__(self, cells: np.ndarray, n_nodes: int, geom: Geometry, lam: float):
        self.cells = cells
        self.n_nodes = n_nodes
        self.geom = geom
        self.lam = float(lam)
        e = len(cells)
        xd = (2 * cells[:, :, None] + np.arange(2)).reshape(e, 12)
        self.edofs = np.concatenate((xd, 2 * n_nodes + cells[:, :3]), axis=1)
        G, w, M = geom.grad, geom.weight, geom.pvalues
        self._wM = w[:, :, None] * M[None]  # (E, q, 3)
        klin = np.einsum("eqaj,eqbj,eq->eab", G, G, w)
        self._kxx0 = np.einsum("eab,ik->eaibk", klin, np.eye(2)).reshape(e, 12, 12)
        self._kpp = -np.einsum("eqa,qb->eab", self._wM, M) / self.lam

    def fields(self, z: np.ndarray, lz: float) -> Fields | None:
        """Kinematics of state ``z``, or None if some J <= 0 (an inverted point)."""
        n = self.n_nodes
        xe = z[: 2 * n].reshape(n, 2)[self.cells]  # (E, 6, 2)
        F = np.einsum("eai,eqaj->eqij", xe, self.geom.grad)
        det = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        if not det.min() > 0:
            return None
        inv = np.empty_like(F)
        inv[..., 0, 0], inv[..., 1, 1] = F[..., 1, 1] / det, F[..., 0, 0] / det
        inv[..., 0, 1], inv[..., 1, 0] = -F[..., 0, 1] / det, -F[..., 1, 0] / det
        g = np.einsum("eqaj,eqjk->eqak", self.geom.grad, inv)
        p = z[2 * n :][self.cells[:, :3]] @ self.geom.pvalues.T
        return Fields(F, g, np.log(lz * det), p)

    def element_residuals(self, f: Fields) -> np.ndarray:
        """Element residual vectors, ``(E, 15)``."""
        w = self.geom.weight
        rx = np.einsum("eqij,eqaj->eai", f.F * w[..., None, None], self.geom.grad)
        rx += np.einsum("eq,eqai->eai", (f.p - 1.0) * w, f.g)
        rp = np.einsum("eq,eqb->eb", f.lnj - f.p / self.lam, self._wM)
        return np.concatenate((rx.reshape(-1, 12), rp), axis=1)

    def element_matrices(self, f: Fields) -> np.ndarray:
        """Element tangent matrices, ``(E, 15, 15)``, symmetric."""
        e = len(self.cells)
        w = self.geom.weight
        out = np.empty((e, 15, 15))
        kgeo = np.einsum("eq,eqak,eqbi->eaibk", (f.p - 1.0) * w, f.g, f.g).reshape(e, 12, 12)
        out[:, :12, :12] = self._kxx0 - kgeo
        kxp = np.einsum("eqai,eqb->eaib", f.g, self._wM).reshape(e, 12, 3)
        out[:, :12, 12:] = kxp
        out[:, 12:, :12] = kxp.transpose(0, 2, 1)
        out[:, 12:, 12:] = self._kpp
        return out


class Pattern:
    """Fixed sparse pattern of the free-free and free-fixed blocks.

    Parameters
    ----------
    edofs : (E, k) int64 ndarray
        Global dofs of each element.
    n_dofs : int
        Total number of dofs.
    fixed : (d,) int64 ndarray
        Prescribed dofs.
    order : (f,) int64 ndarray, optional
        Free dofs in the order wanted for the matrix (a fill-reducing order);
        by default increasing.

    Attributes
    ----------
    free : (f,) int64 ndarray
        Free dofs in matrix order.
    """

    def __init__(self, edofs: np.ndarray, n_dofs: int, fixed: np.ndarray, order: np.ndarray | None = None):
        self.n_dofs = n_dofs
        self.fixed = np.asarray(fixed, dtype=np.int64)
        is_fixed = np.zeros(n_dofs, bool)
        is_fixed[self.fixed] = True
        free = np.flatnonzero(~is_fixed) if order is None else np.asarray(order, dtype=np.int64)
        self.free = free
        num = np.full(n_dofs, -1)
        num[free] = np.arange(len(free))
        dnum = np.full(n_dofs, -1)
        dnum[self.fixed] = np.arange(len(self.fixed))
        k = edofs.shape[1]
        rows = np.broadcast_to(edofs[:, :, None], (len(edofs), k, k)).ravel()
        cols = np.broadcast_to(edofs[:, None, :], (len(edofs), k, k)).ravel()
        self._ff = self._block(num[rows], num[cols], len(free), len(free))
        self._fd = self._block(num[rows], dnum[cols], len(free), len(self.fixed))
        self.edofs = edofs

    @staticmethod
    def _block(r, c, nr, nc):
        keep = np.flatnonzero((r >= 0) & (c >= 0))
        key = c[keep] * nr + r[keep]  # column-major: CSC order
        uniq, inv = np.unique(key, return_inverse=True)
        indptr = np.searchsorted(uniq // nr, np.arange(nc + 1)).astype(np.int32)
        return keep, inv, (uniq % nr).astype(np.int32), indptr, (nr, nc), len(uniq)

    def _matrix(self, block, flat):
        keep, inv, indices, indptr, shape, nnz = block
        data = np.bincount(inv, weights=flat[keep], minlength=nnz)
        return sp.csc_matrix((data, indices, indptr), shape=shape)

    def matrices(self, ke: np.ndarray) -> tuple[sp.csc_matrix, sp.csc_matrix]:
        """``(K_ff, K_fd)`` from element matrices ``(E, k, k)``."""
        flat = ke.ravel()
        return self._matrix(self._ff, flat), self._matrix(self._fd, flat)

    def matrix_ff(self, ke: np.ndarray) -> sp.csc_matrix:
        """``K_ff`` alone."""
        return self._matrix(self._ff, ke.ravel())

    def vector(self, re: np.ndarray) -> np.ndarray:
        """Assembled global vector ``(n_dofs,)`` from element vectors ``(E, k)``."""
        return np.bincount(self.edofs.ravel(), weights=re.ravel(), minlength=self.n_dofs)
