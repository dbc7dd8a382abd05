"""The fast method against the finite-element reference on one case (extra ``[fem]``).

:func:`validate_case` runs both on the same case and measures the distance
between the two deformed upper curves (:mod:`sectiondeform.compare`), their
areas (volumes, for a body of revolution) and their times. A version-2 case
of one body goes through the assembly path of the fast models
(:class:`~sectiondeform.assembly_deform.AssemblyDeformer`, which takes a
body of revolution and its volume law), the reference through its one-body
assembly solve; :func:`save_validation_figure` overlays the two
deformed sections. An assembly of several bodies goes to
:func:`validate_assembly`: the reference of all bodies at once
(:mod:`sectiondeform.reference.assembly`) and per-body figures.
``sectiondeform validate`` and ``benchmarks/validation.py`` are thin
layers over these.

Timing is fair to both: each is timed from the case to the deformed upper
points (section, mesh, solve), after the libraries are imported; the fast
method's time is the median of a few runs (it takes milliseconds), the
reference's a single run at its default, converged, mesh size.
"""

from __future__ import annotations

import statistics
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..assembly_result import AssemblyResult
from ..case import Case
from ..compare import CurveComparison, compare_curves, point_to_curve_distance, section_height
from ..deform import Deformer
from ..errors import CaseError, require
from ..io import check_figure_path
from ..result import Result
from ..section import polygon_area
from . import DEFAULT_MESH_SIZE, ReferenceSolution, check_parameters, solve_reference

__all__ = ["Validation", "AssemblyValidation", "BodyValidation", "validate_case", "validate_assembly",
           "save_validation_figure", "VALIDATION_FORMAT"]

VALIDATION_FORMAT = "section-validation/1"
FAST_RUNS = 5


@dataclass(frozen=True, eq=False)
class Validation:
    """Fast result, reference solution and the distances between them.

    Attributes
    ----------
    case : Case
    fast : Result or BodyResult
        The fast model's result: of the version-1 case, or of the one body
        of a version-2 case (then ``assembly`` holds the whole result).
    reference : ReferenceSolution
    shape : CurveComparison
        Fast upper curve against the reference's, relative figures over the
        mean thickness (kept for the report's ``shape`` keys).
    thickness : float
        Mean thickness, area / lower length, units. It overstates the size
        of a section wider than its base (a lip on a short foot).
    height : float
        The section's height above its lower curve, units
        (:func:`~sectiondeform.compare.section_height`): the size the
        distances are read against (``docs/validation.md``).
    area_reference : float
        Area of the deformed finite-element body, ∫ det F2D dA, units².
    area_reference_polygon : float
        Area of the polygon of the fast result's lower nodes and the
        reference's upper points (the polygon the fast area is measured
        on), units². It differs from ``area_reference`` where the reference
        bends the straight upper segments between characteristic points.
    fast_seconds, reference_seconds : float
        Wall times, case to deformed shape.
    assembly : AssemblyResult or None
        The fast model's whole result of a version-2 case; None for a
        version-1 case.
    """

    case: Case
    fast: Result
    reference: ReferenceSolution
    shape: CurveComparison
    thickness: float
    height: float
    area_reference: float
    area_reference_polygon: float
    fast_seconds: float
    reference_seconds: float
    assembly: AssemblyResult | None = None

    @property
    def model(self) -> str:
        """The fast model checked, ``"paper"`` or ``"hyperelastic"``."""
        return self.assembly.model if self.assembly is not None else self.fast.model

    @property
    def revolution(self) -> bool:
        """True for a body of revolution (the law and the figures are volumes)."""
        return self.reference.revolution

    @property
    def volume_relative_errors(self) -> tuple[float, float] | None:
        """(fast, reference) relative volume errors against the law's target; None in plane."""
        if not self.revolution:
            return None
        f, r = self.fast, self.reference
        return (f.volume_final - f.volume_target) / f.volume_target, r.relative_volume_error

    @property
    def speed_ratio(self) -> float:
        """Reference time over fast time."""
        return self.reference_seconds / self.fast_seconds

    @property
    def pointwise_distance(self) -> np.ndarray:
        """Distance between corresponding upper points, ``(m,)``, units."""
        return np.hypot(*(self.fast.upper - self.reference.upper).T)

    def _area_error(self, area: float) -> float | None:
        target = self.fast.area_target
        return None if target is None else (area - target) / target

    def to_json(self) -> dict:
        """The ``section-validation/1`` report.

        A body of revolution has no area target (its law sets the volume):
        the area errors are None and a ``volume`` object gives the volumes
        of revolution (Pappus, units³) of both models and their errors
        against the law's target, with the axis under ``revolution``.
        """
        f, r = self.fast, self.reference
        out = {
            "format": VALIDATION_FORMAT,
            "name": self.case.name,
            "units": self.case.units,
            "thickness": self.thickness,
            "height": self.height,
            "hausdorff_over_height": self.shape.hausdorff / self.height,
            "max_pointwise_over_height": self.shape.max_pointwise / self.height,
            "area": {"initial": f.area_initial, "target": f.area_target},
            "fast": {
                "model": self.model,
                "area_final": f.area_final,
                "area_relative_error": self._area_error(f.area_final),
                "seconds": self.fast_seconds,
                "upper": f.upper.tolist(),
            },
            "reference": {
                "model": f"finite elements: {r.material.model if r.material is not None else 'neo-hookean'}, "
                         f"{'body of revolution' if r.revolution else 'generalised plane strain'}, P2/P1 Taylor-Hood",
                "area_final": self.area_reference,
                "area_relative_error": self._area_error(self.area_reference),
                "area_polygon": self.area_reference_polygon,
                "seconds": self.reference_seconds,
                "solver": r.summary(),
                "upper": r.upper.tolist(),
            },
            "shape": self.shape.to_json(),
            "pointwise_distance": self.pointwise_distance.tolist(),
            "speed_ratio": self.speed_ratio,
        }
        if self.revolution:
            fast_err, ref_err = self.volume_relative_errors
            out["revolution"] = {"axis": [list(map(float, p)) for p in self.assembly.axis]}
            out["volume"] = {"initial": f.volume_initial, "target": f.volume_target}
            out["fast"].update(volume_final=f.volume_final, volume_relative_error=fast_err)
            out["reference"].update(volume_final=r.volume_final, volume_relative_error=ref_err)
        return out

    def lines(self) -> list[str]:
        """A short human-readable summary."""
        u, height = self.case.units, self.height
        f, r, s = self.fast, self.reference, self.shape
        head = [
            f"{self.case.name}: {self.model} model against the finite-element reference"
            f"{' (body of revolution)' if self.revolution else ''} "
            f"(height {height:.4g} {u}, mean thickness {self.thickness:.4g} {u})",
        ]
        if self.revolution:
            fast_err, ref_err = self.volume_relative_errors
            head += [
                f"  volume target    {f.volume_target:12.6g} {u}³",
                f"  volume fast      {f.volume_final:12.6g} {u}³   relative error {fast_err:+.2e}",
                f"  volume reference {r.volume_final:12.6g} {u}³   relative error {ref_err:+.2e} "
                f"(bulk/shear {r.bulk_to_shear:g}: volume change {r.volume_change:+.2e})",
                f"  area fast        {f.area_final:12.4f} {u}²   reference {self.area_reference:.4f} {u}² "
                f"(initial {f.area_initial:.4f} {u}²)",
            ]
        else:
            target = f.area_target
            head += [
                f"  area target      {target:12.4f} {u}²",
                f"  area fast        {f.area_final:12.4f} {u}²   relative error {self._area_error(f.area_final):+.2e}",
                f"  area reference   {self.area_reference:12.4f} {u}²   relative error "
                f"{self._area_error(self.area_reference):+.2e} (bulk/shear {r.bulk_to_shear:g}: "
                f"volume change {r.volume_change:+.2e})",
            ]
        return head + [
            f"  Hausdorff        {s.hausdorff:12.4f} {u}    {s.hausdorff / height:.2%} of the height, "
            f"{s.hausdorff / self.thickness:.2%} of the mean thickness",
            f"  max pointwise    {s.max_pointwise:12.4f} {u}    {s.max_pointwise / height:.2%} of the height, "
            f"{s.max_pointwise / self.thickness:.2%} of the mean thickness (upper point {s.max_pointwise_index})",
            f"  time fast        {1e3 * self.fast_seconds:12.2f} ms",
            f"  time reference   {1e3 * self.reference_seconds:12.0f} ms   ({r.elements} elements, {r.dofs} unknowns, "
            f"{r.iterations} Newton iterations)  speed ratio {self.speed_ratio:,.0f}",
        ]


def _time_fast(case, model: str | None, runs: int) -> tuple[Result | AssemblyResult, float]:
    """The fast model's result on a case (a version-2 one through the assembly path) and its median time."""
    from ..assembly import Assembly
    from ..assembly_deform import AssemblyDeformer

    deformer = AssemblyDeformer if isinstance(case, Assembly) else Deformer
    times, result = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        result = deformer(case, model=model).deform()
        times.append(time.perf_counter() - t0)
    return result, statistics.median(times)


def validate_case(
    case: Case,
    *,
    model: str | None = None,
    mesh_size: float = DEFAULT_MESH_SIZE,
    bulk_to_shear: float | None = None,
    fast_runs: int = FAST_RUNS,
    progress=None,
) -> Validation:
    """Run the fast model and the finite-element reference on a case and compare them.

    Parameters
    ----------
    case : Case or Assembly
        A version-1 case, or a version-2 case of one body: the fast model
        then deforms it as an assembly (so ``revolution`` and a volume law
        are taken), the reference uses its ``material`` and ``revolution``,
        and the figures are the body's. An assembly of several bodies goes
        to :func:`validate_assembly` (per-body figures).
    model : str, optional
        The fast model to check, ``"paper"`` or ``"hyperelastic"``; by
        default the case's ``options.model``.
    mesh_size : float
        Reference element size, fraction of the mean thickness T.
    bulk_to_shear : float, optional
        κ / μ of the reference; by default the case's, else 1000.
    fast_runs : int
        Runs of the fast model; its time is their median.
    progress : callable, optional
        Called with one line of text per stage of the reference solve.

    Returns
    -------
    Validation or AssemblyValidation

    Raises
    ------
    SectionDeformError
        Whatever either model raises (bad geometry, no convergence...).
    MissingExtraError
        Without the extra ``[fem]``.
    """
    from ..assembly import Assembly

    source = case
    if isinstance(case, Assembly):
        if len(case.bodies) != 1:
            return validate_assembly(case, model=model, mesh_size=mesh_size, bulk_to_shear=bulk_to_shear,
                                     fast_runs=fast_runs, progress=progress)
        case = case.body_case(0)
    require("skfem", "fem", "the finite-element reference")
    require("triangle", "fem", "the finite-element reference")
    check_parameters(mesh_size, case.options.for_model("hyperelastic").bulk_to_shear if bulk_to_shear is None else bulk_to_shear)
    whole, fast_s = _time_fast(source, model, max(1, int(fast_runs)))
    fast, assembly = (whole.bodies[0], whole) if isinstance(whole, AssemblyResult) else (whole, None)
    if progress is not None:
        progress(f"validate: {whole.model} model done in {1e3 * fast_s:.1f} ms; solving the reference")
    t0 = time.perf_counter()
    ref = solve_reference(source, mesh_size=mesh_size, bulk_to_shear=bulk_to_shear, progress=progress)
    ref_s = time.perf_counter() - t0
    mean_thickness = fast.area_initial / case.lower.length
    shape = compare_curves(fast.upper, ref.upper, scale=mean_thickness)
    area_poly = abs(polygon_area(np.concatenate((fast.lower, ref.upper[1:-1]))))
    return Validation(
        case=case,
        fast=fast,
        reference=ref,
        shape=shape,
        thickness=mean_thickness,
        height=section_height(fast.initial_lower, fast.initial_upper),
        area_reference=ref.area_final,
        area_reference_polygon=area_poly,
        fast_seconds=fast_s,
        reference_seconds=ref_s,
        assembly=assembly,
    )


@dataclass(frozen=True, eq=False)
class BodyValidation:
    """One body of an assembly: the fast model's upper curve and law against the reference's.

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
        Their relative errors, each against its own target (the reference's
        is r × the area, or v × the volume, of its own mesh).
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


@dataclass(frozen=True, eq=False)
class AssemblyValidation:
    """An assembly of several bodies: the fast model against the finite-element reference, per body.

    Attributes
    ----------
    case : Assembly
    assembly : AssemblyResult
        The fast model's result.
    reference : AssemblyReference
    bodies : tuple of BodyValidation
    height : float
        The assembly's height above its support: the largest distance of a
        body's upper point from the support, units.
    fast_seconds, reference_seconds : float
        Wall times, case to deformed shape.
    """

    case: object
    assembly: AssemblyResult
    reference: object
    bodies: tuple
    height: float
    fast_seconds: float
    reference_seconds: float

    @property
    def model(self) -> str:
        """The fast model checked."""
        return self.assembly.model

    @property
    def revolution(self) -> bool:
        """True for a body of revolution."""
        return self.reference.revolution

    @property
    def speed_ratio(self) -> float:
        """Reference time over fast time."""
        return self.reference_seconds / self.fast_seconds

    def to_json(self) -> dict:
        """The ``section-validation/1`` report of an assembly: the whole, then a ``bodies`` list."""
        r = self.reference
        kind = "body of revolution" if self.revolution else "generalised plane strain"
        out = {
            "format": VALIDATION_FORMAT,
            "name": self.case.name,
            "units": self.case.units,
            "height": self.height,
            "fast": {"model": self.model, "seconds": self.fast_seconds},
            "reference": {
                "model": f"finite elements: one mesh of {len(self.bodies)} bonded bodies, {kind}, P2/P1 Taylor-Hood",
                "seconds": self.reference_seconds,
                "solver": r.summary(),
            },
            "bodies": [],
            "speed_ratio": self.speed_ratio,
        }
        if self.revolution:
            out["revolution"] = {"axis": [list(map(float, p)) for p in self.assembly.axis]}
        for bv, fb, rb in zip(self.bodies, self.assembly.bodies, r.bodies):
            s = bv.shape
            out["bodies"].append({
                "name": bv.name,
                "thickness": bv.thickness,
                "hausdorff": s.hausdorff,
                "hausdorff_over_thickness": s.hausdorff / bv.thickness,
                "hausdorff_over_height": s.hausdorff / self.height,
                "max_pointwise": s.max_pointwise,
                "max_pointwise_over_thickness": s.max_pointwise / bv.thickness,
                "max_pointwise_over_height": s.max_pointwise / self.height,
                "measure": bv.measure,
                "target": bv.target,
                "fast": {"final": bv.fast_final, "relative_error": bv.fast_error, "upper": fb.upper.tolist()},
                "reference": {"final": bv.reference_final, "relative_error": bv.reference_error,
                              "load": rb.load, "upper": rb.upper.tolist()},
            })
        return out

    def lines(self) -> list[str]:
        """A short human-readable summary: one row per body."""
        u, r = self.case.units, self.reference
        names = ", ".join(b.name for b in self.bodies)
        out = [
            f"{self.case.name}: {self.model} model against the finite-element reference, {len(self.bodies)} bonded "
            f"bodies ({names}){' (body of revolution)' if self.revolution else ''}, height {self.height:.4g} {u}",
            f"  {'body':<14} {'T':>8} {'Hausdorff':>10} {'/ T':>7} {'/ height':>9} {'max pointwise':>13} "
            f"{'law':>6} {'fast rel. err.':>15} {'reference rel. err.':>20}",
        ]
        for b in self.bodies:
            s = b.shape
            out.append(
                f"  {b.name:<14} {b.thickness:8.4g} {s.hausdorff:10.4f} {s.hausdorff / b.thickness:7.2%} "
                f"{s.hausdorff / self.height:9.2%} {s.max_pointwise:13.4f} {b.measure:>6} {b.fast_error:+15.2e} "
                f"{b.reference_error:+20.2e}"
            )
        out += [
            f"  distances in {u}; law: each body's {'volume' if self.revolution else 'area'} against its target",
            f"  time fast        {1e3 * self.fast_seconds:12.2f} ms",
            f"  time reference   {1e3 * self.reference_seconds:12.0f} ms   ({r.elements} elements, {r.dofs} unknowns, "
            f"{r.iterations} Newton iterations)  speed ratio {self.speed_ratio:,.0f}",
        ]
        return out


def _assembly_height(case) -> float:
    """Largest distance of a body's upper point from the support, units."""
    from ..section import build_section

    support = case.layout.fine["support"]
    uppers = np.concatenate([build_section(case.body_case(b)).upper for b in range(len(case.bodies))])
    return section_height(support, uppers)


def validate_assembly(
    case,
    *,
    model: str | None = None,
    mesh_size: float = DEFAULT_MESH_SIZE,
    bulk_to_shear: float | None = None,
    fast_runs: int = FAST_RUNS,
    reference=None,
    progress=None,
) -> AssemblyValidation:
    """Run a fast model and the finite-element reference on an assembly and compare them body by body.

    Parameters
    ----------
    case : Assembly
        Any number of bodies.
    model, mesh_size, bulk_to_shear, fast_runs, progress
        As for :func:`validate_case`.
    reference : AssemblyReference, optional
        A reference already solved on this case (its own time is reported);
        by default solved here with :func:`~sectiondeform.reference.assembly.solve_assembly_reference`.

    Returns
    -------
    AssemblyValidation

    Raises
    ------
    SectionDeformError
        Whatever either model raises.
    MissingExtraError
        Without the extra ``[fem]``.
    """
    from .assembly import solve_assembly_reference

    require("skfem", "fem", "the finite-element reference")
    require("triangle", "fem", "the finite-element reference")
    check_parameters(mesh_size, case.options.for_model("hyperelastic").bulk_to_shear if bulk_to_shear is None else bulk_to_shear)
    whole, fast_s = _time_fast(case, model, max(1, int(fast_runs)))
    if progress is not None:
        progress(f"validate: {whole.model} model done in {1e3 * fast_s:.1f} ms"
                 f"{'; solving the reference' if reference is None else ''}")
    if reference is None:
        t0 = time.perf_counter()
        reference = solve_assembly_reference(case, mesh_size=mesh_size, bulk_to_shear=bulk_to_shear, progress=progress)
        ref_s = time.perf_counter() - t0
    else:
        ref_s = reference.seconds
    rows = []
    for b, (fb, rb) in enumerate(zip(whole.bodies, reference.bodies)):
        if fb.upper.shape != rb.upper.shape:  # pragma: no cover - both take the body's section's upper points
            raise CaseError(f"bodies[{b}]", f"the fast model gives {len(fb.upper)} upper points and the reference "
                            f"{len(rb.upper)}; they cannot be compared point by point")
        thickness = fb.area_initial / case.body_case(b).lower.length
        revolution = rb.volume_target is not None
        rows.append(BodyValidation(
            name=fb.name,
            shape=compare_curves(fb.upper, rb.upper, scale=thickness),
            thickness=thickness,
            measure="volume" if revolution else "area",
            target=fb.target,
            fast_final=fb.final,
            reference_final=rb.volume_final if revolution else rb.area_final,
            fast_error=(fb.final - fb.target) / fb.target,
            reference_error=rb.relative_error,
        ))
    return AssemblyValidation(case=case, assembly=whole, reference=reference, bodies=tuple(rows),
                              height=_assembly_height(case), fast_seconds=fast_s, reference_seconds=ref_s)


def draw_assembly_validation(validation: AssemblyValidation, fig=None):
    """Overlay the fast and reference deformed bodies of an assembly.

    Each body: the reference's deformed mesh (grey edges) and outline
    (blue), the fast model's outline (dashed orange), its upper curve
    coloured by the distance to the reference's.

    Returns
    -------
    matplotlib.figure.Figure
    """
    require("matplotlib", "plot", "drawing the validation figure")
    from matplotlib.collections import LineCollection, PolyCollection

    v = validation
    r, u = v.reference, v.case.units
    if fig is None:
        from ..plot import new_figure

        fig = new_figure(figsize=(10, 6), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    tri = r.mesh.points[r.mesh.cells[:, :3]]
    ax.add_collection(PolyCollection(tri, facecolors="none", edgecolors="0.75", linewidths=0.2, zorder=1))
    dists = [point_to_curve_distance(fb.upper, rb.upper) for fb, rb in zip(v.assembly.bodies, r.bodies)]
    top = max(float(d.max()) for d in dists) or 1.0
    lc = None
    for k, (fb, rb, d) in enumerate(zip(v.assembly.bodies, r.bodies, dists)):
        ax.fill(*fb.initial_contour.T, color="0.92", zorder=0, label="initial bodies" if k == 0 else None)
        ref_contour = np.concatenate((fb.lower, rb.upper[1:-1], fb.lower[:1]))
        ax.plot(*ref_contour.T, color="tab:blue", lw=1.2, zorder=2,
                label="finite-element reference" if k == 0 else None)
        fast_contour = np.concatenate((fb.contour, fb.contour[:1]))
        ax.plot(*fast_contour.T, "--", color="tab:orange", lw=1.2, zorder=3,
                label=f"fast ({v.model} model)" if k == 0 else None)
        segs = np.stack((fb.upper[:-1], fb.upper[1:]), axis=1)
        lc = LineCollection(segs, cmap="viridis", linewidths=3.0, zorder=4)
        lc.set_array(0.5 * (d[:-1] + d[1:]))
        lc.set_clim(0.0, top)
        ax.add_collection(lc)
    cb = fig.colorbar(lc, ax=ax, shrink=0.6, aspect=30)
    cb.set_label(f"distance of the fast upper curves to the reference's ({u})")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(loc="best", fontsize=8)
    per_body = "; ".join(f"{b.name} {b.shape.hausdorff:.3g} {u}" for b in v.bodies)
    ax.set_title(f"{v.case.name}: Hausdorff per body {per_body}; {1e3 * v.fast_seconds:.1f} ms vs "
                 f"{v.reference_seconds:.2f} s", fontsize=9)
    return fig


def draw_validation(validation: Validation, fig=None):
    """Overlay the fast and reference deformed sections, the upper curve coloured by distance.

    An :class:`AssemblyValidation` draws every body (:func:`draw_assembly_validation`).

    Returns
    -------
    matplotlib.figure.Figure
    """
    require("matplotlib", "plot", "drawing the validation figure")
    from matplotlib.collections import LineCollection, PolyCollection

    if isinstance(validation, AssemblyValidation):
        return draw_assembly_validation(validation, fig)
    v = validation
    f, r, u = v.fast, v.reference, v.case.units
    if fig is None:
        from ..plot import new_figure

        fig = new_figure(figsize=(10, 6), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    ax.fill(*f.initial_contour.T, color="0.92", zorder=0, label="initial section")
    tri = r.mesh.points[r.mesh.cells[:, :3]]
    ax.add_collection(PolyCollection(tri, facecolors="none", edgecolors="0.7", linewidths=0.25, zorder=1))
    ref_contour = np.concatenate((f.lower, r.upper[1:-1], f.lower[:1]))
    ax.plot(*ref_contour.T, color="tab:blue", lw=1.4, zorder=2, label="finite-element reference")
    fast_contour = np.concatenate((f.contour, f.contour[:1]))
    ax.plot(*fast_contour.T, "--", color="tab:orange", lw=1.4, zorder=3, label=f"fast ({v.model} model)")
    # Fast upper curve coloured by its distance to the reference upper curve.
    d_pts = point_to_curve_distance(f.upper, r.upper)
    segs = np.stack((f.upper[:-1], f.upper[1:]), axis=1)
    lc = LineCollection(segs, cmap="viridis", linewidths=3.5, zorder=4)
    lc.set_array(0.5 * (d_pts[:-1] + d_pts[1:]))
    ax.add_collection(lc)
    cb = fig.colorbar(lc, ax=ax, shrink=0.6, aspect=30)
    cb.set_label(f"distance of the fast upper curve to the reference ({u})")
    k = v.shape.max_pointwise_index
    ax.plot(*np.stack((f.upper[k], r.upper[k])).T, "-o", color="tab:red", ms=3, lw=1, zorder=5,
            label=f"largest pointwise gap {v.shape.max_pointwise:.3g} {u}")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(loc="best", fontsize=8)
    measure = (f"volumes {f.volume_final:.5g} (fast) / {v.reference.volume_final:.5g} (reference) {u}³" if v.revolution
               else f"areas {f.area_final:.1f} (fast) / {v.area_reference:.1f} (reference) {u}²")
    ax.set_title(
        f"{v.case.name}: Hausdorff {v.shape.hausdorff:.3g} {u} = {v.shape.hausdorff_relative:.1%} of T; "
        f"{measure}; {1e3 * v.fast_seconds:.1f} ms vs {v.reference_seconds:.2f} s",
        fontsize=9,
    )
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
    from ..plot import write_figure

    check_figure_path(path)
    return write_figure(draw_validation(validation), path)
