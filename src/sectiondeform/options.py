"""The options of a problem, common to every model and each model's own, checked once.

Unknown keys are errors naming the nearest known key, except keys starting
with ``x-`` and an ``extra`` object, which hold the user's own data and are
carried through unread.
"""

from __future__ import annotations

import difflib
import json
from dataclasses import dataclass

from .checks import positive
from .errors import CaseError
from .models import DEFAULT_MODEL, check_model_name, get_model, model_options_types
from .models.base import ModelOptions

__all__ = ["Options", "options_from_json", "unknown_key", "is_user_key", "COMMON_OPTIONS"]

COMMON_OPTIONS = ("model", "chordal_error", "element_size", "refine", "contact_tolerance")
REFINE_MAX = 64.0


def is_user_key(key: str) -> bool:
    """Whether ``key`` holds the user's own data (``x-*`` or ``extra``), carried through unread."""
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
        if is_user_key(key):
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
