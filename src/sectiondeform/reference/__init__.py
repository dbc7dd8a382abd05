"""Finite-element reference solution of a problem (optional extra ``[fem]``).

The physics the fast models stand for, solved without their shortcuts, on
one body or several bonded ones: each body a nearly incompressible rubber
(neo-Hookean by default, or any model of :mod:`sectiondeform.materials`:
Mooney–Rivlin, Yeoh, moduli in the case's units so a stiffness contrast
matters), the support bonded to the target, the rest free; mixed P2/P1
(Taylor–Hood) triangles on one conforming quality mesh of the union of the
bodies (:mod:`sectiondeform.reference.mesh`: shared pieces are shared
nodes, a pressure field per body), full Newton with incremental loading
(:mod:`sectiondeform.reference.solver`). Two kinematics:

- generalised plane strain: each body's out-of-plane stretch λz = 1 / r,
  so its area ratio r comes out of its volume constraint; a body whose
  material grows isotropically by v (``{"volume_ratio": v}`` without an
  axis: curing, swelling) has F = Fe · v^(1/3) I and its λz solved so that
  the extrusion is free along its length, no axial force (the hyperelastic
  model's formulation, :mod:`sectiondeform.extrusion`);
- bodies of revolution about an axis in the section's plane (hoop stretch
  r / R at each point, integrals weighted by the radius), each body's
  volume ratio v an isotropic growth (v = 1: plain near-incompressibility).

Every body's load parameter is ramped together with the support motion. A
node on the support at arc-length fraction s goes to the target at s; the
rest is free, a body's holes too (the mesh follows them, no element inside).
See ``docs/validation.md`` for the verification.

>>> import sectiondeform as sd
>>> from sectiondeform.reference import solve_reference
>>> problem = sd.load_case(sd.example_case_path())
>>> ref = solve_reference(problem, mesh_size=0.4)
>>> ref.bodies[0].upper.shape == sd.build_section(problem).upper.shape   # one image per upper point
True
>>> abs(ref.bodies[0].relative_error) < 1e-3                              # r x A0, up to compressibility
True

Needs ``pip install 'sectiondeform[fem]'`` (scikit-fem, triangle); without
it, :func:`solve_reference` raises :class:`~sectiondeform.errors.MissingExtraError`.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ..errors import CaseError
from ..fem.contact import ring_factor
from ..laws import RATIO_RANGE, Law
from ..section import build_section
from .solution import BodyReference, Reference, solution

__all__ = [
    "BodyReference",
    "Reference",
    "solve_reference",
    "check_parameters",
    "DEFAULT_MESH_SIZE",
    "DEFAULT_BULK_TO_SHEAR",
    "MIN_BULK_TO_SHEAR",
]

#: Default element size, as a fraction of each body's mesh scale (:func:`~sectiondeform.section.mesh_scale`).
DEFAULT_MESH_SIZE = 0.1
#: Default κ / μ (the case's ``options.bulk_to_shear`` overrides it).
DEFAULT_BULK_TO_SHEAR = 1000.0
#: Smallest κ / μ accepted: the reference is a nearly incompressible model.
MIN_BULK_TO_SHEAR = 100.0
#: Largest load step with rigid parts: the history (load–deflection curve) has at least 1 / this steps.
HISTORY_STEP = 0.125


def _positive(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not math.isfinite(value) or value <= 0:
        raise CaseError(name, f"must be a finite number > 0, got {value!r}")
    return float(value)


CONTACT_REFINEMENT = 8
"""With frictionless rigid parts, the bodies' contour along the parts' paths (start to end, grown by two element
sizes) is split this many times finer, Triangle grading the elements inward: a contact spans few elements of the
uniform mesh. The lip seal's 0.30 mm contact (`tests/data/cases/v2/lip-seal-on-shaft.json`) was under one of them
at the default size, and its length came out 0.287 mm, 0.2615 and 0.2634 at 1, 1/2 and 1/4 of it, as if converged;
refined 4, 8 and 16 times along the shaft's path, 0.2869, 0.2967 and 0.3011 mm, its force within 0.1 % throughout.
The public cases' figures move by at most 0.07 % (the O-ring's bottom force), their reference time by at most 2.3×
(the sleeve's 3.5 → 7.9 s)."""


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


def body_material(problem, b: int, bulk_to_shear: float | None = None, material=None):
    """Body ``b``'s rubber, checked nearly incompressible.

    Parameters
    ----------
    problem : Problem
    b : int
    bulk_to_shear : float, optional
        κ / μ replacing the rubber's own bulk modulus.
    material : NeoHookean or MooneyRivlin or Yeoh or dict, optional
        A rubber (or the case format's ``material`` object) replacing the body's ``material``.

    Raises
    ------
    CaseError
        Naming the field, for a bad material or a κ / μ below 100.
    """
    from ..materials import material_from_json

    prefix = "" if problem.dialect == "section-case/1" else f"bodies[{b}]."
    data = problem.bodies[b].material_data
    case_k = problem.options.for_model("hyperelastic").bulk_to_shear
    own = material is None and any(k in data for k in ("bulk_modulus", "bulk_to_shear"))
    if material is None or isinstance(material, dict):
        own = own if material is None else any(k in material for k in ("bulk_modulus", "bulk_to_shear"))
        k = None if case_k is None else _positive(case_k, "options.bulk_to_shear")
        field = f"{prefix}material" if material is None else "material"
        material = material_from_json(data if material is None else material, field, default_bulk_to_shear=k)
    elif not (hasattr(material, "kappa") and hasattr(material, "first_piola")):
        raise CaseError("material", f"expected a rubber of sectiondeform.materials, got {type(material).__name__}")
    else:
        own, prefix = True, ""
    field_k = f"{prefix}material.bulk_to_shear" if own else "options.bulk_to_shear"
    if bulk_to_shear is not None:
        material = dataclasses.replace(material, bulk_modulus=None, bulk_to_shear=_positive(bulk_to_shear, field_k))
        field_k = "options.bulk_to_shear"
    ratio = material.kappa / material.shear_modulus
    if ratio < MIN_BULK_TO_SHEAR:
        raise CaseError(field_k, f"the reference is a nearly incompressible model: needs a bulk modulus of at least "
                        f"{MIN_BULK_TO_SHEAR:g} x the shear modulus, got {ratio:g}")
    return material


def body_ratio(law: Law, *, revolution: bool, area: float, field: str = "law") -> float:
    """The area ratio (plane) or the volume ratio (revolution) of a body's law.

    Raises
    ------
    CaseError
        For a law that does not fit the kinematics, or a ratio out of range.
    """
    key = getattr(law, "key", None)
    if revolution:
        if key != "volume_ratio":
            raise CaseError(f"{field}.{key or 'law'}", "a body of revolution needs a volume law {\"volume_ratio\": v} "
                            "in the reference (its area follows from the mechanics)")
        low, high = RATIO_RANGE
        v = _positive(law.ratio, f"{field}.volume_ratio")
        if not low <= v <= high:
            raise CaseError(f"{field}.volume_ratio", f"must be between {low:g} and {high:g}, got {v!r}")
        return v
    return float(law.area_ratio(area))  # an extruded body's growth: a free body's, r^(2/3), until its λz is solved


def body_growth(law: Law, *, revolution: bool) -> float:
    """The isotropic growth v of an extruded body's material (``volume_ratio`` without an axis), else 1."""
    return float(law.growth) if not revolution and law.growth is not None and law.measure == "area" else 1.0


def solve_reference(
    problem,
    target=None,
    *,
    mesh_size: float = DEFAULT_MESH_SIZE,
    bulk_to_shear: float | None = None,
    material=None,
    tol: float = 1e-8,
    initial_step: float = 1.0,
    contact_refinement: int = CONTACT_REFINEMENT,
    progress=None,
) -> Reference:
    """Solve a problem by finite elements: the reference for the fast models.

    Parameters
    ----------
    problem : Problem
        One body or several; each body's ``material`` and law are used, and
        the problem's ``revolution``.
    target : Curve, optional
        The support's image (``at_fractions(s) -> (k, 2)``); by default the problem's.
    mesh_size : float
        Element size as a fraction of each body's mesh scale (the mean
        thickness T = area / lower length, or the square root of the area
        where that is smaller; dimensionless). The default, 0.1, is
        converged to better than 0.1 % of T on the project's cases (see
        ``docs/validation.md``).
    bulk_to_shear : float, optional
        κ / μ of every body, at least 100; by default each material's, else
        the case's ``options.bulk_to_shear``, else 1000. Given explicitly,
        it replaces the materials' own bulk moduli.
    material : NeoHookean or MooneyRivlin or Yeoh or dict, optional
        One rubber (or the case format's ``material`` object) for every
        body, instead of their own ``material`` objects.
    tol : float
        Newton tolerance on the correction, relative to T (displacement) and
        to μ (pressure).
    initial_step : float
        First load increment (fraction of the full support motion and
        loads); steps grow after quick convergence and are halved after a failure.
    contact_refinement : int
        With frictionless rigid parts, the bodies' contour along the parts'
        paths is meshed this many times finer (:data:`CONTACT_REFINEMENT`;
        1: uniform).
    progress : callable, optional
        Called with one line of text at each stage and load step.

    Returns
    -------
    Reference

    Raises
    ------
    CaseError
        If an argument is out of range, a law does not fit the kinematics,
        a material is not nearly incompressible, or the axis touches a body.
    ConvergenceError
        If Newton cannot apply the full load even with small load steps.
    MeshError
        If the union of the bodies cannot be triangulated.
    MissingExtraError
        Without the extra ``[fem]`` (scikit-fem, triangle).
    """
    from .mesh import triangulate
    from .revolution import axis_from_points
    from .solver import MixedProblem, solve_mixed

    t0 = time.perf_counter()
    target = problem.target if target is None else target
    if not hasattr(target, "at_fractions"):
        raise CaseError("target", f"expected a curve with at_fractions(s), got {type(target).__name__}")
    mesh_size = _positive(mesh_size, "mesh_size")
    sections = [build_section(problem.body_case(b)) for b in range(len(problem.bodies))]
    rubbers = [body_material(problem, b, bulk_to_shear, material) for b in range(len(problem.bodies))]
    contour = np.concatenate([s.contour for s in sections])
    ax = None if problem.revolution is None else axis_from_points(problem.revolution.axis, contour)
    prefix = "" if problem.dialect == "section-case/1" else "bodies[{}]."
    ratios = np.array([body_ratio(body.law, revolution=ax is not None, area=sec.area, field=prefix.format(b) + "law")
                       for b, (body, sec) in enumerate(zip(problem.bodies, sections))])
    growths = np.array([body_growth(body.law, revolution=ax is not None) for body in problem.bodies])
    growing = np.flatnonzero(growths != 1.0)
    fine = _contact_zone(problem, sections, mesh_size, contact_refinement)
    mesh = triangulate(problem, mesh_size, sections, fine=fine)
    t1 = time.perf_counter()
    mixed = MixedProblem(mesh, rubbers, axis=ax)
    if progress is not None:
        kind = "body of revolution" if ax is not None else "generalised plane strain"
        names = ", ".join(sorted({r.model for r in rubbers}))
        finer = "" if fine is None else f", {fine[1]} x finer along the parts' paths"
        progress(f"reference: {len(mesh.triangles)} P2/P1 triangles over {len(sections)} "
                 f"bod{'y' if len(sections) == 1 else 'ies'} (h = {', '.join(f'{h:.4g}' for h in mesh.sizes)}, "
                 f"{mesh_size:g} x mesh scale{finer}), "
                 f"{mixed.n_u + mixed.n_p} unknowns, {names} rubber, {kind}")
    support = np.asarray(target.at_fractions(mixed.dirichlet_fractions), dtype=np.float64)
    load = ratios if ax is not None else 1.0 / ratios
    if len(growing):  # λz then the growth; a growing body starts at a free body's axial stretch v^(1/3)
        load = np.stack((np.where(growths != 1.0, np.cbrt(growths), load), growths))
    scale = min(s.mesh_scale for s in sections)
    history: list = []
    on_step = None
    if problem.rigid:
        from .contact import ReferenceContact

        mixed.contact = ReferenceContact(mixed, problem.rigid, tol=1e-6 * problem.size)

        def on_step(x, t, lz):
            history.append(_history_step(mixed, x, t, lz))

    t2 = time.perf_counter()
    x, report = solve_mixed(mixed, support, load, length_scale=scale, tol=tol, initial_step=initial_step,
                            max_step=HISTORY_STEP if problem.rigid else 1.0, progress=progress, on_step=on_step)
    if len(growing):
        x, load, report = _free_extrusion(problem, mixed, sections, x, load, growing, report, scale, tol, progress)
        ratios = np.where(growths != 1.0, growths / load[0], ratios)  # the volume grown over the axial stretch
        if history:
            history[-1] = _history_step(mixed, x, 1.0, load)
    t3 = time.perf_counter()
    ref = solution(problem, mixed, mesh, sections, x, report, ratios, load,
                   {"mesh_s": t1 - t0, "setup_s": t2 - t1, "solve_s": t3 - t2}, t3 - t0)
    if mixed.contact is None:
        return ref
    last = history[-1]
    return dataclasses.replace(ref, rigid=mixed.contact.figures(x, ring_factor(not mixed.revolution)), support_force=last.forces["support"],
                               history=tuple(history))


def _contact_zone(problem, sections, mesh_size: float, ratio: int):
    """Where the reference's mesh is made finer for rigid parts: ``(zone, ratio)`` for :func:`~.mesh.triangulate`, or None.

    The zone is every frictionless part's path, its outline at the start
    and at the end, grown by two of the largest body's element sizes: the
    bodies' contour there is split ``ratio`` times finer, and Triangle's
    quality bound grades the elements from it inward. A part with friction
    keeps the uniform mesh: refined along a plate sliding 3 mm with friction
    0.3 over a block (``tests/test_reference_contact.py``), the block's
    trailing corner, where the pressure is singular, stopped Newton at 54 %
    of the drag.
    """
    if not problem.rigid or ratio == 1:
        return None
    import shapely

    h = max(mesh_size * s.mesh_scale for s in sections)
    tol = 1e-6 * problem.size
    paths = []
    for part in (p for p in problem.rigid if p.friction == 0.0):
        ring = part.contour.discretise(tol)[0]
        end, start = shapely.Polygon(ring), shapely.Polygon(ring - np.asarray(part.travel, dtype=np.float64))
        paths.append(shapely.union(start, end))
    return (shapely.buffer(shapely.union_all(paths), 2.0 * h), int(ratio)) if paths else None


def _history_step(mixed, x, t: float, load):
    """The forces on each rigid part and on the support at the solved state ``x`` of load fraction ``t``."""
    from ..models.hyperelastic_contact import HistoryStep

    ring = ring_factor(not mixed.revolution)
    r = mixed.residual(x, load)[mixed.dirichlet_nodes]  # (2, d/2): what the support does to the bodies
    forces = dict(zip(mixed.contact.names, mixed.contact.forces(x, ring)))
    forces["support"] = (-ring * float(r[0].sum()) + 0.0, -ring * float(r[1].sum()) + 0.0)  # no negative zero
    return HistoryStep(float(t), forces)


def _free_extrusion(problem, mixed, sections, x, load, growing, report, scale, tol, progress):
    """The growing extruded bodies' axial stretches with no axial force (:func:`~sectiondeform.extrusion.free_axial_stretch`).

    Returns the solved state, the load (λz then v per body) and the Newton report with the extra iterations.
    """
    from ..extrusion import free_axial_stretch
    from .solver import NewtonReport, continue_mixed

    now = {"x": x, "load": np.array(load, dtype=np.float64), "its": 0}

    def solve(ln):
        trial = now["load"].copy()
        trial[0] = np.exp(ln)
        now["x"], its = continue_mixed(mixed, now["x"], trial, length_scale=scale, tol=tol)
        now["load"], now["its"] = trial, now["its"] + its
        if progress is not None:
            progress("reference: axial stretch " + ", ".join(f"{v:.9g}" for v in trial[0][growing])
                     + f" of the growing bod{'y' if len(growing) == 1 else 'ies'}, {its} Newton iterations")
        return mixed.axial_forces(now["x"], trial)

    scale_force = np.array([r.shear_modulus * s.area for r, s in zip(mixed.rubbers, sections)])
    free_axial_stretch(np.log(now["load"][0]), mixed.axial_forces(x, now["load"]), solve, growing, scale_force,
                       problem.label(int(growing[0])) or "body")
    report = NewtonReport(iterations=report.iterations + now["its"], steps=report.steps, cuts=report.cuts,
                          residual=report.residual)
    return now["x"], now["load"], report
