"""Real numbers as an Abaqus / CalculiX deck must write them: at most 20 characters.

CalculiX 2.20 reads every real of a data line with a Fortran
``read(textpart(k)(1:20), '(f20.0)')``: only the first 20 characters of
the field count, and the rest is dropped without a word. A displacement
written ``-7.86283353093609e-05`` (21 characters) is read as
``-7.86283353093609e-0``, 100 000 times too large; a node coordinate
``-9.82632404814843e-15`` is read as -0.98. :func:`inp_real` writes
15 significant digits when they fit in 20 characters, else 14 or 13 (which
always fit), so what the solver reads is the value to 13 digits at worst.
"""

from __future__ import annotations

import math

__all__ = ["FIELD_WIDTH", "inp_real"]

FIELD_WIDTH = 20
"""Characters of a real that CalculiX reads from a data field."""


def inp_real(value: float) -> str:
    """A finite real in at most :data:`FIELD_WIDTH` characters, with 13 to 15 significant digits.

    Raises
    ------
    ValueError
        For NaN or an infinity (a deck holds none).

    Examples
    --------
    >>> inp_real(0.5), inp_real(-7.86283353093609e-05)  # 15 digits would take 21 characters
    ('0.5', '-7.8628335309361e-05')
    """
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"a deck holds finite reals only, got {v!r}")
    for digits in (15, 14):
        text = f"{v:.{digits}g}"
        if len(text) <= FIELD_WIDTH:
            return text
    return f"{v:.13g}"  # sign, 13 digits, point, 'e', sign, 3 exponent digits: 20 at most
