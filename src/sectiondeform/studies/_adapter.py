"""The one place where a sweep touches the case's options and the Deformer call.

Everything else in :mod:`sectiondeform.studies` goes through these three small
functions, so a change of the case options or of the ``Deformer`` signature
is adapted here and nowhere else.
"""

from __future__ import annotations

from ..case import Case
from ..deform import Deformer
from ..laws import AreaRatio
from ..result import Result

__all__ = ["case_model", "deform", "prepare"]


def case_model(case: Case) -> str:
    """Name of the model the case asks for (``"paper"`` when it names none)."""
    return case.model


def prepare(case: Case, model: str, element_size: float | None) -> Deformer:
    """A :class:`~sectiondeform.deform.Deformer` for one section: case, model, element size (units or None)."""
    return Deformer(case, model=model, element_size=element_size)


def deform(deformer: Deformer, target, area_ratio: float | None) -> Result:
    """Re-deform a prepared section onto ``target`` (a Curve, or None for the case's) under ``area_ratio``.

    ``area_ratio`` None keeps the case's own law.
    """
    law = None if area_ratio is None else AreaRatio(area_ratio)
    return deformer.deform(target, law)
