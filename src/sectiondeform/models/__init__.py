"""Deformation models, each in a module of its own, found by name.

``"paper"``: the paper's geometric final mesh (:mod:`.paper`).
``"hyperelastic"``: the section's mechanics on a coarse mesh (:mod:`.hyperelastic`).
"""

from __future__ import annotations

import importlib

from ..errors import CaseError
from .base import MeshData, Model, Placement, Prepared

__all__ = ["get_model", "MODEL_MODULES", "MeshData", "Model", "Placement", "Prepared"]

MODEL_MODULES = {"paper": ".paper", "hyperelastic": ".hyperelastic"}


def get_model(name: str) -> Model:
    """The model called ``name`` (``"paper"`` or ``"hyperelastic"``).

    Raises
    ------
    CaseError
        If no model has that name.
    """
    if name not in MODEL_MODULES:
        raise CaseError("options.model", f"unknown model {name!r}; use one of {', '.join(MODEL_MODULES)}")
    module = importlib.import_module(MODEL_MODULES[name], __name__)
    return module.MODEL
