"""Mechanical laws ML: Se(t+1) = f(Se(t)) (paper eq. 1).

A law is a small frozen object that tells the final area of a section from
its initial area. Each law is a class registered under the case-file key it
reads (``{"area_ratio": 0.8}``); a new law is a new class, not a new branch.
The hyperelastic model also asks a law for its out-of-plane stretch, the
physical reason a volume-preserving section changes area.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .checks import number
from .errors import CaseError

__all__ = ["Law", "AreaRatio", "law_from_json", "LAWS", "RATIO_RANGE"]

RATIO_RANGE = (0.01, 100.0)
"""Accepted area ratios, inclusive: beyond them no rubber section means anything."""

LAWS: dict[str, type[Law]] = {}


class Law:
    """Base class of the mechanical laws."""

    key: ClassVar[str] = ""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.key:
            LAWS[cls.key] = cls

    def target_area(self, initial_area: float) -> float:  # pragma: no cover - abstract
        """Final area, in units², from the initial area."""
        raise NotImplementedError

    def area_ratio(self, initial_area: float) -> float:
        """Final over initial area."""
        return self.target_area(initial_area) / initial_area

    def out_of_plane_stretch(self, initial_area: float) -> float:
        """Out-of-plane stretch of a volume-preserving section under this law (1 / area ratio)."""
        return 1.0 / self.area_ratio(initial_area)

    def to_json(self) -> dict:  # pragma: no cover - abstract
        """The ``law`` object of the case format."""
        raise NotImplementedError


@dataclass(frozen=True)
class AreaRatio(Law):
    """Final area = ``ratio`` x initial area (the paper's law, ratio 0.8).

    ``ratio`` is a finite number in :data:`RATIO_RANGE` (0.01 to 100).

    Examples
    --------
    >>> AreaRatio(0.8).target_area(4379.0)
    3503.2000000000003
    """

    ratio: float
    key: ClassVar[str] = "area_ratio"

    def __post_init__(self):
        low, high = RATIO_RANGE
        r = number(self.ratio, "law.area_ratio", low=0.0, strict_low=True)
        if not low <= r <= high:
            raise CaseError("law.area_ratio", f"must be between {low:g} and {high:g}, got {r!r}")
        object.__setattr__(self, "ratio", r)

    def target_area(self, initial_area):
        return self.ratio * initial_area

    def to_json(self):
        return {"area_ratio": float(self.ratio)}


def law_from_json(obj, field: str = "law") -> Law:
    """Build a :class:`Law` from the case's ``law`` object.

    Raises
    ------
    CaseError
        If the object is not a one-key object naming a known law.

    Examples
    --------
    >>> law_from_json({"area_ratio": 0.9})
    AreaRatio(ratio=0.9)
    >>> law_from_json({"volume": 1})
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: law: unknown law 'volume'; use one of area_ratio
    """
    if not isinstance(obj, dict) or len(obj) != 1:
        raise CaseError(field, f"expected one law object such as {{\"area_ratio\": 0.8}}, got {obj!r}")
    (key, value), = obj.items()
    if key not in LAWS:
        raise CaseError(field, f"unknown law {key!r}; use one of {', '.join(sorted(LAWS))}")
    return LAWS[key](value)
