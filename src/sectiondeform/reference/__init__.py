"""Finite-element reference solution of a case (optional extra ``[fem]``).

The physics the fast method stands for, solved without its shortcuts: the
section as a nearly incompressible rubber (neo-Hookean by default, or any
model of :mod:`sectiondeform.materials`: Mooney–Rivlin, Yeoh), its lower
curve bonded to the target, the rest free; mixed P2/P1 (Taylor–Hood)
triangles on a quality mesh, full Newton with incremental loading. Two
kinematics:

- generalised plane strain (out-of-plane stretch λz = 1 / r, so the area
  ratio r comes out of the volume constraint);
- a body of revolution about an axis in the section's plane (hoop stretch
  r / R at each point, integrals weighted by the radius), with the volume
  ratio v as an isotropic growth of the body (v = 1: plain
  near-incompressibility).

See :mod:`sectiondeform.reference.solver` for the model and
``docs/validation.md`` for its verification.

>>> import sectiondeform as sd
>>> from sectiondeform.reference import solve_reference
>>> case = sd.load_case(sd.example_case_path())
>>> ref = solve_reference(case, mesh_size=0.4)
>>> ref.upper.shape == sd.build_section(case).upper.shape   # one image per upper point
True
>>> abs(ref.relative_area_error) < 1e-3                      # r x A0, up to compressibility
True

Needs ``pip install 'sectiondeform[fem]'`` (scikit-fem, triangle); without
it, :func:`solve_reference` raises :class:`~sectiondeform.errors.MissingExtraError`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..case import Case
from ..errors import CaseError
from ..laws import RATIO_RANGE, AreaRatio, Law
from ..models.base import MeshData
from ..section import Section, build_section
from .mesh import SectionMesh, triangulate_section
from .revolution import Axis, axis_from_points

__all__ = [
    "ReferenceSolution",
    "solve_reference",
    "DEFAULT_MESH_SIZE",
    "DEFAULT_BULK_TO_SHEAR",
    "MIN_BULK_TO_SHEAR",
]

#: Default element size, as a fraction of the section's mesh scale (:func:`~sectiondeform.section.mesh_scale`).
DEFAULT_MESH_SIZE = 0.1
#: Default κ / μ (the case's ``options.bulk_to_shear`` overrides it).
DEFAULT_BULK_TO_SHEAR = 1000.0
#: Smallest κ / μ accepted: the reference is a nearly incompressible model.
MIN_BULK_TO_SHEAR = 100.0


@dataclass(frozen=True, eq=False)
class ReferenceSolution:
    """The converged finite-element solution of one case.

    Attributes
    ----------
    upper : (m, 2) float64 ndarray
        Deformed upper characteristic points, B' to A', in the order of
        ``section.upper``, units.
    lower : (n_l, 2) float64 ndarray
        Deformed lower vertices of the mesh (on the target), A' to B', units.
    lower_fractions : (n_l,) float64 ndarray
        Arc-length fraction of each of ``lower``.
    initial_mesh, mesh : MeshData
        The mesh before and after deformation, ``kind="triangle6"`` (corners
        then mid-edge nodes; the deformed edges are the straight chords of
        the quadratic ones).
    pressure : (N,) float64 ndarray
        Pressure p = κ (J − 1) at each mesh vertex (first N points of
        ``mesh.points``), units of ``shear_modulus``.
    area_initial, area_final : float
        Mesh area before, and ∫ det F2D dA after deformation (the exact area
        of the deformed quadratic mesh), units².
    area_target : float or None
        r × initial area under an area law; None for a body of revolution
        (its law sets the volume).
    volume_change : float
        ∫ (Je − 1) w dA / ∫ w dA (w = 1, or the radius for a body of
        revolution; Je the elastic volume ratio): the volume the material
        gave up to its finite bulk modulus; ``area_final = area_target ×
        (1 + volume_change)`` in plane strain, ``volume_final =
        volume_target × (1 + volume_change)`` for a body of revolution.
    max_volume_change : float
        Largest |p| / κ at a vertex: the local volume change the pressure
        field gives (it peaks at the corners A and B, where the bonded
        lower curve meets the free upper one).
    jacobian_min : float
        Smallest det F2D at any quadrature point (> 0: no inversion).
    strain_energy : float
        Stored energy, the mixed form of ∫ Ψ dV: per unit depth in plane
        strain (units of the moduli × units²), of the whole body of
        revolution (2π ∫ Ψ R dA, units of the moduli × units³).
    stretch_z : float or None
        Out-of-plane stretch λz = 1 / r; None for a body of revolution
        (the hoop stretch varies from point to point).
    bulk_to_shear, shear_modulus : float
        κ / μ₀ and the initial shear modulus μ₀ of the rubber.
    mesh_size : float
        Element size h, units.
    elements, dofs : int
        Triangles, and degrees of freedom (displacement + pressure).
    iterations, steps, cuts : int
        Newton iterations, accepted load steps, load steps cut in half.
    seconds : float
        Wall time of mesh, set-up and solve.
    timings : dict
        ``mesh_s``, ``setup_s``, ``solve_s``.
    material : NeoHookean or MooneyRivlin or Yeoh
        The rubber solved (:mod:`sectiondeform.materials`).
    axis : Axis or None
        The axis of revolution, None in plane strain.
    volume_initial, volume_target, volume_final : float or None
        For a body of revolution: 2π ∫ R dA, v × initial, and 2π ∫ r dA of
        the deformed quadratic mesh (exact), units³; None in plane strain.
    volume_ratio : float or None
        The growth v of a body of revolution.
    cauchy : (M, 3, 3) float64 ndarray
        Cauchy stress in each triangle (mean over its quadrature points),
        axes x, y and the out-of-plane (hoop) direction, units of the moduli.
    """

    upper: np.ndarray
    lower: np.ndarray
    lower_fractions: np.ndarray
    initial_mesh: MeshData
    mesh: MeshData
    pressure: np.ndarray
    area_initial: float
    area_target: float | None
    area_final: float
    volume_change: float
    max_volume_change: float
    jacobian_min: float
    strain_energy: float
    stretch_z: float | None
    bulk_to_shear: float
    shear_modulus: float
    mesh_size: float
    elements: int
    dofs: int
    iterations: int
    steps: int
    cuts: int
    seconds: float
    timings: dict = field(default_factory=dict)
    material: object = None
    axis: Axis | None = None
    volume_initial: float | None = None
    volume_target: float | None = None
    volume_final: float | None = None
    volume_ratio: float | None = None
    cauchy: np.ndarray | None = None

    @property
    def revolution(self) -> bool:
        """True for a body of revolution."""
        return self.axis is not None

    @property
    def relative_area_error(self) -> float | None:
        """``(area_final - area_target) / area_target``; None for a body of revolution."""
        if self.area_target is None:
            return None
        return (self.area_final - self.area_target) / self.area_target

    @property
    def relative_volume_error(self) -> float | None:
        """``(volume_final - volume_target) / volume_target``; None in plane strain."""
        if self.volume_target is None:
            return None
        return (self.volume_final - self.volume_target) / self.volume_target

    def summary(self) -> dict:
        """The scalar figures as a plain dictionary (for reports)."""
        keys = ("area_initial", "area_target", "area_final", "volume_change", "max_volume_change",
                "jacobian_min", "strain_energy", "stretch_z", "bulk_to_shear", "shear_modulus", "mesh_size",
                "elements", "dofs", "iterations", "steps", "cuts", "seconds")
        out = {k: getattr(self, k) for k in keys}
        out["relative_area_error"] = self.relative_area_error
        if self.material is not None:
            out["material"] = self.material.to_json()
            out["material"].setdefault("model", self.material.model)
        if self.revolution:
            out["revolution"] = {"axis": [self.axis.point.tolist(), (self.axis.point + [-self.axis.normal[1], self.axis.normal[0]]).tolist()]}
            for k in ("volume_initial", "volume_target", "volume_final", "volume_ratio", "relative_volume_error"):
                out[k] = getattr(self, k)
        out["timings"] = dict(self.timings)
        return out


def _positive(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not math.isfinite(value) or value <= 0:
        raise CaseError(name, f"must be a finite number > 0, got {value!r}")
    return float(value)


def check_parameters(mesh_size: float, bulk_to_shear: float | None) -> tuple[float, float]:
    """Check the reference's mesh size (fraction of T) and κ / μ; returns them as floats.

    Raises
    ------
    CaseError
        If the mesh size is not > 0, or κ / μ is below 100.
    """
    if bulk_to_shear is None:
        bulk_to_shear = DEFAULT_BULK_TO_SHEAR
    bulk_to_shear = _positive(bulk_to_shear, "options.bulk_to_shear")
    if bulk_to_shear < MIN_BULK_TO_SHEAR:
        raise CaseError(
            "options.bulk_to_shear",
            f"the reference is a nearly incompressible model: needs at least {MIN_BULK_TO_SHEAR:g}, got {bulk_to_shear:g}",
        )
    return _positive(mesh_size, "mesh_size"), bulk_to_shear


def solve_reference(
    case,
    target=None,
    law: Law | float | None = None,
    *,
    mesh_size: float = DEFAULT_MESH_SIZE,
    bulk_to_shear: float | None = None,
    shear_modulus: float | None = None,
    material=None,
    axis=None,
    tol: float = 1e-8,
    initial_step: float = 1.0,
    progress=None,
) -> ReferenceSolution:
    """Solve a case by finite elements: the reference for the fast models.

    Parameters
    ----------
    case : Case or Assembly or Section
        A version-1 case (its section is built with
        :func:`~sectiondeform.section.build_section`); a version-2 assembly
        of one body (its ``material``, its law and the assembly's
        ``revolution`` are used; several bodies are refused:
        :func:`~sectiondeform.reference.assembly.solve_assembly_reference`
        solves those); or an already built section, then ``target`` and
        ``law`` are required.
    target : Curve, optional
        Deformed lower curve (anything with ``at_fractions(s) -> (k, 2)``);
        by default the case's.
    law : Law or float, optional
        Mechanical law; by default the case's. A float is an area ratio in
        plane strain, a volume ratio for a body of revolution. A body of
        revolution takes a volume law (``{"volume_ratio": v}``, any object
        with ``key == "volume_ratio"`` and ``ratio``), a plane section an
        area law.
    mesh_size : float
        Element size as a fraction of the section's mesh scale (the mean
        thickness T = area / lower length, or the square root of the area
        where that is smaller; dimensionless). The default, 0.1, is converged to better than
        0.1 % of T on the project's cases (see ``docs/validation.md``).
    bulk_to_shear : float, optional
        κ / μ₀, at least 100; by default the material's, else the case's
        ``options.bulk_to_shear``, else 1000. Given explicitly, it replaces
        the material's own bulk modulus.
    shear_modulus : float, optional
        μ of the default neo-Hookean rubber (1); scales the energy and
        pressure only, not the shape. Not with ``material``.
    material : NeoHookean or MooneyRivlin or Yeoh or dict, optional
        The rubber (:mod:`sectiondeform.materials`), or the case format's
        ``material`` object; by default the one-body assembly's, else a
        neo-Hookean rubber.
    axis : ((float, float), (float, float)), optional
        Two points of the axis of revolution, in the section's plane
        (units): the section is then that of a body of revolution. By
        default the assembly's ``revolution`` axis, else none (plane).
    tol : float
        Newton tolerance on the correction, relative to T (displacement) and
        to μ (pressure).
    initial_step : float
        First load increment (fraction of the full support motion and λz);
        steps grow after quick convergence and are halved after a failure.
    progress : callable, optional
        Called with one line of text at each stage and load step (for
        example ``lambda line: print(line, file=sys.stderr)``).

    Returns
    -------
    ReferenceSolution

    Raises
    ------
    CaseError
        If an argument is out of range or missing, the law does not fit the
        kinematics, the axis touches the section, or the assembly has more
        than one body.
    ConvergenceError
        If Newton cannot apply the full load even with small load steps.
    MeshError
        If the section cannot be triangulated.
    MissingExtraError
        Without the extra ``[fem]`` (scikit-fem, triangle).
    """
    from .solver import MixedProblem, solve_mixed

    t0 = time.perf_counter()
    section, target, law, lower_curve, case_material, case_axis, case_k = _unpack(case, target, law)
    explicit_bulk = bulk_to_shear is not None
    if bulk_to_shear is None:
        bulk_to_shear = case_k
    mesh_size = _positive(mesh_size, "mesh_size")
    rubber = _material(material if material is not None else case_material, bulk_to_shear, shear_modulus,
                       explicit_bulk=explicit_bulk)
    if axis is None:
        axis = case_axis if case_axis is not None else getattr(law, "axis", None)
    if not hasattr(target, "at_fractions"):
        raise CaseError("target", f"expected a curve with at_fractions(s), got {type(target).__name__}")
    ax = None if axis is None else axis_from_points(axis, section.contour)
    ratio = _ratio(law, revolution=ax is not None, area=section.area)

    scale = section.mesh_scale
    h = mesh_size * scale
    mesh = triangulate_section(section, h, lower_curve)
    t1 = time.perf_counter()
    problem = MixedProblem(mesh, material=rubber, axis=ax)
    if progress is not None:
        kind = "body of revolution" if ax is not None else "generalised plane strain"
        progress(
            f"reference: {len(mesh.triangles)} P2/P1 triangles (h = {h:.4g}, {mesh_size:g} x mesh scale), "
            f"{problem.n_u + problem.n_p} unknowns, {rubber.model} rubber, {kind}"
        )
    support = np.asarray(target.at_fractions(problem.dirichlet_fractions), dtype=np.float64)
    load = ratio if ax is not None else 1.0 / ratio
    t2 = time.perf_counter()
    x, report = solve_mixed(problem, support, load, length_scale=scale, tol=tol,
                            initial_step=initial_step, progress=progress)
    t3 = time.perf_counter()
    return _solution(problem, mesh, x, report, ratio, load,
                     {"mesh_s": t1 - t0, "setup_s": t2 - t1, "solve_s": t3 - t2}, t3 - t0)


def _unpack(case, target, law):
    """(section, target, law, lower curve, material, axis, bulk_to_shear) of what was given."""
    from ..assembly import Assembly

    material = axis = None
    if isinstance(case, Assembly):
        if len(case.bodies) != 1:
            names = ", ".join(repr(b.name) for b in case.bodies)
            raise CaseError("bodies", f"the finite-element reference solves one body; this assembly has "
                            f"{len(case.bodies)} ({names}): solve it with "
                            "sectiondeform.reference.assembly.solve_assembly_reference")
        body = case.bodies[0]
        material = body.material_data or None
        axis = case.revolution
        case_k = case.options.for_model("hyperelastic").bulk_to_shear
        sub = case.body_case(0)
        section = build_section(sub)
        return (section, case.target if target is None else target, body.law if law is None else law, sub.lower,
                material, axis, case_k)
    if isinstance(case, Case):
        section = build_section(case)
        return (section, case.target if target is None else target, case.law if law is None else law, case.lower,
                None, None, case.options.for_model("hyperelastic").bulk_to_shear)
    if isinstance(case, Section):
        if target is None or law is None:
            raise CaseError("target", "solve_reference(section, ...) needs the target and the law too")
        return case, target, law, None, None, None, None
    raise CaseError("case", f"expected a Case, a one-body Assembly or a Section, got {type(case).__name__}")


def _material(material, bulk_to_shear, shear_modulus, explicit_bulk: bool):
    """The rubber to solve, checked nearly incompressible."""
    import dataclasses

    from ..materials import NeoHookean, material_from_json

    if material is not None and shear_modulus is not None:
        raise CaseError("shear_modulus", "give shear_modulus or material, not both (the material carries its moduli)")
    field_k = "options.bulk_to_shear"
    if material is None:
        mu = 1.0 if shear_modulus is None else _positive(shear_modulus, "shear_modulus")
        k = DEFAULT_BULK_TO_SHEAR if bulk_to_shear is None else _positive(bulk_to_shear, field_k)
        rubber = NeoHookean(mu, bulk_to_shear=k)
    elif isinstance(material, dict):
        k = None if bulk_to_shear is None else _positive(bulk_to_shear, field_k)
        rubber = material_from_json(material, "material", default_bulk_to_shear=k)
        if explicit_bulk and k is not None:
            rubber = dataclasses.replace(rubber, bulk_modulus=None, bulk_to_shear=k)
        field_k = "material.bulk_to_shear"
    elif hasattr(material, "kappa") and hasattr(material, "first_piola"):
        rubber = material
        if explicit_bulk and bulk_to_shear is not None:
            rubber = dataclasses.replace(rubber, bulk_modulus=None, bulk_to_shear=_positive(bulk_to_shear, field_k))
        field_k = "material.bulk_to_shear"
    else:
        raise CaseError("material", f"expected a rubber of sectiondeform.materials or a material object, got {type(material).__name__}")
    ratio = rubber.kappa / rubber.shear_modulus
    if ratio < MIN_BULK_TO_SHEAR:
        raise CaseError(field_k, f"the reference is a nearly incompressible model: needs a bulk modulus of at least "
                        f"{MIN_BULK_TO_SHEAR:g} x the shear modulus, got {ratio:g}")
    return rubber


def _ratio(law, *, revolution: bool, area: float) -> float:
    """The area ratio (plane) or the volume ratio (revolution) of ``law``."""
    key = getattr(law, "key", None)
    low, high = RATIO_RANGE
    if isinstance(law, bool) or not (isinstance(law, (int, float, np.floating)) or key in ("area_ratio", "volume_ratio")
                                     or isinstance(law, Law)):
        raise CaseError("law", f"expected a law or a ratio, got {type(law).__name__}")
    if revolution:
        if key == "volume_ratio":
            value = law.ratio
        elif isinstance(law, Law):
            raise CaseError(f"law.{key or 'law'}", "a body of revolution needs a volume law {\"volume_ratio\": v} "
                            "in the reference (its area follows from the mechanics)")
        else:
            value = law
        v = _positive(value, "law.volume_ratio")
        if not low <= v <= high:
            raise CaseError("law.volume_ratio", f"must be between {low:g} and {high:g}, got {v!r}")
        return v
    if key == "volume_ratio":
        raise CaseError("law.volume_ratio", "a volume law needs a body of revolution: give the case a revolution axis")
    if not isinstance(law, Law):
        law = AreaRatio(_positive(law, "law.area_ratio"))
    return float(law.area_ratio(area))


def _solution(problem, mesh: SectionMesh, x, report, ratio, load, timings, seconds) -> ReferenceSolution:
    ub = problem.ubasis
    u = x[: problem.n_u]
    skm = problem.skmesh
    u_vert = u[ub.nodal_dofs].T  # (N, 2)
    u_edge = u[ub.facet_dofs].T  # (Nf, 2)
    p0 = np.concatenate((mesh.points, skm.p[:, skm.facets].mean(axis=1).T))
    cells = np.column_stack((mesh.triangles, len(mesh.points) + skm.t2f.T)).astype(np.int64)
    p1 = p0 + np.concatenate((u_vert, u_edge))
    mat = problem.material(x, load, tangent=False)
    dx, wdx = problem.dx, problem.wdx
    area0 = float(dx.sum())
    area1 = float(np.sum(mat["det2"] * dx))
    pressure = x[problem.n_u:][problem.pbasis.nodal_dofs[0]]
    cauchy = np.einsum("eqij,eq->eij", mat["cauchy"], dx) / dx.sum(axis=1)[:, None, None]
    for arr in (p0, p1, cells, pressure, cauchy):
        arr.setflags(write=False)
    upper = p1[mesh.upper_nodes].copy()
    lower = p1[mesh.lower_nodes].copy()
    revolution = problem.revolution
    two_pi = 2.0 * math.pi
    volume0 = two_pi * float(wdx.sum()) if revolution else None
    return ReferenceSolution(
        upper=upper,
        lower=lower,
        lower_fractions=np.array(mesh.lower_fractions),
        initial_mesh=MeshData(points=p0, cells=cells, kind="triangle6"),
        mesh=MeshData(points=p1, cells=cells, kind="triangle6"),
        pressure=pressure,
        area_initial=area0,
        area_target=None if revolution else float(ratio * area0),
        area_final=area1,
        volume_change=float(np.sum((mat["Je"] - 1.0) * wdx) / wdx.sum()),
        max_volume_change=float(np.abs(pressure).max()) / problem.kappa,
        jacobian_min=float(mat["det2"].min()),
        strain_energy=float(np.sum(mat["psi"] * wdx)) * (two_pi if revolution else 1.0),
        stretch_z=None if revolution else float(load),
        bulk_to_shear=float(problem.kappa / problem.mu),
        shear_modulus=float(problem.mu),
        mesh_size=float(mesh.size),
        elements=int(len(mesh.triangles)),
        dofs=int(problem.n_u + problem.n_p),
        iterations=report.iterations,
        steps=report.steps,
        cuts=report.cuts,
        seconds=float(seconds),
        timings=timings,
        material=problem.rubber,
        axis=problem.axis,
        volume_initial=volume0,
        volume_target=ratio * volume0 if revolution else None,
        volume_final=two_pi * float(np.sum(mat["stretch3"] * mat["det2"] * wdx)) if revolution else None,
        volume_ratio=float(ratio) if revolution else None,
        cauchy=cauchy,
    )
