"""The section's initial area is within tolerance of its curves' exact area, for every curve kind.

The exact area of a section bounded by two circular arcs over the same
chord is derived here independently, from circular segments; the section
must report an initial area within ``verify.INITIAL_AREA_TOLERANCE`` of it,
however the two arcs' chord errors would cancel in the contour's area, and
wherever the section sits (far from the origin included).
"""

from __future__ import annotations

import math

import numpy as np
from fuzz_cases import _arc_through
from hypothesis import given, settings
from hypothesis import strategies as st

import sectiondeform as sd
from sectiondeform.section import build_section
from sectiondeform.verify import INITIAL_AREA_TOLERANCE


def segment_area(chord: float, bulge: float) -> float:
    """Area between a chord and an arc whose sagitta is ``|bulge|`` x chord (bulge below 1/2)."""
    s = abs(bulge) * chord
    r = (chord * chord / 4 + s * s) / (2 * s)
    theta = 2.0 * math.asin(min(1.0, chord / (2 * r)))
    return 0.5 * r * r * (theta - math.sin(theta))


def arc_on_arc(a, chord, turn_deg, lower_bulge, upper_bulge, chordal=None):
    """A case dict: lower arc from A to B, upper arc from B back to A, both over the chord AB."""
    a = np.asarray(a, float)
    t = math.radians(turn_deg)
    b = a + chord * np.array([math.cos(t), math.sin(t)])
    lower, end = _arc_through(a, b, lower_bulge)  # positive bulge: into the section
    upper, _ = _arc_through(end, a, upper_bulge)  # negative bulge: out of the section
    options = {"chordal_error": chordal} if chordal else {}
    return {
        "format": "section-case/1",
        "lower": lower,
        "upper": upper,
        "target": {"polyline": [a.tolist(), end.tolist()]},
        "law": {"area_ratio": 1.0},
        "options": options,
    }


@settings(max_examples=150, deadline=None)
@given(
    x=st.floats(-1e6, 1e6),
    y=st.floats(-1e6, 1e6),
    chord=st.floats(1e-2, 1e3),
    turn=st.floats(0.0, 360.0),
    lower_bulge=st.floats(-0.45, 0.3).filter(lambda v: abs(v) > 1e-3),
    extra=st.floats(0.05, 0.4),
    coarse=st.sampled_from([None, 1e-3, 1e-2]),
)
def test_initial_area_is_the_arcs_exact_area(x, y, chord, turn, lower_bulge, extra, coarse):
    upper_bulge = -min(0.49, max(lower_bulge, 0.0) + extra)  # outward, and clear of the lower arc
    chordal = coarse * chord if coarse else None
    case = sd.case_from_dict(arc_on_arc((x, y), chord, turn, lower_bulge, upper_bulge, chordal))
    # A lower arc bulging into the section takes its segment away; out of it, adds it.
    exact = segment_area(chord, upper_bulge) - math.copysign(segment_area(chord, lower_bulge), lower_bulge)
    sec = build_section(case)
    # The arcs' own rounding at |(x, y)|: their points move by about eps x |(x, y)|.
    rounding = 64 * np.spacing(math.hypot(x, y) + chord) * 4 * chord
    assert abs(sec.area - exact) <= INITIAL_AREA_TOLERANCE * exact + rounding
    assert abs(sec.curve_area - exact) <= 1e-9 * exact + rounding


def test_coarse_arcs_whose_errors_cancel_in_the_contour():
    # Same radius both ways: the lower arc's chords gain what the upper's lose.
    case = sd.case_from_dict(arc_on_arc((0.0, 0.0), 100.0, 0.0, -0.2, -0.3, chordal=2.0))
    exact = segment_area(100.0, -0.3) + segment_area(100.0, -0.2)
    sec = build_section(case)
    assert abs(sec.area - exact) <= INITIAL_AREA_TOLERANCE * exact
