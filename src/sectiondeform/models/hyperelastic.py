"""The section's mechanics on a coarse mesh: nearly incompressible neo-Hookean, generalised plane strain.

Physics (the same as the fine reference): compressible neo-Hookean with
bulk/shear ``options.bulk_to_shear`` (default 1000), generalised plane
strain with the out-of-plane stretch ``lz = 1 / r`` of the area law (a
volume-preserving section stretched along its length shrinks in area by
``r``), the lower curve bonded to the target by normalised arc length, the
rest of the contour traction free.

Prepare (once per section, :class:`HyperelasticPrepared`):

* a coarse body-fitted P2 triangle mesh with about
  ``options.elements_through_thickness`` (default
  :data:`DEFAULT_THROUGH_THICKNESS`) elements across the mean thickness T
  (:func:`~sectiondeform.fem.mesh.coarse_mesh`), every contour corner a node;
* Taylor-Hood elements (P2 displacement, P1 pressure), which do not lock;
* the sparse pattern, the tangent at the undeformed state, factorised;
* the upper points located on the coarse boundary edges
  (:func:`~sectiondeform.fem.mapping.boundary_weights`).

Place (once per target): the coarse lower nodes go to the target at their
arc-length fractions; Newton follows the path from the ``start`` state given
(a warm start: the :attr:`~.base.Placement.state` of an earlier placement)
or, without one, from the undeformed section moved rigidly onto the target,
whose tangent is the prepared one rotated, with a linear predictor,
modified-Newton corrections with the factorisation at hand, full Newton
when those stall, a line search and automatic load steps. The upper points
are read off the solved field; a small normal offset (reported in
``info["area_correction"]``, relative to T) then makes the area law exact.

:meth:`HyperelasticPrepared.preview` is the drag preview: one linear step
from the ``start`` state (or the rigidly moved undeformed one) with a
factorisation that does not depend on the new target, as one dense
matrix-vector product.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..checks import positive
from ..fem.assembly import MixedNeoHooke, Pattern
from ..fem.elements import geometry
from ..fem.mapping import boundary_weights, correct_area, interpolation_matrix, rigid_fit
from ..fem.mesh import coarse_mesh
from ..fem.newton import NewtonSolver, State
from ..fem.rubber import MixedRubber
from ..laws import Law
from ..materials import NeoHookean
from ..section import Section
from .base import FinalQuality, Info, MeshData, MeshQuality, Model, ModelOptions, Placement, Prepared

__all__ = [
    "HyperelasticModel", "HyperelasticPrepared", "HyperelasticOptions", "HyperelasticInfo", "PreviewInfo", "MODEL",
    "DEFAULT_THROUGH_THICKNESS", "DEFAULT_BULK_TO_SHEAR",
]

DEFAULT_THROUGH_THICKNESS = 4.0
DEFAULT_BULK_TO_SHEAR = 1000.0
DEFAULT_TOLERANCE = 1e-7
CORRECTION_WARNING = 0.02




@dataclass(frozen=True)
class HyperelasticOptions(ModelOptions):
    """Options of the hyperelastic model.

    Attributes
    ----------
    elements_through_thickness : float
        Elements across the mean thickness T, > 0 and at most 64.
    bulk_to_shear : float
        Bulk over shear modulus, > 0 and at most 1e9.
    newton_tolerance : float
        Newton tolerance on the position increment, relative to T, in (0, 0.1].
    """

    elements_through_thickness: float = DEFAULT_THROUGH_THICKNESS
    bulk_to_shear: float = DEFAULT_BULK_TO_SHEAR
    newton_tolerance: float = DEFAULT_TOLERANCE

    def __post_init__(self):
        for key, high in (("elements_through_thickness", 64.0), ("bulk_to_shear", 1e9), ("newton_tolerance", 0.1)):
            object.__setattr__(self, key, positive(getattr(self, key), f"options.{key}", high=high))


@dataclass(frozen=True)
class HyperelasticInfo(Info):
    """Figures of one hyperelastic solve.

    Attributes
    ----------
    newton_full, newton_modified, load_steps : int
        Iterations of each kind and load steps taken.
    factorisations, assemblies : int
        Work done by this solve.
    warm_start : bool
        Whether the solve started from a given state.
    area_correction : float
        Normal offset that made the area law exact, relative to T.
    out_of_plane_stretch : float
        The law's ``lz``.
    """

    newton_full: int
    newton_modified: int
    load_steps: int
    factorisations: int
    assemblies: int
    warm_start: bool
    area_correction: float
    out_of_plane_stretch: float


@dataclass(frozen=True)
class PreviewInfo(Info):
    """Figures of a drag preview: ``preview`` is always True."""

    area_correction: float
    preview: bool = True


class HyperelasticPrepared(Prepared):
    """A section meshed and factorised for the hyperelastic model.

    Parameters
    ----------
    section : Section
    through_thickness : float
        Elements across the mean thickness T (the element size is T / this).
    bulk_to_shear : float
        Bulk modulus over shear modulus.
    tol : float
        Newton tolerance on the position increment, relative to T.
    material : NeoHookean or MooneyRivlin or Yeoh, optional
        The rubber (:mod:`sectiondeform.materials`); overrides ``bulk_to_shear``.

    Attributes
    ----------
    mesh : CoarseMesh
    solver : NewtonSolver

    Notes
    -----
    Nothing here changes after ``__init__`` but a cache of the preview's
    linear map (rebuilt identically when missing): the same ``place`` or
    ``preview`` arguments give the same answer, bit for bit, whatever was
    computed before, and one object may serve several threads (the
    solver's work counters, reported in ``info``, may then mix).
    """

    def __init__(self, section: Section, through_thickness: float = DEFAULT_THROUGH_THICKNESS,
                 bulk_to_shear: float = DEFAULT_BULK_TO_SHEAR, tol: float = DEFAULT_TOLERANCE, material=None):
        self.section = section
        T = section.mesh_scale
        n_low = len(section.lower)
        mesh = coarse_mesh(section.contour, np.array([0, n_low - 1]), T / through_thickness)
        self.mesh = mesh
        geom = geometry(mesh.nodes, mesh.cells)
        if material is None or type(material) is NeoHookean:  # the closed form, else any rubber
            ratio = bulk_to_shear if material is None else material.kappa / material.shear_modulus
            self.physics = MixedNeoHooke(mesh.cells, len(mesh.nodes), geom, ratio)
        else:
            self.physics = MixedRubber(mesh.cells, len(mesh.nodes), geom, [material])
        ring = mesh.ring
        s_lower = ring.s[:n_low]
        ids, s = mesh.boundary_nodes_between(0.0, float(s_lower[-1]))
        self.lower_ids = ids
        self.lower_interp = interpolation_matrix(np.interp(s, s_lower, section.fractions), section.fractions)
        n = len(mesh.nodes)
        fixed = (2 * ids[:, None] + np.arange(2)).ravel()
        pattern = Pattern(self.physics.edofs, 2 * n + mesh.n_vertices, fixed)
        self.solver = NewtonSolver(self.physics, pattern, T, tol)
        # The upper points on the coarse boundary.
        m = len(section.upper)
        s_up = ring.s[n_low - 1 : n_low - 1 + m].copy()
        s_up[-1] = ring.perimeter
        self.upper_weights = boundary_weights(mesh, s_up, section.upper)
        # The undeformed state and its factorised tangent.
        self.z_ref = np.concatenate((mesh.nodes.ravel(), np.zeros(mesh.n_vertices)))
        fields = self.physics.fields(self.z_ref, 1.0)
        self.reference = State(self.z_ref, 1.0, self.solver.tangent(fields))
        self._preview_cache = None  # (state, _PreviewBase), replaced whole, never mutated
        self.initial_mesh = MeshData(mesh.nodes, mesh.cells, "triangle6")
        self.quality = MeshQuality(
            elements=int(len(mesh.cells)),
            element_size=float(mesh.size),
            nodes=int(n),
            unknowns=int(len(pattern.free)),
            through_thickness=float(through_thickness),
            jacobian_ratio_min=float(geom.detj_ratio.min()),
        )

    # -- helpers -----------------------------------------------------------
    def _fixed_values(self, target_nodes: np.ndarray) -> np.ndarray:
        return self.lower_interp @ target_nodes  # (k, 2)

    def _rigid_start(self, xd: np.ndarray) -> tuple[State, np.ndarray, np.ndarray]:
        nodes = self.mesh.nodes
        q, t = rigid_fit(nodes[self.lower_ids], xd)
        z = np.concatenate(((nodes @ q.T + t).ravel(), np.zeros(self.mesh.n_vertices)))
        return State(z, 1.0, self.reference.tangent.rotated(q)), q, t

    def _finish(self, target_nodes: np.ndarray, law: Law, upper: np.ndarray):
        sec = self.section
        upper[0], upper[-1] = target_nodes[-1], target_nodes[0]
        wanted = sec.orientation * law.target_area(sec.area)
        upper, offset = correct_area(target_nodes, upper, wanted)
        return upper, offset / sec.thickness

    # -- the model's interface --------------------------------------------
    def place(self, target_nodes: np.ndarray, law: Law, start: State | None = None) -> Placement:
        """Solve the section's equilibrium on ``target_nodes`` ((n, 2), units) under ``law``.

        ``start`` is the solved state of an earlier placement of this object
        (its ``Placement.state``) to follow the path from; None starts from
        the undeformed section moved rigidly onto the target. The returned
        placement's ``state`` is the solution, for the next call.

        Raises
        ------
        ConvergenceError
            If Newton fails even with small load steps.
        LawError
            If the area cannot be corrected to the law.
        """
        target_nodes = np.asarray(target_nodes, dtype=np.float64)
        lz = law.out_of_plane_stretch(self.section.area)
        xd = self._fixed_values(target_nodes)
        warm = start is not None
        start = start if warm else self._rigid_start(xd)[0]
        a0, f0 = self.solver.assemblies, self.solver.factorisations
        state = self.solver.solve(start, xd.ravel(), lz)
        n = len(self.mesh.nodes)
        x = state.z[: 2 * n].reshape(n, 2)
        upper, correction = self._finish(target_nodes, law, self.upper_weights @ x)
        quality = self._quality(state)
        info = HyperelasticInfo(
            newton_full=int(state.iterations[0]),
            newton_modified=int(state.iterations[1]),
            load_steps=int(state.iterations[2]),
            factorisations=int(self.solver.factorisations - f0),
            assemblies=int(self.solver.assemblies - a0),
            warm_start=warm,
            area_correction=float(abs(correction)),
            out_of_plane_stretch=float(lz),
        )
        warnings = ()
        if abs(correction) > CORRECTION_WARNING:
            warnings = (
                f"hyperelastic: the area correction moved the upper curve by {abs(correction):.3g} T; the coarse "
                "mesh misses this deformation's physics (refine with options.elements_through_thickness)",
            )
        return Placement(upper, MeshData(x.copy(), self.mesh.cells, "triangle6"), quality, info, warnings, state)

    def _quality(self, state: State) -> FinalQuality:
        f = state.fields if state.fields is not None else self.physics.fields(state.z, state.lz)
        det = f.det
        return FinalQuality(area_stretch_min=float(det.min()), area_stretch_max=float(det.max()))

    def preview(self, target_nodes: np.ndarray, law: Law, start: State | None = None) -> Placement:
        """Drag preview: one linear step from the ``start`` state, no new factorisation.

        The first call after a solve builds the linear map from the target to
        the upper points (one back-substitution per prescribed dof, with the
        factorisation the solve left); later calls are one dense
        matrix-vector product and the area correction. Before any solve, the
        step starts from the undeformed section moved rigidly onto the target
        (best-fit rotation; the map is the undeformed one, rotated). The
        result meets the area law exactly but is only first-order accurate in
        the change of target: call :meth:`place` when the drag ends.

        Parameters
        ----------
        target_nodes : (n, 2) float64 ndarray
            The target at the lower fractions, units.
        law : Law
        start : State, optional
            The solved state to linearise about (a ``Placement.state``).

        Returns
        -------
        Placement
            ``final_mesh`` is the base state's mesh (not updated);
            ``info.preview`` is True; ``state`` is ``start``.
        """
        target_nodes = np.asarray(target_nodes, dtype=np.float64)
        xd = self._fixed_values(target_nodes)
        cached = self._preview_cache
        if cached is not None and cached[0] is start:
            base = cached[1]
        else:
            base = self._build_preview(start)
            self._preview_cache = (start, base)
        upper0, xd0, q = base.upper, base.xd, None
        if base.rigid:  # before any solve: linearise about the rigid fit of this target
            q, t = rigid_fit(self.mesh.nodes[self.lower_ids], xd)
            upper0, xd0 = upper0 @ q.T + t, xd0 @ q.T + t
        dxd = xd - xd0
        if q is not None:
            dxd = dxd @ q  # back to the unrotated frame
        dlnl = math.log(law.out_of_plane_stretch(self.section.area)) - math.log(base.lz)
        du = (base.h_d @ dxd.ravel() + base.h_lz * dlnl).reshape(-1, 2)
        if q is not None:
            du = du @ q.T
        upper, correction = self._finish(target_nodes, law, upper0 + du)
        final = MeshData(base.nodes, self.mesh.cells, "triangle6")
        return Placement(upper, final, FinalQuality(), PreviewInfo(area_correction=float(abs(correction))), (), start)

    def _build_preview(self, start: State | None) -> _PreviewBase:
        solver, pat = self.solver, self.solver.pattern
        n = len(self.mesh.nodes)
        state = start if start is not None else self.reference
        tan = state.tangent
        k = len(pat.fixed)
        # Sensitivity of the free dofs to each fixed dof and to ln lz: -K_ff^-1 [K_fd, dR/dln lz].
        rhs = np.column_stack([tan.kfd_dot(e) for e in np.eye(k)] + [solver.dres_dlnlz])
        sens = -(tan.solve(rhs) if tan.rotation is None else np.column_stack([tan.solve(c) for c in rhs.T]))
        wx = sp.kron(self.upper_weights, sp.eye(2), format="csr")  # (2m, 2N) on position dofs
        free_x = pat.free[solver.free_x]
        resp = wx[:, free_x] @ sens[: len(free_x)]
        resp[:, :-1] += wx[:, pat.fixed].toarray()
        x = state.z[: 2 * n].reshape(n, 2)
        return _PreviewBase(
            upper=self.upper_weights @ x, xd=state.z[pat.fixed].reshape(-1, 2), lz=state.lz,
            h_d=np.ascontiguousarray(resp[:, :-1]), h_lz=resp[:, -1].copy(), nodes=x.copy(),
            rigid=start is None,
        )


@dataclass(frozen=True, eq=False)
class _PreviewBase:
    """The linear map of a preview: upper points ``upper + h_d (xd - xd0) + h_lz d(ln lz)``."""

    upper: np.ndarray  # (m, 2) upper points at the base state
    xd: np.ndarray  # (k, 2) prescribed positions at the base state
    lz: float
    h_d: np.ndarray  # (2m, 2k)
    h_lz: np.ndarray  # (2m,)
    nodes: np.ndarray  # (N, 2) base state's node positions
    rigid: bool  # the base is the undeformed state, to be moved rigidly onto each target


class HyperelasticModel(Model):
    """The hyperelastic model: ``options.elements_through_thickness``, ``options.bulk_to_shear``."""

    name = "hyperelastic"
    options_type = HyperelasticOptions

    def prepare(self, section: Section, options: HyperelasticOptions | None = None) -> HyperelasticPrepared:
        options = options if options is not None else HyperelasticOptions()
        return HyperelasticPrepared(
            section,
            through_thickness=options.elements_through_thickness,
            bulk_to_shear=options.bulk_to_shear,
            tol=options.newton_tolerance,
        )


MODEL = HyperelasticModel()
