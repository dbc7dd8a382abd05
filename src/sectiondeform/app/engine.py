"""The page's only link to the library: cases, models, deformers and their answers.

Every use of ``case.options`` and of :class:`~sectiondeform.deform.Deformer`
by the interactive page lives here, so a change of either touches this module
alone. Everything exchanged with the page is plain JSON: a ``section-case/1``
object for the case, a curve object for the target, numbers for the law.
An assembly (a ``section-case/2`` object) goes to
:class:`~sectiondeform.assembly_deform.AssemblyDeformer`, each body with its
own law; whatever the library refuses of it (a model that does not deform
assemblies, bodies of revolution) is refused to the page with the library's
own message.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import time
from collections import OrderedDict

import numpy as np

from ..assembly import ASSEMBLY_FORMAT, Assembly, assembly_from_dict, assembly_to_dict, revolution_from_json
from ..assembly_deform import AssemblyDeformer
from ..case import MODELS, Case, case_from_dict, case_to_dict
from ..curves import curve_from_json
from ..deform import Deformer
from ..errors import CaseError
from ..laws import AreaRatio, law_from_json
from ..result import Result

__all__ = ["MODELS", "DeformerCache", "answer", "case_model", "is_assembly", "law_of", "outline", "section_key",
           "with_model"]

TARGET_SAMPLES = 129
"""Points of the target sent to draw it under an assembly."""


def is_assembly(case_json) -> bool:
    """True for a ``section-case/2`` object (an assembly of bodies)."""
    return isinstance(case_json, dict) and case_json.get("format") == ASSEMBLY_FORMAT


def case_model(case: Case | Assembly) -> str:
    """The model a case or an assembly asks for (``"paper"`` by default)."""
    return case.model


def model_of_json(case_json: dict) -> str:
    """The model a case object asks for, read without checking the rest of it (``"paper"`` by default)."""
    options = case_json.get("options")
    model = options.get("model") if isinstance(options, dict) else None
    return model if model in MODELS else "paper"


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
    """What a prepared section depends on: everything of the case but its target and law(s), and the model."""
    rest = {k: v for k, v in case_json.items() if k not in ("target", "law")}
    if is_assembly(case_json) and isinstance(rest.get("bodies"), list):
        rest["bodies"] = [{k: v for k, v in b.items() if k != "law"} if isinstance(b, dict) else b for b in rest["bodies"]]
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

    def get(self, case_json: dict, model: str, key: str | None = None) -> tuple[Deformer | AssemblyDeformer, bool]:
        """The deformer of a case for a model; True if it was prepared now.

        ``key`` is the case's :func:`section_key` for ``model`` if known (from :meth:`ready`), not computed again.
        """
        if model not in MODELS:
            raise CaseError("model", f"unknown model {model!r}; use one of {', '.join(MODELS)}")
        key = key or section_key(case_json, model)
        if key in self._items:
            self._items.move_to_end(key)
            return self._items[key], False
        if is_assembly(case_json):
            deformer = AssemblyDeformer(assembly_from_dict(case_json), model=model)
        else:
            deformer = Deformer(case_from_dict(case_json), model=model)
        self._items[key] = deformer
        while len(self._items) > self.size:
            _, old = self._items.popitem(last=False)
            self._last.pop(id(old), None)
        return deformer, True

    def ready(self, case_json, model) -> str | None:
        """The :func:`section_key` of ``case_json`` if its section is already prepared for ``model`` (a preview is then fast), else None.

        Never for an assembly: each of its answers is a full placement of every body.
        """
        if not isinstance(case_json, dict) or is_assembly(case_json) or model not in MODELS:
            return None
        try:
            key = section_key(case_json, model)
        except (TypeError, ValueError):
            return None
        return key if key in self._items else None

    def start(self, deformer: Deformer) -> Result | None:
        """The last full deformation of ``deformer``, from which a preview or a solve starts (or None)."""
        return self._last.get(id(deformer))

    def remember(self, deformer: Deformer, result: Result) -> None:
        """Keep ``result`` (a full deformation) as the next warm start of ``deformer``."""
        if any(d is deformer for d in self._items.values()):
            self._last[id(deformer)] = result


def answer(cache: DeformerCache, case_json: dict, model: str, ratio, final: bool, meshes: bool = True,
           key: str | None = None) -> dict:
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
    key : str, optional
        The case's :func:`section_key` for ``model``, if known (:meth:`DeformerCache.ready`).

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
    if is_assembly(case_json):
        return assembly_answer(cache, case_json, model, final, meshes, t0)
    deformer, prepared = cache.get(case_json, model, key)
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


# ---- assemblies --------------------------------------------------------


def laws_of(case_json: dict) -> tuple:
    """Each body's law of a ``section-case/2`` object, checked by the library."""
    bodies = case_json.get("bodies")
    if not isinstance(bodies, list):
        raise CaseError("bodies", "expected a non-empty list of bodies")
    revolution = case_json.get("revolution")
    axis = revolution_from_json(revolution).axis if revolution is not None else None
    return tuple(law_from_json(b.get("law") if isinstance(b, dict) else None, f"bodies[{i}].law", axis=axis)
                 for i, b in enumerate(bodies))


def with_laws(deformer: AssemblyDeformer, laws: tuple) -> AssemblyDeformer:
    """``deformer`` placing each body under ``laws`` instead of its case's, without preparing again.

    An assembly's preparation (its layout and every body's mesh) does not
    depend on the laws, which :meth:`AssemblyDeformer.deform` reads from the
    deformer's assembly: the copy shares the prepared bodies and carries an
    assembly whose bodies have the new laws (the layout, already checked, is
    kept). The page's law slider thereby costs one placement, not a
    preparation of about a second.
    """
    a = deformer.assembly
    if all(b.law == law for b, law in zip(a.bodies, laws)) and len(laws) == len(a.bodies):
        return deformer
    if len(laws) != len(a.bodies):
        raise CaseError("bodies", f"expected {len(a.bodies)} bodies, got {len(laws)}")
    assembly = copy.copy(a)  # no new layout: the bodies' curves are those of the prepared assembly
    object.__setattr__(assembly, "bodies", tuple(dataclasses.replace(b, law=law) for b, law in zip(a.bodies, laws)))
    placed = copy.copy(deformer)
    placed.assembly = assembly
    return placed


def assembly_answer(cache: DeformerCache, case_json: dict, model: str, final: bool, meshes: bool, t0: float) -> dict:
    """:func:`answer` for an assembly: every body placed under its own law (a full deformation, warm-started from the last final one)."""
    deformer, prepared = cache.get(case_json, model)
    target = curve_from_json(case_json.get("target"), "target")
    result = with_laws(deformer, laws_of(case_json)).deform(target, start=cache.start(deformer))
    if final:
        cache.remember(deformer, result)
    whole = final or prepared
    axis = deformer.assembly.revolution.axis if deformer.assembly.revolution is not None else None
    bodies = []
    for b in result.bodies:
        q = b.quality
        out = {
            "name": b.name,
            "contour": b.contour,
            "area_initial": b.area_initial,
            "area_target": b.area_target,
            "area_final": b.area_final,
            "relative_error": (b.area_final - b.area_target) / b.area_target if b.area_target else None,
            "jacobian_min": q.final.jacobian_min if q is not None else None,
        }
        if axis is not None:  # the library's volumes of revolution (Pappus)
            vt = b.volume_target
            out.update(volume_initial=b.volume_initial, volume_final=b.volume_final, volume_target=vt,
                       volume_error=(b.volume_final - vt) / vt if vt else None)
        if whole:
            out["initial_contour"] = b.initial_contour
        if meshes:
            out["mesh_final"] = {"points": b.final_mesh.points}
            if whole:
                out["mesh_initial"] = {"points": b.initial_mesh.points, "cells": b.initial_mesh.cells.tolist()}
                out["mesh_final"]["cells"] = b.final_mesh.cells.tolist()
        bodies.append(out)
    errors = [o.get("volume_error") if axis is not None else o["relative_error"] for o in bodies]
    worst = max((e for e in errors if e is not None), key=abs, default=None)
    jacobians = [o["jacobian_min"] for o in bodies if o["jacobian_min"] is not None]
    return {
        "final": bool(final),
        "model": result.model,
        "prepared": prepared,
        "assembly": True,
        "revolution": axis is not None,
        "bodies": bodies,
        "lower": target.at_fractions(np.linspace(0.0, 1.0, TARGET_SAMPLES)),
        "area_initial": sum(o["area_initial"] for o in bodies),
        "area_target": None if any(o["area_target"] is None for o in bodies) else sum(o["area_target"] for o in bodies),
        "area_final": sum(o["area_final"] for o in bodies),
        "relative_error": worst,
        "jacobian_min": min(jacobians, default=None),
        "info": {},
        "warnings": list(result.warnings),
        "compute_ms": 1e3 * (time.perf_counter() - t0),
    }


def outline(case_json: dict) -> list[dict]:
    """Each body of an assembly as a closed ``(n, 2)`` outline (lower then upper), to draw before any answer.

    Only the curves are read: the page shows an assembly whose deformation
    the library refuses (with its message).
    """
    out = []
    for i, body in enumerate(case_json.get("bodies") or []):
        if not isinstance(body, dict):
            raise CaseError(f"bodies[{i}]", f"expected a body object, got {type(body).__name__}")
        lower = curve_from_json(body.get("lower"), f"bodies[{i}].lower")
        upper = curve_from_json(body.get("upper"), f"bodies[{i}].upper")
        s = np.linspace(0.0, 1.0, 65)
        out.append({"name": str(body.get("name", i)), "contour": np.concatenate((lower.at_fractions(s), upper.at_fractions(s)[1:-1]))})
    return out


# ---- files --------------------------------------------------------------


def case_from_json(case_json: dict) -> Case | Assembly:
    """The :class:`Case` of a ``section-case/1`` object, the :class:`Assembly` of a ``section-case/2`` one."""
    return assembly_from_dict(case_json) if is_assembly(case_json) else case_from_dict(case_json)


def case_json_of(case: Case | Assembly) -> dict:
    """The ``section-case/1`` object of a case, the ``section-case/2`` object of an assembly."""
    return assembly_to_dict(case) if isinstance(case, Assembly) else case_to_dict(case)


def full_result(case_json: dict, model: str) -> Result:
    """The full deformation of a case (for saving)."""
    if is_assembly(case_json):
        raise CaseError("case", "the page saves an assembly's case only; deform it with the deform command to save its result")
    case = with_model(case_from_dict(case_json), model)
    return Deformer(case, model=model).deform()
