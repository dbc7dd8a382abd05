"""The pipeline: case -> section -> model -> result, once or for many targets.

>>> import sectiondeform as sd
>>> deformer = sd.Deformer(sd.load_case(sd.example_case_path()))
>>> result = deformer.deform()                      # the case's own target
>>> round(result.area_final, 1)
3503.2

``Deformer`` keeps the section, its mesh and the point locations, so
``deformer.deform(other_target)`` redoes only the final mesh, the law's
solve and the placement: the interactive use.
"""

from __future__ import annotations

import time

import numpy as np
import shapely

from .case import Case
from .checks import check_result
from .curves import Curve, as_points
from .errors import CaseError, GeometryError, LawError, MeshError
from .laws import Law
from .models import get_model
from .result import Result
from .section import build_section, polygon_area

__all__ = ["Deformer", "deform", "AREA_TOLERANCE"]

AREA_TOLERANCE = 1e-9


class Deformer:
    """A section prepared once for deformation onto any number of targets.

    Parameters
    ----------
    case : Case
    model : str, optional
        ``"paper"`` or ``"hyperelastic"``; by default ``case.options["model"]``.
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
        self.prepared = self.model.prepare(self.section, case.options)
        self.check = check
        self.prepare_seconds = time.perf_counter() - t0

    def target_nodes(self, target: Curve | np.ndarray | None = None) -> np.ndarray:
        """The target at the lower nodes' arc-length fractions, ``(n, 2)``.

        ``target`` may be a :class:`~sectiondeform.curves.Curve`, an ``(n, 2)``
        array of nodes already at those fractions, or None for the case's own.
        """
        if target is None:
            target = self.case.target
        if isinstance(target, Curve):
            nodes = target.at_fractions(self.section.fractions)
        else:
            nodes = as_points(target, "target", min_count=2)
            if len(nodes) != len(self.section.fractions):
                raise CaseError(
                    "target",
                    f"expected {len(self.section.fractions)} nodes (one per lower node), got {len(nodes)}",
                )
        steps = nodes[1:] - nodes[:-1]
        length = np.hypot(steps[:, 0], steps[:, 1]).sum()
        if not length > 1e-9 * self.section.lower_length:
            raise CaseError("target", "the target has zero length")
        return nodes

    def deform(self, target: Curve | np.ndarray | None = None, law: Law | None = None) -> Result:
        """Deform the section onto ``target`` under ``law`` (the case's by default).

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
            If the deformed contour crosses itself.
        """
        return self._run(self.prepared.place, target, law)

    def preview(self, target: Curve | np.ndarray | None = None, law: Law | None = None) -> Result:
        """A fast deformation for dragging the target (interactive preview).

        The paper model answers exactly as :meth:`deform`; the hyperelastic
        model takes one linearised step from its last solution, meeting the
        law exactly but first-order in the change of target
        (``result.info["preview"]`` is True): call :meth:`deform` when the
        drag ends.
        """
        return self._run(self.prepared.preview, target, law)

    def _run(self, placer, target, law) -> Result:
        """Place with ``placer`` (the model's ``place`` or ``preview``), check, explain a refusal."""
        t0 = time.perf_counter()
        law = law or self.case.law
        nodes = self.target_nodes(target)
        try:
            return self._result(nodes, placer(nodes, law), law, t0)
        except (MeshError, LawError, GeometryError) as exc:
            better = self._explained(exc)
            if better is exc:
                raise
            raise better from exc

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

    def _result(self, nodes, placement, law, t0) -> Result:
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
        quality = dict(self.prepared.quality)
        quality.update({f"final_{k}": v for k, v in placement.quality.items()})
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
            quality=quality,
            info=dict(placement.info),
            timings={"prepare_s": self.prepare_seconds, "place_s": seconds},
            warnings=tuple(placement.warnings),
        )
        failed = check_result(result)  # independent checks: inverted elements, reported areas, ends
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
