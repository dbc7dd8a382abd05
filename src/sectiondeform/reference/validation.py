"""A fast model against a finite-element reference, body by body (extra ``[fem]``).

:func:`validate` runs the fast model (:class:`~sectiondeform.deform.Deformer`)
and a reference on the same problem, one body or several, plane or of
revolution, and measures for each body the distance between the two
deformed upper curves (:mod:`sectiondeform.compare`), the law's measure
(area, or volume for a body of revolution), the times, and for the
hyperelastic model the stresses recovered at the nodes against the
reference's away from the singular points (:class:`StressDistance`). The reference is
the project's own finite elements (:func:`~sectiondeform.reference.solve_reference`,
one mesh of all bodies) by default, or any :class:`ReferenceRun`, such as
CalculiX's (:func:`~sectiondeform.external.solve.calculix_run`).
``sectiondeform validate`` and ``benchmarks/validation.py`` are thin layers
over it; :func:`save_validation_figure` overlays the deformed bodies.

The report (:meth:`Validation.to_json`, ``section-validation/1``) lists the
bodies; a ``section-case/1`` problem keeps its version-1 report, the one
body's figures at the top level.

Timing is fair to both: each is timed from the case to the deformed upper
points (section, mesh, solve), after the libraries are imported; the fast
model's time is the median of a few runs (it takes milliseconds), the
reference's a single run.
"""

from __future__ import annotations

import math
import statistics
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..compare import CurveComparison, compare_curves, point_to_curve_distance, section_height
from ..errors import CaseError, require
from ..problem import V1
from ..result import contact_units
from ..section import polygon_area
from . import DEFAULT_MESH_SIZE, Reference, check_parameters, solve_reference

__all__ = ["BodyValidation", "ReferenceRun", "StressDistance", "Validation", "fem_run", "validate", "draw_validation",
           "save_validation_figure", "VALIDATION_FORMAT"]

VALIDATION_FORMAT = "section-validation/1"
FAST_RUNS = 5


@dataclass(frozen=True, eq=False)
class ReferenceRun:
    """A reference solution as :func:`validate` reads it.

    Attributes
    ----------
    solution : object
        The solver's own solution (a :class:`~sectiondeform.reference.Reference`,
        a CalculiX :class:`~sectiondeform.result.Result`...).
    bodies : tuple
        Per body, anything with ``upper`` (the deformed upper points, in the
        order of the body's section), ``final`` (the law's measure after)
        and ``relative_error`` (against its own target).
    meshes : tuple of MeshData
        Deformed meshes, drawn under the figure.
    model : str
        One line naming the solver and its physics.
    summary : dict
        The solver's figures, for the report's ``reference.solver``.
    note : str
        One line of size and effort, for the summary lines.
    seconds : float
        Wall time, case to deformed shape.
    """

    solution: object
    bodies: tuple
    meshes: tuple
    model: str
    summary: dict
    note: str
    seconds: float


def fem_run(reference: Reference) -> ReferenceRun:
    """The project's finite-element reference as a :class:`ReferenceRun`."""
    r = reference
    rubbers = ", ".join(dict.fromkeys(m.model for m in r.materials))
    kind = "body of revolution" if r.revolution else "generalised plane strain"
    bodies = "" if len(r.bodies) == 1 else f"one mesh of {len(r.bodies)} bonded bodies, "
    return ReferenceRun(solution=r, bodies=r.bodies, meshes=(r.mesh,), summary=r.summary(), seconds=r.seconds,
                        model=f"finite elements: {bodies}{rubbers}, {kind}, P2/P1 Taylor-Hood",
                        note=f"{r.elements} elements, {r.dofs} unknowns, {r.iterations} Newton iterations")


@dataclass(frozen=True, eq=False)
class BodyValidation:
    """One body: the fast model's upper curve and law against the reference's.

    Attributes
    ----------
    name : str
    shape : CurveComparison
        Fast deformed upper curve against the reference's, point by point
        and as curves; relative figures over ``thickness``.
    thickness : float
        The body's mean thickness T = area / lower length, units.
    measure : str
        ``"area"`` (units²) or ``"volume"`` (units³): what the body's law sets.
    target : float
        The law's target (the fast model's, from the body's section).
    fast_final, reference_final : float
        The measure after deformation, fast and reference.
    fast_error, reference_error : float
        Their relative errors, each against its own target.
    area_polygon : float
        Area of the polygon of the fast lower nodes and the reference's
        upper points (the polygon the fast area is measured on), less the
        reference's holes, units².
    holes : tuple of CurveComparison
        Per hole of the body, its fast deformed points against the
        reference's (closed curves), relative figures over ``thickness``.
    """

    name: str
    shape: CurveComparison
    thickness: float
    measure: str
    target: float
    fast_final: float
    reference_final: float
    fast_error: float
    reference_error: float
    area_polygon: float
    holes: tuple = ()


@dataclass(frozen=True, eq=False)
class StressDistance:
    """One body's stresses recovered at the nodes, fast against reference, away from its singular points.

    Both sides are recovered alike (:func:`~sectiondeform.strain_fields.nodal_stresses`,
    per body) and compared only at the nodes farther than ``radius`` from
    every singular point of the body (initial positions): there the exact
    stress is infinite and neither mesh converges.

    Attributes
    ----------
    radius : float
        The neighbourhood left out around each singular point, units (the
        fast model's :data:`~sectiondeform.strain_fields.SINGULAR_RADIUS_ELEMENTS`
        element sizes).
    singular_points : int
        How many there are.
    von_mises_fast, von_mises_reference : float
        The largest von Mises stress, units of the moduli.
    pressure_max_fast, pressure_max_reference, pressure_min_fast, pressure_min_reference : float
        The largest and smallest pressure (positive in compression).
    samples : int
        Reference nodes of the body, away from the singular points, inside the fast mesh.
    von_mises_l2, pressure_l2 : float
        ‖fast − reference‖ / ‖reference‖ over those nodes (the fast nodal
        field interpolated there by its P2 shape functions).
    von_mises_max, pressure_max : float
        The largest |fast − reference| there, over the reference's largest |value|.
    """

    radius: float
    singular_points: int
    von_mises_fast: float
    von_mises_reference: float
    pressure_max_fast: float
    pressure_max_reference: float
    pressure_min_fast: float
    pressure_min_reference: float
    samples: int
    von_mises_l2: float
    pressure_l2: float
    von_mises_max: float
    pressure_max: float

    @property
    def von_mises_peak_error(self) -> float:
        """Fast peak von Mises over the reference's, minus 1."""
        return self.von_mises_fast / self.von_mises_reference - 1.0

    @property
    def pressure_peak_error(self) -> float:
        """The larger gap of the pressure's two extremes, over the reference's largest |pressure|."""
        scale = max(abs(self.pressure_max_reference), abs(self.pressure_min_reference))
        return max(abs(self.pressure_max_fast - self.pressure_max_reference),
                   abs(self.pressure_min_fast - self.pressure_min_reference)) / scale

    def to_json(self) -> dict:
        """The figures, and both peak errors."""
        out = {k: getattr(self, k) for k in self.__dataclass_fields__}
        out.update(von_mises_peak_error=self.von_mises_peak_error, pressure_peak_error=self.pressure_peak_error)
        return out


def _locate(mesh, points: np.ndarray, chunk: int = 256) -> tuple[np.ndarray, np.ndarray]:
    """The corner triangle of a P2 mesh holding each point and the point's local (xi, eta); element −1 outside."""
    tri = mesh.points[np.asarray(mesh.cells)[:, :3]]  # (M, 3, 2)
    a, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    element, local = np.full(len(points), -1), np.zeros((len(points), 2))
    for start in range(0, len(points), chunk):
        d = points[start:start + chunk, None, :] - a[None]  # (k, M, 2)
        xi = (d[..., 0] * e2[:, 1] - d[..., 1] * e2[:, 0]) / det
        eta = (e1[:, 0] * d[..., 1] - e1[:, 1] * d[..., 0]) / det
        worst = np.minimum(np.minimum(xi, eta), 1.0 - xi - eta)  # >= 0 inside
        best = np.argmax(worst, axis=1)
        rows = np.arange(len(best))
        element[start:start + chunk] = np.where(worst[rows, best] >= -1e-9, best, -1)
        local[start:start + chunk] = np.column_stack((xi[rows, best], eta[rows, best]))
    return element, local


def _stress_distance(problem, fast, reference: Reference, b: int) -> StressDistance | None:
    """Body ``b``'s :class:`StressDistance`; None without stresses on both sides."""
    from ..fem.elements import p2_values
    from ..models.base import MeshData
    from ..strain_fields import nodal_stresses, result_mechanics

    mechanics = result_mechanics(fast)[b]
    if mechanics is None or "pressure" not in mechanics.nodal or reference.corner_pressure is None:
        return None
    on = np.flatnonzero(reference.body == b)
    used, local_cells = np.unique(reference.mesh.cells[on], return_inverse=True)
    cells = local_cells.reshape(-1, 6)
    initial = MeshData(reference.initial_mesh.points[used], cells, "triangle6")
    rb, axis = reference.bodies[b], None if problem.revolution is None else problem.revolution.axis
    ref = nodal_stresses(initial, MeshData(reference.mesh.points[used], cells, "triangle6"), rb.material,
                         reference.corner_pressure[on], 1.0 if axis else rb.load, axis, rb.load if axis else 1.0)
    body, points = fast.bodies[b], mechanics.singular_points
    radius = points[0].radius if points else 0.0

    def away(X):
        if not points:
            return np.ones(len(X), bool)
        corners = np.array([p.initial for p in points])
        return np.hypot(*(X[:, None, :] - corners[None]).transpose(2, 0, 1)).min(axis=1) >= radius

    vf, pf = mechanics.nodal["von_mises_stress"], mechanics.nodal["pressure"]
    keep_f = away(body.initial_mesh.points) & np.isfinite(vf)
    keep_r = away(initial.points) & np.isfinite(ref["von_mises_stress"])
    vr, pr = ref["von_mises_stress"][keep_r], ref["pressure"][keep_r]
    element, local = _locate(body.initial_mesh, initial.points[keep_r])
    found = element >= 0
    shape, nodes = p2_values(local[found]), np.asarray(body.initial_mesh.cells)[element[found]]
    vm_at, p_at = (np.einsum("ka,ka->k", shape, values[nodes]) for values in (vf, pf))
    vs, ps = vr[found], pr[found]
    return StressDistance(
        radius=float(radius), singular_points=len(points),
        von_mises_fast=float(vf[keep_f].max()), von_mises_reference=float(vr.max()),
        pressure_max_fast=float(pf[keep_f].max()), pressure_max_reference=float(pr.max()),
        pressure_min_fast=float(pf[keep_f].min()), pressure_min_reference=float(pr.min()),
        samples=int(found.sum()),
        von_mises_l2=float(np.linalg.norm(vm_at - vs) / np.linalg.norm(vs)),
        pressure_l2=float(np.linalg.norm(p_at - ps) / np.linalg.norm(ps)),
        von_mises_max=float(np.abs(vm_at - vs).max() / np.abs(vs).max()),
        pressure_max=float(np.abs(p_at - ps).max() / np.abs(ps).max()),
    )


@dataclass(frozen=True, eq=False)
class Validation:
    """A fast result against a reference, body by body.

    Attributes
    ----------
    problem : Problem
    fast : Result
        The fast model's result.
    reference : ReferenceRun
    bodies : tuple of BodyValidation
    height : float
        The problem's height above its support: the largest distance of a
        body's upper point from the support, units (the size the distances
        are read against, ``docs/validation.md``).
    fast_seconds : float
        Median wall time of the fast model.
    stresses : tuple of StressDistance or None
        Per body, the recovered stresses against the reference's away from
        its singular points (the hyperelastic model against the project's
        own reference); None for a body without stresses on both sides.
    """

    problem: object
    fast: object
    reference: ReferenceRun
    bodies: tuple
    height: float
    fast_seconds: float
    stresses: tuple = ()

    @property
    def model(self) -> str:
        """The fast model checked."""
        return self.fast.model

    @property
    def contacts(self) -> tuple:
        """Per rigid part both sides have, ``{"name", "force_fast", "force_reference", "force_error", "length_fast",
        "length_reference", "length_error", "pressure_max_fast", "pressure_max_reference"}``.

        ``force_error`` is the distance between the two forces over the
        reference's magnitude; ``length_error`` the contact lengths' relative
        difference (the reference's length as the unit).
        """
        ref = {p.name: p for p in getattr(self.reference.solution, "rigid", ()) or ()}
        out = []
        for p in getattr(self.fast, "rigid", ()) or ():
            q = ref.get(p.name)
            if q is None:
                continue
            size = float(np.hypot(*q.force))
            out.append({"name": p.name, "force_fast": list(p.force), "force_reference": list(q.force),
                        "force_error": float(np.hypot(*np.subtract(p.force, q.force))) / size if size > 0 else math.nan,
                        "length_fast": p.length, "length_reference": q.length,
                        "length_error": (p.length - q.length) / q.length if q.length > 0 else math.nan,
                        "pressure_max_fast": p.pressure_max, "pressure_max_reference": q.pressure_max})
        return tuple(out)

    @property
    def revolution(self) -> bool:
        """True for bodies of revolution (the laws and figures are volumes)."""
        return self.problem.revolution is not None

    @property
    def reference_seconds(self) -> float:
        """Wall time of the reference."""
        return self.reference.seconds

    @property
    def speed_ratio(self) -> float:
        """Reference time over fast time."""
        return self.reference_seconds / self.fast_seconds

    def to_json(self) -> dict:
        """The ``section-validation/1`` report: the whole, then a ``bodies`` list (version 1: one body's keys)."""
        if self.problem.dialect == V1:
            return self._v1_json()
        out = {"format": VALIDATION_FORMAT, "name": self.problem.name, "units": self.problem.units,
               "height": self.height, "fast": {"model": self.model, "seconds": self.fast_seconds},
               "reference": {"model": self.reference.model, "seconds": self.reference_seconds,
                             "solver": self.reference.summary},
               "bodies": [self._body_json(i) for i in range(len(self.bodies))], "speed_ratio": self.speed_ratio}
        if self.revolution:
            out["revolution"] = {"axis": [list(map(float, p)) for p in self.problem.revolution.axis]}
        if self.contacts:
            out["rigid"] = list(self.contacts)
        return out

    def _body_json(self, i: int) -> dict:
        bv, fb, rb = self.bodies[i], self.fast.bodies[i], self.reference.bodies[i]
        s = bv.shape
        return {
            "name": bv.name, "thickness": bv.thickness,
            "hausdorff": s.hausdorff, "hausdorff_over_thickness": s.hausdorff / bv.thickness,
            "hausdorff_over_height": s.hausdorff / self.height,
            "max_pointwise": s.max_pointwise, "max_pointwise_over_thickness": s.max_pointwise / bv.thickness,
            "max_pointwise_over_height": s.max_pointwise / self.height,
            "measure": bv.measure, "target": bv.target,
            "fast": {"final": bv.fast_final, "relative_error": bv.fast_error, "upper": fb.upper.tolist()},
            "reference": {"final": bv.reference_final, "relative_error": bv.reference_error,
                          "load": getattr(rb, "load", None), "upper": np.asarray(rb.upper).tolist()},
            **self._holes_json(i),
            **self._stress_json(i),
        }

    def _holes_json(self, i: int) -> dict:
        """``{"holes": [...]}`` of body ``i``, each hole's distances fast to reference, or nothing."""
        bv = self.bodies[i]
        if not bv.holes:
            return {}
        return {"holes": [{"hausdorff": h.hausdorff, "hausdorff_over_height": h.hausdorff / self.height,
                           "max_pointwise": h.max_pointwise, "max_pointwise_over_height": h.max_pointwise / self.height,
                           "fast": np.asarray(f).tolist(), "reference": np.asarray(r).tolist()}
                          for h, f, r in zip(bv.holes, self.fast.bodies[i].holes, self.reference.bodies[i].holes)]}

    def _stress_json(self, i: int) -> dict:
        """``{"stresses": ...}`` of body ``i``, or nothing."""
        sd = self.stresses[i] if i < len(self.stresses) else None
        return {} if sd is None else {"stresses": sd.to_json()}

    def _v1_json(self) -> dict:
        """The version-1 report of the one body of a ``section-case/1`` problem."""
        bv, f, r = self.bodies[0], self.fast.bodies[0], self.reference.bodies[0]
        solver = dict(self.reference.summary)
        solver.update({k: v for k, v in (solver.pop("bodies", None) or [{}])[0].items() if k != "name"})
        target = f.area_target
        return {
            "format": VALIDATION_FORMAT, "name": self.problem.name, "units": self.problem.units,
            "thickness": bv.thickness, "height": self.height,
            "hausdorff_over_height": bv.shape.hausdorff / self.height,
            "max_pointwise_over_height": bv.shape.max_pointwise / self.height,
            "area": {"initial": f.area_initial, "target": target},
            "fast": {"model": self.model, "area_final": f.area_final,
                     "area_relative_error": (f.area_final - target) / target, "seconds": self.fast_seconds,
                     "upper": f.upper.tolist()},
            "reference": {"model": self.reference.model, "area_final": bv.reference_final,
                          "area_relative_error": (bv.reference_final - target) / target,
                          "area_polygon": bv.area_polygon, "seconds": self.reference_seconds, "solver": solver,
                          "upper": np.asarray(r.upper).tolist()},
            "shape": bv.shape.to_json(),
            "pointwise_distance": np.hypot(*(f.upper - np.asarray(r.upper)).T).tolist(),
            "speed_ratio": self.speed_ratio,
            **self._stress_json(0),
        }

    def lines(self) -> list[str]:
        """A short human-readable summary: a few lines per body, then the times."""
        u, height = self.problem.units, self.height
        cube = "³" if self.revolution else "²"
        out = [f"{self.problem.name}: {self.model} model against the reference ({self.reference.model})"
               f"{' (bodies of revolution)' if self.revolution else ''}, height {height:.4g} {u}"]
        for i, bv in enumerate(self.bodies):
            s = bv.shape
            out += [
                f"  body {bv.name!r} (mean thickness {bv.thickness:.4g} {u})",
                f"    {bv.measure} target    {bv.target:12.6g} {u}{cube}",
                f"    {bv.measure} fast      {bv.fast_final:12.6g} {u}{cube}   relative error {bv.fast_error:+.2e}",
                f"    {bv.measure} reference {bv.reference_final:12.6g} {u}{cube}   relative error "
                f"{bv.reference_error:+.2e}",
                f"    Hausdorff        {s.hausdorff:12.4f} {u}    {s.hausdorff / height:.2%} of the height, "
                f"{s.hausdorff / bv.thickness:.2%} of the mean thickness",
                f"    max pointwise    {s.max_pointwise:12.4f} {u}    {s.max_pointwise / height:.2%} of the height, "
                f"{s.max_pointwise / bv.thickness:.2%} of the mean thickness (upper point {s.max_pointwise_index})",
            ]
            out += [f"    hole {k} Hausdorff {h.hausdorff:11.4f} {u}    {h.hausdorff / height:.2%} of the height, "
                    f"max pointwise {h.max_pointwise:.4f} {u} ({h.max_pointwise / height:.2%})"
                    for k, h in enumerate(bv.holes)]
            sd = self.stresses[i] if i < len(self.stresses) else None
            if sd is not None:
                out += [
                    f"    von Mises peak   {sd.von_mises_fast:12.4g} fast, {sd.von_mises_reference:.4g} reference "
                    f"({sd.von_mises_peak_error:+.1%}), farther than {sd.radius:.3g} {u} from its "
                    f"{sd.singular_points} singular point(s)",
                    f"    pressure         {sd.pressure_min_fast:.4g} to {sd.pressure_max_fast:.4g} fast, "
                    f"{sd.pressure_min_reference:.4g} to {sd.pressure_max_reference:.4g} reference "
                    f"(extremes {sd.pressure_peak_error:.1%} of the largest apart)",
                    f"    at {sd.samples} common nodes: von Mises L2 {sd.von_mises_l2:.1%}, max "
                    f"{sd.von_mises_max:.1%}; pressure L2 {sd.pressure_l2:.1%}, max {sd.pressure_max:.1%}",
                ]
        units = contact_units(u, self.revolution)
        force = f"{units['force']}, the whole ring" if self.revolution else units["force"]
        for c in self.contacts:
            out += [
                f"  rigid {c['name']!r}: force [{c['force_fast'][0]:.5g}, {c['force_fast'][1]:.5g}] fast, "
                f"[{c['force_reference'][0]:.5g}, {c['force_reference'][1]:.5g}] reference ({force}), "
                f"{c['force_error']:.2%} apart",
                f"    contact length {c['length_fast']:.4g} fast, {c['length_reference']:.4g} reference {u} "
                f"({c['length_error']:+.1%}); peak pressure {c['pressure_max_fast']:.4g} fast, "
                f"{c['pressure_max_reference']:.4g} reference {units['pressure']}",
            ]
        return out + [
            f"  time fast        {1e3 * self.fast_seconds:12.2f} ms",
            f"  time reference   {1e3 * self.reference_seconds:12.0f} ms   ({self.reference.note})  "
            f"speed ratio {self.speed_ratio:,.0f}",
        ]


def _time_fast(problem, model: str | None, runs: int):
    """The fast model's result on a problem and its median time."""
    from ..deform import Deformer

    times, result = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        result = Deformer(problem, model=model).deform()
        times.append(time.perf_counter() - t0)
    return result, statistics.median(times)


def _row(problem, i: int, fb, rb) -> BodyValidation:
    """Body ``i``'s comparison of the fast result ``fb`` and the reference's ``rb``."""
    upper = np.asarray(rb.upper)
    if fb.upper.shape != upper.shape:  # pragma: no cover - both take the body's section's upper points
        raise CaseError(f"bodies[{i}]", f"the fast model gives {len(fb.upper)} upper points and the reference "
                        f"{len(upper)}; they cannot be compared point by point")
    thickness = fb.area_initial / problem.bodies[i].lower.length
    fast_holes, ref_holes = tuple(getattr(fb, "holes", ())), tuple(np.asarray(h) for h in getattr(rb, "holes", ()))
    if len(fast_holes) != len(ref_holes) or any(a.shape != b.shape for a, b in zip(fast_holes, ref_holes)):  # pragma: no cover
        raise CaseError(f"bodies[{i}].holes", "the fast model's holes and the reference's differ in number or points; "
                        "they cannot be compared point by point")

    def closed(h):
        return np.concatenate((h, h[:1]))

    return BodyValidation(
        name=fb.name, shape=compare_curves(fb.upper, upper, scale=thickness), thickness=thickness,
        measure=fb.measure, target=fb.target, fast_final=fb.final, reference_final=rb.final,
        fast_error=fb.relative_error, reference_error=rb.relative_error,
        area_polygon=abs(polygon_area(np.concatenate((fb.lower, upper[1:-1])))) - sum(abs(polygon_area(h))
                                                                                        for h in ref_holes),
        holes=tuple(compare_curves(closed(a), closed(b), scale=thickness) for a, b in zip(fast_holes, ref_holes)),
    )


def validate(
    problem,
    *,
    model: str | None = None,
    mesh_size: float = DEFAULT_MESH_SIZE,
    bulk_to_shear: float | None = None,
    fast_runs: int = FAST_RUNS,
    reference=None,
    progress=None,
) -> Validation:
    """Run a fast model and a reference on a problem and compare them body by body.

    Parameters
    ----------
    problem : Problem
        One body or several, plane or of revolution.
    model : str, optional
        The fast model to check, ``"paper"`` or ``"hyperelastic"``; by
        default the problem's ``options.model``.
    mesh_size : float
        Reference element size, fraction of each body's mesh scale.
    bulk_to_shear : float, optional
        κ / μ of the reference; by default the materials', else the case's, else 1000.
    fast_runs : int
        Runs of the fast model; its time is their median.
    reference : Reference or ReferenceRun, optional
        A reference already solved on this problem (its own time is
        reported), e.g. CalculiX's; by default the project's finite elements
        are solved here.
    progress : callable, optional
        Called with one line of text per stage of the reference solve.

    Returns
    -------
    Validation

    Raises
    ------
    SectionDeformError
        Whatever either model raises (bad geometry, no convergence...).
    MissingExtraError
        Without the extra ``[fem]``.
    """
    if reference is None:
        require("skfem", "fem", "the finite-element reference")
        require("triangle", "fem", "the finite-element reference")
        check_parameters(mesh_size, problem.options.for_model("hyperelastic").bulk_to_shear
                         if bulk_to_shear is None else bulk_to_shear)
    fast, fast_s = _time_fast(problem, model, max(1, int(fast_runs)))
    if progress is not None:
        progress(f"validate: {fast.model} model done in {1e3 * fast_s:.1f} ms"
                 f"{'; solving the reference' if reference is None else ''}")
    if reference is None:
        reference = solve_reference(problem, mesh_size=mesh_size, bulk_to_shear=bulk_to_shear, progress=progress)
    if isinstance(reference, Reference):
        reference = fem_run(reference)
    rows = tuple(_row(problem, i, fb, rb) for i, (fb, rb) in enumerate(zip(fast.bodies, reference.bodies)))
    uppers = np.concatenate([b.initial_upper for b in fast.bodies])
    stresses = ()
    if isinstance(reference.solution, Reference):
        stresses = tuple(_stress_distance(problem, fast, reference.solution, b) for b in range(len(rows)))
    return Validation(problem=problem, fast=fast, reference=reference, bodies=rows,
                      height=section_height(problem.layout.fine["support"], uppers), fast_seconds=fast_s,
                      stresses=stresses)


def draw_validation(validation: Validation, fig=None):
    """Overlay the fast and reference deformed bodies.

    Each body: the reference's deformed mesh (grey edges) and outline
    (blue), the fast model's outline (dashed orange), its upper curve
    coloured by the distance to the reference's; the largest pointwise gap in red.

    Returns
    -------
    matplotlib.figure.Figure
    """
    require("matplotlib", "plot", "drawing the validation figure")
    from matplotlib.collections import LineCollection, PolyCollection

    v = validation
    r, u = v.reference, v.problem.units
    if fig is None:
        from ..plot import new_figure

        fig = new_figure(figsize=(10, 6), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    for mesh in r.meshes:
        corners = 3 if mesh.kind.startswith("triangle") else 4
        ax.add_collection(PolyCollection(mesh.points[mesh.cells[:, :corners]], facecolors="none", edgecolors="0.75",
                                         linewidths=0.2, zorder=1))
    uppers = [np.asarray(rb.upper) for rb in r.bodies]
    dists = [point_to_curve_distance(fb.upper, ru) for fb, ru in zip(v.fast.bodies, uppers)]
    top = max(float(d.max()) for d in dists) or 1.0
    lc = None
    for k, (fb, ru, d) in enumerate(zip(v.fast.bodies, uppers, dists)):
        first = k == 0
        ax.fill(*fb.initial_contour.T, color="0.92", zorder=0, label="initial" if first else None)
        ax.plot(*np.concatenate((fb.lower, ru[1:-1], fb.lower[:1])).T, color="tab:blue", lw=1.2, zorder=2,
                label="reference" if first else None)
        ax.plot(*np.concatenate((fb.contour, fb.contour[:1])).T, "--", color="tab:orange", lw=1.2, zorder=3,
                label=f"fast ({v.model} model)" if first else None)
        lc = LineCollection(np.stack((fb.upper[:-1], fb.upper[1:]), axis=1), cmap="viridis", linewidths=3.0, zorder=4)
        lc.set_array(0.5 * (d[:-1] + d[1:]))
        lc.set_clim(0.0, top)
        ax.add_collection(lc)
    worst = max(range(len(v.bodies)), key=lambda b: v.bodies[b].shape.max_pointwise)
    i, gap = v.bodies[worst].shape.max_pointwise_index, v.bodies[worst].shape.max_pointwise
    ax.plot(*np.stack((v.fast.bodies[worst].upper[i], uppers[worst][i])).T, "-o", color="tab:red", ms=3, lw=1,
            zorder=5, label=f"largest pointwise gap {gap:.3g} {u}")
    fig.colorbar(lc, ax=ax, shrink=0.6, aspect=30).set_label(f"distance of the fast upper curve to the reference ({u})")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(loc="best", fontsize=8)
    per_body = "; ".join(f"{b.name} {b.shape.hausdorff:.3g} {u}" for b in v.bodies)
    ax.set_title(f"{v.problem.name}: Hausdorff {per_body}; {1e3 * v.fast_seconds:.1f} ms vs "
                 f"{v.reference_seconds:.2f} s", fontsize=9)
    return fig


def save_validation_figure(validation: Validation, path) -> Path:
    """Draw :func:`draw_validation` and write it atomically to ``path`` (.png, .svg or .pdf).

    Raises
    ------
    CaseError
        If the extension or folder is wrong.
    MissingExtraError
        Without matplotlib.
    """
    from ..io import check_figure_path
    from ..plot import write_figure

    check_figure_path(path)
    return write_figure(draw_validation(validation), path)
