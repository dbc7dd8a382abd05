"""The pipeline: case -> section -> model -> result, once or for many targets.

>>> import sectiondeform as sd
>>> deformer = sd.Deformer(sd.load_case(sd.example_case_path()))
>>> result = deformer.deform()                      # the case's own target
>>> round(result.area_final, 1)
3503.2

``Deformer`` keeps the section, its mesh and the point locations, so
``deformer.deform(other_target)`` redoes only the final mesh, the law's
solve and the placement: the interactive use.

Prepare once, place many: the lower curve was sampled finely enough for the
case's own target. Another target is sampled at the same arc-length
fractions; where it bends more than the case's target, the deformed lower
polyline strays from it. Every placement measures that deviation (the
target's points at the mid-fractions against the chords' midpoints) and,
above the section's chordal error, says so in ``result.warnings`` with the
number and the fix (build a :class:`Deformer` on a case with that target).

A section that would come out turned over -- the case's lower curve drawn
the other way than its target, so the section hangs on the other side of
the support -- is refused with :class:`~sectiondeform.errors.GeometryError`.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import shapely

from .case import Case
from .curves import Curve, Polyline, as_points
from .errors import CaseError, GeometryError, LawError, MeshError
from .laws import Law
from .models import get_model
from .result import Result, ResultQuality
from .section import build_section, polygon_area
from .verify import check_placement, inverted

__all__ = ["Deformer", "deform", "AREA_TOLERANCE", "TARGET_DEVIATION_SLACK"]

AREA_TOLERANCE = 1e-9
TURNED_OVER_NEAR = 0.05  # a target this close to the reversed lower curve (fraction of its length) is a drawing error
TARGET_DEVIATION_SLACK = 1.5
"""A target is reported as under-sampled when it strays from the deformed lower
polyline by more than this times the section's chordal error."""


def _centroid(ring: np.ndarray) -> np.ndarray:
    """Area centroid of a closed polygon ``(N, 2)``."""
    x, y = ring[:, 0], ring[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    a = c.sum()
    if a == 0:
        return ring.mean(axis=0)
    return np.array([((x + x1) * c).sum(), ((y + y1) * c).sum()]) / (3.0 * a)


class Deformer:
    """A section prepared once for deformation onto any number of targets.

    Parameters
    ----------
    case : Case
    model : str, optional
        A name of :data:`~sectiondeform.models.MODEL_NAMES`; by default ``case.options.model``.
    element_size : float, optional
        Element size of the layered mesh, units; overrides the case's.
    check : bool
        Check every deformed contour for self-intersection (shapely).

    Attributes
    ----------
    section : Section
    prepared : Prepared
        The model's section-dependent state (mesh, locations).
    """

    def __init__(self, case: Case, model: str | None = None, element_size: float | None = None, check: bool = True):
        t0 = time.perf_counter()
        self.case = case
        self.model_name = model or case.model
        self.model = get_model(self.model_name)
        self.section = build_section(case, element_size)
        self.prepared = self.model.prepare(self.section, case.options.for_model(self.model_name))
        bad = inverted(self.prepared.initial_mesh)  # checked once per section, independently of the model
        if bad:
            raise MeshError(f"initial mesh: {bad}; lower options.element_size or smooth the section's corners")
        self.check = check
        self.prepare_seconds = time.perf_counter() - t0

    def target_nodes(self, target: Curve | np.ndarray | None = None) -> np.ndarray:
        """The target at the lower nodes' arc-length fractions, ``(n, 2)``.

        ``target`` may be a :class:`~sectiondeform.curves.Curve`, any
        ``(k, 2)`` polyline (k >= 2, taken as a :class:`~sectiondeform.curves.Polyline`),
        or None for the case's own.
        """
        return self._sample(self._target_curve(target))

    def _target_curve(self, target) -> Curve:
        if target is None:
            return self.case.target
        if isinstance(target, Curve):
            return target
        return Polyline(as_points(target, "target", min_count=2))

    def _sample(self, curve: Curve) -> np.ndarray:
        return self._checked_nodes(curve.at_fractions(self.section.fractions))

    def _checked_nodes(self, nodes) -> np.ndarray:
        nodes = as_points(nodes, "target_nodes", min_count=2)
        if len(nodes) != len(self.section.fractions):
            raise CaseError(
                "target_nodes",
                f"expected {len(self.section.fractions)} nodes (one per lower node), got {len(nodes)}; "
                "give the target as a curve or polyline instead",
            )
        steps = nodes[1:] - nodes[:-1]
        length = np.hypot(steps[:, 0], steps[:, 1]).sum()
        if not length > 1e-9 * self.section.lower_length:
            raise CaseError("target", "the target has zero length")
        return nodes

    def target_deviation(self, target: Curve | np.ndarray | None = None) -> float:
        """Largest distance, in units, between the target and its polyline at the lower fractions.

        Measured at the middle of every step: the target's point at the
        mid-fraction against the midpoint of the chord. Compare with
        ``section.chordal_error``.
        """
        curve = self._target_curve(target)
        return self._deviation(curve, curve.at_fractions(self.section.fractions))

    def _deviation(self, curve: Curve, nodes: np.ndarray) -> float:
        """:meth:`target_deviation` of ``curve`` given its ``nodes`` at the lower fractions (not sampled twice)."""
        s = self.section.fractions
        mids = curve.at_fractions(0.5 * (s[1:] + s[:-1]))
        d = mids - 0.5 * (nodes[1:] + nodes[:-1])
        return float(np.hypot(d[:, 0], d[:, 1]).max())

    def deform(self, target: Curve | np.ndarray | None = None, law: Law | None = None, *,
               target_nodes: np.ndarray | None = None, start: Result | None = None) -> Result:
        """Deform the section onto ``target`` under ``law`` (the case's by default).

        Parameters
        ----------
        target : Curve or (k, 2) array_like, optional
            The deformed lower curve, A' to B', units: a curve, or any
            polyline (it need not have one node per lower node). By default
            the case's own target.
        law : Law, optional
        target_nodes : (n, 2) array_like, optional
            Fast path for dragging: the target already at the lower nodes'
            arc-length fractions (``section.fractions``), one node per lower
            node, instead of ``target``. No deviation is measured.
        start : Result, optional
            An earlier result of this deformer to start the solve from (a warm
            start; the hyperelastic model only). Without it the answer
            depends on the arguments alone, bit for bit.

        Returns
        -------
        Result

        Raises
        ------
        MeshError
            If the final mesh would have an inverted element.
        LawError
            If the law cannot be met to 1e-9.
        GeometryError
            If the deformed contour crosses itself, or the section would come
            out turned over.
        CaseError
            If the target is not a curve or a polyline of finite points.
        """
        return self._run(self.prepared.place, target, law, target_nodes, start)

    def preview(self, target: Curve | np.ndarray | None = None, law: Law | None = None, *,
                target_nodes: np.ndarray | None = None, start: Result | None = None) -> Result:
        """A fast deformation for dragging the target (interactive preview).

        The paper model answers exactly as :meth:`deform`; the hyperelastic
        model takes one linearised step from ``start`` (a result of this
        deformer) or from the undeformed section, meeting the law exactly
        but first-order in the change of target (``result.info.preview`` is
        True): call :meth:`deform` when the drag ends. Arguments as
        :meth:`deform`.
        """
        return self._run(self.prepared.preview, target, law, target_nodes, start)

    def _run(self, placer, target, law, target_nodes=None, start=None) -> Result:
        """Place with ``placer`` (the model's ``place`` or ``preview``), check, explain a refusal."""
        t0 = time.perf_counter()
        law = law or self.case.law
        warnings: list[str] = []
        if target_nodes is not None:
            if target is not None:
                raise CaseError("target_nodes", "give either target or target_nodes, not both")
            nodes = self._checked_nodes(target_nodes)
        else:
            curve = self._target_curve(target)
            nodes = self._sample(curve)
            deviation = self._deviation(curve, nodes)
            tol = self.section.chordal_error
            if deviation > TARGET_DEVIATION_SLACK * tol:
                warnings.append(
                    f"target: the deformed lower curve strays {deviation:.3g} {self.case.units} from the target "
                    f"(chordal error {tol:.3g}): the section was sampled for another target; "
                    "build a Deformer on a case with this target for a resolved lower curve"
                )
        state = start.state if start is not None else None
        try:
            with np.errstate(all="ignore"):
                placement = placer(nodes, law, state)
                result = self._result(nodes, placement, law, t0, tuple(warnings))
        except (MeshError, LawError, GeometryError) as exc:
            better = self._explained(exc)
            if better is exc:
                raise
            raise better from exc
        if target is None and target_nodes is None:
            result = self._check_not_turned_over(result)
        return result

    def _check_not_turned_over(self, result: Result) -> Result:
        """Refuse, or flag, a section that comes out on the other side of the case's target than of its lower curve.

        That happens when the lower curve is drawn the other way than the
        target (B to A) on the same support: the target starts near the lower
        curve's end B and ends near its start A, and the deformed section
        lies on the other side of the target than the initial one of the
        lower curve. The map then turns the section over to hang under the
        support. When the target is the lower curve reversed (ends and
        points within ``TURNED_OVER_NEAR`` of its length), that is refused;
        when it is only near it (a quarter of the length: a half turn on
        purpose cannot be told from a drawing error), the result carries a
        warning.
        """
        low0, low1 = result.initial_lower, result.lower
        length = self.section.lower_length
        ends = max(np.hypot(*(low1[0] - low0[-1])), np.hypot(*(low1[-1] - low0[0])))
        side0 = _centroid(result.initial_contour) - low0.mean(axis=0)
        side1 = _centroid(result.contour) - low1.mean(axis=0)
        if ends >= 0.25 * length or float(side0 @ side1) >= 0:
            return result
        fix = "reverse the lower curve or the target"
        apart = shapely.hausdorff_distance(shapely.linestrings(low0), shapely.linestrings(low1))
        if ends < TURNED_OVER_NEAR * length and apart < TURNED_OVER_NEAR * length:
            raise GeometryError(
                "target: the section would come out turned over, on the other side of the target than of "
                f"its lower curve (the lower curve runs the other way than the target); {fix}"
            )
        note = (f"target: its ends are within {ends / length:.2g} of the lower curve's length of the lower curve's "
                "ends swapped and the section comes out on the other side of it (turned over); "
                f"if the lower curve was drawn the other way than the target, {fix}")
        return dataclasses.replace(result, warnings=(*result.warnings, note))

    def _explained(self, exc: Exception) -> Exception:
        """The refusal ``exc`` with the likeliest cause the user can fix: a long straight upper segment.

        Only the upper curve's characteristic points are mapped, so a long
        segment of an upper polyline stays a straight chord in the deformed
        contour, however much the target bends under it.
        """
        up = self.section.upper
        seg = np.hypot(*np.diff(up, axis=0).T)
        i = int(np.argmax(seg))
        if seg[i] <= 2.0 * self.section.mesh_scale:
            return exc
        return type(exc)(
            f"{exc}; note: upper segment {i} ({np.round(up[i], 6).tolist()} to {np.round(up[i + 1], 6).tolist()}, "
            f"length {seg[i]:.6g}) stays a straight chord in the deformed section: split it into shorter segments"
        )

    def _result(self, nodes, placement, law, t0, warnings=()) -> Result:
        """Check a placement (area law, simple contour) and wrap it in a :class:`Result`."""
        sec = self.section
        contour = np.concatenate((nodes, placement.upper[1:-1]))
        if not (np.isfinite(contour).all() and np.isfinite(placement.final_mesh.points).all()):
            raise GeometryError("result: the deformation produced non-finite points; the target or the law is too severe for this section")
        final = abs(polygon_area(contour))
        wanted = law.target_area(sec.area)
        if abs(final - wanted) > AREA_TOLERANCE * wanted:
            raise LawError(f"law: the final area {final:.9g} misses the target {wanted:.9g} by more than 1e-9")
        if self.check and not shapely.is_simple(shapely.linearrings(contour)):
            raise GeometryError("result: the deformed contour crosses itself; the target or the law is too severe for this section")
        seconds = time.perf_counter() - t0
        result = Result(
            name=self.case.name,
            units=self.case.units,
            model=self.model_name,
            lower=nodes,
            upper=placement.upper,
            initial_lower=sec.lower,
            initial_upper=sec.upper,
            area_initial=sec.area,
            area_target=wanted,
            area_final=final,
            initial_mesh=self.prepared.initial_mesh,
            final_mesh=placement.final_mesh,
            quality=ResultQuality(self.prepared.quality, placement.quality),
            info=placement.info,
            timings={"prepare_s": self.prepare_seconds, "place_s": seconds},
            warnings=tuple(warnings) + tuple(placement.warnings),
            state=placement.state,
        )
        failed = check_placement(result)  # independent checks: no NaN, no final element inverted anywhere
        if failed:
            kind = MeshError if "mesh" in failed[0].split(":")[0] else GeometryError
            raise kind(f"result: refused, an independent check failed: {failed[0]}")
        return result


def deform(case: Case, model: str | None = None, element_size: float | None = None) -> Result:
    """Deform a case once: :class:`Deformer` then :meth:`Deformer.deform`.

    Parameters
    ----------
    case : Case
    model : str, optional
        ``"paper"`` (default) or ``"hyperelastic"``.
    element_size : float, optional
        Element size, units.

    Returns
    -------
    Result
    """
    return Deformer(case, model, element_size).deform()
