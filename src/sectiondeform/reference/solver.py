"""Mixed finite-element solve of the bonded section (scikit-fem, extra ``[fem]``).

Model
-----
The deformation gradient is block diagonal,

    F = [[F2D, 0], [0, F₃₃]],   F2D = I + ∇u,

with two kinematics:

- generalised plane strain (a long extruded body): F₃₃ = λz prescribed, so
  the section may change area while the body keeps its volume: with
  λz = 1 / r an incompressible section ends with area r × A0, the law; a
  body that grows isotropically by v (F = Fe · v^(1/3) I, as for bodies of
  revolution) has its λz solved so that its extrusion is free, no axial
  force (:mod:`sectiondeform.extrusion`, :meth:`MixedProblem.axial_forces`);
- a body of revolution about an axis of the section's plane: F₃₃ = r / R,
  the hoop stretch, the current distance of the point from the axis over
  its initial one, and every integral weighted by R (the volume is
  2π ∫ R dA). A volume law v is an isotropic growth of the body,
  F = Fe · v^(1/3) I (:mod:`sectiondeform.reference.mixed`); v = 1 is
  plain near-incompressibility.

Material: any rubber of :mod:`sectiondeform.materials` (neo-Hookean by
default, Mooney–Rivlin, Yeoh), W = W_iso(F) + κ/2 (J − 1)², written in
mixed displacement–pressure form (perturbed Lagrangian) so the nearly
incompressible material (κ/μ ≥ 100) does not lock:

    Π(u, p) = ∫ W_iso(F) + p (J − 1) − p² / (2κ) w dA,   w = 1 or R.

Eliminating p (p = κ (J − 1)) gives back W. Elements: Taylor–Hood, P2
displacement with continuous P1 pressure, inf-sup stable.

Boundary conditions: every lower node (vertices and mid-edge nodes) at
arc-length fraction s goes to the target point at s; the rest is traction
free.

Solution: full Newton on (u, p), with the support displacement and the load
parameter (λz, or the growth v) ramped together. The load path splits the
support's motion into a rigid part (the best-fitting rotation and
translation, Kabsch) and a remainder; each load step first moves the whole
body by the step's rigid increment (exact and stress free in plane strain;
for a body of revolution a predictor only, as moving off the axis stretches
the hoops), then imposes the remainder's increment through the tangent. A
step that does not converge, or that would invert an element, is cut in
half; a backtracking line search on the residual guards each Newton update.
The weak forms are evaluated on scikit-fem's bases (shape functions,
quadrature, degree-of-freedom numbering) and assembled in a few vectorised
``einsum`` calls. :func:`neo_hookean` is the closed-form plane neo-Hookean
of the first version, kept as an independent check of the general path.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError, require
from .mesh import ReferenceMesh
from .mixed import mixed_state
from .revolution import Axis

#: The components (i, J) of F that vary: the in-plane block, then the out-of-plane (hoop) stretch.
COMPONENTS = np.array([[0, 0], [0, 1], [1, 0], [1, 1], [2, 2]])

__all__ = ["MixedProblem", "NewtonReport", "neo_hookean", "kabsch", "solve_mixed", "continue_mixed"]


def neo_hookean(grad_u: np.ndarray, stretch_z: float, p: np.ndarray, mu: float, kappa: float, tangent: bool = True):
    """Stress and tangent of the mixed neo-Hookean model in generalised plane strain, in closed form.

    Parameters
    ----------
    grad_u : (2, 2, ...) float64 ndarray
        Displacement gradient ∂u_i/∂X_J at each point.
    stretch_z : float
        Out-of-plane stretch λz.
    p : (...) float64 ndarray
        Pressure at each point, units of μ.
    mu, kappa : float
        Shear and bulk moduli.
    tangent : bool
        Also compute the tangent moduli.

    Returns
    -------
    dict
        ``P`` (2, 2, ...) first Piola stress, in-plane block; ``A``
        (2, 2, 2, 2, ...) ∂P/∂F (if ``tangent``); ``dPdp`` (2, 2, ...);
        ``J`` (...) volume ratio; ``det2`` (...) det F2D; ``psi_iso`` (...)
        isochoric energy density μ/2 (J^(-2/3) tr(FᵀF) − 3); ``psi_mixed``
        (...) the mixed density ``psi_iso + p (J − 1) − p² / (2κ)``, which
        equals Ψ when p = κ (J − 1).

    Examples
    --------
    >>> out = neo_hookean(np.zeros((2, 2, 1)), 1.0, np.zeros(1), 1.0, 1000.0)
    >>> float(abs(out["P"]).max()), float(out["psi_mixed"][0])
    (0.0, 0.0)
    """
    F = grad_u + np.eye(2).reshape((2, 2) + (1,) * (grad_u.ndim - 2))
    det2 = F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0]
    # F^-T: cofactor over determinant.
    Fit = np.stack((np.stack((F[1, 1], -F[1, 0])), np.stack((-F[0, 1], F[0, 0])))) / det2
    J = stretch_z * det2
    I1 = np.einsum("ij...,ij...->...", F, F) + stretch_z**2
    c = mu * J ** (-2.0 / 3.0)
    P = c * (F - I1 / 3.0 * Fit) + p * J * Fit
    out = {
        "P": P,
        "dPdp": J * Fit,
        "J": J,
        "det2": det2,
        "psi_iso": 0.5 * mu * (J ** (-2.0 / 3.0) * I1 - 3.0),
    }
    out["psi_mixed"] = out["psi_iso"] + p * (J - 1.0) - p * p / (2.0 * kappa)
    if tangent:
        d = np.eye(2)
        idil = np.einsum("ik,jl->ijkl", d, d).reshape((2, 2, 2, 2) + (1,) * (grad_u.ndim - 2))
        FiFi = np.einsum("ij...,kl...->ijkl...", Fit, Fit)
        FiFi_t = np.einsum("il...,kj...->ijkl...", Fit, Fit)
        FFi = np.einsum("kl...,ij...->ijkl...", F, Fit)
        A = c * (idil - 2.0 / 3.0 * (FFi + np.swapaxes(np.swapaxes(FFi, 0, 2), 1, 3))
                 + 2.0 / 9.0 * I1 * FiFi + I1 / 3.0 * FiFi_t)
        A += p * J * (FiFi - FiFi_t)
        out["A"] = A
    return out


def kabsch(source: np.ndarray, target: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """Rigid motion closest to ``source -> target`` in least squares.

    Parameters
    ----------
    source, target : (n, 2) float64 ndarray

    Returns
    -------
    angle : float
        Rotation, radians, counter-clockwise.
    source_centre, target_centre : (2,) float64 ndarray
        Centroids; the motion is x -> R(angle) (x - source_centre) + target_centre.

    Examples
    --------
    >>> a = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    >>> b = a @ np.array([[0.0, 1.0], [-1.0, 0.0]]) + 5.0   # rotated by +90 degrees
    >>> round(math.degrees(kabsch(a, b)[0]), 9)
    90.0
    """
    cs, ct = source.mean(axis=0), target.mean(axis=0)
    a, b = source - cs, target - ct
    h = a.T @ b
    angle = math.atan2(h[0, 1] - h[1, 0], h[0, 0] + h[1, 1])
    return angle, cs, ct


def _rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


@dataclass(frozen=True)
class NewtonReport:
    """How the incremental Newton solve went.

    Attributes
    ----------
    iterations : int
        Newton iterations over all load steps (failed attempts included).
    steps : int
        Load steps accepted.
    cuts : int
        Load steps cut in half after a failure.
    residual : float
        Norm of the last residual on the free degrees of freedom.
    """

    iterations: int
    steps: int
    cuts: int
    residual: float


class MixedProblem:
    """The discrete Taylor–Hood problem on one mesh: bases, Dirichlet data, assembly.

    Two kinematics: generalised plane strain (no ``axis``), the out-of-plane
    stretch λz the load parameter; or a body of revolution (``axis``), the
    hoop stretch r / R at each point, every integral weighted by the initial
    radius R (per radian: the volume is 2π ∫ R dA), the load parameter the
    volume ratio v of the body's isotropic growth (F = Fe · v^(1/3) I).

    At each quadrature point the strain is written as the five components
    (F₀₀, F₀₁, F₁₀, F₁₁, F₃₃) of the block-diagonal 3 × 3 gradient: the
    in-plane block and the out-of-plane stretch. ``B[a, e, q, m]`` is the
    derivative of component m by displacement dof a of element e (the
    shape-function gradients, and for F₃₃ the hoop term n · φ_a / R), so
    the residual is ∫ Bᵀ P and the tangent ∫ Bᵀ A B.

    Parameters
    ----------
    mesh : ReferenceMesh
        Its ``body`` gives each triangle's body.
    materials : sequence of NeoHookean or MooneyRivlin or Yeoh
        One rubber per body (:mod:`sectiondeform.materials`).
    axis : Axis, optional
        The axis of revolution (:mod:`sectiondeform.reference.revolution`);
        without it, generalised plane strain.

    The displacement is continuous over the whole mesh (bonded
    interfaces); the pressure is continuous within each body and has its
    own degrees of freedom on either side of an interface (the pressure
    jumps there, and each body's volume constraint is its own). The load
    parameter of :meth:`material`, :meth:`residual` and :func:`solve_mixed`
    is one value per body (each body's own λz or growth), or one for all.

    Attributes
    ----------
    n_u, n_p : int
        Number of displacement and pressure degrees of freedom.
    pressure_vertex : (n_p,) int64 ndarray
        The mesh vertex of each pressure degree of freedom (one per vertex
        and body meeting there).
    mu, kappa : float
        The smallest initial shear and bulk moduli of the bodies' rubbers
        (the scale of the pressure tolerance).
    weight : (nel, nq) float64 ndarray
        Integration weight: the initial radius R, or 1 in plane strain.
    dirichlet : (d,) int64 ndarray
        Displacement dofs of the lower nodes (x and y of vertices and
        mid-edge nodes).
    dirichlet_points : (d / 2, 2) float64 ndarray
        Initial position of each Dirichlet node.
    dirichlet_fractions : (d / 2,) float64 ndarray
        Arc-length fraction of each Dirichlet node on the lower curve.
    """

    def __init__(self, mesh: ReferenceMesh, materials, *, axis: Axis | None = None):
        skfem = require("skfem", "fem", "the finite-element reference")
        from ..materials import NeoHookean

        self.section_mesh = mesh
        self.groups = np.asarray(mesh.body, dtype=np.int64)
        self.rubbers = tuple(materials)
        self._members = [np.flatnonzero(self.groups == g) for g in range(len(self.rubbers))]
        self.mu = min(float(r.shear_modulus) for r in self.rubbers)
        self.kappa = min(float(r.kappa) for r in self.rubbers)
        self.axis = axis
        # The first version's closed form, same model, for one neo-Hookean rubber in plane strain (faster).
        self._closed_form = axis is None and len(self.rubbers) == 1 and type(self.rubbers[0]) is NeoHookean
        m = skfem.MeshTri(np.ascontiguousarray(mesh.points.T), np.ascontiguousarray(mesh.triangles.T))
        self.skmesh = m
        self.ubasis = skfem.Basis(m, skfem.ElementVector(skfem.ElementTriP2()), intorder=4)
        self.pbasis = self.ubasis.with_element(skfem.ElementTriP1())
        ub, pb = self.ubasis, self.pbasis
        self.n_u, self.n_p = ub.N, pb.N
        self.dx = ub.dx  # (nel, nq)
        self.G = np.stack([ub.basis[a][0].grad for a in range(ub.Nbfun)])  # (12, 2, 2, nel, nq)
        self.Nq = np.stack([pb.basis[c][0] for c in range(pb.Nbfun)])  # (3, nel, nq)
        self.udofs = ub.element_dofs  # (12, nel)
        self.pdofs = pb.element_dofs  # (3, nel)
        # Pressure vertex of each pressure dof (the P1 dofs are the vertices).
        # Continuous within a body, free to jump between bodies: a bonded interface between
        # two rubbers carries a pressure jump, and each body's volume constraint stays its own.
        key = self.pdofs * len(self.rubbers) + self.groups[None, :]
        uniq, inverse = np.unique(key, return_inverse=True)
        self.pdofs = inverse.reshape(self.pdofs.shape)
        self.pressure_vertex = uniq // len(self.rubbers)
        self.pressure_body = uniq % len(self.rubbers)
        self.n_p = len(uniq)
        # Initial position of every displacement dof's node (x and y rows repeat the node).
        self.doflocs = ub.doflocs.T  # (n_u, 2)
        nb_u, nel, nq = self.G.shape[0], self.dx.shape[0], self.dx.shape[1]
        B = np.empty((nb_u, nel, nq, 5))
        B[..., :4] = np.moveaxis(self.G, (1, 2), (3, 4)).reshape(nb_u, nel, nq, 4)
        if axis is None:
            self.weight = np.ones_like(self.dx)
            B[..., 4] = 0.0
        else:
            self.weight = axis.radius(np.moveaxis(np.asarray(ub.global_coordinates()), 0, -1))  # R, (nel, nq)
            phi = np.stack([np.asarray(ub.basis[a][0]) for a in range(ub.Nbfun)])  # (12, 2, nel, nq)
            B[..., 4] = np.einsum("i,aieq->aeq", axis.normal, phi) / self.weight
        self.B = B
        self.wdx = self.weight * self.dx

        # Dirichlet nodes: lower vertices, and the mid-edge nodes of lower edges.
        pos = np.full(len(mesh.points), -1, dtype=np.int64)
        pos[mesh.lower_nodes] = np.arange(len(mesh.lower_nodes))
        f0, f1 = pos[m.facets[0]], pos[m.facets[1]]
        lower_facets = np.flatnonzero((f0 >= 0) & (f1 >= 0) & (np.abs(f0 - f1) == 1))
        s_v = mesh.lower_fractions
        s_f = 0.5 * (s_v[f0[lower_facets]] + s_v[f1[lower_facets]])
        nodes = np.concatenate((ub.nodal_dofs[:, mesh.lower_nodes], ub.facet_dofs[:, lower_facets]), axis=1)
        self.lower_facets = lower_facets  # the support's facets (of ``skmesh``)
        self.dirichlet_nodes = nodes  # (2, d/2): x dof, y dof
        self.dirichlet = nodes.T.ravel()
        self.dirichlet_fractions = np.concatenate((s_v, s_f))
        self.dirichlet_points = self.doflocs[nodes[0]]
        self.free = np.setdiff1d(np.arange(self.n_u + self.n_p), self.dirichlet)

        # Sparsity pattern once: COO entry -> CSR slot.
        dofs = np.concatenate((self.udofs, self.pdofs + self.n_u)).astype(np.int64)  # (15, nel)
        nb = dofs.shape[0]
        rows = np.repeat(dofs[:, None, :], nb, axis=1).ravel()  # [a, b, e] -> dofs[a, e]
        cols = np.repeat(dofs[None, :, :], nb, axis=0).ravel()  # [a, b, e] -> dofs[b, e]
        n = self.n_u + self.n_p
        key = rows * n + cols
        uniq, self._slot = np.unique(key, return_inverse=True)
        r, c = np.divmod(uniq, n)
        self._indices = c.astype(np.int32)
        self._indptr = np.concatenate(([0], np.cumsum(np.bincount(r, minlength=n)))).astype(np.int32)
        self._nb = nb
        self._dofs = dofs
        #: The rigid parts' contact terms (:class:`~sectiondeform.reference.contact.ReferenceContact`), or None.
        self.contact = None

    @property
    def revolution(self) -> bool:
        """True for a body of revolution."""
        return self.axis is not None

    # --- fields ---------------------------------------------------------------

    def grad_u(self, u: np.ndarray) -> np.ndarray:
        """Displacement gradient at the quadrature points, ``(2, 2, nel, nq)``."""
        return np.einsum("ae,aijeq->ijeq", u[self.udofs], self.G)

    def pressure(self, p: np.ndarray) -> np.ndarray:
        """Pressure at the quadrature points, ``(nel, nq)``."""
        return np.einsum("ce,ceq->eq", p[self.pdofs], self.Nq)

    def gradient(self, x: np.ndarray, load: float) -> np.ndarray:
        """The 3 × 3 deformation gradient at the quadrature points, ``(nel, nq, 3, 3)``.

        ``load`` is λz in plane strain; for a body of revolution the
        out-of-plane component is the hoop stretch 1 + n · u / R and ``load``
        (the growth) does not enter F.
        """
        strain = np.einsum("ae,aeqm->eqm", x[: self.n_u][self.udofs], self.B)
        F = np.zeros(self.dx.shape + (3, 3))
        F[..., :2, :2] = strain[..., :4].reshape(self.dx.shape + (2, 2)) + np.eye(2)
        F[..., 2, 2] = 1.0 + strain[..., 4] if self.revolution else self.per_cell(self.split(load)[0])
        return F

    def split(self, load) -> tuple:
        """The out-of-plane stretch λz and the growth of each body, ``(λz, (bodies,) v)``, from a load parameter.

        ``load`` is the growth v (body of revolution: λz is None), λz
        (plane, no growth: v = 1), or a ``(2, bodies)`` array of λz then v
        (plane bodies of which some grow).
        """
        n = len(self.rubbers)
        if self.revolution:
            return None, np.broadcast_to(np.asarray(load, dtype=np.float64), (n,))
        if np.ndim(load) == 2:
            return load[0], np.asarray(load[1], dtype=np.float64)
        return load, np.ones(n)

    def axial_forces(self, x: np.ndarray, load) -> np.ndarray:
        """Each body's axial force ``∫ P_zz dA`` in generalised plane strain, ``(bodies,)``, moduli x units² (per unit depth).

        ``P_zz`` is the nominal stress along the extrusion, conjugate to λz:
        the derivative of the body's energy by λz. Zero for a free extrusion.
        """
        mat = self.material(x, load, tangent=False, extras=False)
        per_cell = (mat["P5"][..., 4] * self.dx).sum(axis=1)
        return np.bincount(self.groups, weights=per_cell, minlength=len(self.rubbers))
    def per_cell(self, load):
        """``load`` as the value of each triangle, ``(nel, 1)``, for a load per body; a scalar as it is."""
        if np.ndim(load) == 0:
            return load
        return np.asarray(load, dtype=np.float64)[self.groups][:, None]

    def material(self, x: np.ndarray, load: float, tangent: bool = True, extras: bool = True) -> dict:
        """The mixed rubber (:func:`~sectiondeform.reference.mixed.mixed_state`) at every quadrature point.

        Parameters
        ----------
        x : (n_u + n_p,) float64 ndarray
            Displacements then pressures.
        load : float
            λz (generalised plane strain) or the growth volume ratio (body
            of revolution).
        tangent : bool
            Also the tangent ``A5``.
        extras : bool
            Also ``psi`` and ``cauchy`` (not needed by Newton).

        Returns
        -------
        dict
            ``valid`` (False if an element inverts: then nothing else but
            ``det2`` and ``stretch3``); ``P5`` (nel, nq, 5) the stress
            components conjugate to the five strain components, ``A5``
            (nel, nq, 5, 5), ``D5`` (nel, nq, 5) their derivative by p,
            ``constraint``, ``kpp``, ``Je``, (with ``extras``) ``psi`` and ``cauchy`` (nel, nq, 3, 3),
            ``det2`` det F2D and ``stretch3`` F₃₃ (nel, nq).
        """
        F = self.gradient(x, load)
        det2 = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        out = {"det2": det2, "stretch3": F[..., 2, 2], "valid": bool(np.all(det2 > 0) and np.all(F[..., 2, 2] > 0))}
        if not out["valid"]:
            return out
        if self._closed_form and not extras and np.ndim(load) < 2:
            return self._neo_hookean(x, load, tangent, out)
        s = self._grouped_state(F, self.pressure(x[self.n_u:]), load, tangent, extras)
        out.update(s)
        i, j = COMPONENTS.T
        out["P5"] = s["P"][..., i, j]
        out["D5"] = s["dPdp"][..., i, j]
        if tangent:
            out["A5"] = s["A"]
        out["valid"] = bool(np.all(np.isfinite(out["P5"])))
        return out

    def _grouped_state(self, F: np.ndarray, p: np.ndarray, load, tangent: bool, extras: bool) -> dict:
        """:func:`~sectiondeform.reference.mixed.mixed_state` of each body's rubber on its triangles, gathered."""
        growths = self.split(load)[1]
        out: dict = {}
        kpp = np.empty(len(self.groups))
        for g, (rubber, cells) in enumerate(zip(self.rubbers, self._members)):
            if not len(cells):
                continue
            s = mixed_state(rubber, F[cells], p[cells], float(growths[g]), tangent,
                            components=COMPONENTS, extras=extras)
            kpp[cells] = s.pop("kpp")
            for key, value in s.items():
                if key not in out:
                    out[key] = np.empty((len(self.groups),) + value.shape[1:])
                out[key][cells] = value
        out["kpp"] = kpp
        return out

    def _neo_hookean(self, x: np.ndarray, load: float, tangent: bool, out: dict) -> dict:
        """:meth:`material` of a neo-Hookean rubber in plane strain through the closed form :func:`neo_hookean` (faster)."""
        s = neo_hookean(self.grad_u(x[: self.n_u]), float(np.ravel(load)[0]), self.pressure(x[self.n_u:]), self.mu, self.kappa, tangent)
        shape = self.dx.shape
        out["P5"] = np.concatenate((np.moveaxis(s["P"], (0, 1), (2, 3)).reshape(shape + (4,)), np.zeros(shape + (1,))), axis=-1)
        out["D5"] = np.concatenate((np.moveaxis(s["dPdp"], (0, 1), (2, 3)).reshape(shape + (4,)), np.zeros(shape + (1,))), axis=-1)
        if tangent:
            A5 = np.zeros(shape + (5, 5))
            A5[..., :4, :4] = np.moveaxis(s["A"], (0, 1, 2, 3), (2, 3, 4, 5)).reshape(shape + (4, 4))
            out["A5"] = A5
        out["Je"] = s["J"]
        out["constraint"] = s["J"] - 1.0 - self.pressure(x[self.n_u:]) / self.kappa
        out["kpp"] = -1.0 / self.kappa
        out["valid"] = bool(np.all(np.isfinite(out["P5"])))
        return out

    # --- assembly -------------------------------------------------------------

    def residual(self, x: np.ndarray, load: float, mat: dict | None = None) -> np.ndarray:
        """Residual ``[∫ P : δF w dA, ∫ q ∂ψ/∂p w dA]``, ``(n_u + n_p,)``, w the weight (R or 1)."""
        if mat is None:
            mat = self.material(x, load, tangent=False)
        r_u = np.einsum("aeqm,eqm->ae", self.B, mat["P5"] * self.wdx[..., None])
        r_p = np.einsum("ceq,eq->ce", self.Nq, mat["constraint"] * self.wdx)
        out = np.bincount(self.udofs.ravel(), r_u.ravel(), minlength=self.n_u)
        if self.contact is not None:
            out += self.contact.residual(x)
        return np.concatenate((out, np.bincount(self.pdofs.ravel(), r_p.ravel(), minlength=self.n_p)))

    def tangent(self, mat: dict, x: np.ndarray | None = None):
        """Tangent matrix of the residual at ``x``, CSR ``(n_u + n_p, n_u + n_p)``, symmetric indefinite.

        ``mat`` is :meth:`material` at ``x``; ``x`` is needed only with contact (:attr:`contact`).
        """
        from scipy import sparse

        B, Nq, wdx = self.B, self.Nq, self.wdx
        AB = np.einsum("eqmn,beqn->beqm", mat["A5"] * wdx[..., None, None], B)
        k_uu = np.einsum("aeqm,beqm->abe", B, AB)
        k_up = np.einsum("aeqm,eqm,ceq->ace", B, mat["D5"] * wdx[..., None], Nq)
        k_pp = mat["kpp"] * np.einsum("ceq,deq,eq->cde", Nq, Nq, wdx)
        nu, nel = B.shape[0], wdx.shape[0]
        blocks = np.empty((self._nb, self._nb, nel))
        blocks[:nu, :nu] = k_uu
        blocks[:nu, nu:] = k_up
        blocks[nu:, :nu] = np.swapaxes(k_up, 0, 1)
        blocks[nu:, nu:] = k_pp
        if self.contact is not None:  # a contact point's terms are its own triangle's: the same pattern
            np.add.at(blocks, (slice(0, nu), slice(0, nu), self.contact.cell), self.contact.blocks(x))
        n = self.n_u + self.n_p
        data = np.bincount(self._slot, blocks.ravel(), minlength=len(self._indices))
        return sparse.csr_matrix((data, self._indices, self._indptr), shape=(n, n))

    def energy(self, x: np.ndarray, load: float) -> float:
        """Strain energy per unit depth (plane) or per radian (revolution), units of μ × length² (× length).

        The mixed form ∫ ψ_iso + p (Je − 1) − p² / (2κ) w dA, which at a
        solution equals ∫ ψ_iso + p² / (2κ) w dA: the volumetric energy is
        taken from the pressure field, as the formulation controls J only
        through it (κ/2 (J − 1)² from the displacement alone would pick up
        the pointwise part of J − 1 that the P1 pressure does not see).
        """
        mat = self.material(x, load, tangent=False)
        return float(np.sum(mat["psi"] * self.wdx))


def solve_mixed(
    problem: MixedProblem,
    support: np.ndarray,
    load: float,
    *,
    length_scale: float,
    tol: float = 1e-8,
    max_iterations: int = 25,
    initial_step: float = 0.5,
    min_step: float = 1.0 / 1024.0,
    max_step: float = 1.0,
    progress=None,
    on_step=None,
) -> tuple[np.ndarray, NewtonReport]:
    """Solve the mixed problem with the support moved to ``support`` and the load parameter at ``load``.

    Parameters
    ----------
    problem : MixedProblem
    support : (d / 2, 2) float64 ndarray
        Final position of each Dirichlet node (``problem.dirichlet_points``).
    load : float or (bodies,) or (2, bodies) float64 ndarray
        Final load parameter, ramped from 1 with the support: the
        out-of-plane stretch λz (generalised plane strain), or the growth
        volume ratio v (body of revolution, ``problem.axis`` set); one per
        body (all ramped together); in plane strain with growing bodies,
        λz then v per body (:meth:`MixedProblem.split`).
    length_scale : float
        Length for the convergence test (the mean thickness T), units.
    tol : float
        Newton stops when the correction is below ``tol × length_scale`` in
        displacement and ``tol × μ`` in pressure.
    max_iterations : int
        Newton iterations allowed per load step before the step is cut.
    initial_step : float
        First load increment, fraction of the full load.
    min_step : float
        Smallest load increment before giving up.
    max_step : float
        Largest load increment (the steps grow after quick convergence up to it).
    progress : callable, optional
        Called with one line of text per accepted load step.
    on_step : callable, optional
        Called as ``on_step(x, t, load)`` after each accepted load step (t the fraction done, 0 first).

    Returns
    -------
    x : (n_u + n_p,) float64 ndarray
        Displacement then pressure degrees of freedom.
    report : NewtonReport

    Raises
    ------
    ConvergenceError
        If the load cannot be applied with increments of ``min_step`` or more.

    With rigid parts (``problem.contact``), the parts stand at the load
    fraction of each step, and once the load is applied the contact's
    multipliers are updated (augmented Lagrangian, :func:`_augment`).
    """
    pr = problem
    n_u = pr.n_u
    X_d = pr.dirichlet_points
    angle, c0, c1 = kabsch(X_d, support)
    rest = support - ((X_d - c0) @ _rotation(angle).T + c1)  # non-rigid part of the support motion
    node_x, node_y = pr.dirichlet_nodes

    def centre(t):
        return c0 + t * (c1 - c0)

    def lam(t):
        return 1.0 + t * (load - 1.0)

    def rigid_increment(x, t, t_new):
        """Move the whole deformed body by the rigid part of the load from t to t_new."""
        # Displacement dofs come in (x, y) pairs of the same node: 2k, 2k + 1.
        nodes = pr.doflocs[0::2]
        pos = nodes + x[:n_u].reshape(-1, 2)
        moved = (pos - centre(t)) @ _rotation((t_new - t) * angle).T + centre(t_new)
        out = x.copy()
        out[:n_u] = (moved - nodes).ravel()
        return out

    def support_at(t):
        return (X_d - c0) @ _rotation(t * angle).T + centre(t) + t * rest

    x = np.zeros(n_u + pr.n_p)
    t, dt = 0.0, min(1.0, initial_step, max_step)
    iterations = steps = cuts = 0
    residual = 0.0
    free = pr.free
    t_start = time.perf_counter()
    last = None  # the state and load fraction before the last accepted step
    if pr.contact is not None:  # friction's anchors where the bodies are drawn
        pr.contact.t = 0.0
        pr.contact.commit(x)
    if on_step is not None:
        on_step(x, 0.0, lam(0.0))
    while t < 1.0:
        t_new = min(1.0, t + dt)
        lz = lam(t_new)
        if pr.contact is not None:
            pr.contact.t = t_new
        trial = _predict(pr, x, t, t_new, lz, last) if pr.contact is not None else None
        if trial is None:
            trial = rigid_increment(x, t, t_new)
        want = support_at(t_new)
        lift = np.zeros_like(x)
        lift[node_x] = want[:, 0] - (X_d[:, 0] + trial[node_x])
        lift[node_y] = want[:, 1] - (X_d[:, 1] + trial[node_y])
        ok, its, residual, trial = _newton(pr, trial, lz, lift, free, length_scale, tol, max_iterations)
        iterations += its
        if ok:
            last = (x, t)
            x, t = trial, t_new
            steps += 1
            if pr.contact is not None:
                pr.contact.commit(x)
            if progress is not None:
                progress(
                    f"reference: load {t:6.1%} (step {dt:.3g}) converged in {its} Newton iterations, "
                    f"{time.perf_counter() - t_start:.1f} s"
                )
            if on_step is not None and t < 1.0:
                on_step(x, t, lz)
            if its <= 5:
                dt = min(1.0, max_step, 1.5 * dt)
        else:
            cuts += 1
            dt *= 0.5
            if progress is not None:
                progress(f"reference: step to load {t_new:.1%} failed; cutting the load step to {dt:.3g}")
            if dt < min_step:
                raise ConvergenceError(
                    f"reference: Newton did not converge beyond load {t:.1%} of the support motion and "
                    f"out-of-plane stretch even with load steps of {min_step:.3g} (elements invert or the "
                    f"residual stalls); the target or the law is too severe for this section, or refine the mesh"
                )
    if pr.contact is not None:
        x, its = _augment(pr, x, lam(1.0), length_scale, tol, max_iterations, progress)
        iterations += its
    if on_step is not None:
        on_step(x, 1.0, lam(1.0))
    return x, NewtonReport(iterations=iterations, steps=steps, cuts=cuts, residual=residual)


def _predict(pr: MixedProblem, x, t: float, t_new: float, load, last):
    """The state at ``t_new`` extrapolated linearly from the last two accepted ones, or None (no valid extrapolation).

    With contact, the rigid-increment predictor leaves the bodies where
    they were while the parts move into them: Newton's first iteration
    then presses far too many points and sheds them one layer per
    iteration. The secant through the last two states starts it with the
    contact nearly where it ends.
    """
    if last is None or last[1] >= t:
        return None
    x0, t0 = last
    trial = x + (t_new - t) / (t - t0) * (x - x0)
    return trial if pr.material(trial, load, tangent=False, extras=False)["valid"] else None


#: The penetration the contact's multiplier updates aim at, as a fraction of the smallest element size.
PENETRATION = 1e-4
#: Multiplier updates at most.
AUGMENTATIONS = 8


def _augment(pr: MixedProblem, x, load, length_scale, tol, max_iterations, progress):
    """Update the contact's multipliers and solve again until the penetration is below :data:`PENETRATION` h.

    Returns the state and the Newton iterations spent. An update whose
    solve fails is undone: the state before it stands (its penetration, a
    penalty's, is then in the contact figures).
    """
    contact = pr.contact
    goal = PENETRATION * float(pr.section_mesh.sizes.min())
    iterations = 0
    for k in range(AUGMENTATIONS):
        pen = contact.penetration(x)
        if pen <= goal:
            break
        before = contact.lam
        contact.update(x)
        ok, its, _, trial = _newton(pr, x, load, np.zeros_like(x), pr.free, length_scale, tol, max_iterations)
        iterations += its
        if not ok:
            contact.lam = before
            break
        x = trial
        if progress is not None:
            progress(f"reference: contact update {k + 1}: penetration {pen:.3g} -> {contact.penetration(x):.3g}, "
                     f"{its} Newton iterations")
    return x, iterations


def continue_mixed(problem: MixedProblem, x: np.ndarray, load, *, length_scale: float, tol: float = 1e-8,
                   max_iterations: int = 25) -> tuple[np.ndarray, int]:
    """Newton from a solved state ``x`` to the solution at a nearby ``load``, the support where ``x`` has it.

    Parameters
    ----------
    problem : MixedProblem
    x : (n_u + n_p,) float64 ndarray
        A solved state (its Dirichlet values are kept).
    load
        The new load parameter (as :func:`solve_mixed`'s).
    length_scale, tol, max_iterations
        As :func:`solve_mixed`'s.

    Returns
    -------
    x : (n_u + n_p,) float64 ndarray
    iterations : int

    Raises
    ------
    ConvergenceError
        If Newton does not converge from ``x``.
    """
    ok, its, _, out = _newton(problem, x, load, np.zeros_like(x), problem.free, length_scale, tol, max_iterations)
    if not ok:
        raise ConvergenceError("reference: Newton did not converge at a new axial stretch of a growing extruded body; "
                               "the growth is too severe for this section, or refine the mesh")
    return out, its


def _newton(pr: MixedProblem, x, load, lift, free, length_scale, tol, max_iterations):
    """Newton iterations of one load step; returns (converged, iterations, residual norm, x)."""
    from scipy.sparse.linalg import spsolve

    n_u = pr.n_u
    mat = pr.material(x, load, extras=False)
    if not mat["valid"]:
        return False, 0, math.inf, x
    r = pr.residual(x, load, mat)
    norm = float(np.linalg.norm(r[free]))
    first = bool(lift.any())
    for it in range(1, max_iterations + 1):
        K = pr.tangent(mat, x)
        dx = np.zeros_like(x)
        if first:
            dx += lift
            rhs = -(r + K @ lift)
        else:
            rhs = -r
        Kf = K[free][:, free]
        with np.errstate(all="ignore"):
            dx[free] = spsolve(Kf.tocsc(), rhs[free])
        if not np.all(np.isfinite(dx)):
            return False, it, norm, x
        small = (np.abs(dx[:n_u]).max() <= tol * length_scale
                 and np.abs(dx[n_u:]).max(initial=0.0) <= tol * pr.mu)
        # Backtracking line search: elements must stay valid; after the first
        # iteration (which imposes the new support) the residual must not grow.
        alpha = 1.0
        for _ in range(6):
            cand = x + alpha * dx
            with np.errstate(all="ignore"):
                mat_c = pr.material(cand, load, extras=False)
            if mat_c["valid"]:
                r_c = pr.residual(cand, load, mat_c)
                norm_c = float(np.linalg.norm(r_c[free]))
                if first or norm_c <= norm or small:
                    break
            if first:
                return False, it, norm, x
            alpha *= 0.5
        else:
            return False, it, norm, x
        x, mat, r, norm = cand, mat_c, r_c, norm_c
        if first:
            first = False
            continue
        if small and alpha == 1.0:
            return True, it, norm, x
    return False, max_iterations, norm, x
