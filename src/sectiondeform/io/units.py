"""Length units of drawings and cases: one table, and the check of a unit's name."""

from __future__ import annotations

import difflib

from ..errors import CaseError

__all__ = ["MM_PER_UNIT", "CSS_UNITS", "DXF_UNITS", "mm_per_unit"]

# Unit name (as a case's ``units`` gives it) -> millimetres per unit.
MM_PER_UNIT = {
    "mm": 1.0, "cm": 10.0, "dm": 100.0, "m": 1000.0, "km": 1e6, "um": 1e-3, "nm": 1e-6, "angstrom": 1e-7,
    "in": 25.4, "ft": 304.8, "yd": 914.4, "mil": 0.0254, "uin": 25.4e-6, "pt": 25.4 / 72, "pc": 25.4 / 6,
    "px": 25.4 / 96,
}
# The units CSS (and so SVG) knows by name; "q" is the quarter-millimetre.
CSS_UNITS = {**{u: MM_PER_UNIT[u] for u in ("mm", "cm", "in", "pt", "pc", "px")}, "q": 0.25}
# DXF $INSUNITS code -> unit name.
DXF_UNITS = {1: "in", 2: "ft", 4: "mm", 5: "cm", 6: "m", 7: "km", 8: "uin", 9: "mil", 10: "yd", 11: "angstrom",
             12: "nm", 13: "um", 14: "dm"}
# Spelled-out names, only to suggest the short one in a message.
_SPELLED = {
    "millimeter": "mm", "millimetre": "mm", "centimeter": "cm", "centimetre": "cm", "decimeter": "dm",
    "decimetre": "dm", "meter": "m", "metre": "m", "kilometer": "km", "kilometre": "km", "micrometer": "um",
    "micrometre": "um", "micron": "um", "nanometer": "nm", "nanometre": "nm", "inch": "in", "inches": "in",
    "foot": "ft", "feet": "ft", "yard": "yd", "point": "pt", "pica": "pc", "pixel": "px", "thou": "mil",
}


def mm_per_unit(name: str, field: str = "units") -> float:
    """Millimetres per unit of a unit ``name`` from :data:`MM_PER_UNIT`.

    Parameters
    ----------
    name : str
    field : str
        What named the unit, for the message.

    Raises
    ------
    CaseError
        For an unknown name, naming the nearest known unit.

    Examples
    --------
    >>> mm_per_unit("in")
    25.4
    >>> mm_per_unit("milimeter")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: units: unknown unit 'milimeter'; did you mean 'mm'? use one of mm, cm, dm, m, km, um, nm, angstrom, in, ft, yd, mil, uin, pt, pc, px
    """
    if isinstance(name, str) and name in MM_PER_UNIT:
        return MM_PER_UNIT[name]
    known = ", ".join(MM_PER_UNIT)
    text = str(name).strip().lower()
    candidates = list(MM_PER_UNIT) + list(_SPELLED)
    close = difflib.get_close_matches(text, candidates, n=1, cutoff=0.6)
    if text in MM_PER_UNIT:  # a matter of case: "MM"
        close = [text]
    if close:
        nearest = _SPELLED.get(close[0], close[0])
        raise CaseError(field, f"unknown unit {name!r}; did you mean {nearest!r}? use one of {known}")
    raise CaseError(field, f"unknown unit {name!r}; use one of {known}")
