"""The mixed problem of :mod:`.assembly` for any rubber of :mod:`sectiondeform.materials`.

:class:`~.assembly.MixedNeoHooke` writes the neo-Hookean stress and tangent
in closed form; :class:`MixedRubber` takes them from the material models
(neo-Hookean, Mooney–Rivlin, Yeoh), one material per element, with the same
perturbed-Lagrangian form (the pressure ``p`` an unknown of its own)::

    F3 = [[F, 0], [0, lz]],   J = lz det F
    psi(F, p) = W_iso(F3) + p (J - 1) - p^2 / (2 kappa)

    P = P_iso(F3)[:2, :2] + p J F^-T
    A = A_iso(F3)[:2, :2, :2, :2] + p J (F^-T (x) F^-T - F^-T_il F^-T_kj)
    R_x[a, i] = sum_q w P_iJ dN_a/dX_J,        R_p[b] = sum_q w M_b (J - 1 - p / kappa)
    K_xx[a i, b k] = sum_q w dN_a/dX_J A_iJkL dN_b/dX_L
    K_xp[a i, b] = sum_q w J (F^-T grad N_a)_i M_b,   K_pp = -sum_q w M_a M_b / kappa

Only the in-plane block of F varies (``lz`` is prescribed), so only the
in-plane block of the material's ∂P/∂F enters. The moduli are used as given
(MPa or relative): ``p`` is in their unit. The shape of one body does not
depend on their scale (the residual scales with it); an assembly's depends
on their ratios.
"""

from __future__ import annotations

import math

import numpy as np

from ..materials.models import gradient_3d
from .elements import Geometry
from .neohooke import Fields, MixedNeoHooke

__all__ = ["MixedRubber"]


class MixedRubber(MixedNeoHooke):
    """Residual and tangent of the Taylor-Hood problem for rubbers of :mod:`sectiondeform.materials`.

    Same interface as :class:`~.assembly.MixedNeoHooke` (``fields``,
    ``residual``, ``element_residuals``, ``element_matrices``), whose
    kinematics it shares; the stress and tangent come from the materials.

    Parameters
    ----------
    cells : (E, 6) int64 ndarray
        P2 cells; their first three nodes are the pressure nodes.
    n_nodes : int
        Number of displacement nodes N.
    geom : Geometry
        Shape-function gradients and weights at the quadrature points.
    materials : sequence of NeoHookean or MooneyRivlin or Yeoh
        The rubbers (one per body).
    body : (E,) int ndarray, optional
        Index into ``materials`` of each element; all 0 by default.
    ln_stretch : (E,) float64 ndarray, optional
        Per-element exponent of the out-of-plane stretch: with it, the
        solver's ``lz`` is a path parameter ``s`` and element ``e`` has
        ``lz_e = exp(ln s * ln_stretch[e])`` (``s = e``: each body's own
        stretch); without it every element has ``lz``.
    pressure_cells : (E, 3) int64 ndarray, optional
        The pressure unknown at each element's corners (one field per body
        in an assembly); ``cells[:, :3]`` by default (see
        :class:`~.assembly.MixedNeoHooke`).

    Examples
    --------
    >>> from sectiondeform.fem.elements import geometry
    >>> from sectiondeform.materials import Yeoh
    >>> nodes = np.array([[0, 0], [1, 0], [0, 1], [.5, 0], [.5, .5], [0, .5]], float)
    >>> cells = np.arange(6)[None]
    >>> phys = MixedRubber(cells, 6, geometry(nodes, cells), [Yeoh(0.5, 0.1, 0.01)])
    >>> z = np.concatenate((nodes.ravel(), np.zeros(3)))
    >>> bool(np.abs(phys.residual(phys.fields(z, 1.0))).max() < 1e-12)   # the undeformed state is free
    True
    """

    def __init__(self, cells: np.ndarray, n_nodes: int, geom: Geometry, materials, body: np.ndarray | None = None,
                 ln_stretch: np.ndarray | None = None, pressure_cells: np.ndarray | None = None):
        e = len(cells)
        self.materials = tuple(materials)
        self.body = np.zeros(e, np.int64) if body is None else np.asarray(body, dtype=np.int64)
        kappa = np.array([m.kappa for m in self.materials], dtype=np.float64)[self.body]
        super().__init__(cells, n_nodes, geom, kappa, pressure_cells=pressure_cells)
        self._kappa_e = kappa[:, None]  # (E, 1)
        self._groups = [(m, np.flatnonzero(self.body == i)) for i, m in enumerate(self.materials)]
        self._groups = [(m, idx) for m, idx in self._groups if idx.size]
        self.ln_stretch = None if ln_stretch is None else np.asarray(ln_stretch, dtype=np.float64).reshape(e, 1)
        M, w = geom.pvalues, geom.weight
        self._rubber_kpp = -np.einsum("eq,qa,qb->eab", w, M, M) / self._kappa_e[:, :, None]

    def fields(self, z: np.ndarray, lz: float) -> Fields | None:
        """Kinematics of state ``z``, or None if some J <= 0 (an inverted point)."""
        if self.ln_stretch is not None:
            lz = np.exp(math.log(lz) * self.ln_stretch)
        return super().fields(z, lz)

    # -- the material at the quadrature points --------------------------------
    def _points(self, f: Fields, tangent: bool):
        """``(P, A, F^-T)`` at the quadrature points: (E, q, 2, 2), (E, q, 2, 2, 2, 2) or None, (E, q, 2, 2)."""
        F, det = f.F, f.det
        lz = f.J / det
        P = np.empty_like(F)
        A = np.empty(F.shape + (2, 2)) if tangent else None
        for mat, idx in self._groups:
            F3 = gradient_3d(F[idx], lz[idx])
            P[idx] = mat.first_piola(F3, volumetric=False)[..., :2, :2]
            if tangent:
                A[idx] = mat.tangent(F3, volumetric=False, plane=True)
        scale = self._iso_scale(f)
        if scale is not None:
            P *= scale[..., None, None]
            if tangent:
                A *= scale[..., None, None, None, None]
        fit = np.empty_like(F)
        fit[..., 0, 0], fit[..., 1, 1] = F[..., 1, 1] / det, F[..., 0, 0] / det
        fit[..., 0, 1], fit[..., 1, 0] = -F[..., 1, 0] / det, -F[..., 0, 1] / det
        pJ = f.p * f.J
        P += pJ[..., None, None] * fit
        if tangent:
            A += pJ[..., None, None, None, None] * (np.einsum("...ij,...kl->...ijkl", fit, fit)
                                                    - np.einsum("...il,...kj->...ijkl", fit, fit))
        return P, A, fit

    def _iso_scale(self, f: Fields) -> np.ndarray | None:
        """A factor of the isochoric stress per cell, ``(E, 1)``, or None (1): a growth's, in a subclass."""
        return None

    def _constraint(self, f: Fields) -> np.ndarray:
        return (f.J - 1.0 - f.p / self._kappa_e) * self.geom.weight

    # -- the interface ----------------------------------------------------------
    def residual(self, f: Fields) -> np.ndarray:
        """Assembled residual ``(2 N + n_pressures,)``."""
        wP = self._points(f, False)[0] * self.geom.weight[..., None, None]
        rx = self.Bt @ wP.ravel()
        rp = self.Mpt @ self._constraint(f).ravel()
        return np.concatenate((rx, rp))

    def element_residuals(self, f: Fields) -> np.ndarray:
        """Element residual vectors, ``(E, 15)``."""
        wP = self._points(f, False)[0] * self.geom.weight[..., None, None]
        rx = np.einsum("eqij,eqaj->eai", wP, self.geom.grad)
        rp = np.einsum("eq,qb->eb", self._constraint(f), self.geom.pvalues)
        return np.concatenate((rx.reshape(-1, 12), rp), axis=1)

    def element_matrices(self, f: Fields) -> np.ndarray:
        """Element tangent matrices, ``(E, 15, 15)``, symmetric."""
        e = len(self.cells)
        w, G, M = self.geom.weight, self.geom.grad, self.geom.pvalues
        _, A, fit = self._points(f, True)
        q = w.shape[1]
        # kxx[a i, b k] = sum_q w G_aJ A_iJkL G_bL, as two batched matrix products (3x faster than einsum)
        x = (A * w[..., None, None, None, None]).reshape(e, q, 8, 2) @ G.transpose(0, 1, 3, 2)  # [(i, J, k), b]
        x = x.reshape(e, q, 2, 2, 2, 6).transpose(0, 1, 3, 2, 4, 5).reshape(e, q, 2, 24)  # [J, (i, k, b)]
        kxx = (G @ x).sum(axis=1).reshape(e, 6, 2, 2, 6).transpose(0, 1, 2, 4, 3).reshape(e, 12, 12)
        kxp = np.einsum("eqiJ,eqaJ,eq,qb->eaib", fit, G, w * f.J, M).reshape(e, 12, 3)
        out = np.empty((e, 15, 15))
        out[:, :12, :12] = 0.5 * (kxx + kxx.transpose(0, 2, 1))
        out[:, :12, 12:] = kxp
        out[:, 12:, :12] = kxp.transpose(0, 2, 1)
        out[:, 12:, 12:] = self._rubber_kpp
        return out
