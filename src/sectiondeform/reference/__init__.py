"""Finite-element reference solution of a case (optional extra ``[fem]``).

The physics the fast method stands for, solved without its shortcuts: the
section as a nearly incompressible neo-Hookean solid in generalised plane
strain (out-of-plane stretch λz = 1 / r, so the area ratio r comes out of
the volume constraint), its lower curve bonded to the target, the rest free;
mixed P2/P1 (Taylor–Hood) triangles on a quality mesh, full Newton with
incremental loading. See :mod:`sectiondeform.reference.solver` for the model
and ``docs/validation.md`` for its verification.

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
from ..laws import AreaRatio, Law
from ..models.base import MeshData
from ..section import Section, build_section
from .mesh import SectionMesh, triangulate_section

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
    area_initial, area_target, area_final : float
        Mesh area before, r × initial, and ∫ det F2D dA after deformation
        (the exact area of the deformed quadratic mesh), units².
    volume_change : float
        ∫ (J − 1) dA / area_initial: the volume the material gave up to its
        finite bulk modulus; ``area_final = area_target × (1 + volume_change)``.
    max_volume_change : float
        Largest |p| / κ at a vertex: the local volume change the pressure
        field gives (it peaks at the corners A and B, where the bonded
        lower curve meets the free upper one).
    jacobian_min : float
        Smallest det F2D at any quadrature point (> 0: no inversion).
    strain_energy : float
        Stored energy per unit depth, ∫ Ψ_iso + p (J − 1) − p²/(2κ) dA
        (the mixed form of ∫ Ψ dA), units of ``shear_modulus`` × units².
    stretch_z : float
        Out-of-plane stretch λz = 1 / r.
    bulk_to_shear, shear_modulus : float
        κ / μ and μ.
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
    """

    upper: np.ndarray
    lower: np.ndarray
    lower_fractions: np.ndarray
    initial_mesh: MeshData
    mesh: MeshData
    pressure: np.ndarray
    area_initial: float
    area_target: float
    area_final: float
    volume_change: float
    max_volume_change: float
    jacobian_min: float
    strain_energy: float
    stretch_z: float
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

    @property
    def relative_area_error(self) -> float:
        """``(area_final - area_target) / area_target``."""
        return (self.area_final - self.area_target) / self.area_target

    def summary(self) -> dict:
        """The scalar figures as a plain dictionary (for reports)."""
        keys = ("area_initial", "area_target", "area_final", "volume_change", "max_volume_change",
                "jacobian_min", "strain_energy", "stretch_z", "bulk_to_shear", "shear_modulus", "mesh_size",
                "elements", "dofs", "iterations", "steps", "cuts", "seconds")
        out = {k: getattr(self, k) for k in keys}
        out["relative_area_error"] = self.relative_area_error
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
    case: Case | Section,
    target=None,
    law: Law | float | None = None,
    *,
    mesh_size: float = DEFAULT_MESH_SIZE,
    bulk_to_shear: float | None = None,
    shear_modulus: float = 1.0,
    tol: float = 1e-8,
    initial_step: float = 1.0,
    progress=None,
) -> ReferenceSolution:
    """Solve a case by finite elements: the reference for the fast models.

    Parameters
    ----------
    case : Case or Section
        A case (its section is built with :func:`~sectiondeform.section.build_section`),
        or an already built section, then ``target`` and ``law`` are required.
    target : Curve, optional
        Deformed lower curve (anything with ``at_fractions(s) -> (k, 2)``);
        by default the case's.
    law : Law or float, optional
        Mechanical law, or an area ratio r; by default the case's.
    mesh_size : float
        Element size as a fraction of the section's mesh scale (the mean
        thickness T = area / lower length, or the square root of the area
        where that is smaller; dimensionless). The default, 0.1, is converged to better than
        0.1 % of T on the project's cases (see ``docs/validation.md``).
    bulk_to_shear : float, optional
        κ / μ, at least 100; by default the case's ``options.bulk_to_shear``,
        else 1000.
    shear_modulus : float
        μ; scales the energy and pressure only, not the shape.
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
        If an argument is out of range or missing.
    ConvergenceError
        If Newton cannot apply the full load even with small load steps.
    MeshError
        If the section cannot be triangulated.
    MissingExtraError
        Without the extra ``[fem]`` (scikit-fem, triangle).
    """
    from .solver import MixedProblem, solve_mixed

    t0 = time.perf_counter()
    lower_curve = None
    if isinstance(case, Case):
        section = build_section(case)
        target = case.target if target is None else target
        law = case.law if law is None else law
        if bulk_to_shear is None:
            bulk_to_shear = case.options.for_model("hyperelastic").bulk_to_shear
        lower_curve = case.lower
    elif isinstance(case, Section):
        section = case
        if target is None or law is None:
            raise CaseError("target", "solve_reference(section, ...) needs the target and the law too")
    else:
        raise CaseError("case", f"expected a Case or a Section, got {type(case).__name__}")
    mesh_size, bulk_to_shear = check_parameters(mesh_size, bulk_to_shear)
    shear_modulus = _positive(shear_modulus, "shear_modulus")
    if not isinstance(law, Law):
        law = AreaRatio(_positive(law, "law.area_ratio"))
    if not hasattr(target, "at_fractions"):
        raise CaseError("target", f"expected a curve with at_fractions(s), got {type(target).__name__}")

    scale = section.mesh_scale
    h = mesh_size * scale
    mesh = triangulate_section(section, h, lower_curve)
    t1 = time.perf_counter()
    problem = MixedProblem(mesh, shear_modulus, bulk_to_shear)
    if progress is not None:
        progress(
            f"reference: {len(mesh.triangles)} P2/P1 triangles (h = {h:.4g}, {mesh_size:g} x mesh scale), "
            f"{problem.n_u + problem.n_p} unknowns"
        )
    support = np.asarray(target.at_fractions(problem.dirichlet_fractions), dtype=np.float64)
    ratio = law.area_ratio(section.area)
    stretch_z = 1.0 / ratio
    t2 = time.perf_counter()
    x, report = solve_mixed(problem, support, stretch_z, length_scale=scale, tol=tol,
                            initial_step=initial_step, progress=progress)
    t3 = time.perf_counter()
    return _solution(problem, mesh, x, report, section, law, stretch_z, bulk_to_shear, shear_modulus,
                     {"mesh_s": t1 - t0, "setup_s": t2 - t1, "solve_s": t3 - t2}, t3 - t0)


def _solution(problem, mesh: SectionMesh, x, report, section, law, stretch_z, bulk_to_shear, shear_modulus,
              timings, seconds) -> ReferenceSolution:
    ub = problem.ubasis
    u = x[: problem.n_u]
    skm = problem.skmesh
    u_vert = u[ub.nodal_dofs].T  # (N, 2)
    u_edge = u[ub.facet_dofs].T  # (Nf, 2)
    p0 = np.concatenate((mesh.points, skm.p[:, skm.facets].mean(axis=1).T))
    cells = np.column_stack((mesh.triangles, len(mesh.points) + skm.t2f.T)).astype(np.int64)
    p1 = p0 + np.concatenate((u_vert, u_edge))
    mat = problem.material(x, stretch_z, tangent=False)
    dx = problem.dx
    area0 = float(dx.sum())
    area1 = float(np.sum(mat["det2"] * dx))
    pressure = x[problem.n_u:][problem.pbasis.nodal_dofs[0]]
    for arr in (p0, p1, cells, pressure):
        arr.setflags(write=False)
    upper = p1[mesh.upper_nodes].copy()
    lower = p1[mesh.lower_nodes].copy()
    return ReferenceSolution(
        upper=upper,
        lower=lower,
        lower_fractions=np.array(mesh.lower_fractions),
        initial_mesh=MeshData(points=p0, cells=cells, kind="triangle6"),
        mesh=MeshData(points=p1, cells=cells, kind="triangle6"),
        pressure=pressure,
        area_initial=area0,
        area_target=float(law.target_area(area0)),
        area_final=area1,
        volume_change=float(np.sum((mat["J"] - 1.0) * dx)) / area0,
        max_volume_change=float(np.abs(pressure).max()) / problem.kappa,
        jacobian_min=float(mat["det2"].min()),
        strain_energy=float(np.sum(mat["psi_mixed"] * dx)),
        stretch_z=float(stretch_z),
        bulk_to_shear=float(bulk_to_shear),
        shear_modulus=float(shear_modulus),
        mesh_size=float(mesh.size),
        elements=int(len(mesh.triangles)),
        dofs=int(problem.n_u + problem.n_p),
        iterations=report.iterations,
        steps=report.steps,
        cuts=report.cuts,
        seconds=float(seconds),
        timings=timings,
    )
