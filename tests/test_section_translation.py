"""A section far from the origin deforms as it does at the origin, shifted (translation invariance).

The shared cases are moved by (1e6, -1e6), and the same cases scaled down
to a tenth of a millimetre (where integrating areas in absolute coordinates
once lost the digits and refused them) by (1e3, -1e3), ten thousand times
their size: the result must be the same points shifted, to a tolerance
derived from float rounding at that magnitude (``np.spacing`` of the
offset, the rounding of every input coordinate there, 1.2e-10 at 1e6,
amplified at most a thousandfold through the model's solves).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd

CASES = Path(__file__).parent / "data" / "cases"
OFFSET = np.array([1e6, -1e6])


def moved(case: sd.Problem, scale: float, offset: np.ndarray, model: str) -> sd.Problem:
    """``case`` scaled about the origin by ``scale``, then moved by ``offset``, under ``model``."""
    m = scale * np.eye(2)
    curves = {k: getattr(case, k).transformed(m, offset) for k in ("lower", "upper", "target")}
    options = dataclasses.replace(case.options, model=model, chordal_error=None, element_size=None)
    return case.replace(options=options, **curves)


@pytest.mark.parametrize("scale", [1.0, 1e-3])
@pytest.mark.parametrize(
    "name, model",
    [("paper-example", "paper"), ("thick-block-s-curve", "paper"), ("grooved-tread", "paper"),
     ("thick-block-s-curve", "hyperelastic")],
)
def test_translated_case_gives_the_result_shifted(name, model, scale):
    case = sd.load_case(CASES / f"{name}.json")
    here = sd.deform(moved(case, scale, np.zeros(2), model))
    offset = scale * OFFSET
    tolerance = 1e3 * float(np.spacing(np.abs(offset).max()))
    there = sd.deform(moved(case, scale, offset, model))
    assert there.lower.shape == here.lower.shape and there.upper.shape == here.upper.shape
    assert np.abs(there.lower - offset - here.lower).max() <= tolerance
    assert np.abs(there.upper - offset - here.upper).max() <= tolerance
    assert there.area_initial == pytest.approx(here.area_initial, rel=1e-9)
    assert there.area_final == pytest.approx(here.area_final, rel=1e-9)
    assert len(there.warnings) == len(here.warnings)
