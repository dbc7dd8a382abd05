"""A deformation case: section curves, target, law and options (``section-case/1``).

:func:`load_case` reads a case file, :func:`case_from_dict` checks a parsed
one field by field, :func:`case_to_dict` writes it back; ``read(write(c))``
gives back an equal case. A :class:`Case` and its :class:`Options` are
immutable and hashable; two cases are equal when their case objects are.

Unknown keys are errors naming the nearest known key, at the top level and
in ``options``, except keys starting with ``x-`` and an ``extra`` object,
which hold the user's own data and are carried through unread (``note`` is
also accepted at the top level).
"""

from __future__ import annotations

import dataclasses
import difflib
import json
from dataclasses import dataclass
from pathlib import Path

from .checks import positive
from .curves import Curve, curve_from_json
from .errors import CaseError
from .laws import Law, law_from_json
from .models import DEFAULT_MODEL, MODEL_NAMES, check_model_name, get_model, model_options_types
from .models.base import ModelOptions

__all__ = [
    "Case", "Options", "load_case", "case_from_dict", "case_to_dict", "options_from_json", "read_json",
    "CASE_FORMAT", "MODELS", "CASE_KEYS", "COMMON_OPTIONS",
]

CASE_FORMAT = "section-case/1"
MODELS = MODEL_NAMES  # the registry's names (sectiondeform.models)
CASE_KEYS = ("format", "name", "units", "lower", "upper", "target", "law", "options", "note")
COMMON_OPTIONS = ("model", "chordal_error", "element_size", "refine", "contact_tolerance")
REFINE_MAX = 64.0


def _is_user_key(key: str) -> bool:
    return key.startswith("x-") or key == "extra"


def unknown_key(field: str, key, known) -> CaseError:
    """The error for an unknown ``key`` under ``field``, naming the nearest known key (difflib)."""
    near = difflib.get_close_matches(str(key), list(known), n=1)
    hint = f"did you mean {near[0]}?" if near else f"use one of {', '.join(known)}"
    where = f"{field}.{key}" if field else str(key)
    return CaseError(where, f"unknown {'option' if field == 'options' else 'key'}; {hint} "
                            "(own data: prefix x- or put it under extra)")


@dataclass(frozen=True)
class Options:
    """The case's ``options``, checked once: the common ones and every model's.

    Attributes
    ----------
    model : str
        Name of the deformation model (:data:`~sectiondeform.models.MODEL_NAMES`).
    chordal_error : float or None
        Chordal error of the discretisation, units; None: 1e-4 of the
        section's diagonal.
    element_size : float or None
        Element size, units; None: from the discretisation.
    refine : float
        Divides the element size (1 to refine nothing), at most 64.
    contact_tolerance : float or None
        Reserved for assemblies, units.
    model_values : tuple of (str, float)
        Options of the models (``bulk_to_shear``...), sorted by key; each
        key is read by at least one registered model. :meth:`for_model`
        gives one model's options type.
    user : str
        The ``x-*`` keys and ``extra`` object, as canonical JSON, carried
        through unread (:attr:`user_data`).
    """

    model: str = DEFAULT_MODEL
    chordal_error: float | None = None
    element_size: float | None = None
    refine: float = 1.0
    contact_tolerance: float | None = None
    model_values: tuple = ()
    user: str = "{}"

    def __post_init__(self):
        check_model_name(self.model)
        for key in ("chordal_error", "element_size", "contact_tolerance"):
            if getattr(self, key) is not None:
                object.__setattr__(self, key, positive(getattr(self, key), f"options.{key}"))
        object.__setattr__(self, "refine", positive(self.refine, "options.refine", high=REFINE_MAX))
        values = tuple(sorted(dict(self.model_values).items()))
        if values:
            types = model_options_types()
            for key, value in values:
                owners = [t for t in types.values() if key in t.keys()]
                if not owners:
                    known = COMMON_OPTIONS + tuple(k for t in types.values() for k in t.keys())
                    raise unknown_key("options", key, known)
                for t in owners:
                    t(**{key: value})  # checks the value
        object.__setattr__(self, "model_values", values)

    def for_model(self, name: str | None = None) -> ModelOptions:
        """The options of model ``name`` (by default :attr:`model`) as its own frozen type."""
        t = get_model(name or self.model).options_type
        keys = t.keys()
        return t(**{k: v for k, v in self.model_values if k in keys})

    @property
    def user_data(self) -> dict:
        """The user's own ``x-*`` keys and ``extra`` object (a new dict each time)."""
        return json.loads(self.user)

    def to_json(self) -> dict:
        """The ``options`` object: the values set, the model's if not the default, and the user's keys."""
        out = {} if self.model == DEFAULT_MODEL else {"model": self.model}
        for key in ("chordal_error", "element_size", "contact_tolerance"):
            if getattr(self, key) is not None:
                out[key] = getattr(self, key)
        if self.refine != 1.0:
            out["refine"] = self.refine
        out.update(self.model_values)
        out.update(self.user_data)
        return out

    def replace(self, **changes) -> Options:
        """These options with ``changes`` (any option key, common or a model's), checked."""
        return options_from_json({**self.to_json(), **changes})


def options_from_json(obj, field: str = "options") -> Options:
    """Check an ``options`` object and build :class:`Options`.

    Raises
    ------
    CaseError
        For an unknown key (naming the nearest known one) or a bad value.

    Examples
    --------
    >>> options_from_json({"chordal_eror": 0.01})
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: options.chordal_eror: unknown option; did you mean chordal_error? (own data: prefix x- or put it under extra)
    """
    if obj is None:
        obj = {}
    if isinstance(obj, Options):
        return obj
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected an object, got {type(obj).__name__}")
    common, model_values, user = {}, {}, {}
    for key, value in obj.items():
        if not isinstance(key, str):
            raise CaseError(field, f"option names must be strings, got {key!r}")
        if _is_user_key(key):
            user[key] = value
        elif key in COMMON_OPTIONS:
            common[key] = value
        else:
            model_values[key] = value
    try:
        user_json = json.dumps(user, sort_keys=True, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise CaseError(f"{field}.extra", f"the user's data must be plain JSON ({exc})") from None
    return Options(**common, model_values=tuple(model_values.items()), user=user_json)


@dataclass(frozen=True, eq=False)
class Case:
    """One deformation problem; immutable, hashable, equal to another with the same case object.

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
    options : Options
        A dict is accepted and checked (:func:`options_from_json`).
    """

    lower: Curve
    upper: Curve
    target: Curve
    law: Law
    name: str = "section"
    units: str = "mm"
    options: Options = Options()

    def __post_init__(self):
        if not isinstance(self.options, Options):
            object.__setattr__(self, "options", options_from_json(self.options))

    @property
    def model(self) -> str:
        """Name of the deformation model the case asks for."""
        return self.options.model

    def _key(self) -> str:
        key = self.__dict__.get("_json_key")
        if key is None:
            key = json.dumps(case_to_dict(self), sort_keys=True)
            object.__setattr__(self, "_json_key", key)
        return key

    def __eq__(self, other):
        if not isinstance(other, Case):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def replace(self, **changes) -> Case:
        """The case with ``changes`` (fields of :class:`Case`); ``options`` may be a dict."""
        return dataclasses.replace(self, **changes)


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
    for key in data:
        if not isinstance(key, str) or not (key in CASE_KEYS or _is_user_key(key)):
            raise unknown_key("", key, CASE_KEYS)
    for key in ("lower", "upper", "target", "law"):
        if key not in data:
            raise CaseError(key, "missing; a case needs lower, upper, target and law")
    options = options_from_json(data.get("options"))
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
        options=options,
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
    options = case.options.to_json()
    if options:
        out["options"] = options
    return out


def load_case(path):
    """Read a case JSON file.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    Case or Assembly

    Raises
    ------
    CaseError
        If the file cannot be read, is not JSON, or is not a valid case.

    A ``section-case/2`` file gives an :class:`~sectiondeform.assembly.Assembly`
    (a version-1 file stays a version-1 :class:`Case`).
    """
    data = read_json(path)
    if isinstance(data, dict) and data.get("format") == "section-case/2":
        from .assembly import assembly_from_dict  # the assembly module imports this one

        return assembly_from_dict(data)
    return case_from_dict(data)


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
