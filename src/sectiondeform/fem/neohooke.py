"""Vectorised assembly of the mixed neo-Hookean problem, generalised plane strain.

The material is the reference's (:mod:`sectiondeform.reference.solver`):
per unit reference area and unit length out of plane, with shear modulus 1
(the shape does not depend on it: only positions are prescribed) and bulk
modulus ``kappa``::

    F3 = [[F, 0], [0, lz]],   J = lz det F,   I1 = |F|^2 + lz^2,   a = J^(-2/3)
    psi(F, p) = (a I1 - 3) / 2 + p (J - 1) - p^2 / (2 kappa)

the decoupled compressible neo-Hookean energy ``(a I1 - 3)/2 + kappa (J - 1)^2 / 2``
with its volumetric part written through an independent pressure ``p``
(stationarity in p gives p = kappa (J - 1)). The out-of-plane stretch ``lz``
is given (1 / area ratio). With ``g_a = F^-T grad N_a`` (spatial gradients)
and ``h_a = F grad N_a``::

    P = a (F - I1 F^-T / 3) + p J F^-T
    R_x[a, i] = sum_q w (P grad N_a)_i,      R_p[b] = sum_q w M_b (J - 1 - p / kappa)
    K_xx[a i, b k] = sum_q w ( a delta_ik grad N_a . grad N_b
                               - 2a/3 (h_ai g_bk + g_ai h_bk)
                               + (2 a I1 / 9 + p J) g_ai g_bk
                               + (a I1 / 3 - p J) g_ak g_bi )
    K_xp[a i, b] = sum_q w J g_ai M_b,       K_pp = -sum_q w M_a M_b / kappa

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
    det : (E, q) float64 ndarray
        det F (the in-plane area stretch).
    J : (E, q) float64 ndarray
        Volume ratio ``lz det F``.
    i1 : (E, q) float64 ndarray
        ``|F|^2 + lz^2``.
    p : (E, q) float64 ndarray
        Pressure at the quadrature points (units of the shear modulus).
    """

    F: np.ndarray
    det: np.ndarray
    J: np.ndarray
    i1: np.ndarray
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
    kappa : float or (E,) float64 ndarray
        Bulk modulus over the shear modulus, or per element the bulk modulus
        (in the units of ``mu``).
    mu : (E,) float64 ndarray, optional
        Shear modulus per element (several materials in one mesh); 1 by default.
    pressure_cells : (E, 3) int64 ndarray, optional
        The pressure unknown at each element's three corners; by default
        the corner nodes themselves (``cells[:, :3]``: one pressure field,
        continuous over the mesh). An assembly gives each body its own
        unknowns at the vertices it shares with others
        (:attr:`~.union_mesh.UnionMesh.pressure_cells`): the pressure is then
        continuous within a body and free to jump across its interfaces.

    Attributes
    ----------
    n_pressures : int
        Number of pressure unknowns (``pressure_cells.max() + 1``).

    Notes
    -----
    The unknown vector is ``z = [x (2 N, node-major), p (n_pressures)]`` with
    ``x`` the deformed node positions; the element dofs are
    ``(x0, y0, ..., x5, y5, p0, p1, p2)``, ``p_k`` the unknown
    ``pressure_cells[e, k]``.

    The deformation gradients at all quadrature points are one sparse
    product ``B x`` (``B`` of shape ``(4 E q, 2 N)``, built once), and the
    assembled position residual is ``B^T (w P)``: no element loop and no
    scatter for the residual, the cheap part of a warm re-solve.
    """

    def __init__(self, cells: np.ndarray, n_nodes: int, geom: Geometry, kappa, mu: np.ndarray | None = None,
                 pressure_cells: np.ndarray | None = None):
        self.cells = cells
        self.n_nodes = n_nodes
        self.geom = geom
        e, q = geom.weight.shape
        self.kappa = float(kappa) if np.ndim(kappa) == 0 else np.asarray(kappa, dtype=np.float64).reshape(e, 1)
        self._mu = None if mu is None else np.asarray(mu, dtype=np.float64).reshape(e, 1)
        pc = cells[:, :3] if pressure_cells is None else np.asarray(pressure_cells, dtype=np.int64)
        self.pressure_cells = pc
        self.n_pressures = int(pc.max()) + 1
        xd = (2 * cells[:, :, None] + np.arange(2)).reshape(e, 12)
        self.edofs = np.concatenate((xd, 2 * n_nodes + pc), axis=1)
        G, w, M = geom.grad, geom.weight, geom.pvalues
        # B[(e, q, i, j), 2 node + i] = G[e, q, a, j]
        rows = (((np.arange(e)[:, None, None, None, None] * q + np.arange(q)[None, :, None, None, None]) * 2
                 + np.arange(2)[None, None, None, :, None]) * 2 + np.arange(2)[None, None, None, None, :])
        cols = 2 * cells[:, None, :, None, None] + np.arange(2)[None, None, None, :, None]
        vals = G[:, :, :, None, :]
        shape5 = (e, q, 6, 2, 2)
        self.B = sp.csr_matrix(
            (np.broadcast_to(vals, shape5).ravel(), (np.broadcast_to(rows, shape5).ravel(), np.broadcast_to(cols, shape5).ravel())),
            shape=(4 * e * q, 2 * n_nodes),
        )
        self.Bt = self.B.T.tocsr()
        prow = np.broadcast_to(np.arange(e * q).reshape(e, q, 1), (e, q, 3)).ravel()
        pcol = np.broadcast_to(pc[:, None, :], (e, q, 3)).ravel()
        pval = np.broadcast_to(M[None], (e, q, 3)).ravel()
        self.Mp = sp.csr_matrix((pval, (prow, pcol)), shape=(e * q, self.n_pressures))
        self.Mpt = self.Mp.T.tocsr()
        self._wM = w[:, :, None] * M[None]  # (E, q, 3)
        self._Gt = np.ascontiguousarray(G.transpose(0, 2, 1, 3))  # (E, 6, q, 2)
        self._gg = np.einsum("eqaj,eqbj,eq->eabq", G, G, w).reshape(e, 36, q)  # w grad N_a . grad N_b
        self._kpp = -np.einsum("eqa,qb->eab", self._wM, M) / (self.kappa if np.ndim(self.kappa) == 0 else self.kappa[:, :, None])

    def fields(self, z: np.ndarray, lz: float) -> Fields | None:
        """Kinematics of state ``z``, or None if some J <= 0 (an inverted point)."""
        n = self.n_nodes
        e, q = self.geom.weight.shape
        F = (self.B @ z[: 2 * n]).reshape(e, q, 2, 2)
        det = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        if not det.min() > 0:
            return None
        p = (self.Mp @ z[2 * n :]).reshape(e, q)
        i1 = np.einsum("eqij,eqij->eq", F, F) + lz * lz
        return Fields(F, det, lz * det, i1, p)

    @staticmethod
    def _inverse_transpose(f: Fields) -> np.ndarray:
        F, det = f.F, f.det
        it = np.empty_like(F)
        it[..., 0, 0], it[..., 1, 1] = F[..., 1, 1] / det, F[..., 0, 0] / det
        it[..., 0, 1], it[..., 1, 0] = -F[..., 1, 0] / det, -F[..., 0, 1] / det
        return it

    def _shear(self, f: Fields) -> np.ndarray:
        """``mu J^(-2/3)`` at the quadrature points, ``(E, q)``."""
        a = f.J ** (-2.0 / 3.0)
        return a if self._mu is None else a * self._mu

    def _stress(self, f: Fields) -> np.ndarray:
        """``w P`` at the quadrature points, ``(E, q, 2, 2)``."""
        a = self._shear(f)
        c_f = a * self.geom.weight
        c_it = (f.p * f.J - a * f.i1 / 3.0) * self.geom.weight
        return f.F * c_f[..., None, None] + self._inverse_transpose(f) * c_it[..., None, None]

    def _pressure_residual(self, f: Fields) -> np.ndarray:
        return (f.J - 1.0 - f.p / self.kappa) * self.geom.weight

    def residual(self, f: Fields) -> np.ndarray:
        """Assembled residual ``(2 N + n_pressures,)``."""
        rx = self.Bt @ self._stress(f).ravel()
        rp = self.Mpt @ self._pressure_residual(f).ravel()
        return np.concatenate((rx, rp))

    def element_residuals(self, f: Fields) -> np.ndarray:
        """Element residual vectors, ``(E, 15)`` (for checks; :meth:`residual` is faster)."""
        rx = np.einsum("eqij,eqaj->eai", self._stress(f), self.geom.grad)
        rp = np.einsum("eq,qb->eb", self._pressure_residual(f), self.geom.pvalues)
        return np.concatenate((rx.reshape(-1, 12), rp), axis=1)

    def element_matrices(self, f: Fields) -> np.ndarray:
        """Element tangent matrices, ``(E, 15, 15)``, symmetric."""
        e, q = self.geom.weight.shape
        w = self.geom.weight
        a = self._shear(f)
        G = self.geom.grad
        finv_t = self._inverse_transpose(f)
        g = np.matmul(G, finv_t.transpose(0, 1, 3, 2)).reshape(e, q, 12).transpose(0, 2, 1)  # (E, (a,i), q)
        h = np.matmul(G, f.F.transpose(0, 1, 3, 2)).reshape(e, q, 12).transpose(0, 2, 1)  # F grad N_a
        gt = g.transpose(0, 2, 1)
        c_gg = w * (2.0 * a * f.i1 / 9.0 + f.p * f.J)
        c_sw = w * (a * f.i1 / 3.0 - f.p * f.J)
        c_hg = -2.0 / 3.0 * w * a
        kxx = np.matmul(g * c_gg[:, None], gt)
        khg = np.matmul(h * c_hg[:, None], gt)
        kxx += khg + khg.transpose(0, 2, 1)
        sw = np.matmul(g * c_sw[:, None], gt)  # [(a,k),(b,i)]
        kxx += sw.reshape(e, 6, 2, 6, 2).transpose(0, 1, 4, 3, 2).reshape(e, 12, 12)
        lin = np.matmul(self._gg, a[:, :, None]).reshape(e, 6, 6)
        kxx[:, 0::2, 0::2] += lin
        kxx[:, 1::2, 1::2] += lin
        out = np.empty((e, 15, 15))
        out[:, :12, :12] = kxx
        kxp = np.matmul(g * f.J[:, None], self._wM)  # (E, 12, 3)
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
    coupling : (Q, m) int64 ndarray, optional
        Dofs of further blocks that couple dofs of different elements (the
        contact's between two boundary edges): :meth:`matrices` then takes
        their ``(Q, m, m)`` matrices too.

    Attributes
    ----------
    free : (f,) int64 ndarray
        Free dofs in matrix order.
    """

    def __init__(self, edofs: np.ndarray, n_dofs: int, fixed: np.ndarray, order: np.ndarray | None = None,
                 coupling: np.ndarray | None = None):
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
        self.coupling = None if coupling is None or not len(coupling) else np.asarray(coupling, dtype=np.int64)
        rows, cols = [], []
        for dofs in (edofs,) if self.coupling is None else (edofs, self.coupling):
            k = dofs.shape[1]
            rows.append(np.broadcast_to(dofs[:, :, None], (len(dofs), k, k)).ravel())
            cols.append(np.broadcast_to(dofs[:, None, :], (len(dofs), k, k)).ravel())
        rows, cols = np.concatenate(rows), np.concatenate(cols)
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

    def _flat(self, ke: np.ndarray, kc: np.ndarray | None) -> np.ndarray:
        if self.coupling is None:
            return ke.ravel()
        if kc is None:
            kc = np.zeros((len(self.coupling), self.coupling.shape[1], self.coupling.shape[1]))
        return np.concatenate((ke.ravel(), kc.ravel()))

    def matrices(self, ke: np.ndarray, kc: np.ndarray | None = None) -> tuple[sp.csc_matrix, sp.csc_matrix]:
        """``(K_ff, K_fd)`` from element matrices ``(E, k, k)`` and the coupling's ``(Q, m, m)`` (zeros if None)."""
        flat = self._flat(ke, kc)
        return self._matrix(self._ff, flat), self._matrix(self._fd, flat)

    def matrix_ff(self, ke: np.ndarray, kc: np.ndarray | None = None) -> sp.csc_matrix:
        """``K_ff`` alone."""
        return self._matrix(self._ff, self._flat(ke, kc))

    def vector(self, re: np.ndarray) -> np.ndarray:
        """Assembled global vector ``(n_dofs,)`` from element vectors ``(E, k)``."""
        return np.bincount(self.edofs.ravel(), weights=re.ravel(), minlength=self.n_dofs)
