"""The page's only link to the library: cases, models, deformers and their answers.

Every use of ``case.options`` and of :class:`~sectiondeform.deform.Deformer`
by the interactive page lives here, so a change of either touches this module
alone. Everything exchanged with the page is plain JSON: a ``section-case/1``
object for the case, a curve object for the target, numbers for the law.
"""

from __future__ import annotations

import json
import time
from collections import OrderedDict

from ..case import MODELS, Case, case_from_dict, case_to_dict
from ..curves import curve_from_json
from ..deform import Deformer
from ..errors import CaseError
from ..laws import AreaRatio
from ..result import Result

__all__ = ["MODELS", "DeformerCache", "answer", "case_model", "law_of", "section_key", "with_model"]


def case_model(case: Case) -> str:
    """The model a case asks for (``"paper"`` by default)."""
    return case.model


def with_model(case: Case, model: str) -> Case:
    """The case with its model option set to ``model``."""
    if model not in MODELS:
        raise CaseError("model", f"unknown model {model!r}; use one of {', '.join(MODELS)}")
    return case.replace(options=case.options.replace(model=model))


def law_of(ratio) -> AreaRatio:
    """The area-ratio law of the page's slider (final area = ratio x initial area)."""
    if isinstance(ratio, bool) or not isinstance(ratio, (int, float)):
        raise CaseError("ratio", f"expected a number, got {ratio!r}")
    return AreaRatio(float(ratio))


def section_key(case_json: dict, model: str) -> str:
    """What a prepared section depends on: everything of the case but its target and law, and the model."""
    rest = {k: v for k, v in case_json.items() if k not in ("target", "law")}
    return json.dumps([rest, model], sort_keys=True)


class DeformerCache:
    """The last few prepared sections, by :func:`section_key`.

    Dragging the target reuses one :class:`Deformer`; editing the section or
    switching the model prepares another (kept, so switching back is free).
    """

    def __init__(self, size: int = 4):
        self.size = size
        self._items: OrderedDict[str, Deformer] = OrderedDict()
        self._last: dict[int, Result] = {}  # the last full deformation of each deformer: the next warm start

    def get(self, case_json: dict, model: str) -> tuple[Deformer, bool]:
        """The deformer of a case for a model; True if it was prepared now."""
        if model not in MODELS:
            raise CaseError("model", f"unknown model {model!r}; use one of {', '.join(MODELS)}")
        key = section_key(case_json, model)
        if key in self._items:
            self._items.move_to_end(key)
            return self._items[key], False
        deformer = Deformer(case_from_dict(case_json), model=model)
        self._items[key] = deformer
        while len(self._items) > self.size:
            _, old = self._items.popitem(last=False)
            self._last.pop(id(old), None)
        return deformer, True

    def ready(self, case_json, model) -> bool:
        """True if the section of ``case_json`` is already prepared for ``model`` (a preview is then fast)."""
        try:
            return isinstance(case_json, dict) and section_key(case_json, model) in self._items
        except (TypeError, ValueError):
            return False

    def start(self, deformer: Deformer) -> Result | None:
        """The last full deformation of ``deformer``, from which a preview or a solve starts (or None)."""
        return self._last.get(id(deformer))

    def remember(self, deformer: Deformer, result: Result) -> None:
        """Keep ``result`` (a full deformation) as the next warm start of ``deformer``."""
        if any(d is deformer for d in self._items.values()):
            self._last[id(deformer)] = result


def answer(cache: DeformerCache, case_json: dict, model: str, ratio, final: bool, meshes: bool = True) -> dict:
    """Deform a case for the page: the preview while dragging, the full deformation on release.

    Parameters
    ----------
    cache : DeformerCache
    case_json : dict
        A ``section-case/1`` object (its ``target`` is the dragged curve).
    model : str
    ratio : float
        Area ratio of the law.
    final : bool
        Full deformation (True) or the model's fast preview (False).
    meshes : bool
        Send the meshes.

    Returns
    -------
    dict
        Contours and mesh points as ``(n, 2)`` float64 arrays, mesh cells,
        areas, quality figures, compute time in ms (see :func:`describe`
        for what a preview leaves out).

    Raises
    ------
    SectionDeformError
        A refusal, shown on the page.
    """
    t0 = time.perf_counter()
    if not isinstance(case_json, dict):
        raise CaseError("case", "expected a section-case/1 object")
    deformer, prepared = cache.get(case_json, model)
    target = curve_from_json(case_json.get("target"), "target")
    law = law_of(ratio)
    start = cache.start(deformer)
    if final:
        result = deformer.deform(target, law, start=start)
        cache.remember(deformer, result)
    else:
        result = deformer.preview(target, law, start=start)
    return describe(result, final, prepared, meshes, 1e3 * (time.perf_counter() - t0))


def describe(result: Result, final: bool, prepared: bool, meshes: bool, compute_ms: float) -> dict:
    """The page's view of a :class:`Result`.

    A full deformation, or the first answer of a newly prepared section,
    carries everything; a preview while dragging carries only what moves
    (the contour, the support and the final mesh's points), the page keeping
    the initial contour and the meshes' cells of the last full answer.
    """
    q = result.quality
    whole = final or prepared  # the initial contour and mesh change only with the section
    out = {
        "final": bool(final),
        "model": result.model,
        "prepared": prepared,
        "contour": result.contour,
        "lower": result.lower,
        "area_initial": result.area_initial,
        "area_target": result.area_target,
        "area_final": result.area_final,
        "relative_error": result.relative_error,
        "jacobian_min": q.final.jacobian_min if q is not None else None,
        "info": {k: v for k, v in result.info.to_json().items() if isinstance(v, (int, float, str, bool))},
        "warnings": list(result.warnings),
        "compute_ms": compute_ms,
    }
    if whole:
        out["initial_contour"] = result.initial_contour
    if meshes:
        out["mesh_final"] = {"points": result.final_mesh.points}
        if whole:
            out["mesh_initial"] = {"points": result.initial_mesh.points, "cells": result.initial_mesh.cells.tolist()}
            out["mesh_final"]["cells"] = result.final_mesh.cells.tolist()
    return out


def case_from_json(case_json: dict) -> Case:
    """The :class:`Case` of a ``section-case/1`` object."""
    return case_from_dict(case_json)


def case_json_of(case: Case) -> dict:
    """The ``section-case/1`` object of a case."""
    return case_to_dict(case)


def full_result(case_json: dict, model: str) -> Result:
    """The full deformation of a case (for saving)."""
    case = with_model(case_from_dict(case_json), model)
    return Deformer(case, model=model).deform()
