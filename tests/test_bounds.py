"""Work bounds of the hyperelastic stages and the chordal check of the upper points."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import shapely

import sectiondeform as sd
import sectiondeform.fem.newton as newton
from sectiondeform.curves import DEFAULT_CHORDAL_FRACTION
from sectiondeform.errors import ConvergenceError, MeshError
from sectiondeform.limits import MAX_FE_VERTICES, MAX_NEWTON_ITERATIONS, MAX_NEWTON_WORK, newton_budget
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
    assert b * unknowns <= MAX_NEWTON_WORK or b == 1
    if unknowns <= MAX_NEWTON_WORK // MAX_NEWTON_ITERATIONS:
        assert b == MAX_NEWTON_ITERATIONS


def test_newton_stops_at_its_budget_with_one_line_naming_it(monkeypatch):
    case = _bent_box("hyperelastic")
    assert check_result(sd.deform(case), case) == []  # solvable within the real budget
    monkeypatch.setattr(newton, "newton_budget", lambda unknowns: 2)
    with pytest.raises(ConvergenceError) as err:
        sd.deform(case)
    message = str(err.value)
    assert "\n" not in message and "bound of 2 iterations" in message and "elements_through_thickness" in message


def test_a_mesh_that_keeps_splitting_to_conform_is_refused_at_the_vertex_bound(monkeypatch):
    """The union mesher gives up when splitting stops helping; without that stop, the vertex bound refuses it."""
    from sectiondeform.fem import union_mesh

    case = sd.load_case(FOUND / "hang-fem-mesh-coarse-mesh-246.json")
    with pytest.raises(MeshError) as err:
        sd.deform(case)
    message = str(err.value)
    assert "\n" not in message and "cannot be made to follow" in message and "however they are split" in message
    monkeypatch.setattr(union_mesh, "STALL_ITERATIONS", 10**6)  # only the vertex bound stops the splitting now
    with pytest.raises(MeshError) as err:
        sd.deform(case)
    message = str(err.value)
    assert "\n" not in message and "splitting the contour segments" in message
    count = int(message.split("assembly: ")[1].split()[0])
    assert count > MAX_FE_VERTICES


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
