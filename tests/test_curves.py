import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.curves import Arc, BSpline, Chain, Polyline, curve_from_json
from sectiondeform.errors import CaseError

from conftest import Outcomes


def _max_chord_error(curve, pts, fr, probes=9):
    """Largest distance from the curve between vertices to the chord."""
    worst = 0.0
    for i in range(len(fr) - 1):
        s = np.linspace(fr[i], fr[i + 1], probes)[1:-1]
        q = curve.at_fractions(s)
        a, b = pts[i], pts[i + 1]
        d = b - a
        n = math.hypot(*d)
        dist = np.abs(d[0] * (q[:, 1] - a[1]) - d[1] * (q[:, 0] - a[0])) / n
        worst = max(worst, dist.max())
    return worst


def test_arc_discretisation_within_tolerance_and_adaptive():
    arc = Arc(np.array([0.0, 0.0]), 50.0, 0.0, 180.0)
    for tol in (1e-1, 1e-2, 1e-3):
        pts, fr = arc.discretise(tol)
        assert _max_chord_error(arc, pts, fr) <= tol * (1 + 1e-9)
        assert np.allclose(np.hypot(*pts.T), 50.0)
    # ten times finer tolerance -> about sqrt(10) times more points, not 10 times
    n1, n2 = len(arc.discretise(1e-2)[0]), len(arc.discretise(1e-3)[0])
    assert 2.5 < n2 / n1 < 4.0


def test_bspline_discretisation_is_adaptive():
    # straight first half, tight bend in the second half
    cp = [[0, 0], [10, 0], [20, 0], [30, 0], [31, 1], [31, 2]]
    b = curve_from_json({"bspline": {"degree": 3, "control_points": cp}}, "upper")
    pts, fr = b.discretise(1e-3)
    assert _max_chord_error(b, pts, fr) <= 1e-3 * 1.05
    steps = np.hypot(*np.diff(pts, axis=0).T)
    assert steps[: len(steps) // 4].mean() > 5 * steps[-len(steps) // 4 :].mean()


def test_bspline_default_knots_are_uniform_clamped():
    b = BSpline(3, np.array([[0, 0], [1, 1], [2, 1], [3, 0], [4, 0]], float))
    assert b.knots.tolist() == [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
    assert np.allclose(b.start, [0, 0]) and np.allclose(b.end, [4, 0])


def test_bspline_arc_length_fractions():
    # a degree-1 spline is a polyline: fractions are exact
    b = BSpline(1, np.array([[0, 0], [3, 0], [3, 1]], float), np.array([0, 0, 0.2, 1, 1.0]))
    assert b.length == pytest.approx(4.0, rel=1e-12)
    assert np.allclose(b.at_fractions(np.array([0.5, 0.875])), [[2, 0], [3, 0.5]], atol=1e-9)


@pytest.mark.parametrize("tol", [1e-1, 1e-3])
def test_polyline_douglas_peucker_within_tolerance(tol):
    x = np.linspace(0, 10, 200)
    p = Polyline(np.column_stack((x, 0.3 * np.sin(x))))
    pts, fr = p.discretise(tol)
    assert _max_chord_error(p, pts, fr, probes=30) <= tol * (1 + 1e-9)
    assert len(pts) < 200
    assert np.allclose(p.at_fractions(fr), pts)


def test_green_areas_exact():
    # unit circle as two arcs
    c = Chain((Arc(np.zeros(2), 1.0, 0.0, 180.0), Arc(np.zeros(2), 1.0, 180.0, 360.0)))
    assert c.green() == pytest.approx(math.pi, rel=1e-14)
    sq = Polyline(np.array([[0, 0], [2, 0], [2, 2], [0, 2], [0, 0]], float))
    assert sq.green() == 4.0
    # the cubic Bezier quarter-circle approximation: known area
    k = 0.5522847498
    b = BSpline(3, np.array([[1, 0], [1, k], [k, 1], [0, 1]], float))
    closing = Polyline(np.array([[0, 1], [0, 0], [1, 0]], float))
    assert b.green() + closing.green() == pytest.approx(math.pi / 4, rel=3e-4)


def test_chain_fractions_and_join_error():
    c = curve_from_json({"chain": [{"polyline": [[0, 0], [1, 0]]},
                                   {"arc": {"center": [1, 1], "radius": 1, "start_deg": -90, "end_deg": 0}}]}, "upper")
    assert c.length == pytest.approx(1 + math.pi / 2)
    assert np.allclose(c.end, [2, 1])
    with pytest.raises(CaseError, match=r"upper.chain\[1\]: starts 0.5 away"):
        curve_from_json({"chain": [{"polyline": [[0, 0], [1, 0]]}, {"polyline": [[1.5, 0], [2, 0]]}]}, "upper")


@pytest.mark.parametrize(
    "obj, message",
    [
        ({"spiral": {}}, "unknown curve kind 'spiral'"),
        ({"polyline": [[0, 0]]}, "needs at least 2 points"),
        ({"polyline": [[0, 0], [1, float("nan")]]}, r"lower.polyline\[1\]: coordinates must be finite"),
        ({"polyline": [[0, 0], [0, 0]]}, "zero length"),
        ({"polyline": "abc"}, "expected a list of"),
        ({"arc": {"center": [0, 0], "radius": -1, "start_deg": 0, "end_deg": 90}}, "radius: must be positive"),
        ({"arc": {"center": [0, 0], "radius": 1, "start_deg": 0}}, "end_deg: missing"),
        ({"bspline": {"degree": 3, "control_points": [[0, 0], [1, 1]]}}, "needs at least 4 points"),
        ({"bspline": {"degree": 2, "control_points": [[0, 0], [1, 1], [2, 0]], "knots": [0, 0.2, 0.5, 0.6, 1, 1]}},
         "must be clamped"),
        ({"bspline": {"degree": 2, "control_points": [[0, 0], [1, 1], [2, 0]], "knots": [0, 0, 0, 1]}},
         "expected 6 knots"),
        ({"polyline": [[0, 0], [1, 0]], "arc": {}}, "exactly one key"),
    ],
)
def test_bad_curves_name_the_field(obj, message):
    with pytest.raises(CaseError, match=message) as info:
        curve_from_json(obj, "lower")
    assert str(info.value).startswith("lower")
    assert "\n" not in str(info.value)


def test_polyline_fractions_measure_arc_length():
    outcomes = Outcomes()

    @settings(max_examples=60, deadline=None)
    @given(
        st.lists(st.tuples(st.floats(-100, 100), st.floats(-100, 100)), min_size=2, max_size=12),
        st.lists(st.floats(0, 1), min_size=1, max_size=10),
    )
    def check(verts, fractions):
        v = np.array(verts)
        seg = np.hypot(*np.diff(v, axis=0).T)
        if seg.sum() < 1e-3:
            outcomes.refused("vertices within 1e-3 of each other")
            return
        p = Polyline(v)
        cum = np.concatenate(([0.0], np.cumsum(seg))) / seg.sum()
        scale = 1 + np.abs(v).max()
        # vertices sit at their own cumulative fractions
        moved = np.concatenate(([True], seg > 1e-9 * scale))
        assert np.allclose(p.at_fractions(cum[moved]), v[moved], atol=1e-9 * scale)
        # between two fractions, the chord is never longer than the arc length
        s = np.sort(np.array(fractions))
        q = p.at_fractions(s)
        chords = np.hypot(*np.diff(q, axis=0).T)
        assert np.all(chords <= np.diff(s) * p.length + 1e-9 * scale)
        outcomes.checked()

    check()
    outcomes.assert_mostly_checked(at_least=40, max_refused_fraction=0.25)


def test_round_trip_json():
    objs = [
        {"polyline": [[0.0, 0.0], [1.0, 2.0]]},
        {"arc": {"center": [1.0, 2.0], "radius": 3.0, "start_deg": 10.0, "end_deg": -20.0}},
        {"bspline": {"degree": 2, "control_points": [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]], "knots": [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]}},
    ]
    for obj in objs:
        assert curve_from_json(obj).to_json() == obj
    chain = {"chain": objs[:1] + [{"polyline": [[1.0, 2.0], [5.0, 5.0]]}]}
    assert curve_from_json(chain).to_json() == chain


def _nested(curve, depth: int) -> Chain:
    for _ in range(depth):
        curve = Chain((curve,))
    return curve


def test_the_ends_of_a_deeply_nested_chain_take_linear_work():
    """A chain of one chain of one chain...: each level asked its only piece twice, 2**depth work."""
    import time

    line = Polyline([[0.0, 0.0], [3.0, 4.0]])
    t0 = time.process_time()
    chain = _nested(line, 200)
    start, end = chain.ends
    assert time.process_time() - t0 < 1.0
    assert start.tolist() == [0.0, 0.0] and end.tolist() == [3.0, 4.0]
    assert chain.length == 5.0 and len(chain.parts()) == 1


def test_a_case_whose_lower_curve_is_nested_50_chains_deep_deforms_in_time():
    """tests/data/fuzz-found/v2/api-HANG-curves-py-ends-400.json: minutes before, now well under a second."""
    import time
    from pathlib import Path

    import sectiondeform as sd

    path = Path(__file__).parent / "data" / "fuzz-found" / "v2" / "api-HANG-curves-py-ends-400.json"
    t0 = time.process_time()
    result = sd.deform(sd.load_case(path))
    assert time.process_time() - t0 < 10.0
    assert all(abs(b.volume_final - b.volume_target) <= 1e-9 * b.volume_target for b in result.bodies)
