"""Inputs the fuzz benchmark found that still break the promise (open; each must start to pass when fixed).

All three: a section whose lower and upper curves are both arcs comes back
with its initial contour's area further from the curves' exact area than
the documented tolerance (``verify.INITIAL_AREA_TOLERANCE``), with no
warning. The section's refinement loop measures the area of the whole
contour, so the lower arc's chords (gaining area) and the upper arc's
(losing it) cancel; the lower curve is then resampled finer for the mesh
and the upper curve's error shows (7e-4 of the area on the first file). The
third is small and far from the origin, where the exact area is also
integrated in absolute coordinates. ``strict``: a fix makes these tests
fail until the mark is removed.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_cases import TIME_LIMIT_S, outcome_api

DATA = Path(__file__).parent / "data" / "fuzz-open"
FILES = sorted(DATA.glob("*.json"))


def test_the_open_inputs_are_present():
    assert len(FILES) == 3


@pytest.mark.xfail(strict=True, reason="open: the section's area check lets the two arcs' chord errors cancel")
@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_checked_result_or_one_line_error(path):
    outcome = outcome_api(path, TIME_LIMIT_S)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}"
