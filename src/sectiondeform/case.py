"""A deformation case: section curves, target, law and options (``section-case/1``).

:func:`load_case` reads a case file, :func:`case_from_dict` checks a parsed
one field by field, :func:`case_to_dict` writes it back; ``read(write(c))``
gives back an equal case.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from .curves import Curve, curve_from_json
from .errors import CaseError
from .laws import Law, law_from_json

__all__ = ["Case", "load_case", "case_from_dict", "case_to_dict", "CASE_FORMAT", "MODELS"]

CASE_FORMAT = "section-case/1"
MODELS = ("paper", "hyperelastic")


@dataclass(frozen=True)
class Case:
    """One deformation problem.

    Attributes
    ----------
    lower : Curve
        Boundary curve BC, from A to B, lying on the support.
    upper : Curve
        The rest of the contour, from B back to A.
    target : Curve
        Deformed boundary curve, from A' to B'.
    law : Law
        Mechanical law ML.
    name : str
    units : str
        Length unit of every coordinate (``"mm"``).
    options : dict
        ``chordal_error`` (units), ``model`` (``"paper"`` or
        ``"hyperelastic"``), ``bulk_to_shear``, and the project's own keys
        (``element_size`` in units, ``refine`` factor).
    """

    lower: Curve
    upper: Curve
    target: Curve
    law: Law
    name: str = "section"
    units: str = "mm"
    options: dict = field(default_factory=dict)

    @property
    def model(self) -> str:
        """Name of the deformation model the case asks for."""
        return self.options.get("model", "paper")


def _positive(options: dict, key: str) -> None:
    if key in options:
        v = options[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
            raise CaseError(f"options.{key}", f"must be a finite number > 0, got {v!r}")


def case_from_dict(data) -> Case:
    """Check a parsed case object and build a :class:`Case`.

    Parameters
    ----------
    data : dict
        A ``section-case/1`` object.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        Naming the first field at fault.

    Examples
    --------
    >>> c = case_from_dict({"format": "section-case/1",
    ...     "lower": {"polyline": [[0, 0], [1, 0]]},
    ...     "upper": {"polyline": [[1, 0], [1, 1], [0, 1], [0, 0]]},
    ...     "target": {"polyline": [[0, 0], [1, 0]]}, "law": {"area_ratio": 0.8}})
    >>> c.law.ratio, c.model
    (0.8, 'paper')
    """
    if not isinstance(data, dict):
        raise CaseError("case", f"expected a JSON object, got {type(data).__name__}")
    fmt = data.get("format", CASE_FORMAT)
    if fmt != CASE_FORMAT:
        raise CaseError("format", f"expected {CASE_FORMAT!r}, got {fmt!r}")
    for key in ("lower", "upper", "target", "law"):
        if key not in data:
            raise CaseError(key, "missing; a case needs lower, upper, target and law")
    options = data.get("options", {}) or {}
    if not isinstance(options, dict):
        raise CaseError("options", f"expected an object, got {type(options).__name__}")
    for key in ("chordal_error", "bulk_to_shear", "element_size", "refine"):
        _positive(options, key)
    model = options.get("model", "paper")
    if model not in MODELS:
        raise CaseError("options.model", f"unknown model {model!r}; use one of {', '.join(MODELS)}")
    for key in ("name", "units"):
        if key in data and not isinstance(data[key], str):
            raise CaseError(key, f"expected a string, got {data[key]!r}")
    return Case(
        lower=curve_from_json(data["lower"], "lower"),
        upper=curve_from_json(data["upper"], "upper"),
        target=curve_from_json(data["target"], "target"),
        law=law_from_json(data["law"]),
        name=data.get("name", "section"),
        units=data.get("units", "mm"),
        options=dict(options),
    )


def case_to_dict(case: Case) -> dict:
    """The ``section-case/1`` object of a :class:`Case`."""
    out = {
        "format": CASE_FORMAT,
        "name": case.name,
        "units": case.units,
        "lower": case.lower.to_json(),
        "upper": case.upper.to_json(),
        "target": case.target.to_json(),
        "law": case.law.to_json(),
    }
    if case.options:
        out["options"] = dict(case.options)
    return out


def load_case(path) -> Case:
    """Read a case JSON file.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        If the file cannot be read, is not JSON, or is not a valid case.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise CaseError(str(path), f"cannot read the case file ({exc.strerror})") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise CaseError(str(path), f"not valid JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}") from None
    return case_from_dict(data)
