"""The page's only link to the library: problems, models, deformers and their answers.

Every use of the case's options and of :class:`~sectiondeform.deform.Deformer`
by the interactive page lives here, so a change of either touches this module
alone. Everything exchanged with the page is plain JSON: a case object
(``section-case/1`` or ``/2``) for the problem, a curve object for the
target, numbers for the law. One problem type and one deformer serve both:
a ``section-case/1`` case takes its law from the page's slider (``ratio``),
a ``section-case/2`` case each body's from the case, and the answer comes
in the case's dialect (the one body at the top level for ``/1``, a list of
bodies for ``/2``). Whatever the library refuses is refused to the page
with the library's own message.
"""

from __future__ import annotations

import contextlib
import json
import threading
import time
from collections import OrderedDict

import numpy as np

from ..curves import curve_from_json
from ..deform import Deformer
from ..errors import CaseError
from ..io.case import case_from_dict, case_to_dict, revolution_from_json
from ..laws import AreaRatio, law_from_json
from ..models import MODEL_NAMES
from ..problem import V2, Problem
from ..result import RESULT_V1, Result, contact_units
from ..section import local_green

__all__ = ["FIELDS", "MODELS", "DeformerCache", "SharedDeformers", "answer", "case_from_json", "case_json_of", "case_model",
           "contact_units", "contact_view", "describe", "field_view", "full_result", "is_assembly", "law_of", "laws_of",
           "model_of_json", "outline", "report_figure", "rigid_outline", "section_key", "travels_of", "with_model"]

MODELS = MODEL_NAMES
OUTLINE_SAMPLES = 65
"""Points of each curve of a body's outline."""
FIELDS = ("J", "max_principal_strain", "von_mises_stress", "pressure")
"""The colour maps the page offers on the final mesh (:data:`sectiondeform.field_plot.PLOT_FIELDS` names)."""
RIGID_CHORDAL = 1e-3
"""Chordal error of a rigid part's drawn outline, relative to the part's size."""


def is_assembly(case_json) -> bool:
    """True for a ``section-case/2`` object (bodies on a support, each with its own law)."""
    return isinstance(case_json, dict) and case_json.get("format") == V2


def case_model(problem: Problem) -> str:
    """The model a problem asks for (``"paper"`` by default)."""
    return problem.model


def model_of_json(case_json: dict) -> str:
    """The model a case object asks for, read without checking the rest of it (``"paper"`` by default)."""
    options = case_json.get("options")
    model = options.get("model") if isinstance(options, dict) else None
    return model if model in MODELS else "paper"


def with_model(problem: Problem, model: str) -> Problem:
    """The problem with its model option set to ``model``."""
    _check_model(model)
    return problem.replace(options=problem.options.replace(model=model))


def _check_model(model) -> None:
    if model not in MODELS:
        raise CaseError("model", f"unknown model {model!r}; use one of {', '.join(MODELS)}")


def law_of(ratio) -> AreaRatio:
    """The area-ratio law of the page's slider (final area = ratio x initial area)."""
    if isinstance(ratio, bool) or not isinstance(ratio, (int, float)):
        raise CaseError("ratio", f"expected a number, got {ratio!r}")
    return AreaRatio(float(ratio))


def laws_of(case_json: dict, ratio=None) -> tuple:
    """Each body's law, checked by the library: the slider's ``ratio`` for a ``section-case/1`` case, else the bodies'."""
    if not is_assembly(case_json):
        return (law_of(ratio),)
    bodies = case_json.get("bodies")
    if not isinstance(bodies, list):
        raise CaseError("bodies", "expected a non-empty list of bodies")
    revolution = case_json.get("revolution")
    axis = revolution_from_json(revolution).axis if revolution is not None else None
    return tuple(law_from_json(b.get("law") if isinstance(b, dict) else None, f"bodies[{i}].law", axis=axis)
                 for i, b in enumerate(bodies))


def section_key(case_json: dict, model: str) -> str:
    """What a prepared problem depends on: everything of the case but its target, its laws and its rigid parts'
    travels (a part counts by where it starts: its contour less its travel), and the model.
    """
    rest = {k: v for k, v in case_json.items() if k not in ("target", "law")}
    if isinstance(rest.get("bodies"), list):
        rest["bodies"] = [{k: v for k, v in b.items() if k != "law"} if isinstance(b, dict) else b for b in rest["bodies"]]
    if isinstance(rest.get("rigid"), list):
        rest["rigid"] = [_rigid_start(part) for part in rest["rigid"]]
    return json.dumps([rest, model], sort_keys=True)


def _rigid_start(part):
    """A rigid part as its prepared problem depends on it: all but its travel, its contour moved to where it starts
    (rounded to 10 digits: the page moves the contour by the travel in its own arithmetic). Anything unreadable is
    kept as it is (the library refuses it when the case is prepared).
    """
    if not isinstance(part, dict) or "contour" not in part:
        return part
    try:
        travel = np.asarray(part.get("travel", [0.0, 0.0]), dtype=np.float64)
        start = curve_from_json(part["contour"], "contour").transformed(np.eye(2), -travel).to_json()
    except Exception:  # noqa: BLE001 - refused with its own message where the case is read
        return part
    rest = {k: v for k, v in part.items() if k not in ("contour", "travel")}
    rest["start"] = _rounded(start)
    return rest


def _rounded(value):
    """A JSON value with every float rounded to 10 significant digits."""
    if isinstance(value, float):
        return float(f"{value:.10g}")
    if isinstance(value, (list, tuple)):
        return [_rounded(v) for v in value]
    if isinstance(value, dict):
        return {k: _rounded(v) for k, v in value.items()}
    return value


class SharedDeformers:
    """Prepared problems shared by every page of a server, by :func:`section_key` (the last ``size`` used).

    Pages on the same case prepare it once (thirty pages of the paper example,
    one preparation). A :class:`Deformer` holds no state between calls, but
    one thread at a time uses it: each comes with its lock, held by
    :func:`answer` while it deforms. A page keeps the deformers it uses
    (:class:`DeformerCache`) even when they leave this list.
    """

    def __init__(self, size: int = 8):
        self.size = size
        self._items: OrderedDict[str, tuple[Deformer, threading.Lock]] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: str, build) -> tuple[Deformer, threading.Lock]:
        """The deformer of ``key`` and its lock; ``build()`` prepares it if no page has (outside the list's lock)."""
        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
                return self._items[key]
        deformer = build()  # another page's preparation meanwhile does not wait for this one
        with self._lock:
            entry = self._items.setdefault(key, (deformer, threading.Lock()))
            self._items.move_to_end(key)
            while len(self._items) > self.size:
                self._items.popitem(last=False)
        return entry

    def __len__(self) -> int:
        return len(self._items)


class DeformerCache:
    """The last few prepared problems of one page, by :func:`section_key`.

    Dragging the target or a law reuses one :class:`Deformer`; editing the
    section or switching the model prepares another (kept, so switching back
    is free). With ``shared`` (the server's :class:`SharedDeformers`), a
    problem another page has prepared is not prepared again.
    """

    def __init__(self, size: int = 4, shared: SharedDeformers | None = None):
        self.size = size
        self.shared = shared
        self._items: OrderedDict[str, Deformer] = OrderedDict()
        self._locks: dict[int, threading.Lock] = {}
        self._last: dict[int, Result] = {}  # the last full deformation of each deformer: the next warm start

    def get(self, case_json: dict, model: str, key: str | None = None) -> tuple[Deformer, bool]:
        """The deformer of a case for a model; True if it is new to this page (prepared now, or by another page).

        ``key`` is the case's :func:`section_key` for ``model`` if known (from :meth:`ready`), not computed again.
        """
        _check_model(model)
        key = key or section_key(case_json, model)
        if key in self._items:
            self._items.move_to_end(key)
            return self._items[key], False
        def build():
            return Deformer(case_from_dict(case_json), model=model)

        if self.shared is not None:
            deformer, lock = self.shared.get(key, build)
        else:
            deformer, lock = build(), threading.Lock()
        self._items[key] = deformer
        self._locks[id(deformer)] = lock
        while len(self._items) > self.size:
            _, old = self._items.popitem(last=False)
            self._last.pop(id(old), None)
            self._locks.pop(id(old), None)
        return deformer, True

    def lock(self, deformer: Deformer):
        """The lock a thread holds while it uses ``deformer`` (shared deformers: one thread at a time)."""
        return self._locks.get(id(deformer)) or contextlib.nullcontext()

    def ready(self, case_json, model) -> str | None:
        """The :func:`section_key` of ``case_json`` if it is already prepared for ``model`` (a preview is then fast), else None."""
        if not isinstance(case_json, dict) or model not in MODELS:
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
           key: str | None = None, field: str | None = None) -> dict:
    """Deform a case for the page: the preview while dragging, the full deformation on release.

    Parameters
    ----------
    cache : DeformerCache
    case_json : dict
        A case object, either version (its ``target`` is the dragged curve).
    model : str
    ratio : float
        Area ratio of the law of a ``section-case/1`` case (a
        ``section-case/2`` case's bodies carry their laws).
    final : bool
        Full deformation (True) or the model's fast preview (False).
    meshes : bool
        Send the meshes.
    key : str, optional
        The case's :func:`section_key` for ``model``, if known (:meth:`DeformerCache.ready`).
    field : str, optional
        One of :data:`FIELDS`: its values on each body's final mesh come
        with a full deformation (:func:`field_view`).

    Returns
    -------
    dict
        See :func:`describe`.

    Raises
    ------
    SectionDeformError
        A refusal, shown on the page.
    """
    t0 = time.perf_counter()
    if not isinstance(case_json, dict):
        raise CaseError("case", "expected a section-case/1 or section-case/2 object")
    deformer, prepared = cache.get(case_json, model, key)
    target = curve_from_json(case_json.get("target"), "target")
    laws = laws_of(case_json, ratio)
    travel = travels_of(case_json)
    start = cache.start(deformer)
    with cache.lock(deformer):
        run = deformer.deform if final else deformer.preview
        result = run(target, laws, start=start, travel=travel)
    if final:
        cache.remember(deformer, result)
    support = target.at_fractions(deformer.fractions)
    out = describe(result, support, final, prepared, meshes, 1e3 * (time.perf_counter() - t0))
    if final and result.rigid:  # a preview's contact figures would be the last full deformation's: not sent
        out.update(contact_view(result, deformer.problem, travel))
    if field is not None and final:
        out.update(field_view(result, field))
        out["compute_ms"] = 1e3 * (time.perf_counter() - t0)
    return out


def field_view(result: Result, name) -> dict:
    """A colour map of the page: ``{"field": {...}}``, the values of ``name`` per element of each body's final mesh.

    The strain and stress fields the command line draws
    (:func:`sectiondeform.field_plot.field_values`): ``values`` is one
    ``(M_b,)`` float64 array per body, element by element of its final mesh
    (at the top level for a ``section-case/1`` case, under each body for
    an assembly), with the field's ``label`` (the stresses' unit), ``kind``
    (``mechanical``, or ``geometric`` for the paper model's mesh), ``min``
    and ``max``. A field the result has not (a stress of the paper model)
    comes back as ``{"field": {"name", "error"}}``, one line.
    """
    from ..field_plot import PLOT_FIELDS, STRESS_FIELDS, field_values, stress_unit

    if name not in FIELDS:
        raise CaseError("field", f"unknown field {name!r}; use one of {', '.join(FIELDS)}")
    if name in STRESS_FIELDS and result.model != "hyperelastic":
        return {"field": {"name": name, "error": f"field: {name} is a stress and the {result.model} model has no "
                                                  "material; choose the hyperelastic model or a strain field"}}
    try:
        kind, values = field_values(result, name)
    except CaseError as exc:
        return {"field": {"name": name, "error": f"field: {exc.problem}"}}
    label = PLOT_FIELDS[name][2] + (f" ({stress_unit(result)})" if name in STRESS_FIELDS else "")
    if kind == "geometric":
        label += " (geometric: the paper model's mesh, not a material)"
    both = np.concatenate(values)
    view = {"name": name, "kind": kind, "label": label, "min": float(both.min()), "max": float(both.max())}
    if result.dialect == RESULT_V1:
        view["values"] = values[0]
    else:
        view["values"] = None
        view["bodies"] = [{"values": v} for v in values]
    return {"field": view}


def travels_of(case_json: dict):
    """The rigid parts' travels of a case object, in order (checked by the library), or None without rigid parts."""
    parts = case_json.get("rigid")
    if not isinstance(parts, list) or not parts:
        return None
    return [part.get("travel", [0.0, 0.0]) if isinstance(part, dict) else part for part in parts]


def contact_view(result: Result, problem: Problem, travel=None) -> dict:
    """The page's view of a full deformation's contact with rigid parts (:attr:`Result.rigid`).

    Returns
    -------
    dict
        ``rigid``: per part (in the case's order) its ``name``, the
        ``travel`` it was solved for (``[dx, dy]``, units), ``force``
        (``[fx, fy]``: what the bodies exert on it, see :func:`contact_units`),
        ``length``, ``pressure_max``, ``pressure_mean``, ``penetration_max``,
        ``pressure`` (``(m, 3)`` float64, ``[x, y, p]`` along the contact)
        and ``outline`` (``(k, 2)`` float64, where it ends); the support's
        ``support_force``, the load steps' forces ``history`` and the
        ``contact_units``. ``travel``: the travels the result was solved
        for, one ``[dx, dy]`` per part, if not the problem's.
    """
    pairs = travel if travel is not None else [part.travel for part in problem.rigid]
    travels = {part.name: [float(v) for v in pair] for part, pair in zip(problem.rigid, pairs)}
    parts = []
    for part in result.rigid:
        outline = np.asarray(part.outline, dtype=np.float64)
        parts.append({"name": part.name, "travel": travels[part.name], "force": [float(v) for v in part.force],
                      "length": float(part.length), "pressure_max": float(part.pressure_max),
                      "pressure_mean": float(part.pressure_mean), "penetration_max": float(part.penetration_max),
                      "pressure": np.asarray(part.pressure, dtype=np.float64).reshape(-1, 3), "outline": outline})
    return {"rigid": parts, "support_force": [float(v) for v in result.support_force],
            "history": [step.to_json() for step in result.history],
            "contact_units": contact_units(result.units, result.axis is not None)}


def rigid_outline(case_json: dict) -> list[dict]:
    """Each rigid part of a case as drawn, before any answer: ``{"name", "contour", "travel"}``.

    ``contour`` is the part's closed outline where it ends (``(k, 2)``
    float64, units, within :data:`RIGID_CHORDAL` of its size), ``travel``
    its ``[dx, dy]``: the page draws it at its start (``contour - travel``)
    and its end, for either model (the paper model refuses rigid parts, and
    the page shows them with the refusal). Only the parts' curves and
    travels are read.
    """
    parts = case_json.get("rigid") if isinstance(case_json, dict) else None
    if parts is None:
        return []
    if not isinstance(parts, list):
        raise CaseError("rigid", f"expected a list of rigid parts, got {type(parts).__name__}")
    out = []
    for i, part in enumerate(parts):
        if not isinstance(part, dict):
            raise CaseError(f"rigid[{i}]", f"expected a rigid part object, got {type(part).__name__}")
        curve = curve_from_json(part.get("contour"), f"rigid[{i}].contour")
        travel = part.get("travel", [0.0, 0.0])
        if (not isinstance(travel, list) or len(travel) != 2
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) for v in travel)):
            raise CaseError(f"rigid[{i}].travel", f"expected two finite numbers [dx, dy], got {travel!r}")
        size = float(np.hypot(*np.ptp(curve.at_fractions(np.linspace(0.0, 1.0, OUTLINE_SAMPLES)), axis=0)))
        points = curve.discretise(RIGID_CHORDAL * size)[0] if size > 0 else curve.at_fractions(np.zeros(1))
        out.append({"name": str(part.get("name", i)), "contour": np.asarray(points, dtype=np.float64),
                    "travel": [float(v) for v in travel]})
    return out


def describe(result: Result, support: np.ndarray, final: bool, prepared: bool, meshes: bool, compute_ms: float) -> dict:
    """The page's view of a :class:`Result`, in its case's dialect.

    The totals over the bodies (areas, the worst law error, the smallest
    Jacobian), the deformed support ``lower`` (``(k, 2)``), and each body's
    contour, holes, areas (volumes of revolution), error and meshes: at the top
    level for the one body of a ``section-case/1`` case, else under
    ``bodies`` (with ``assembly`` and ``revolution`` flags). A full
    deformation, or the first answer of a newly prepared problem, carries
    everything; a preview while dragging only what moves (the contours and
    holes, the support and the final meshes' points), the page keeping the
    initial contours and holes and the meshes' cells of the last full answer.
    """
    whole = final or prepared  # the initial contours and meshes change only with the section
    views = [_body_view(b, whole, meshes) for b in result.bodies]
    targets = [b.area_target for b in result.bodies]
    jacobians = [v["jacobian_min"] for v in views if v["jacobian_min"] is not None]
    stretches = [v["det_f_min"] for v in views if v["det_f_min"] is not None]
    out = {
        "final": bool(final),
        "model": result.model,
        "prepared": prepared,
        "lower": support,
        "area_initial": sum(b.area_initial for b in result.bodies),
        "area_target": None if None in targets else sum(targets),
        "area_final": sum(b.area_final for b in result.bodies),
        "relative_error": result.relative_error,
        "jacobian_min": min(jacobians, default=None),
        "det_f_min": min(stretches, default=None),
        "info": {},
        "warnings": list(result.warnings),
        "compute_ms": compute_ms,
    }
    if result.dialect == RESULT_V1:  # the paper's one body at the top level
        view = views[0]
        del view["name"]
        out.update(view)
    else:
        out.update(assembly=True, revolution=result.axis is not None, bodies=views)
    return out


def _body_view(body, whole: bool, meshes: bool) -> dict:
    """One body of :func:`describe`: contour, holes, areas (and volumes), errors, figures and meshes.

    ``holes`` (and, with the initial contour, ``initial_holes``): the
    library's :attr:`BodyResult.holes <sectiondeform.result.BodyResult.holes>`,
    one ``(k_h, 2)`` float64 array per hole (closed, the first point not
    repeated), an empty list for a solid body. The areas are net of the holes.
    """
    q = body.quality
    out = {
        "name": body.name,
        "contour": body.contour,
        "holes": list(body.holes),
        "area_initial": body.area_initial,
        "area_target": body.area_target,
        "area_final": body.area_final,
        "relative_error": (body.area_final - body.area_target) / body.area_target if body.area_target else None,
        "jacobian_min": q.final.jacobian_min if q is not None else None,  # a layered mesh's, units²
        "det_f_min": q.final.area_stretch_min if q is not None else None,  # a finite-element solution's, a ratio
        "info": {k: v for k, v in body.info.to_json().items() if isinstance(v, (int, float, str, bool))},
    }
    if body.volume_initial is not None:  # the library's volumes of revolution (Pappus)
        vt = body.volume_target
        out.update(volume_initial=body.volume_initial, volume_final=body.volume_final, volume_target=vt,
                   volume_error=(body.volume_final - vt) / vt if vt else None)
    if whole:
        out["initial_contour"] = body.initial_contour
        out["initial_holes"] = list(body.initial_holes)
    if meshes:
        out["mesh_final"] = {"points": body.final_mesh.points}
        if whole:
            out["mesh_initial"] = {"points": body.initial_mesh.points, "cells": body.initial_mesh.cells.tolist()}
            out["mesh_final"]["cells"] = body.final_mesh.cells.tolist()
    return out


def outline(case_json: dict) -> list[dict]:
    """Each body of a case as a closed ``(n, 2)`` outline (lower then upper), to draw before any answer.

    Only the curves are read: the page shows a problem whose deformation
    the library refuses (with its message). Each body's ``holes`` are its
    holes' closed ``(k, 2)`` outlines (the first point not repeated), its
    ``area`` the exact area its curves enclose less its holes' (units²),
    shown until the first answer.
    """
    bodies = (case_json.get("bodies") or []) if is_assembly(case_json) else [case_json]
    s = np.linspace(0.0, 1.0, OUTLINE_SAMPLES)
    out = []
    for i, body in enumerate(bodies):
        if not isinstance(body, dict):
            raise CaseError(f"bodies[{i}]", f"expected a body object, got {type(body).__name__}")
        where = f"bodies[{i}]." if is_assembly(case_json) else ""
        lower = curve_from_json(body.get("lower"), f"{where}lower")
        upper = curve_from_json(body.get("upper"), f"{where}upper")
        area = abs(local_green(lower, lower.start) + local_green(upper, lower.start))
        holes = body.get("holes", []) if is_assembly(case_json) else []
        if not isinstance(holes, list):
            raise CaseError(f"{where}holes", f"expected a list of closed curves, got {type(holes).__name__}")
        holes = [curve_from_json(h, f"{where}holes[{k}]") for k, h in enumerate(holes)]
        area -= sum(abs(local_green(h, h.start)) for h in holes)  # each about its own start: its digits kept
        out.append({"name": str(body.get("name", i)), "area": float(area),
                    "contour": np.concatenate((lower.at_fractions(s), upper.at_fractions(s)[1:-1])),
                    "holes": [h.at_fractions(s)[:-1] for h in holes]})
    return out


# ---- files --------------------------------------------------------------


def case_from_json(case_json: dict) -> Problem:
    """The :class:`~sectiondeform.problem.Problem` of a case object, either version."""
    return case_from_dict(case_json)


def case_json_of(problem: Problem) -> dict:
    """The case object of a problem, in its dialect."""
    return case_to_dict(problem)


def full_result(case_json: dict, model: str) -> Result:
    """The full deformation of a case, one body or several, by ``model`` (for saving)."""
    return Deformer(with_model(case_from_dict(case_json), model), model=model).deform()


def report_figure(case_json: dict, model: str, path) -> None:
    """Write the report figure of a case's full deformation by ``model`` to ``path`` (.png, .svg, .pdf).

    The library's figure (:func:`sectiondeform.plot.draw_result`: the title
    with the case's name and each body's law, the four panels with the
    model, the legends with the areas or volumes), its axes labelled with
    the case's units (the scale). Drawn with matplotlib's Agg canvas, on
    the caller's thread (the server's workers), never pyplot.
    """
    from ..plot import draw_result, write_figure

    result = full_result(case_json, model)
    fig = draw_result(result)
    unit = f" ({result.units})" if result.units else ""
    for ax in fig.axes:
        ax.set_xlabel("x" + unit, fontsize=8)
        ax.set_ylabel("y" + unit, fontsize=8)
    write_figure(fig, path)
