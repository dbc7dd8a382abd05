"""The layers of a problem and of a result in a drawing (DXF layers, SVG ids), and the case data a drawing stores.

The names are a function of the dialect and the body (:func:`case_layers`,
:func:`result_layers`); both drawing formats write the same list, DXF as
layers, SVG as path or group ids.

================  ==========================================  ==============================================
dialect           case                                        result
================  ==========================================  ==============================================
``/1`` (one body  ``LOWER``, ``UPPER``, ``TARGET`` (SVG ids   ``MESH_INITIAL``, ``INITIAL``, ``MESH_FINAL``,
on its own lower  lower-case)                                 ``TARGET`` (the deformed lower curve),
curve)                                                        ``DEFORMED`` (SVG ids lower-case, ``-`` for ``_``)
``/2``            ``SUPPORT``, ``TARGET``,                    per body ``MESH-INITIAL-<name>``,
                  ``BODY-<name>-LOWER``, ``BODY-<name>-UPPER``  ``MESH-FINAL-<name>``, ``INITIAL-<name>-LOWER``,
                  (and ``AXIS`` for a body of revolution)     ``-UPPER``, ``DEFORMED-<name>-LOWER``, ``-UPPER``;
                                                              ``SUPPORT`` and ``TARGET`` when the case is given
``/2`` with       ``RIGID-<name>``: each rigid part's         ``RIGID-<name>``: each rigid part's outline at
rigid parts       contour (where it ends up)                  its end position
``/2`` with       ``BODY-<name>-HOLE``: the body's holes,     ``INITIAL-<name>-HOLE``, ``DEFORMED-<name>-HOLE``:
holes             one closed curve each                       the holes before and after, one closed polyline
                                                              each
================  ==========================================  ==============================================

A hole layer holds all the body's holes (DXF: one closed entity or chain
each; SVG: one path, a subpath each); the readers find holes there, inside
a body's contour on ``BODY-<name>``, or on a layer they do not read
(:mod:`.holes`).

The case data (:func:`case_meta`: name, units, options, laws, materials,
start points, the rigid parts' travel and friction) is stored as JSON in the DXF header property or SVG root
attribute ``sectiondeform``, so case -> drawing -> case gives the same case.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass

import numpy as np

from ..curves import DEFAULT_CHORDAL_FRACTION, Polyline
from ..errors import CaseError
from ..problem import V1, V2, Problem
from ..result import RESULT_V1

__all__ = [
    "Layer", "case_layers", "result_layers", "case_meta", "read_meta", "check_layer_names", "check_case",
    "is_bodies_drawing", "tolerance", "SUPPORT", "TARGET", "AXIS", "BODY", "RIGID", "ROLE_SUFFIXES", "HOLE_SUFFIX",
    "ONE_BODY_LAYERS",
]

SUPPORT, TARGET, AXIS, BODY, RIGID = "SUPPORT", "TARGET", "AXIS", "BODY-", "RIGID-"
HOLE_SUFFIX = "-HOLE"
DARK = (250, "#333333")
ROLE_SUFFIXES = ("-LOWER", "-UPPER")
ONE_BODY_LAYERS = ("LOWER", "UPPER", "CONTOUR")
DXF_COLORS = (1, 3, 4, 6, 2, 30, 140, 200)
SVG_COLORS = ("#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2", "#bcbd22")
GREY, LIGHT, BLUE = (8, "#777777"), (9, "#bbbbbb"), (5, "#1f77b4")
_DXF_BAD = re.compile(r'[<>/\\":;?*|=`]')


@dataclass(frozen=True, eq=False)
class Layer:
    """One layer of a drawing and what it holds.

    Attributes
    ----------
    name : str
        The DXF layer name.
    svg : str
        The SVG id.
    dxf_color : int
        AutoCAD colour index.
    svg_color : str
    kind : str
        ``"curve"`` (a :class:`~sectiondeform.curves.Curve`, written natively),
        ``"curves"`` (a tuple of them: a body's holes),
        ``"open"`` or ``"closed"`` (an ``(N, 2)`` polyline, units),
        ``"rings"`` (a tuple of ``(k, 2)`` closed polylines, the first point
        not repeated: a body's holes in a result) or
        ``"mesh"`` (a :class:`~sectiondeform.models.base.MeshData`, one closed
        polyline per element).
    data : object
    splines : tuple of ndarray
        For a deformed curve: the point runs written as fitted splines
        instead of ``data`` when a writer is asked for splines.
    """

    name: str
    svg: str
    dxf_color: int
    svg_color: str
    kind: str
    data: object
    splines: tuple = ()


def _style(i: int) -> tuple[int, str]:
    return DXF_COLORS[i % len(DXF_COLORS)], SVG_COLORS[i % len(SVG_COLORS)]


def tolerance(problem: Problem) -> float:
    """Chordal error of curves written as polylines: the case's, else 1e-4 of its size, units."""
    return problem.options.chordal_error or DEFAULT_CHORDAL_FRACTION * (problem.size or 1.0)


def case_layers(problem: Problem) -> list[Layer]:
    """The layers of a case, in drawing order (see the module docstring)."""
    if problem.dialect == V1:
        body = problem.bodies[0]
        return [Layer("LOWER", "lower", 1, "#d62728", "curve", body.lower),
                Layer("UPPER", "upper", 7, "#222222", "curve", body.upper),
                Layer(TARGET, "target", *BLUE, "curve", problem.target)]
    out = [Layer(SUPPORT, SUPPORT, 8, "#555555", "curve", problem.support),
           Layer(TARGET, TARGET, *BLUE, "curve", problem.target)]
    for i, b in enumerate(problem.bodies):
        dxf, svg = _style(i)
        out += [Layer(f"{BODY}{b.name}{s}", f"{BODY}{b.name}{s}", dxf, svg, "curve", c)
                for s, c in zip(ROLE_SUFFIXES, (b.lower, b.upper))]
        if b.holes:
            out.append(Layer(f"{BODY}{b.name}{HOLE_SUFFIX}", f"{BODY}{b.name}{HOLE_SUFFIX}", dxf, svg, "curves", b.holes))
    if problem.revolution is not None:
        out.append(Layer(AXIS, AXIS, 9, "#999999", "curve", Polyline(np.array(problem.revolution.axis, dtype=np.float64))))
    out += [Layer(f"{RIGID}{r.name}", f"{RIGID}{r.name}", *DARK, "curve", r.contour) for r in problem.rigid]
    return out


def result_layers(result, case: Problem | None = None) -> list[Layer]:
    """The layers of a result, in drawing order (see the module docstring).

    ``case``, the problem deformed, adds its support and target to a
    ``section-result/2`` drawing (a ``section-result/1`` one draws the
    deformed lower curve on ``TARGET`` itself).
    """
    if result.dialect == RESULT_V1:
        b = result.bodies[0]
        return [Layer("MESH_INITIAL", "mesh-initial", *LIGHT, "mesh", b.initial_mesh),
                Layer("INITIAL", "initial", *GREY, "closed", b.initial_contour),
                Layer("MESH_FINAL", "mesh-final", 3, "#2ca02c", "mesh", b.final_mesh),
                Layer(TARGET, "target", *BLUE, "open", b.lower),
                Layer("DEFORMED", "deformed", 1, "#d62728", "closed", b.contour, splines=(b.lower, b.upper))]
    out = []
    if case is not None:
        tol = tolerance(case)
        out += [Layer(SUPPORT, SUPPORT, *GREY, "open", case.support.discretise(tol)[0]),
                Layer(TARGET, TARGET, *BLUE, "open", case.target.discretise(tol)[0])]
    for i, b in enumerate(result.bodies):
        style = _style(i)
        out += [
            Layer(f"MESH-INITIAL-{b.name}", f"MESH-INITIAL-{b.name}", *LIGHT, "mesh", b.initial_mesh),
            Layer(f"MESH-FINAL-{b.name}", f"MESH-FINAL-{b.name}", *style, "mesh", b.final_mesh),
            Layer(f"INITIAL-{b.name}-LOWER", f"INITIAL-{b.name}-LOWER", *GREY, "open", b.initial_lower),
            Layer(f"INITIAL-{b.name}-UPPER", f"INITIAL-{b.name}-UPPER", *GREY, "open", b.initial_upper),
            Layer(f"DEFORMED-{b.name}-LOWER", f"DEFORMED-{b.name}-LOWER", *style, "open", b.lower, splines=(b.lower,)),
            Layer(f"DEFORMED-{b.name}-UPPER", f"DEFORMED-{b.name}-UPPER", *style, "open", b.upper, splines=(b.upper,)),
        ]
        if b.holes:
            out += [Layer(f"INITIAL-{b.name}{HOLE_SUFFIX}", f"INITIAL-{b.name}{HOLE_SUFFIX}", *GREY, "rings", b.initial_holes),
                    Layer(f"DEFORMED-{b.name}{HOLE_SUFFIX}", f"DEFORMED-{b.name}{HOLE_SUFFIX}", *style, "rings", b.holes)]
    out += [Layer(f"{RIGID}{p.name}", f"{RIGID}{p.name}", *DARK, "closed", np.asarray(p.outline))
            for p in result.rigid if p.outline is not None]
    return out


def check_case(result, case) -> None:
    """Refuse a case that is not the problem the result was deformed from (its bodies differ)."""
    if case is None:
        return
    if not isinstance(case, Problem) or [b.name for b in case.bodies] != [b.name for b in result.bodies]:
        raise CaseError("case", "is not the problem this result was deformed from (its bodies differ); give that case")


def check_layer_names(problem, dxf: bool) -> None:
    """Refuse body names that cannot name a layer: two equal but for case; for DXF, a forbidden character.

    ``problem``: a :class:`~sectiondeform.problem.Problem` or a result (its
    bodies' names). A ``section-case/1`` problem or ``section-result/1``
    result has no names in its layers and passes.

    Raises
    ------
    CaseError
        Naming the body (``bodies[i].name``) and what to change.
    """
    if problem.dialect in (V1, RESULT_V1):
        return
    seen: dict[str, int] = {}
    for i, b in enumerate(problem.bodies):
        if b.name.upper() in seen:
            raise CaseError(f"bodies[{i}].name", f"{b.name!r} differs from bodies[{seen[b.name.upper()]}]'s name only by "
                            "case; drawings match layer names without regard to case: rename one")
        seen[b.name.upper()] = i
        if dxf and (_DXF_BAD.search(b.name) or b.name != b.name.strip()):
            raise CaseError(f"bodies[{i}].name", f"{b.name!r} cannot be part of a DXF layer name (no <>/\\\":;?*|=` "
                            "characters, no leading or trailing spaces); rename the body")


def case_meta(problem: Problem) -> dict:
    """The case data a drawing stores: what its curves do not say (laws, options, start points...)."""
    if problem.dialect == V1:
        body = problem.bodies[0]
        return {"law": body.law.to_json(), "name": problem.name, "options": problem.options.to_json(),
                "units": problem.units, "lower_start": body.lower.start.tolist(),
                "target_start": problem.target.start.tolist()}
    meta = {"format": V2, "name": problem.name, "units": problem.units, "options": problem.options.to_json(),
            "support_start": problem.support.start.tolist(), "target_start": problem.target.start.tolist(), "bodies": []}
    if problem.revolution is not None:
        meta["revolution"] = problem.revolution.to_json()
    for b in problem.bodies:
        entry = {"name": b.name, "law": b.law.to_json(), "lower_start": b.lower.start.tolist()}
        if b.material != "{}":
            entry["material"] = b.material_data
        meta["bodies"].append(entry)
    if problem.rigid:
        meta["rigid"] = [{"name": r.name, "travel": list(r.travel), "friction": r.friction} for r in problem.rigid]
    return meta


def read_meta(text: str | None, where: str) -> dict:
    """The case data a writer of this package stored in a drawing, from its JSON text.

    Parameters
    ----------
    text : str or None
        The stored JSON; None or empty when the drawing stores none.
    where : str
        Where it is stored, for the message (file and property).

    Returns
    -------
    dict
        {} when nothing is stored.

    Raises
    ------
    CaseError
        If the stored text is not a JSON object: the data is corrupt, and
        reading on without it would give a misleading error later.
    """
    if not text:
        return {}
    try:
        meta = json.loads(text)
    except (TypeError, ValueError) as exc:
        raise CaseError(where, f"the stored case data is not valid JSON ({exc}); remove it or write the file again") from None
    if not isinstance(meta, dict):
        raise CaseError(where, f"the stored case data is a JSON {type(meta).__name__}, not an object; remove it or write the file again")
    return meta


def is_bodies_drawing(drawing) -> bool:
    """Whether a drawing holds a ``section-case/2`` problem: stored as such, or with a SUPPORT or BODY-... layer."""
    if (drawing.meta or {}).get("format") == V2:
        return True
    return any(t == SUPPORT or t.startswith(BODY) for p in drawing.pieces for t in p.tags)
