"""Work bounds of the hyperelastic stages and the chordal check of the upper points."""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path

import numpy as np
import pytest
import shapely

import sectiondeform as sd
import sectiondeform.fem.newton as newton
from sectiondeform.curves import DEFAULT_CHORDAL_FRACTION
from sectiondeform.errors import ConvergenceError, MeshError
from sectiondeform.limits import MAX_NEWTON_ITERATIONS, MAX_SOLVE_WORK, newton_budget
from sectiondeform.verify import check_result

from conftest import box_case

FOUND = Path(__file__).parent / "data" / "fuzz-found"


def _bent_box(model: str) -> sd.Problem:
    t = np.linspace(0.0, 1.0, 41)
    arc = np.column_stack((10.0 * np.sin(t), 10.0 * (1.0 - np.cos(t))))
    return sd.case_from_dict(box_case(target={"polyline": arc.tolist()}, ratio=0.9, model=model))


@pytest.mark.parametrize("unknowns", [1, 50, 700, 4_000, 27_000, 10**6])
def test_newton_budget_bounds_iterations_and_work(unknowns):
    b = newton_budget(unknowns)
    assert 1 <= b <= MAX_NEWTON_ITERATIONS
    assert b * unknowns**1.5 <= MAX_SOLVE_WORK or b == 1
    if MAX_NEWTON_ITERATIONS * unknowns**1.5 <= MAX_SOLVE_WORK:
        assert b == MAX_NEWTON_ITERATIONS
    assert (b + 1) * unknowns**1.5 > MAX_SOLVE_WORK or b == MAX_NEWTON_ITERATIONS  # the whole budget given


def test_newton_stops_at_its_budget_with_one_line_naming_it(monkeypatch):
    case = _bent_box("hyperelastic")
    assert check_result(sd.deform(case), case) == []  # solvable within the real budget
    monkeypatch.setattr(newton, "newton_budget", lambda unknowns: 2)
    with pytest.raises(ConvergenceError) as err:
        sd.deform(case)
    message = str(err.value)
    assert "\n" not in message and "bound of 2 iterations" in message and "elements_through_thickness" in message


def test_a_mesh_that_kept_splitting_to_conform_is_now_meshed_and_answered_in_one_line():
    """The input that made the meshers split without end is meshed about its first point at once.

    The vertex bound and the stall stop of the conforming loop are tested on their own inputs
    (tests/test_union_mesh.py); here the case is answered quickly, in one line (the solver's refusal
    on this degenerate sliver), never a hang.
    """
    case = sd.load_case(FOUND / "hang-fem-mesh-coarse-mesh-246.json")
    t0 = time.process_time()
    with pytest.raises((MeshError, ConvergenceError)) as err:
        sd.deform(case)
    assert "\n" not in str(err.value) and time.process_time() - t0 < 20.0


def test_upper_on_curve_is_a_chordal_check():
    """An upper point moved off the curve by a few chordal errors fails, one moved by rounding passes."""
    case = sd.load_case(sd.example_case_path())
    result = sd.deform(case)
    assert check_result(result, case) == []
    nominal = DEFAULT_CHORDAL_FRACTION * float(np.hypot(*np.ptp(result.initial_contour, axis=0)))
    up = result.initial_upper
    i = len(up) // 2
    inward = result.initial_contour.mean(axis=0) - up[i]
    inward /= np.hypot(*inward)
    fine = case.upper.at_fractions(np.linspace(0.0, 1.0, 200_001))

    def moved(by):
        pts = up.copy()
        pts[i] = pts[i] + by * inward
        true = float(shapely.distance(shapely.Point(pts[i]), shapely.LineString(fine)))
        body = dataclasses.replace(result.bodies[0], initial_upper=pts)
        return dataclasses.replace(result, bodies=(body,)), true

    # 3 chordal errors: under the old slack of one step of a 4097-point sampling (0.042 here).
    far, true_far = moved(3.0 * nominal)
    assert true_far > 2.0 * nominal  # really off the curve (independent dense sampling)
    assert any(f.startswith("upper_on_curve") for f in check_result(far, case))
    near, _ = moved(1e-7 * nominal)
    assert not any(f.startswith("upper_on_curve") for f in check_result(near, case))
