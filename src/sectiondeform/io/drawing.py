"""From a drawing (DXF or SVG), or a case JSON naming one, to a :class:`~sectiondeform.problem.Problem`.

A drawing holds either dialect of the case format, by its layers
(:mod:`.layers`; DXF layer names, SVG ids or classes, matched without
regard to case):

- ``section-case/1``, the paper's one body: its lower and upper curves on
  ``LOWER`` and ``UPPER`` (or one closed contour split at two points), the
  target on ``TARGET`` (:mod:`.outline` says how, with every option);
- ``section-case/2``, when it stores that format or has a ``SUPPORT`` or a
  ``BODY-...`` layer: the support, the target and the bodies on their
  layers or as contours resting on each other (:mod:`.stacking`).

Both are read by :func:`case_from_drawing` along one path: the pieces are
chained into the bodies' curves, the target is drawn or built
(``target_arc``), each body's law is ``law=`` or the one the drawing
stores, and ``units`` converts the problem at the end. The options are a
:class:`DrawingOptions`. A body's holes are the closed contours on its
``BODY-<name>-HOLE`` layer, inside its contour on ``BODY-<name>``, beside
its open curve on its curve layers, or on a layer the case does not read
lying inside it (:mod:`.holes`); they are
reported per body, and a one-body drawing with holes becomes a
``section-case/2`` problem. A closed contour crossing or touching a body's
contour is refused. Entities no curve of the problem comes from are
reported (how many, on which layers).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from ..curves import DEFAULT_CHORDAL_FRACTION, curve_from_json
from ..errors import CaseError
from ..laws import law_from_json
from ..options import is_user_key, unknown_key
from ..problem import V1, V2, Body, Problem, Revolution
from .case import case_from_dict, load_case, material_from_json, read_json, revolution_from_json
from .chaining import unused_summary
from .holes import body_holes, loops_beside
from .layers import AXIS, SUPPORT, TARGET, is_bodies_drawing
from .outline import (
    JSON_KEYS,
    ROLES,
    SIDES,
    SPLIT_FRACTION,
    Context,
    DrawingOptions,
    curves_from_contour,
    curves_from_layers,
    find_target,
    inside_bbox,
    make_target_arc,
    say,
    unused_pieces,
)
from .pieces import Drawing
from .stacking import bodies_from_drawing, check_options, revolution_from_drawing, rigid_from_drawing, stored_bodies, unused_body_pieces
from .units import mm_per_unit

__all__ = [
    "DrawingOptions", "case_from_drawing", "drawing_file_of", "convert_units", "make_target_arc", "read_json_case", "read_drawing_file",
    "ROLES", "SIDES", "SPLIT_FRACTION",
]


def convert_units(case: Problem, units: str, report=None) -> Problem:
    """The problem in other length units: curves, axis and lengths among its options scaled.

    Raises
    ------
    CaseError
        Naming the nearest known unit when either is unknown.
    """
    if units == case.units:
        return case
    k = mm_per_unit(case.units, "units") / mm_per_unit(units, "units")
    o = case.options
    scaled = {key: getattr(o, key) * k for key in ("chordal_error", "element_size", "contact_tolerance")
              if getattr(o, key) is not None}
    rev = case.revolution
    if rev is not None:
        rev = Revolution(tuple(tuple(float(v) * k for v in p) for p in rev.axis))
    bodies = tuple(replace(b, lower=b.lower.scaled(k), upper=b.upper.scaled(k), holes=tuple(h.scaled(k) for h in b.holes))
                   for b in case.bodies)
    say(report, f"units: {case.units} -> {units} (x {k:g})")
    return case.replace(support=case.support.scaled(k), target=case.target.scaled(k), bodies=bodies, units=units,
                        options=o.replace(**scaled) if scaled else o, revolution=rev)


def case_from_drawing(drawing: Drawing, options: DrawingOptions | None = None, *, report=None, **keywords) -> Problem:
    """Build a problem from the pieces of a drawing (see the module docstring).

    Parameters
    ----------
    drawing : Drawing
        From :func:`sectiondeform.io.dxf.read_drawing` or
        :func:`sectiondeform.io.svg.read_drawing`.
    options : DrawingOptions, optional
    report : list, optional
        Lines saying what was done (pieces, snapped gaps...) are appended.
    **keywords
        Instead of ``options``: its attributes by name (a misspelt name is
        an error).

    Returns
    -------
    Problem
        ``section-case/1`` from a one-body drawing without holes, else
        ``section-case/2``.

    Raises
    ------
    CaseError
        A missing layer, a gap, a branch, an unsupported entity, no law,
        no target, an unknown option; each names where. A closed contour
        crossing or touching a body's contour, a bad hole (:mod:`.holes`).
    GeometryError
        If the bodies do not rest on each other as the format says.

    Notes
    -----
    Entities no curve of the problem comes from (other layers, ids or
    classes, annotation) are reported in ``report``: how many, and where.
    """
    if options is None:
        options = DrawingOptions.from_mapping(keywords)
    elif keywords:
        raise CaseError(next(iter(keywords)), "give the options either as DrawingOptions or as keywords, not both")
    o = options
    meta = dict(drawing.meta or {})
    dialect = V2 if is_bodies_drawing(drawing) else V1
    if dialect == V2:
        check_options(o)
        roles = {"support": SUPPORT, "target": (o.layers or {}).get("target", TARGET), "axis": AXIS}
    else:
        roles = {"lower": "LOWER", "upper": "UPPER", "target": TARGET, "contour": "CONTOUR", **(o.layers or {})}
    pieces, ctx = _selection(drawing, o, roles, report)
    revolution, own = None, {}
    if dialect == V2:
        support, found, own = bodies_from_drawing(pieces, ctx, drawing, meta, report)
        revolution = revolution_from_drawing(pieces, ctx, meta, report)
    else:
        if o.split is None:
            pieces, beside = _loops_beside(pieces, ctx, ("lower", "upper"))
            own = {o.name or meta.get("name") or drawing.path.stem: beside}
        lower, upper = (curves_from_contour(pieces, ctx, report) if o.split is not None
                        else curves_from_layers(pieces, ctx, meta, drawing.path, report))
        found = [(None, lower, upper)]
    found = [_simplified(f, o.simplify, dialect, report) for f in found] if o.simplify else found
    support = found[0][1] if dialect == V1 else support
    target = find_target(pieces, support, [c for _, lo, up in found for c in (lo, up)], ctx, meta, drawing.path, report)
    unused = unused_pieces(pieces, ctx) if dialect == V1 else unused_body_pieces(pieces, ctx)
    name = o.name or meta.get("name") or drawing.path.stem
    if dialect == V1:
        found = [(name, *found[0][1:])]
    holes, unused = body_holes(found, own, unused, ctx, drawing.labels, report)
    line = unused_summary(unused, drawing.ignored, drawing.labels, ctx.what)
    if line is not None:
        say(report, line)
    case_options = {**(meta.get("options") or {}), **({"chordal_error": o.chordal_error} if o.chordal_error else {})}
    if dialect == V1 and holes:
        _, lower, upper = found[0]
        body = Body(name=name, lower=lower, upper=upper, law=o.law or _stored_law(meta, "law", ""), holes=holes[name])
        case = Problem(support=lower, target=target, bodies=(body,), name=name, units=drawing.units,
                       options=case_options, dialect=V2)
        say(report, "the section has holes: read as a section-case/2 problem (one body on the support)")
    elif dialect == V1:
        _, lower, upper = found[0]
        case = Problem.single(lower, upper, target, o.law or _stored_law(meta, "law", ""), name=name,
                              units=drawing.units, options=case_options)
    else:
        case = Problem(support=support, target=target, bodies=_bodies(found, holes, meta, o, revolution), name=name,
                       units=drawing.units, options=case_options, revolution=revolution, dialect=V2,
                       rigid=rigid_from_drawing(pieces, ctx, drawing, meta, report))
        say(report, f"bodies: {len(found)} ({', '.join(b.name for b in case.bodies)}), resting order "
                    f"{' < '.join(case.bodies[k].name for k in case.layout.order)}")
    return convert_units(case, o.units, report) if o.units else case


def _selection(drawing: Drawing, o: DrawingOptions, roles: dict, report) -> tuple[list, Context]:
    """The pieces read (inside ``bbox``) and the context of their chaining: names and tolerances."""
    pieces = list(drawing.pieces)
    if o.bbox is not None:
        pieces = inside_bbox(pieces, o.bbox, report)
    if drawing.unitless:
        say(report, f"the drawing declares no units ($INSUNITS): taken as {drawing.units}")
    curves = [p for p in pieces if p.curve is not None]
    if not curves:
        raise CaseError(str(drawing.path), "the drawing has no curves" + (" inside the bbox" if o.bbox is not None else ""))
    ends = np.concatenate([np.vstack(p.curve.ends) for p in curves])
    diag = float(np.hypot(*np.ptp(ends, axis=0))) or 1.0
    ctx = Context(what="layer" if drawing.path.suffix.lower() == ".dxf" else "id/class", roles=roles,
                  tol=o.join_tol if o.join_tol is not None else 1e-6 * diag,
                  chord=o.chordal_error or DEFAULT_CHORDAL_FRACTION * diag, diag=diag, options=o)
    return pieces, ctx


def _loops_beside(pieces: list, ctx: Context, roles) -> tuple[list, list]:
    """``pieces`` less the closed contours drawn beside the open curves of ``roles``' layers; those contours (:func:`.holes.loops_beside`)."""
    loops = []
    for role in roles:
        if not ctx.has(pieces, role):
            continue
        chosen = ctx.select(pieces, role)
        kept, found = loops_beside(chosen, ctx.where(role), ctx)
        if found:
            drop = {id(p) for p in chosen} - {id(p) for p in kept}
            pieces = [p for p in pieces if id(p) not in drop]
            loops += found
    return pieces, loops


def _simplified(found: tuple, tol: float, dialect: str, report) -> tuple:
    """A body's (name, lower, upper) with its curves simplified within ``tol``, reported."""
    name, lower, upper = found
    before = lower.point_count + upper.point_count
    lower, upper = lower.simplified(tol), upper.simplified(tol)
    who = "" if dialect == V1 else f"body {name!r}: "
    say(report, f"{who}simplified within {tol:g}: {before} -> {lower.point_count + upper.point_count} points "
                f"(lower {lower.point_count}, upper {upper.point_count})")
    return name, lower, upper


def _stored_law(data: dict, field: str, who: str, axis=None):
    """The law a drawing stores (``data["law"]``); an error saying how to give one if it stores none."""
    if "law" not in data:
        raise CaseError("law", f"{who}the drawing stores no law; give law=AreaRatio(R) (final area = R x initial area)"
                        + (", or the bodies' laws in a case JSON" if who else ""))
    return law_from_json(data["law"], field, axis)


def _bodies(found: list, holes: dict, meta: dict, o: DrawingOptions, revolution) -> tuple:
    """The bodies of a ``section-case/2`` drawing: curves and holes found, laws and materials given or stored."""
    stored = stored_bodies(meta)
    axis = revolution.axis if revolution is not None else None
    out = []
    for i, (name, lower, upper) in enumerate(found):
        data = stored.get(name.upper(), {})
        law = o.law or _stored_law(data, f"bodies[{i}].law", f"body {name!r}: ", axis)
        material = material_from_json(data.get("material"), f"bodies[{i}].material")
        out.append(Body(name=name, lower=lower, upper=upper, law=law, material=material, holes=holes.get(name, ())))
    return tuple(out)


# --------------------------------------------------------------------------
# Case JSON that names a drawing


def read_drawing_file(path, chordal_error=None) -> Drawing:
    """The pieces of a drawing file, by extension (the formats :func:`sectiondeform.io.read_drawing` knows)."""
    from . import read_drawing

    return read_drawing(path, chordal_error)


def _plain_case(path: Path, options: DrawingOptions, given, report) -> Problem:
    """A case JSON without a drawing, with the options that apply to any case (units, law, chordal error, name)."""
    drawing_only = [k for k in given if k not in ("units", "law", "chordal_error", "name")]
    if drawing_only:
        raise CaseError(drawing_only[0], f"applies to drawings (DXF, SVG) only, and {path.name} is a case JSON without one")
    case = load_case(path)
    if options.law is not None:
        if len(case.bodies) != 1:
            raise CaseError("law", f"the case has {len(case.bodies)} bodies and does not take this option; set each "
                                   "body's law in the case")
        case = case.replace(law=options.law)
    if options.name is not None:
        case = case.replace(name=options.name)
    if options.chordal_error:
        case = case.replace(options=case.options.replace(chordal_error=options.chordal_error))
    return convert_units(case, options.units, report) if options.units else case


def drawing_file_of(path, name, allow_files=True) -> Path:
    """The drawing file a case JSON at ``path`` names, confined to the folder the caller allows.

    Parameters
    ----------
    path : path-like
        The case JSON; ``name`` is relative to its folder.
    name : str
        The JSON's ``drawing.file``.
    allow_files : bool or path-like
        True: files inside the JSON's own folder (or below it); a folder:
        files inside that folder; False or None: no file at all.

    Returns
    -------
    Path
        ``path``'s folder / ``name``, not yet opened.

    Raises
    ------
    CaseError
        On ``drawing.file``, the same whether or not the file exists: no
        files allowed, or one outside the allowed folder (an absolute path,
        ``..`` or a link leading out of it).
    """
    if allow_files is None or allow_files is False:
        raise CaseError("drawing.file", "this reader opens no drawing files; give the curves in the case, "
                                        "or read the drawing itself")
    base = Path(path).parent if allow_files is True else Path(allow_files)
    wanted = Path(path).parent / name
    try:
        inside = wanted.resolve().is_relative_to(base.resolve())
    except (OSError, RuntimeError, ValueError):
        inside = False
    if Path(name).is_absolute() or not inside:
        raise CaseError("drawing.file", f"{name!r} is outside the case's folder; name a drawing file in the "
                                        "case file's folder (or below it)")
    return wanted


def read_json_case(path, *, report=None, allow_files=True, **options) -> Problem:
    """Read a case JSON file; one with a ``"drawing"`` key takes its curves from a DXF or SVG.

    ``"drawing": {"file": "profile.dxf", "layers": {"lower": "BASE"}, ...}``
    (file relative to the JSON's folder; the other keys are
    :class:`DrawingOptions`). Curves given in the JSON (``lower``,
    ``upper``, ``target``) take precedence over the drawing's; ``law``,
    ``name``, ``units`` and ``options`` are read as usual. Options given
    here (the :class:`DrawingOptions` attributes, by name) override the
    JSON's ``drawing`` keys; for a case JSON without a drawing only
    ``units``, ``law``, ``name`` and ``chordal_error`` apply, and the
    others are an error. A ``section-case/2`` JSON gives the bodies' laws
    and materials by name (:func:`_bodies_with_drawing`).

    The drawing file must lie in the folder ``allow_files`` allows (see
    :func:`drawing_file_of`): by default the JSON's own folder, never an
    absolute path or one leading out of it with ``..``; ``False`` reads no
    drawing file (a program reading cases from others, such as the page's
    server, passes it).
    """
    path = Path(path)
    given = {k: v for k, v in options.items() if v is not None}
    overrides = DrawingOptions.from_mapping(given)
    data = read_json(path)
    if not isinstance(data, dict) or "drawing" not in data:
        return _plain_case(path, overrides, given, report)
    d = data["drawing"]
    if not isinstance(d, dict) or not isinstance(d.get("file"), str):
        raise CaseError("drawing.file", "expected {\"file\": \"profile.dxf\", ...} naming a DXF or SVG file")
    opts = {k: v for k, v in d.items() if k != "file"}
    DrawingOptions.from_mapping(opts, "drawing", allowed=JSON_KEYS)
    drawing_path = drawing_file_of(path, d["file"], allow_files)
    opts.update(given)
    if data.get("format") == V2:
        return _bodies_with_drawing(drawing_path, data, opts, report)
    if "law" in data and overrides.law is None:
        opts["law"] = law_from_json(data["law"])
    if "target" in data:
        opts["target"] = curve_from_json(data["target"], "target")
    drawing = _drawing_of(drawing_path, data, opts)
    case = case_from_drawing(drawing, DrawingOptions.from_mapping(opts), report=report)
    merged = {"format": data.get("format", V1), "lower": case.lower.to_json(), "upper": case.upper.to_json(),
              "target": case.target.to_json(), "law": case.law.to_json(), "name": data.get("name", case.name),
              "units": data.get("units", case.units), "options": {**case.options.to_json(), **(data.get("options") or {})}}
    for key in ("lower", "upper"):
        if key in data:
            merged[key] = data[key]
    return case_from_dict(merged)


def _drawing_of(drawing_path: Path, data: dict, opts: dict) -> Drawing:
    """The drawing a case JSON names (at ``drawing_path``, already confined), read with the chordal error of the options or of the case."""
    chordal = (data.get("options") or {}).get("chordal_error")
    return read_drawing_file(drawing_path, opts.get("chordal_error") or chordal)


JSON_BODY_KEYS = ("name", "law", "material", "note")
BODIES_JSON_KEYS = ("format", "name", "units", "target", "revolution", "bodies", "options", "drawing", "note")


def _bodies_with_drawing(drawing_path: Path, data: dict, opts: dict, report=None) -> Problem:
    """A ``section-case/2`` problem whose curves are a drawing's and whose laws and materials a case JSON gives.

    ``{"format": "section-case/2", "drawing": {"file": "layup.dxf", ...},
    "bodies": [{"name": "tread", "law": {...}, "material": {...}}, ...]}``:
    the bodies are the drawing's, matched by name (without regard to case),
    in the JSON's order; ``target``, ``revolution``, ``options``, ``name``
    and ``units`` (a relabelling, as for one body) of the JSON take
    precedence over the drawing's.

    Raises
    ------
    CaseError
        A key this form does not take (curves of a body: draw them), a body
        of the JSON with no layer, or the errors of :func:`case_from_drawing`.
    """
    for key in data:
        if key not in BODIES_JSON_KEYS and not is_user_key(key):
            raise unknown_key("", key, BODIES_JSON_KEYS)
    bodies = data.get("bodies", [])
    if not isinstance(bodies, list):
        raise CaseError("bodies", f"expected a list of {{\"name\", \"law\", \"material\"}}, got {bodies!r}")
    for i, b in enumerate(bodies):
        if not isinstance(b, dict) or not isinstance(b.get("name"), str):
            raise CaseError(f"bodies[{i}]", "expected {\"name\": ..., \"law\": ...}; the curves are the drawing's")
        for key in b:
            if key not in JSON_BODY_KEYS and not str(key).startswith("x-"):
                hint = "; with a drawing, a body's curves are drawn on its layers" if key in ("lower", "upper") else ""
                raise CaseError(f"bodies[{i}].{key}", f"not taken here{hint}; use {', '.join(JSON_BODY_KEYS)}")
    revolution = revolution_from_json(data["revolution"]) if "revolution" in data else None
    axis = revolution.axis if revolution is not None else None
    if "target" in data:
        opts["target"] = curve_from_json(data["target"], "target")
    drawing = _drawing_of(drawing_path, data, opts)
    meta = dict(drawing.meta or {})
    stored = stored_bodies(meta)
    merged = []
    for i, b in enumerate(bodies):
        entry = {**stored.pop(b["name"].upper(), {}), **{k: v for k, v in b.items() if k in ("name", "law", "material")}}
        if "law" in b:
            law_from_json(b["law"], f"bodies[{i}].law", axis)  # checked here, to name the JSON's field
        merged.append(entry)
    meta.update(bodies=merged + list(stored.values()), format=V2,
                options={**(meta.get("options") or {}), **(data.get("options") or {})})
    if revolution is not None:
        meta["revolution"] = revolution.to_json()
    if "name" in data:
        meta["name"] = data["name"]
    problem = case_from_drawing(replace(drawing, meta=meta), DrawingOptions.from_mapping(opts), report=report)
    if "units" in data and "units" not in opts:
        problem = problem.replace(units=data["units"])
    return problem
