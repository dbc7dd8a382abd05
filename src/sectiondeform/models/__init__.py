"""Deformation models, each in a module of its own, found by name: the one registry.

``"paper"``: the paper's geometric final mesh (:mod:`.paper`).
``"hyperelastic"``: the section's mechanics on a coarse mesh (:mod:`.hyperelastic`).

A new model is a module with a ``MODEL`` object (a :class:`Model` with its
``options_type``) and one line in :data:`MODEL_MODULES`; the case reader and
the command line take the names from here. A model's module is imported
only when the model or its options are asked for.
"""

from __future__ import annotations

import difflib
import importlib

from ..errors import CaseError
from .base import FinalQuality, Info, MeshData, MeshQuality, Model, ModelOptions, Placement, Prepared

__all__ = [
    "get_model", "model_options_types", "MODEL_MODULES", "MODEL_NAMES", "DEFAULT_MODEL",
    "MeshData", "Model", "ModelOptions", "Placement", "Prepared", "MeshQuality", "FinalQuality", "Info",
]

MODEL_MODULES = {"paper": ".paper", "hyperelastic": ".hyperelastic"}
MODEL_NAMES = tuple(MODEL_MODULES)
DEFAULT_MODEL = "paper"


def check_model_name(name, field: str = "options.model") -> str:
    """``name`` if a model has it, else a one-line :class:`~sectiondeform.errors.CaseError`."""
    if not isinstance(name, str) or name not in MODEL_MODULES:
        near = difflib.get_close_matches(str(name), MODEL_NAMES, n=1)
        hint = f"; did you mean {near[0]}?" if near else ""
        raise CaseError(field, f"unknown model {name!r}; use one of {', '.join(MODEL_NAMES)}{hint}")
    return name


def get_model(name: str) -> Model:
    """The model called ``name`` (one of :data:`MODEL_NAMES`).

    Raises
    ------
    CaseError
        If no model has that name.
    """
    check_model_name(name)
    return importlib.import_module(MODEL_MODULES[name], __name__).MODEL


def model_options_types() -> dict[str, type[ModelOptions]]:
    """Every model's options type, by model name (imports every model)."""
    return {name: get_model(name).options_type for name in MODEL_NAMES}
