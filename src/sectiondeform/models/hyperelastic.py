"""The bodies' mechanics on a coarse mesh: nearly incompressible rubber, all bodies in one solve.

Physics (the same as the fine reference): each body's rubber (its
``material``: neo-Hookean in closed form, Mooney–Rivlin or Yeoh through
:class:`~sectiondeform.fem.rubber.MixedRubber`; neo-Hookean with bulk/shear
``options.bulk_to_shear`` by default), generalised plane strain with each
body's out-of-plane stretch ``lz = 1 / r`` of its area law (a
volume-preserving section stretched along its length shrinks in area by
``r``), or an axisymmetric solve for a body of revolution
(:mod:`.hyperelastic_revolution`); the lower nodes resting on the support
bonded to the target by their arc-length fraction on the support, the rest
of every contour traction free, bonded bodies sharing their nodes.

Prepare (once, :class:`HyperelasticPrepared`):

* one P2 mesh of all bodies (:func:`~sectiondeform.fem.union_mesh.union_mesh`)
  from the bodies' contours as the :class:`~sectiondeform.stack.Stack`
  prepares them (on a shared piece both contours have exactly the same
  points), so a shared piece has shared nodes; every cell carries its body;
  each body's element size is its own thickness over
  ``options.elements_through_thickness`` (a shared piece takes the smaller
  of its two bodies');
* Taylor-Hood elements (P2 displacement, P1 pressure), which do not lock;
  the displacement is shared across the interfaces, the pressure is one P1
  field per body (each body has its own unknown at a vertex it shares,
  :attr:`~sectiondeform.fem.union_mesh.UnionMesh.pressure_cells`), so it
  jumps across an interface between bodies of different stiffness as the
  exact pressure does;
* the sparse pattern, the tangent at the undeformed state, factorised.

Place (once per target): Newton from the undeformed bodies moved rigidly
onto the target (:class:`~sectiondeform.fem.newton.NewtonSolver`, the
stretches following the same path as the target), or from the state of an
earlier result solved under the same laws (a warm start, ``start=``; the
state is carried by the result, never kept here). The drag preview is that
path's linear predictor alone, with the factorisation at hand. The laws are
given per call: the mesh, pattern and undeformed tangent serve any laws
(every cell's stretch is 1 at the undeformed state). Every contour point has
one image (a point shared by two bodies is one point of the mesh's graph);
the points on the support go exactly to the target at their fractions.

**The exact law per body.** From the support up (the layout's order), each
body's upper points are offset along their normals by one distance that
makes its area exact (a quadratic solved in closed form), except the
points that belong to a body already corrected (its foundations, or a body
touching it at a point) and the points on the support. The points a body
shares with the bodies resting on it move with it, and those bodies' lower
curves are these very points: the interfaces stay bonded exactly, and each
resting body then meets its own law by its own upper points. A body
covered all over by others still meets its law. The offset, relative to
the body's thickness, is ``info.area_correction``.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from ..checks import positive
from ..errors import CaseError, ConvergenceError, LawError, MeshError
from ..extrusion import free_axial_stretch
from ..fem.diagnosis import physical_reason
from ..fem.elements import geometry
from ..fem.mapping import offset_to_law, rigid_fit
from ..fem.neohooke import Fields, MixedNeoHooke, Pattern
from ..fem.newton import NewtonSolver, State
from ..fem.rubber import MixedRubber
from ..fem.union_mesh import union_mesh
from ..limits import MAX_FE_UNKNOWNS, bounded
from ..materials import NeoHookean, material_from_json
from ..materials.models import gradient_3d
from ..stack import SUPPORT, Stack, renamed
from .base import FinalQuality, Info, MeshData, MeshQuality, Model, ModelOptions, Placed, Placement, Prepared
from .hyperelastic_revolution import RevolutionPhysics

__all__ = [
    "HyperelasticModel", "HyperelasticPrepared", "HyperelasticState", "HyperelasticOptions", "HyperelasticInfo",
    "PreviewInfo", "MODEL", "DEFAULT_THROUGH_THICKNESS", "DEFAULT_BULK_TO_SHEAR",
]

DEFAULT_THROUGH_THICKNESS = 4.0
DEFAULT_BULK_TO_SHEAR = 1000.0
DEFAULT_TOLERANCE = 1e-7
CONTACT_REFINEMENTS = (1, 2)
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
    contact_refinement : float or None
        With rigid parts, the element size is divided by this where they
        will press (:func:`~sectiondeform.models.hyperelastic_contact.contact_zones`):
        1 (the same mesh everywhere) or 2; None (the default) chooses
        (:func:`~sectiondeform.models.hyperelastic_contact.auto_refinement`).
    """

    elements_through_thickness: float = DEFAULT_THROUGH_THICKNESS
    bulk_to_shear: float = DEFAULT_BULK_TO_SHEAR
    newton_tolerance: float = DEFAULT_TOLERANCE
    contact_refinement: float | None = None

    def __post_init__(self):
        for key, high in (("elements_through_thickness", 64.0), ("bulk_to_shear", 1e9), ("newton_tolerance", 0.1)):
            object.__setattr__(self, key, positive(getattr(self, key), f"options.{key}", high=high))
        if self.contact_refinement is not None and self.contact_refinement not in CONTACT_REFINEMENTS:
            raise CaseError("options.contact_refinement", f"{self.contact_refinement!r} is not 1 or 2 (the element size is "
                            "halved where rigid parts press with 2, not with 1)")


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


@dataclass(frozen=True, eq=False)
class _GrownFields(Fields):
    """:class:`~sectiondeform.fem.neohooke.Fields` with each cell's volumetric growth ``c`` ``(E, 1)``."""

    c: np.ndarray = None


class _Stretches(MixedNeoHooke):
    """The mixed neo-Hookean problem with one out-of-plane stretch and one volumetric growth per body.

    The solver's scalar stretch ``s`` is a path parameter: cell ``e`` has
    ``lz_e = exp(ln s * ln lz_b(e))`` and ``c_e = exp(ln s * ln c_b(e))``,
    so ``s = 1`` is the undeformed state and ``s = e`` every body's own
    stretch and growth. A growth ``c`` (an extruded body growing
    isotropically, ``F = Fe c^(1/3)``) makes the energy per unit initial
    volume ``c (a I1 - 3) / 2 + p (J - c) - c p² / (2 kappa)`` (times the
    shear modulus), as for bodies of revolution
    (:mod:`~sectiondeform.fem.axisymmetric`): the isochoric part does not
    see an isotropic growth.
    """

    def __init__(self, cells, n_nodes, geom, kappa, mu, ln_stretch, pressure_cells=None, ln_growth=None):
        super().__init__(cells, n_nodes, geom, kappa, mu, pressure_cells)
        self.ln_stretch = np.asarray(ln_stretch, dtype=np.float64)[:, None]  # (E, 1)
        self.ln_growth = np.zeros_like(self.ln_stretch) if ln_growth is None else np.asarray(ln_growth, np.float64)[:, None]

    def fields(self, z, lz):
        f = super().fields(z, np.exp(math.log(lz) * self.ln_stretch))
        if f is None:
            return None
        return _GrownFields(f.F, f.det, f.J, f.i1, f.p, np.exp(math.log(lz) * self.ln_growth))

    def _shear(self, f):
        return super()._shear(f) * f.c

    def _pressure_residual(self, f):
        return (f.J - f.c - f.c * f.p / self.kappa) * self.geom.weight

    def element_matrices(self, f):
        out = super().element_matrices(f)
        out[:, 12:, 12:] *= f.c[:, :, None]
        return out

    def axial_force(self, f, body: np.ndarray, n_bodies: int) -> np.ndarray:
        """Each body's axial force ``∫ P_zz dA`` (per unit shear modulus x length², in the moduli's units), ``(B,)``.

        ``P_zz = c mu a (lz - I1 / (3 lz)) + p det F``, the nominal stress
        along the extrusion; zero for a free extrusion.
        """
        lz = np.sqrt(np.maximum(f.i1 - np.einsum("eqij,eqij->eq", f.F, f.F), 0.0))
        pzz = self._shear(f) * (lz - f.i1 / (3.0 * lz)) + f.p * f.det
        return np.bincount(body, weights=(pzz * self.geom.weight).sum(axis=1), minlength=n_bodies)


class _GrownRubber(MixedRubber):
    """:class:`~sectiondeform.fem.rubber.MixedRubber` with one volumetric growth per body, as :class:`_Stretches`.

    A growth ``c`` (``F = Fe c^(1/3)``) leaves the isochoric part of any
    rubber unchanged (``Fe`` and ``F`` have the same isochoric part), so the
    energy per unit initial volume is ``c W_iso(F3) + p (J - c) - c p² / (2 kappa)``:
    the isochoric stress and tangent times ``c``, the constraint ``J - c - c p / kappa``.
    """

    def __init__(self, cells, n_nodes, geom, materials, body, ln_stretch, pressure_cells, ln_growth):
        super().__init__(cells, n_nodes, geom, materials, body, ln_stretch, pressure_cells)
        self.ln_growth = np.asarray(ln_growth, np.float64).reshape(-1, 1)

    def fields(self, z, lz):
        f = super().fields(z, lz)
        if f is None:
            return None
        return _GrownFields(f.F, f.det, f.J, f.i1, f.p, np.exp(math.log(lz) * self.ln_growth))

    def _iso_scale(self, f):
        return f.c

    def _constraint(self, f):
        return (f.J - f.c - f.c * f.p / self._kappa_e) * self.geom.weight

    def element_matrices(self, f):
        out = super().element_matrices(f)
        out[:, 12:, 12:] *= f.c[:, :, None]
        return out

    def axial_force(self, f, body: np.ndarray, n_bodies: int) -> np.ndarray:
        """Each body's axial force ``∫ P_zz dA``, ``(B,)``: ``P_zz = c P_iso,zz(F3) + p det F``."""
        pzz = f.p * f.det
        lz = f.J / f.det
        for mat, idx in self._groups:
            pzz[idx] += f.c[idx] * mat.first_piola(gradient_3d(f.F[idx], lz[idx]), volumetric=False)[..., 2, 2]
        return np.bincount(body, weights=(pzz * self.geom.weight).sum(axis=1), minlength=n_bodies)


@dataclass(frozen=True, eq=False)
class _BodyMesh:
    """What the result reads of a prepared body: its part of the mesh and figures."""

    initial_mesh: MeshData
    quality: MeshQuality
    cells: np.ndarray  # (e_b, 6) in the body's own node numbering
    used: np.ndarray  # (n_b,) global node of each body node
    elements: np.ndarray  # (e_b,) global cell indices


@dataclass(frozen=True, eq=False)
class HyperelasticState:
    """A solved state of the whole problem and the out-of-plane stretches (one per body) it was solved for.

    Also what the bodies' stresses need beyond their meshes
    (:func:`~sectiondeform.strain_fields.result_mechanics`): ``materials``,
    each body's rubber; ``pressure_dofs``, per body an ``(M_b, 3)`` int
    array, the entries of ``state.z`` holding the pressure unknown at its
    elements' corners (in the order of its final mesh's cells; the body's
    own unknowns, so at a shared vertex each body reads its own pressure); ``growth``,
    True when ``stretches`` are volumetric growths (bodies of revolution);
    ``growths``, each extruded body's growth (empty: none); ``guess``, the
    stretches the laws start from (:meth:`HyperelasticPrepared.stretches_of`)
    when the solve found others (a growing body's axial stretch).
    """

    state: State
    stretches: tuple
    materials: tuple = ()
    pressure_dofs: tuple = ()
    growth: bool = False
    growths: tuple = ()
    guess: tuple = ()
    contact: object = None  # a ContactState with rigid parts (models/hyperelastic_contact.py)


class HyperelasticPrepared(Prepared):
    """Every body of a problem meshed as one and factorised for the hyperelastic model.

    Parameters
    ----------
    stack : Stack
        The bodies' sections (with the resting nodes in their foundations'
        upper polylines) and node sources.
    options : HyperelasticOptions

    Raises
    ------
    CaseError
        For a body whose material is invalid.
    MeshError
        If the bodies cannot be meshed.
    """

    def __init__(self, stack: Stack, options: HyperelasticOptions):
        a = stack.problem
        self.problem = a
        self.stack = stack
        self.layout = stack.layout
        bodies = stack.bodies
        self.sections = [b.section for b in bodies]
        materials = []
        for i, body in enumerate(a.bodies):
            materials.append(material_from_json(body.material_data, f"bodies[{i}].material", default_bulk_to_shear=options.bulk_to_shear))
        self.materials = tuple(materials)
        thickness = min(s.mesh_scale for s in self.sections)
        self.sizes = np.array([s.mesh_scale for s in self.sections]) / options.elements_through_thickness
        rings = [s.contour for s in self.sections]
        fixed = [np.array([0, len(s.lower) - 1]) for s in self.sections]
        fine, ratio = None, 1
        if a.rigid:  # finer where the parts will press (hyperelastic_contact.py)
            from .hyperelastic_contact import auto_refinement, contact_zones

            ratio = options.contact_refinement or auto_refinement(rings, self.sizes, a.rigid)
            if ratio > 1:
                fine = contact_zones(rings, self.sizes, a.rigid, 1e-6 * a.size)
        mesh = union_mesh(rings, fixed, self.sizes, self.layout.tolerance, [s.holes for s in self.sections], fine,
                          int(ratio))
        self.mesh = mesh
        n_low = [len(s.lower) for s in self.sections]
        self.lower_ids = [r[:n] for r, n in zip(mesh.rings, n_low)]
        self.upper_ids = [np.concatenate(([r[n - 1]], r[n:], [r[0]])) for r, n in zip(mesh.rings, n_low)]
        # The support's points: each vertex's fraction, and the chains bonded to the target.
        V = len(mesh.points)
        vfrac = np.full(V, np.nan)
        support_chains = set()
        for b, body in enumerate(bodies):
            sup = body.source == SUPPORT
            ids = self.lower_ids[b]
            new = sup & np.isnan(vfrac[ids])
            vfrac[ids[new]] = body.where[new]
            for i in np.flatnonzero(sup[:-1] & sup[1:]):
                if ids[i] != ids[i + 1]:
                    support_chains.add(mesh.chain_of(int(ids[i]), int(ids[i + 1])))
        self.support_vertices = np.flatnonzero(~np.isnan(vfrac))
        self.support_fractions = vfrac[self.support_vertices]
        node_ids, node_frac = [], []
        for c in sorted(support_chains):
            ch = mesh.chains[c]
            f = vfrac[ch.vertices]
            node_ids += [ch.nodes, ch.mids]
            node_frac += [np.interp(ch.node_s, ch.s, f), np.interp(0.5 * (ch.node_s[:-1] + ch.node_s[1:]), ch.s, f)]
        ids, first = np.unique(np.concatenate(node_ids), return_index=True)
        self.fixed_ids = ids
        self.fixed_fractions = np.concatenate(node_frac)[first]
        # Physics: per-cell moduli and stretches.
        cells = mesh.cells
        geom = geometry(mesh.nodes, cells)
        mu = np.array([m.shear_modulus for m in materials])[mesh.body]
        kappa = np.array([m.kappa for m in materials])[mesh.body]
        self.physics = self._physics(cells, geom, kappa, mu)
        n = len(mesh.nodes)
        axis_dofs, self.axis_values, self.axis_vertices = self._on_axis(mesh, ids)
        fixed = np.concatenate(((2 * ids[:, None] + np.arange(2)).ravel(), axis_dofs))
        self.boundary = None
        if a.rigid:  # the free boundary the parts press on: its pressure couples neighbouring edges' nodes
            from .hyperelastic_contact import contact_boundary

            self.boundary = contact_boundary(self)
        pattern = Pattern(self.physics.edofs, 2 * n + mesh.n_pressures, fixed,
                          coupling=None if self.boundary is None else self.boundary.pair_dofs)
        bounded(len(pattern.free), MAX_FE_UNKNOWNS, "unknowns",  # each factorisation grows faster than the unknowns
                "lower options.elements_through_thickness, or simplify the bodies' thin or small features", MeshError, "mesh")
        self.solver = NewtonSolver(self.physics, pattern, thickness, options.newton_tolerance)
        self.solver.dres_dlnlz = self._dres_dlns(self.physics)
        z_ref = np.concatenate((mesh.nodes.ravel(), np.zeros(mesh.n_pressures)))
        at_rest = self.physics.fields(z_ref, 1.0)
        if at_rest is None:  # a curved element folded over at rest: no state can start from it
            raise MeshError("the coarse mesh has an element turned inside out before any deformation (a feature too "
                            "small or too curved for it); raise options.elements_through_thickness or simplify the "
                            "bodies' small features")
        self.reference = State(z_ref, 1.0, self.solver.tangent(at_rest))
        self.bodies = tuple(self._body_mesh(b, geom, len(pattern.free), options.elements_through_thickness)
                                 for b in range(len(a.bodies)))
        self.pressure_dofs = tuple(2 * n + mesh.pressure_cells[bm.elements] for bm in self.bodies)
        self.contact = None
        if a.rigid:  # rigid parts: the contact terms and the loading (hyperelastic_contact.py)
            from .hyperelastic_contact import Contact

            self.contact = Contact(self)

    plane = True
    """Plane sections: ``stretches`` are the bodies' out-of-plane stretches (else growths, reported as 1)."""

    def _on_axis(self, mesh, support_ids: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The dofs held on a revolution axis, their values and the contour vertices there: none for a plane section."""
        return np.zeros(0, np.int64), np.zeros(0), np.zeros(0, np.int64)

    def _data(self, xd: np.ndarray) -> np.ndarray:
        """The prescribed dofs' values: the support nodes at ``xd`` ``(k, 2)``, then the nodes held on the axis."""
        return np.concatenate((xd.ravel(), self.axis_values))

    def _physics(self, cells, geom, kappa, mu):
        """The mixed problem on the union mesh, per cell its body's moduli and out-of-plane stretch; sets ``stretches``."""
        laws = tuple(body.law for body in self.problem.bodies)
        self.stretches = self.stretches_of(laws)
        ln_stretch = np.log(self.stretches[: len(laws)])[self.mesh.body]
        ln_growth = np.log(self.growths_of(laws))[self.mesh.body]
        if all(type(m) is NeoHookean for m in self.materials):  # the closed form, else any rubber
            return _Stretches(cells, len(self.mesh.nodes), geom, kappa, mu, ln_stretch, self.mesh.pressure_cells, ln_growth)
        if any(g != 1.0 for g in self.growths_of(laws)):
            return _GrownRubber(cells, len(self.mesh.nodes), geom, self.materials, self.mesh.body, ln_stretch,
                                self.mesh.pressure_cells, ln_growth)
        return MixedRubber(cells, len(self.mesh.nodes), geom, self.materials, self.mesh.body, ln_stretch,
                           self.mesh.pressure_cells)

    def _physics_for(self, stretches: tuple):
        """A copy of the prepared physics under other per-body ``stretches`` and growths (same mesh and moduli).

        ``stretches`` are the bodies' out-of-plane stretches, followed, for
        growing extruded bodies, by their growths (:meth:`stretches_of`).
        """
        physics = copy.copy(self.physics)
        n = len(self.sections)
        physics.ln_stretch = np.log(np.asarray(stretches[:n]))[self.mesh.body][:, None]
        if len(stretches) > n:
            physics.ln_growth = np.log(np.asarray(stretches[n:]))[self.mesh.body][:, None]
        return physics

    def _law_offset(self, b: int, ring: np.ndarray, movable: np.ndarray, law, wanted: float) -> tuple[np.ndarray, float]:
        """Body ``b``'s contour ``ring`` with its movable points offset to meet ``law`` (:func:`~sectiondeform.fem.mapping.offset_to_law`)."""
        return offset_to_law(ring, movable, law, wanted)

    @staticmethod
    def growths_of(laws) -> tuple:
        """Each body's volumetric growth under ``laws``: an extruded body's growth, else 1."""
        return tuple(float(law.growth) if law.growth is not None and law.measure == "area" else 1.0 for law in laws)

    def _body_mesh(self, b: int, geom, unknowns: int, through: float) -> _BodyMesh:
        mesh = self.mesh
        elements = np.flatnonzero(mesh.body == b)
        used, local = np.unique(mesh.cells[elements], return_inverse=True)
        cells = local.reshape(-1, 6).astype(np.int64)
        quality = MeshQuality(elements=int(len(elements)), element_size=float(self.sizes[b]), nodes=int(len(used)),
                              unknowns=int(unknowns), through_thickness=float(through),
                              jacobian_ratio_min=float(geom.detj_ratio[elements].min()))
        return _BodyMesh(MeshData(mesh.nodes[used], cells, "triangle6"), quality, cells, used, elements)

    def stretches_of(self, laws) -> tuple:
        """Each body's out-of-plane stretch ``lz`` under ``laws`` (one :class:`~sectiondeform.laws.Law` per body).

        A growing extruded body starts from a free body's axial stretch
        (its growth's cube root); :meth:`place` then solves the stretch that
        leaves no axial force. When a body grows, the growths follow the
        stretches in the tuple (what the physics is solved for).
        """
        out = tuple(float(law.out_of_plane_stretch(sec.area)) for law, sec in zip(laws, self.sections))
        growths = self.growths_of(laws)
        return out + growths if any(g != 1.0 for g in growths) else out

    def _problem(self, stretches: tuple) -> tuple[_Stretches, NewtonSolver]:
        """The physics and solver for other stretches than the prepared ones (same mesh, pattern, reference tangent).

        At the undeformed state (path parameter 1) every cell's stretch is 1
        whatever the laws, so the prepared reference tangent serves all.
        """
        if stretches == self.stretches:
            return self.physics, self.solver
        physics = self._physics_for(stretches)
        solver = copy.copy(self.solver)
        solver.physics = physics
        solver.dres_dlnlz = self._dres_dlns(physics)
        return physics, solver

    def _dres_dlns(self, physics: _Stretches) -> np.ndarray:
        """The derivative d R_free / d ln s at J = 1: each cell's pressure rows times its body's ln lz."""
        mesh, pattern = self.mesh, self.solver.pattern
        ln = physics.ln_stretch - physics.ln_growth if hasattr(physics, "ln_growth") else physics.ln_stretch  # R_p: J - c
        wm = (physics._wM * ln[:, :, None]).sum(axis=1)
        full = np.zeros(pattern.n_dofs)
        full[2 * len(mesh.nodes) :] = np.bincount(mesh.pressure_cells.ravel(), weights=wm.ravel(), minlength=mesh.n_pressures)
        return full[pattern.free]

    def _base(self, xd: np.ndarray, start: HyperelasticState | None, stretches: tuple, drawn: bool = False) -> State:
        """The state a solve or a preview starts from.

        ``start``'s, if it was solved under the same stretches; else (no
        start, or other laws: no path to follow) the undeformed bodies
        moved rigidly onto ``xd``, or left where they are drawn if
        ``drawn`` (rigid parts: the support moves with the parts, from
        where it is drawn, as one loading).
        """
        if start is not None:
            if not isinstance(start, HyperelasticState) or start.state.z.shape != self.reference.z.shape:
                raise CaseError("start", "give an earlier result of this problem's deformer (its state is of another problem or model)")
            if (start.guess or start.stretches) == stretches:
                return start.state
        mesh = self.mesh
        if drawn:
            return self.reference
        q, t = self._start_motion(mesh.nodes[self.fixed_ids], xd)
        z0 = np.concatenate(((mesh.nodes @ q.T + t).ravel(), np.zeros(mesh.n_pressures)))
        return State(z0, 1.0, self.reference.tangent.rotated(q))

    def _start_motion(self, points: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The rigid motion ``(Q, t)`` that best takes the support nodes ``points`` onto ``targets``."""
        return rigid_fit(points, targets)

    def place(self, curve, laws: tuple, start: HyperelasticState | None = None, travels=None) -> Placed:
        """Solve the bodies on the target ``curve``; per body its lower nodes, upper points and placement.

        Parameters
        ----------
        curve : Curve
            The target, A' to B', units.
        laws : tuple of Law
            Each body's law (the prepared mesh and tangent serve any laws).
        start : HyperelasticState, optional
            The solved state of an earlier result of this problem (its
            ``Result.state``) to follow the path from (a warm start);
            None, or a state solved under other laws, starts from the
            undeformed bodies moved rigidly onto the target. The answer
            depends on the arguments alone.
        travels : sequence of (float, float), optional
            Each rigid part's travel, units, if not the problem's: the part
            starts where the problem starts it and ends this far from there.

        Returns
        -------
        lowers : list of (n_b, 2) float64 ndarray
            Each body's deformed lower nodes (its section's), units.
        images : list of (m_b, 2) float64 ndarray
            Each body's deformed upper points (its section's, with the
            resting nodes), B' to A', units.
        placements : list of Placement
        state : HyperelasticState
            The solution, for the next warm start.

        Raises
        ------
        ConvergenceError
            If Newton fails even with small load steps.
        LawError
            Naming the body whose area cannot be corrected.
        MeshError
            Naming the body with an inverted element.
        CaseError
            If ``start`` is not a state of this problem.
        """
        xd = curve.at_fractions(self.fixed_fractions)
        guess = self.stretches_of(laws)
        if self.contact is not None and start is not None and start.contact is not None and \
                self.contact.end_shifts(start.contact, travels).any():
            start = None  # the parts moved: loaded again from where they start (a result independent of the path)
        base = self._base(xd, start, guess, drawn=self.contact is not None)
        stretches = start.stretches if start is not None and base is start.state else guess
        physics, solver = self._problem(stretches)
        a0, f0 = solver.assemblies, solver.factorisations
        contact = None
        try:
            if self.contact is not None:  # rigid parts: loaded with the support, the contact carried by the state
                warm = start.contact if start is not None and base is start.state else None
                state, contact = self.contact.solve(physics, solver, base, self._data(xd), math.e, warm, travels)
            else:
                state = solver.solve(base, self._data(xd), math.e)
        except ConvergenceError as exc:
            raise self._diagnosed(exc, physics) from None
        f = state.fields if state.fields is not None else physics.fields(state.z, state.lz)
        if self.plane and len(stretches) > len(laws):  # growing extruded bodies: the axial stretch with no axial force
            stretches, state, f, physics, solver = self._free_extrusion(stretches, state, f, physics, solver, xd)

        def info(b, correction):
            return HyperelasticInfo(
                newton_full=int(state.iterations[0]), newton_modified=int(state.iterations[1]),
                load_steps=int(state.iterations[2]), factorisations=int(solver.factorisations - f0),
                assemblies=int(solver.assemblies - a0), warm_start=start is not None and base is start.state,
                area_correction=float(correction), out_of_plane_stretch=float(stretches[b]) if self.plane else 1.0,
            )

        growths = tuple(stretches[len(laws):]) if self.plane else ()
        return Placed(*self._finish(curve, laws, state.z, f, info, stretches),
                      HyperelasticState(state, stretches, self.materials, self.pressure_dofs, not self.plane, growths,
                                        guess if stretches != guess else (), contact))

    def _diagnosed(self, exc: ConvergenceError, physics) -> ConvergenceError:
        """``exc``, or with the physical reason its last equilibrium shows (:func:`~sectiondeform.fem.diagnosis.physical_reason`)
        in place of its advice: a body folding onto itself or into another, across the axis, or crushed.
        """
        state = getattr(exc, "state", None)
        f = physics.fields(state.z, state.lz) if state is not None else None
        if f is None:
            return exc
        mesh = self.mesh
        n = len(mesh.nodes)
        x = state.z[: 2 * n].reshape(n, 2)
        contour = mesh.vertex_weights @ x
        labels = [self.problem.label(b) or "the body" for b in range(len(self.sections))]
        reason = physical_reason(contour, mesh.rings, x[mesh.cells[:, :3]].mean(axis=1), mesh.body, f.F, labels,
                                 self._axis_side(contour))
        if reason is None:
            return exc
        return ConvergenceError(f"{exc.stopped}; at the last equilibrium reached, {reason}",
                                "no equilibrium is near it along this path: a milder target or law, or a shorter travel")

    def _axis_side(self, points: np.ndarray) -> np.ndarray | None:
        """Distance of ``points`` from the axis, positive on the bodies' side (bodies of revolution); None for a plane section."""
        return None

    def _free_extrusion(self, stretches, state, f, physics, solver, xd):
        """Solve each growing extruded body's axial stretch so that its axial force vanishes.

        A scalar condition per body, ``∫ P_zz dA = 0``, met by
        :func:`~sectiondeform.extrusion.free_axial_stretch` (secant steps on
        ``ln lz``, each a Newton solve continued from the last); a free body
        starts at its root (the growth's cube root) and stops at once.

        Raises
        ------
        ConvergenceError
            If the axial forces do not vanish within :data:`~sectiondeform.extrusion.AXIAL_STEPS` solves.
        """
        n = len(self.sections)
        growing = np.flatnonzero(np.asarray(stretches[n:]) != 1.0)
        mu = np.array([m.shear_modulus for m in self.materials])
        scale = mu * np.array([s.area for s in self.sections])
        now = {"stretches": stretches, "state": state, "f": f, "physics": physics, "solver": solver}

        def solve(ln):
            now["stretches"] = tuple(float(v) for v in np.exp(ln)) + tuple(stretches[n:])
            now["physics"], now["solver"] = self._problem(now["stretches"])
            now["state"] = now["solver"].solve(now["state"], self._data(xd), math.e)
            st = now["state"]
            now["f"] = st.fields if st.fields is not None else now["physics"].fields(st.z, st.lz)
            return now["physics"].axial_force(now["f"], self.mesh.body, n)

        free_axial_stretch(np.log(np.asarray(stretches[:n], dtype=np.float64)),
                           physics.axial_force(f, self.mesh.body, n), solve, growing, scale,
                           self.problem.label(int(growing[0])) or "body")
        return now["stretches"], now["state"], now["f"], now["physics"], now["solver"]

    def preview(self, curve, laws: tuple, start: HyperelasticState | None = None, travels=None) -> Placed:
        """Drag preview: one linear step from ``start`` (or the undeformed bodies), no new factorisation.

        The step is the Newton predictor: one back-substitution with the
        factorisation ``start`` carries, for the change of the support's
        nodes (and, from the undeformed bodies, of the out-of-plane
        stretches), and, from a start with rigid parts, for the parts moved
        to ``travels`` (:meth:`~sectiondeform.models.hyperelastic_contact.Contact.preview`). Every body's law is then met exactly and the interfaces
        stay bonded (the same correction as :meth:`place`); the shape is
        first-order in the change of target: call :meth:`place` when the
        drag ends. Arguments and returns as :meth:`place` (the state
        returned is ``start``).
        """
        xd = curve.at_fractions(self.fixed_fractions)
        guess = self.stretches_of(laws)
        base = self._base(xd, start, guess)
        stretches = start.stretches if start is not None and base is start.state else guess
        physics, solver = self._problem(stretches)
        warm = start.contact if start is not None and base is start.state else None
        if self.contact is not None and warm is not None:
            base = self.contact.tangent_at(physics, solver, base, warm)
        z = solver.predict(base, self._data(xd), math.e)
        if self.contact is not None and warm is not None:
            z = self.contact.preview(physics, solver, base, z, warm, travels)
        f = physics.fields(z, math.e)
        if f is None:
            raise MeshError("preview: an element is inverted in the linear step; the target moved too far from the "
                            "start for a preview (deform instead)")
        return Placed(*self._finish(curve, laws, z, f, lambda b, correction: PreviewInfo(area_correction=float(correction)),
                                    stretches), start)

    def _finish(self, curve, laws: tuple, z: np.ndarray, f, info, stretches) -> tuple[list, list, list]:
        """Per body its lower nodes, upper points (each law made exact) and placement, from the solved ``z``."""
        mesh = self.mesh
        n = len(mesh.nodes)
        x = z[: 2 * n].reshape(n, 2)
        img = self.mesh.vertex_weights @ x
        img[self.support_vertices] = curve.at_fractions(self.support_fractions)
        fixed = np.zeros(len(img), bool)
        fixed[self.support_vertices] = True
        fixed[self.axis_vertices] = True  # held on the axis: the law's offset does not move them off it
        corrections = [0.0] * len(self.sections)
        targets = [None] * len(self.sections)
        for b in self.layout.order:
            sec = self.sections[b]
            ring = mesh.rings[b]
            n_low = len(sec.lower)
            movable = np.zeros(len(ring), bool)
            movable[n_low:] = ~fixed[ring[n_low:]]
            law = laws[b]
            initial = self.stack.initial_quantity(b, law)
            wanted = law.target(initial)
            if self.plane and law.growth is not None and law.measure == "area":  # the volume grown over the axial stretch
                wanted = targets[b] = law.area_for_axial_stretch(initial, stretches[b])
            # The holes are not moved: the outer contour takes the holes' quantity on top of the body's.
            wanted -= sum(law.quantity(img[h]) for h in mesh.holes[b]) if mesh.holes else 0.0
            try:
                new, k = self._law_offset(b, img[ring], movable, law, wanted)
            except LawError as exc:
                raise renamed(exc, self.problem.label(b)) from None
            img[ring[movable]] = new[movable]
            fixed[ring] = True
            corrections[b] = abs(k) / sec.thickness
        lowers, images, placements = [], [], []
        for b, bm in enumerate(self.bodies):
            lowers.append(img[self.lower_ids[b]])
            images.append(img[self.upper_ids[b]])
            det = f.det[bm.elements]
            if not det.min() > 0:
                raise renamed(MeshError(f"an element is inverted after deformation (area stretch "
                                f"{det.min():.3g}); the target or the laws are too severe for these bodies"), self.problem.label(b))
            warnings = ()
            if corrections[b] > CORRECTION_WARNING:
                warnings = (f"hyperelastic: the area correction moved the upper curve by {corrections[b]:.3g} T; the coarse "
                            "mesh misses this deformation's physics (refine with options.elements_through_thickness)",)
            final = MeshData(x[bm.used].copy(), bm.cells, "triangle6")
            quality = FinalQuality(area_stretch_min=float(det.min()), area_stretch_max=float(det.max()))
            holes = tuple(img[h] for h in mesh.holes[b]) if mesh.holes else ()
            placements.append(Placement(images[-1], final, quality, info(b, corrections[b]), warnings, None, holes, targets[b]))
        return lowers, images, placements


class RevolutionPrepared(RevolutionPhysics, HyperelasticPrepared):
    """Bodies of revolution meshed as one and factorised for the hyperelastic model (:mod:`.hyperelastic_revolution`).

    Parameters
    ----------
    stack : Stack
        Of a problem with a ``revolution`` axis.
    options : HyperelasticOptions
    """


class HyperelasticModel(Model):
    """The bodies' mechanics on a coarse mesh, all bodies in one solve."""

    name = "hyperelastic"
    options_type = HyperelasticOptions

    def prepare(self, stack: Stack, options: HyperelasticOptions | None = None) -> HyperelasticPrepared:
        options = options or HyperelasticOptions()
        if stack.problem.revolution is not None:
            return RevolutionPrepared(stack, options)
        return HyperelasticPrepared(stack, options)


MODEL = HyperelasticModel()
