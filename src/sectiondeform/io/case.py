"""The case file format: ``section-case/1`` and ``section-case/2`` objects to and from a :class:`Problem`.

:func:`case_from_dict` checks a parsed case object field by field and
builds a :class:`~sectiondeform.problem.Problem`; :func:`case_to_dict`
writes it back in the dialect it came in (``read(write(p))`` gives back an
equal problem). Version 1 is the paper's one body on its own lower curve;
version 2 gives a support, a target and any number of bodies. Unknown keys
are errors naming the nearest known key, except keys starting with ``x-``
and an ``extra`` object, which hold the user's own data (``note`` is also
accepted at the top level and in a body).
"""

from __future__ import annotations

import json
from pathlib import Path

from ..checks import number
from ..curves import curve_from_json
from ..errors import CaseError
from ..laws import law_from_json
from ..materials import MATERIAL_MODELS as RUBBERS
from ..options import is_user_key, options_from_json, unknown_key
from ..problem import V1, V2, Body, Problem, Revolution, Rigid
from .units import mm_per_unit

__all__ = [
    "case_from_dict", "case_to_dict", "load_case", "read_json", "revolution_from_json", "material_from_json",
    "V1_KEYS", "V2_KEYS", "BODY_KEYS", "RIGID_KEYS", "MATERIAL_KEYS", "MATERIAL_MODELS",
]

V1_KEYS = ("format", "name", "units", "lower", "upper", "target", "law", "options", "note")
V2_KEYS = ("format", "name", "units", "support", "target", "revolution", "bodies", "rigid", "options", "note")
RIGID_KEYS = ("name", "contour", "travel", "friction", "note")
BODY_KEYS = ("name", "lower", "upper", "holes", "law", "material", "note")
MATERIAL_KEYS = ("model", "shear_modulus", "bulk_to_shear", "bulk_modulus", "c10", "c01", "c20", "c30")
MATERIAL_MODELS = tuple(RUBBERS)


def case_from_dict(data) -> Problem:
    """Check a parsed case object (either version) and build a :class:`~sectiondeform.problem.Problem`.

    Parameters
    ----------
    data : dict
        A ``section-case/1`` object (``format`` may be left out) or a
        ``section-case/2`` one.

    Raises
    ------
    CaseError
        Naming the first field at fault.
    GeometryError
        If the bodies do not rest on each other as the format says, or the
        axis of revolution crosses a body.

    Examples
    --------
    >>> p = case_from_dict({"format": "section-case/1",
    ...     "lower": {"polyline": [[0, 0], [1, 0]]},
    ...     "upper": {"polyline": [[1, 0], [1, 1], [0, 1], [0, 0]]},
    ...     "target": {"polyline": [[0, 0], [1, 0]]}, "law": {"area_ratio": 0.8}})
    >>> p.law.ratio, p.model, len(p.bodies)
    (0.8, 'paper', 1)
    >>> a = case_from_dict({"format": "section-case/2",
    ...     "support": {"polyline": [[0, 0], [2, 0]]}, "target": {"polyline": [[0, 0], [2, 0]]},
    ...     "bodies": [{"name": "base", "lower": {"polyline": [[0, 0], [2, 0]]},
    ...                 "upper": {"polyline": [[2, 0], [2, 1], [0, 1], [0, 0]]}, "law": {"area_ratio": 0.9}},
    ...                {"name": "top", "lower": {"polyline": [[0, 1], [2, 1]]},
    ...                 "upper": {"polyline": [[2, 1], [1, 2], [0, 1]]}, "law": {"area_ratio": 1.0}}]})
    >>> a.layout.order, a.layout.foundations
    ((0, 1), ((), (0,)))
    """
    if not isinstance(data, dict):
        raise CaseError("case", f"expected a JSON object, got {type(data).__name__}")
    fmt = data.get("format", V1)
    if fmt not in (V1, V2):
        raise CaseError("format", f"expected {V1!r} or {V2!r}, got {fmt!r}")
    known = V1_KEYS if fmt == V1 else V2_KEYS
    for key in data:
        if not isinstance(key, str) or not (key in known or is_user_key(key)):
            raise unknown_key("", key, known)
    needed = ("lower", "upper", "target", "law") if fmt == V1 else ("support", "target", "bodies")
    for key in needed:
        if key not in data:
            raise CaseError(key, f"missing; a {fmt} case needs {', '.join(needed)}")
    for key in ("name", "units"):
        if key in data and not isinstance(data[key], str):
            raise CaseError(key, f"expected a string, got {data[key]!r}")
    units = data.get("units", "mm")
    mm_per_unit(units)
    options = options_from_json(data.get("options"))
    if fmt == V1:
        name = data.get("name", "section")
        return Problem.single(curve_from_json(data["lower"], "lower"), curve_from_json(data["upper"], "upper"),
                              curve_from_json(data["target"], "target"), law_from_json(data["law"]),
                              name=name, units=units, options=options)
    revolution = revolution_from_json(data["revolution"]) if "revolution" in data else None
    raw = data["bodies"]
    if not isinstance(raw, list) or not raw:
        raise CaseError("bodies", f"expected a non-empty list of bodies, got {raw!r}")
    axis = revolution.axis if revolution is not None else None
    bodies = [_body_from_json(b, f"bodies[{i}]", axis) for i, b in enumerate(raw)]
    rigid = data.get("rigid", [])
    if not isinstance(rigid, list):
        raise CaseError("rigid", f"expected a list of rigid parts, got {rigid!r}")
    return Problem(
        support=curve_from_json(data["support"], "support"),
        target=curve_from_json(data["target"], "target"),
        bodies=tuple(bodies),
        name=data.get("name", "assembly"),
        units=units,
        options=options,
        revolution=revolution,
        dialect=V2,
        rigid=tuple(_rigid_from_json(r, f"rigid[{i}]") for i, r in enumerate(rigid)),
    )


def _rigid_from_json(obj, field: str) -> Rigid:
    """Check one ``rigid`` object: a name, a closed ``contour``, a ``travel`` [dx, dy], a ``friction`` >= 0."""
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected a rigid part object, got {type(obj).__name__}")
    for key in obj:
        if not isinstance(key, str) or not (key in RIGID_KEYS or is_user_key(key)):
            raise unknown_key(field, key, RIGID_KEYS)
    for key in ("name", "contour"):
        if key not in obj:
            raise CaseError(f"{field}.{key}", "missing; a rigid part needs name and contour (travel and friction optional)")
    name = obj["name"]
    if not isinstance(name, str) or not name:
        raise CaseError(f"{field}.name", f"expected a non-empty string, got {name!r}")
    travel = obj.get("travel", [0.0, 0.0])
    if not isinstance(travel, list) or len(travel) != 2:
        raise CaseError(f"{field}.travel", f"expected two finite numbers [dx, dy], got {travel!r}")
    travel = tuple(number(v, f"{field}.travel[{k}]") for k, v in enumerate(travel))
    friction = number(obj.get("friction", 0.0), f"{field}.friction", low=0.0)
    return Rigid(name=name, contour=curve_from_json(obj["contour"], f"{field}.contour"), travel=travel, friction=friction)


def _body_from_json(obj, field: str, axis=None) -> Body:
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected a body object, got {type(obj).__name__}")
    for key in obj:
        if not isinstance(key, str) or not (key in BODY_KEYS or is_user_key(key)):
            raise unknown_key(field, key, BODY_KEYS)
    for key in ("name", "lower", "upper", "law"):
        if key not in obj:
            raise CaseError(f"{field}.{key}", "missing; a body needs name, lower, upper and law")
    name = obj["name"]
    if not isinstance(name, str) or not name:
        raise CaseError(f"{field}.name", f"expected a non-empty string, got {name!r}")
    holes = obj.get("holes", [])
    if not isinstance(holes, list):
        raise CaseError(f"{field}.holes", f"expected a list of closed curves, got {type(holes).__name__}")
    return Body(
        name=name,
        lower=curve_from_json(obj["lower"], f"{field}.lower"),
        upper=curve_from_json(obj["upper"], f"{field}.upper"),
        law=law_from_json(obj["law"], f"{field}.law", axis),
        material=material_from_json(obj.get("material"), f"{field}.material"),
        holes=tuple(curve_from_json(h, f"{field}.holes[{k}]") for k, h in enumerate(holes)),
    )


def revolution_from_json(obj, field: str = "revolution") -> Revolution:
    """Check a ``revolution`` object: ``{"axis": [[x, y], [x, y]]}`` with two distinct points."""
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected an object {{\"axis\": [[x, y], [x, y]]}}, got {obj!r}")
    for key in obj:
        if key != "axis":
            raise unknown_key(field, key, ("axis",))
    axis = obj.get("axis")
    if not isinstance(axis, list) or len(axis) != 2 or not all(isinstance(p, list) and len(p) == 2 for p in axis):
        raise CaseError(f"{field}.axis", f"expected two points [[x, y], [x, y]], got {axis!r}")
    pts = tuple(tuple(number(v, f"{field}.axis[{i}]") for v in p) for i, p in enumerate(axis))
    if pts[0] == pts[1]:
        raise CaseError(f"{field}.axis", "the two points coincide; give two distinct points of the axis")
    return Revolution(pts)


def material_from_json(obj, field: str) -> str:
    """Check a body's ``material`` object; its canonical JSON text (the paper model ignores it)."""
    if obj is None:
        return "{}"
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected an object such as {{\"shear_modulus\": 1.0}}, got {obj!r}")
    for key, value in obj.items():
        if key not in MATERIAL_KEYS:
            raise unknown_key(field, key, MATERIAL_KEYS)
        if key == "model":
            if value not in MATERIAL_MODELS:
                raise CaseError(f"{field}.model", f"unknown rubber model {value!r}; use one of {', '.join(MATERIAL_MODELS)}")
        elif key in ("shear_modulus", "bulk_to_shear", "bulk_modulus", "c10"):
            number(value, f"{field}.{key}", low=0.0, strict_low=True)
        else:
            number(value, f"{field}.{key}")
    return json.dumps(obj, sort_keys=True)


def case_to_dict(problem: Problem) -> dict:
    """The case object of a problem, in its dialect (``section-case/1`` for the paper's one body)."""
    if problem.dialect == V1:
        body = problem.bodies[0]
        out = {"format": V1, "name": problem.name, "units": problem.units, "lower": body.lower.to_json(),
               "upper": body.upper.to_json(), "target": problem.target.to_json(), "law": body.law.to_json()}
    else:
        out = {"format": V2, "name": problem.name, "units": problem.units, "support": problem.support.to_json(),
               "target": problem.target.to_json()}
        if problem.revolution is not None:
            out["revolution"] = problem.revolution.to_json()
        out["bodies"] = [b.to_json() for b in problem.bodies]
        if problem.rigid:
            out["rigid"] = [r.to_json() for r in problem.rigid]
    options = problem.options.to_json()
    if options:
        out["options"] = options
    return out


def load_case(path) -> Problem:
    """Read a case JSON file (either version) as a :class:`~sectiondeform.problem.Problem`.

    Raises
    ------
    CaseError
        If the file cannot be read, is not JSON, or is not a valid case.
    """
    return case_from_dict(read_json(path))


def read_json(path):
    """Parse a JSON file, any failure as one line naming the file.

    Raises
    ------
    CaseError
        If the file cannot be read, is not UTF-8, is not JSON, or nests too deeply.
    """
    path = Path(path)
    try:
        text = path.read_bytes().decode("utf-8")
    except OSError as exc:
        raise CaseError(str(path), f"cannot read the case file ({exc.strerror})") from None
    except UnicodeDecodeError as exc:
        raise CaseError(str(path), f"not UTF-8 text (byte {exc.start}); save the file as UTF-8") from None
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise CaseError(str(path), f"not valid JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}") from None
    except RecursionError:
        raise CaseError(str(path), "the JSON nests too deeply to be a case") from None
