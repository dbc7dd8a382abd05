"""The one place where a number read from a case is checked.

JSON gives numbers as Python ``int`` or ``float``; an ``int`` may be too
large for a float (``10**400``), a string may look like a number, ``true`` is
an ``int`` to Python. :func:`number` accepts a real number only, inside a
finite and sane range, and says in one line what is wrong otherwise.
"""

from __future__ import annotations

import math

from .errors import CaseError

__all__ = ["COORDINATE_LIMIT", "number", "positive"]

COORDINATE_LIMIT = 1e9
"""Largest absolute coordinate, radius or length accepted, in the case's units."""


def number(value, field: str, *, low: float | None = None, high: float | None = None,
           strict_low: bool = False) -> float:
    """``value`` as a float, checked: a real number (not a string, not a bool), finite, in range.

    Parameters
    ----------
    value : object
        What the case gave.
    field : str
        Where it sits in the case, for the message (``"options.refine"``).
    low, high : float, optional
        Bounds; ``low`` is exclusive when ``strict_low``.
    strict_low : bool

    Returns
    -------
    float

    Raises
    ------
    CaseError
        One line naming ``field`` and what is accepted.

    Examples
    --------
    >>> number(3, "x")
    3.0
    >>> number("3", "x")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: x: expected a number, got '3'
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise CaseError(field, f"expected a number, got {_short(value)}")
    if isinstance(value, int) and abs(value) > 1e300:  # no float conversion: 10**400 overflows it
        raise CaseError(field, f"expected a finite number, got an integer of {len(str(abs(value)))} digits")
    v = float(value)
    if not math.isfinite(v):
        raise CaseError(field, f"expected a finite number, got {v!r}")
    if low is not None and (v <= low if strict_low else v < low):
        raise CaseError(field, f"must be a finite number {'>' if strict_low else '>='} {low:g}, got {v!r}")
    if high is not None and v > high:
        raise CaseError(field, f"must be a finite number <= {high:g}, got {v!r}")
    return v


def positive(value, field: str, high: float = COORDINATE_LIMIT) -> float:
    """A finite number > 0 and <= ``high`` (see :func:`number`).

    Examples
    --------
    >>> positive(0.5, "options.chordal_error")
    0.5
    >>> positive(0, "options.chordal_error")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: options.chordal_error: must be a finite number > 0, got 0.0
    """
    return number(value, field, low=0.0, high=high, strict_low=True)


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."
