"""Vectorised assembly of the mixed problem of a body of revolution: neo-Hookean in closed form, or any rubber.

The section lies in a half-plane bounded by the axis; a point ``X`` of it is
at the distance ``R = n · (X − a)`` from the axis (``a`` a point of the
axis, ``n`` its unit normal towards the section). Under the deformation
``x(X)`` the three principal directions are the section's two and the hoop
direction, with the hoop stretch ``λ = n · (x − a) / R``: the current
distance from the axis over the initial one. It is linear in the node
positions, ``∂λ/∂x_a = N_a n / R``, so it enters the residual and the
tangent through the constant rows of ``B`` below; the kinematics carry no
second derivative.

With ``F3 = [[F, 0], [0, λ]]`` (``F`` the in-plane gradient), ``J = λ det F``,
``I1 = |F|² + λ²``, ``a = J^(-2/3)`` and per body the shear modulus ``μ``,
the bulk modulus ``κ`` and a volumetric growth ``c`` (the law's volume ratio
``v``: ``F = Fe · c^(1/3) I``, the elastic part carrying the energy per unit
grown volume), the energy per unit initial volume is (see
:mod:`sectiondeform.reference.mixed`: the isochoric part does not see an
isotropic growth)::

    ψ(F3, p) = c μ (a I1 − 3) / 2 + p (J − c) − c p² / (2 κ)

and every integral is over the body of revolution per radian,
``∫ · R dA``. With the five varying components of ``F3`` as a vector
``f = (F11, F12, F21, F22, λ)`` and ``B`` the constant map from an element's
node positions to ``f`` at a quadrature point::

    P  = c μ a (F3 − I1 F3^-T / 3) + p J F3^-T         (its five components)
    R_x = Σ_q w R Bᵀ P,          R_p[b] = Σ_q w R M_b (J − c − c p / κ)
    K_xx = Σ_q w R Bᵀ A B,       K_xp = Σ_q w R J Bᵀ F3^-T M,   K_pp = −Σ_q w R c M M / κ
    A_iJkL = c μ a (δ_ik δ_JL − 2/3 (F_iJ G_kL + G_iJ F_kL) + 2 I1/9 G_iJ G_kL + I1/3 G_iL G_kJ)
             + p J (G_iJ G_kL − G_iL G_kJ),     G = F3^-T

``c = 1`` is plain near-incompressibility. The growth follows a path
parameter ``s`` of the Newton solver (its ``lz``): ``c = exp(ln s · ln v)``,
so ``s = 1`` is the undeformed state and ``s = e`` every body's own ratio.

:class:`AxisymmetricRubber` replaces the closed-form isochoric part
``c μ (a I1 − 3) / 2`` by ``c W_iso(F3)`` of any rubber of
:mod:`sectiondeform.materials` (Mooney–Rivlin, Yeoh), its stress and
tangent taken from the material on the five components; the pressure
part is the same. In both, the pressure unknown ``p`` is the mean Cauchy
stress tr σ / 3 (the isochoric part's Cauchy stress is deviatoric).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..materials.models import gradient_3d
from .elements import QUAD_POINTS, Geometry, p2_values

__all__ = ["AxisymmetricNeoHooke", "AxisymmetricRubber", "AxisymmetricFields"]

_I = np.array([0, 0, 1, 1, 2])
_J = np.array([0, 1, 0, 1, 2])
_DELTA = ((_I[:, None] == _I[None, :]) & (_J[:, None] == _J[None, :])).astype(np.float64)


@dataclass(frozen=True, eq=False)
class AxisymmetricFields:
    """Kinematics at the quadrature points for one state.

    Attributes
    ----------
    F : (E, q, 2, 2) float64 ndarray
        In-plane deformation gradient.
    det : (E, q) float64 ndarray
        det F (the in-plane area stretch).
    hoop : (E, q) float64 ndarray
        Hoop stretch λ, current over initial distance from the axis.
    J : (E, q) float64 ndarray
        Volume ratio ``λ det F``.
    i1 : (E, q) float64 ndarray
        ``|F|² + λ²``.
    p : (E, q) float64 ndarray
        Pressure at the quadrature points (units of the moduli).
    growth : (E, 1) float64 ndarray
        Volumetric growth ``c`` of each element at this point of the path.
    """

    F: np.ndarray
    det: np.ndarray
    hoop: np.ndarray
    J: np.ndarray
    i1: np.ndarray
    p: np.ndarray
    growth: np.ndarray


class AxisymmetricNeoHooke:
    """Residual and tangent of the Taylor-Hood neo-Hookean problem of a body of revolution.

    Same interface as :class:`~sectiondeform.fem.neohooke.MixedNeoHooke`
    (what :class:`~sectiondeform.fem.newton.NewtonSolver` uses): the unknown
    vector ``z = [x (2 N, node-major), p (n_pressures)]``, element dofs
    ``(x0, y0, ..., x5, y5, p0, p1, p2)``, and the solver's scalar ``lz``
    read as the growth path parameter ``s``.

    Parameters
    ----------
    cells : (E, 6) int64 ndarray
        P2 cells; their first three nodes are the pressure nodes.
    nodes : (N, 2) float64 ndarray
        Initial node positions, units.
    geom : Geometry
        Shape-function gradients and weights at the quadrature points.
    origin : (2,) float64 array_like
        A point of the axis, units.
    normal : (2,) float64 array_like
        Unit normal of the axis, pointing to the section's side.
    kappa : float or (E,) float64 ndarray
        Bulk modulus (in the units of ``mu``).
    mu : float or (E,) float64 ndarray
        Shear modulus.
    ln_growth : float or (E,) float64 ndarray
        ``ln v`` of each element's volume ratio (0: no growth).
    pressure_cells : (E, 3) int64 ndarray, optional
        The pressure unknown at each element's corners; ``cells[:, :3]`` by
        default (one continuous field), one field per body in an assembly
        (see :class:`~.assembly.MixedNeoHooke`).

    Attributes
    ----------
    n_pressures : int
        Number of pressure unknowns.
    radius : (E, q) float64 ndarray
        Initial distance of each quadrature point from the axis, units.
    ln_stretch : (E, 1) float64 ndarray
        ``−ln v``: the pressure rows of the residual change along the path
        by ``Σ_q w R M ln_stretch`` per unit ``ln s`` at the undeformed state
        (the role the out-of-plane stretch's logarithm plays in the plane
        problem, so an assembly's predictor reads both alike).
    """

    def __init__(self, cells: np.ndarray, nodes: np.ndarray, geom: Geometry, origin, normal, kappa, mu, ln_growth=0.0,
                 pressure_cells: np.ndarray | None = None):
        e, q = geom.weight.shape
        self.cells = cells
        self.n_nodes = len(nodes)
        self.geom = geom
        self.origin = np.asarray(origin, dtype=np.float64)
        self.normal = np.asarray(normal, dtype=np.float64)
        column = lambda v: np.broadcast_to(np.asarray(v, dtype=np.float64).reshape(-1, 1), (e, 1)).copy()  # noqa: E731
        self.kappa, self.mu, self.ln_growth = column(kappa), column(mu), column(ln_growth)
        self.ln_stretch = -self.ln_growth
        pc = cells[:, :3] if pressure_cells is None else np.asarray(pressure_cells, dtype=np.int64)
        self.pressure_cells = pc
        self.n_pressures = int(pc.max()) + 1
        self.n_dofs = 2 * self.n_nodes + self.n_pressures
        xd = (2 * cells[:, :, None] + np.arange(2)).reshape(e, 12)
        self.edofs = np.concatenate((xd, 2 * self.n_nodes + pc), axis=1)
        self.values = p2_values(QUAD_POINTS)  # (q, 6)
        self.radius = self.distance(np.einsum("qa,eai->eqi", self.values, nodes[cells]))
        if not self.radius.min() > 0:
            raise ValueError("AxisymmetricNeoHooke: a quadrature point lies on the axis or beyond it")
        self.wr = geom.weight * self.radius  # (E, q), units³ per radian
        M = geom.pvalues
        self._wM = self.wr[:, :, None] * M[None]  # (E, q, 3)
        # B: (E, q, 5, 12), the five components of F3 from the element's positions.
        G = geom.grad
        B = np.zeros((e, q, 5, 6, 2))
        for m in range(4):
            B[:, :, m, :, _I[m]] = G[:, :, :, _J[m]]
        B[:, :, 4] = (self.values[None, :, :, None] * self.normal) / self.radius[:, :, None, None]
        self.B = B.reshape(e, q, 5, 12)
        # The same map assembled once, sparse: f = Bs x - hoop_offset at all points (one product), and
        # the assembled position residual Bs^T (w R P) (no element loop, no scatter).
        rows = np.broadcast_to(np.arange(e * q * 5).reshape(e, q, 5, 1), (e, q, 5, 12)).ravel()
        cols = np.broadcast_to(xd[:, None, None, :], (e, q, 5, 12)).ravel()
        self.Bs = sp.csr_matrix((self.B.ravel(), (rows, cols)), shape=(5 * e * q, 2 * self.n_nodes))
        self.Bst = self.Bs.T.tocsr()
        self.hoop_offset = float(self.origin @ self.normal) / self.radius  # (E, q)
        prow = np.broadcast_to(np.arange(e * q).reshape(e, q, 1), (e, q, 3)).ravel()
        pcol = np.broadcast_to(pc[:, None, :], (e, q, 3)).ravel()
        self.Mp = sp.csr_matrix((np.broadcast_to(M[None], (e, q, 3)).ravel(), (prow, pcol)), shape=(e * q, self.n_pressures))
        self.Mpt = self.Mp.T.tocsr()

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance of points ``(..., 2)`` from the axis (positive on the bodies' side), units, ``(...)``."""
        return (points[..., 0] - self.origin[0]) * self.normal[0] + (points[..., 1] - self.origin[1]) * self.normal[1]

    def fields(self, z: np.ndarray, lz: float) -> AxisymmetricFields | None:
        """Kinematics of state ``z`` at path parameter ``lz``, or None if some J <= 0 or a point reaches the axis."""
        n = self.n_nodes
        e, q = self.radius.shape
        f5 = (self.Bs @ z[: 2 * n]).reshape(e, q, 5)
        F = f5[..., :4].reshape(e, q, 2, 2)
        det = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        hoop = f5[..., 4] - self.hoop_offset
        if not (det.min() > 0 and hoop.min() > 0):
            return None
        p = (self.Mp @ z[2 * n :]).reshape(e, q)
        i1 = (f5[..., :4] ** 2).sum(axis=-1) + hoop * hoop
        growth = np.exp(math.log(lz) * self.ln_growth)
        return AxisymmetricFields(F, det, hoop, hoop * det, i1, p, growth)

    @staticmethod
    def _inverse_transpose(f: AxisymmetricFields) -> np.ndarray:
        """``F3^-T``, ``(E, q, 3, 3)``."""
        F, det = f.F, f.det
        it = np.zeros(F.shape[:2] + (3, 3))
        it[..., 0, 0], it[..., 1, 1] = F[..., 1, 1] / det, F[..., 0, 0] / det
        it[..., 0, 1], it[..., 1, 0] = -F[..., 1, 0] / det, -F[..., 0, 1] / det
        it[..., 2, 2] = 1.0 / f.hoop
        return it

    def _vectors(self, f: AxisymmetricFields):
        """``(f, F3^-T)`` as five-component vectors, the full ``F3^-T`` and ``c μ a``."""
        fv = np.concatenate((f.F.reshape(f.F.shape[:2] + (4,)), f.hoop[..., None]), axis=-1)
        it = self._inverse_transpose(f)
        gv = it[..., _I, _J]
        shear = f.growth * self.mu * f.J ** (-2.0 / 3.0)
        return fv, gv, it, shear

    def _stress(self, f: AxisymmetricFields) -> np.ndarray:
        """``P`` (five components) at the quadrature points, ``(E, q, 5)``."""
        fv, gv, _, shear = self._vectors(f)
        return self._iso_stress(f, fv, gv, shear) + (f.p * f.J)[..., None] * gv

    def _iso_stress(self, f: AxisymmetricFields, fv, gv, shear) -> np.ndarray:
        """The isochoric part of ``P`` (five components), ``(E, q, 5)``: closed-form neo-Hookean."""
        return shear[..., None] * (fv - (f.i1 / 3.0)[..., None] * gv)

    def _iso_tangent(self, f: AxisymmetricFields, fv, gv, it, shear) -> np.ndarray:
        """The isochoric part of ``A`` on the five components, ``(E, q, 5, 5)``: closed-form neo-Hookean."""
        cross = it[..., _I[:, None], _J[None, :]]  # [m, n] = G_{i_m J_n}
        swap = cross * cross.swapaxes(-1, -2)  # G_iL G_kJ
        gg = gv[..., :, None] * gv[..., None, :]
        fg = fv[..., :, None] * gv[..., None, :]
        s, i1 = shear[..., None, None], f.i1[..., None, None]
        return s * (_DELTA - 2.0 / 3.0 * (fg + fg.swapaxes(-1, -2)) + 2.0 * i1 / 9.0 * gg + i1 / 3.0 * swap)

    def _pressure_residual(self, f: AxisymmetricFields) -> np.ndarray:
        return (f.J - f.growth - f.growth * f.p / self.kappa) * self.wr

    def element_residuals(self, f: AxisymmetricFields) -> np.ndarray:
        """Element residual vectors, ``(E, 15)``."""
        rx = np.einsum("eqm,eqmr->er", self._stress(f) * self.wr[..., None], self.B)
        rp = np.einsum("eq,qb->eb", self._pressure_residual(f), self.geom.pvalues)
        return np.concatenate((rx, rp), axis=1)

    def residual(self, f: AxisymmetricFields) -> np.ndarray:
        """Assembled residual ``(2 N + n_pressures,)`` (the sparse transposes of the maps; :meth:`element_residuals` summed)."""
        rx = self.Bst @ (self._stress(f) * self.wr[..., None]).ravel()
        rp = self.Mpt @ self._pressure_residual(f).ravel()
        return np.concatenate((rx, rp))

    def element_matrices(self, f: AxisymmetricFields) -> np.ndarray:
        """Element tangent matrices, ``(E, 15, 15)``, symmetric."""
        e, q = self.geom.weight.shape
        fv, gv, it, shear = self._vectors(f)
        cross = it[..., _I[:, None], _J[None, :]]  # [m, n] = G_{i_m J_n}
        swap = cross * cross.swapaxes(-1, -2)  # G_iL G_kJ
        gg = gv[..., :, None] * gv[..., None, :]
        A = self._iso_tangent(f, fv, gv, it, shear) + (f.p * f.J)[..., None, None] * (gg - swap)
        wB = self.B * self.wr[..., None, None]
        wBt = wB.reshape(e, q * 5, 12).transpose(0, 2, 1)  # (E, 12, 5 q)
        kxx = np.matmul(wBt, np.matmul(A, self.B).reshape(e, q * 5, 12))
        jgm = (gv * f.J[..., None])[..., None] * self.geom.pvalues[None, :, None, :]  # (E, q, 5, 3): J G_m M_b
        kxp = np.matmul(wBt, jgm.reshape(e, q * 5, 3))
        kpp = -np.einsum("eqa,qb,e->eab", self._wM, self.geom.pvalues, (f.growth / self.kappa)[:, 0])
        out = np.empty((e, 15, 15))
        out[:, :12, :12] = kxx
        out[:, :12, 12:] = kxp
        out[:, 12:, :12] = kxp.transpose(0, 2, 1)
        out[:, 12:, 12:] = kpp
        return out


class AxisymmetricRubber(AxisymmetricNeoHooke):
    """The problem of :class:`AxisymmetricNeoHooke` for any rubber of :mod:`sectiondeform.materials`.

    What :class:`~.rubber.MixedRubber` is to the plane problem: the
    kinematics, the pressure and the growth are the neo-Hookean class's; the
    isochoric stress and tangent come from the materials (neo-Hookean,
    Mooney–Rivlin, Yeoh), one per body, evaluated on ``F3`` and restricted
    to its five varying components. The isochoric energy does not see an
    isotropic growth (``Ī₁``, ``Ī₂`` of ``F`` and of ``c^(-1/3) F`` are the
    same), so per unit initial volume it is ``c W_iso(F3)``::

        P = c P_iso(F3) + p J F3^-T,    A = c A_iso(F3) + p J (G ⊗ G − G_iL G_kJ),   G = F3^-T

    With a neo-Hookean material of shear modulus μ this is
    :class:`AxisymmetricNeoHooke` with that μ, to rounding.

    Parameters
    ----------
    cells, nodes, geom, origin, normal : as :class:`AxisymmetricNeoHooke`
    materials : sequence of NeoHookean or MooneyRivlin or Yeoh
        The rubbers (one per body), moduli in their own unit (MPa or relative).
    body : (E,) int ndarray, optional
        Index into ``materials`` of each element; all 0 by default.
    ln_growth : float or (E,) float64 ndarray
        ``ln v`` of each element's volume ratio (0: no growth).
    pressure_cells : (E, 3) int64 ndarray, optional
        As :class:`AxisymmetricNeoHooke`.

    Examples
    --------
    >>> from sectiondeform.fem.elements import geometry
    >>> from sectiondeform.materials import MooneyRivlin
    >>> nodes = np.array([[0, 1], [1, 1], [0, 2], [.5, 1], [.5, 1.5], [0, 1.5]], float)
    >>> cells = np.arange(6)[None]
    >>> phys = AxisymmetricRubber(cells, nodes, geometry(nodes, cells), [0, 0], [0, 1], [MooneyRivlin(0.3, 0.1)])
    >>> z = np.concatenate((nodes.ravel(), np.zeros(3)))
    >>> bool(np.abs(phys.residual(phys.fields(z, 1.0))).max() < 1e-12)   # the undeformed state is free
    True
    """

    def __init__(self, cells: np.ndarray, nodes: np.ndarray, geom: Geometry, origin, normal, materials,
                 body: np.ndarray | None = None, ln_growth=0.0, pressure_cells: np.ndarray | None = None):
        self.materials = tuple(materials)
        e = len(cells)
        self.body = np.zeros(e, np.int64) if body is None else np.asarray(body, dtype=np.int64)
        kappa = np.array([m.kappa for m in self.materials], dtype=np.float64)[self.body]
        mu = np.array([m.shear_modulus for m in self.materials], dtype=np.float64)[self.body]
        super().__init__(cells, nodes, geom, origin, normal, kappa, mu, ln_growth, pressure_cells)
        self._groups = [(m, np.flatnonzero(self.body == i)) for i, m in enumerate(self.materials)]
        self._groups = [(m, idx) for m, idx in self._groups if idx.size]

    def _material(self, f: AxisymmetricFields, tangent: bool):
        """``c P_iso`` (E, q, 5) and ``c A_iso`` (E, q, 5, 5) or None, from the materials."""
        e, q = f.det.shape
        P = np.empty((e, q, 5))
        A = np.empty((e, q, 5, 5)) if tangent else None
        for mat, idx in self._groups:
            F3 = gradient_3d(f.F[idx], f.hoop[idx])
            c = f.growth[idx][..., None]  # (e_b, 1, 1)
            P[idx] = c * mat.first_piola(F3, volumetric=False)[..., _I, _J]
            if tangent:
                full = mat.tangent(F3, volumetric=False)
                A[idx] = c[..., None] * full[..., _I[:, None], _J[:, None], _I[None, :], _J[None, :]]
        return P, A

    def _iso_stress(self, f: AxisymmetricFields, fv, gv, shear) -> np.ndarray:
        return self._material(f, False)[0]

    def _iso_tangent(self, f: AxisymmetricFields, fv, gv, it, shear) -> np.ndarray:
        A = self._material(f, True)[1]
        return 0.5 * (A + A.swapaxes(-1, -2))
