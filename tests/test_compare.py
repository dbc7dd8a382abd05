"""Curve distances: metric properties, against shapely, and the comparison record."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import sectiondeform as sd
from sectiondeform.compare import compare_curves, hausdorff_distance, point_to_curve_distance

from conftest import Outcomes

coords = st.integers(-1000, 1000).map(lambda i: i / 10.0)  # no sub-normal segments for shapely


def polylines(n_min=2, n_max=12):
    return st.integers(n_min, n_max).flatmap(lambda n: arrays(np.float64, (n, 2), elements=coords))


def test_hausdorff_is_symmetric_and_bounded_by_shapely():
    outcomes = Outcomes()

    @settings(max_examples=60, deadline=None)
    @given(a=polylines(), b=polylines())
    def check(a, b):
        h = hausdorff_distance(a, b)
        assert h == pytest.approx(hausdorff_distance(b, a), abs=1e-9)
        la, lb = shapely.LineString(a), shapely.LineString(b)
        res = 1e-3 * max(la.length, lb.length)
        if min(la.length, lb.length) == 0.0:  # shapely cannot densify a point
            outcomes.refused("a curve of zero length")
            return
        # Sampled every `res`, the result can only fall short of the exact value by res / 2,
        # and can never exceed it; shapely's vertex-only figure is a lower bound.
        with np.errstate(all="ignore"):  # shapely divides by repeated vertices' zero lengths
            exact_ub = shapely.hausdorff_distance(la, lb, densify=1e-4) + res
            vertex_lb = shapely.hausdorff_distance(la, lb)
        assert h <= exact_ub + 1e-9
        assert h >= vertex_lb - 1e-9
        outcomes.checked()

    check()
    outcomes.assert_mostly_checked(at_least=40, max_refused_fraction=0.25)


@settings(max_examples=60, deadline=None)
@given(a=polylines(), dx=coords, dy=coords)
def test_hausdorff_of_a_translate_is_at_most_the_shift(a, dx, dy):
    assert hausdorff_distance(a, a) <= 1e-12 * (1.0 + np.abs(a).max())
    assert hausdorff_distance(a, a + [dx, dy]) <= np.hypot(dx, dy) * (1 + 1e-12) + 1e-9


@settings(max_examples=40, deadline=None)
@given(a=polylines(), b=polylines(), k=st.floats(0.1, 10.0))
def test_comparison_scales_with_the_shapes(a, b, k):
    n = min(len(a), len(b))
    a, b = a[:n], b[:n]
    c1 = compare_curves(a, b, scale=2.0)
    c2 = compare_curves(k * a, k * b, scale=2.0 * k)
    assert c2.hausdorff == pytest.approx(k * c1.hausdorff, rel=1e-6, abs=1e-6)
    assert c2.max_pointwise_relative == pytest.approx(c1.max_pointwise_relative, rel=1e-9, abs=1e-12)
    assert c1.hausdorff <= c1.max_pointwise + 1e-9  # corresponding points bound the curve distance


def test_hausdorff_sees_inside_segments():
    # Shapely's documentation example: the vertices alone say 14.1; the curves are 74.6 apart,
    # at an interior point of a segment (shapely's densify=0.5 finds 70, densify=0.001 74.56).
    a = np.array([[130.0, 0.0], [0.0, 0.0], [0.0, 150.0]])
    b = np.array([[10.0, 10.0], [10.0, 150.0], [130.0, 10.0]])
    assert shapely.hausdorff_distance(shapely.LineString(a), shapely.LineString(b)) == pytest.approx(14.142, abs=1e-3)
    exact = hausdorff_distance(a, b, resolution=1e-3)
    assert exact == pytest.approx(74.615, abs=1e-3)
    default_step = 1e-3 * (140.0 + np.hypot(120.0, 140.0))  # 1e-3 of the longer polyline, b
    assert exact - default_step / 2 <= hausdorff_distance(a, b) <= exact


def test_point_to_curve_distance():
    d = point_to_curve_distance(np.array([[0.5, 3.0], [-4.0, 0.0], [0.25, 0.0]]), np.array([[0.0, 0.0], [1.0, 0.0]]))
    np.testing.assert_allclose(d, [3.0, 4.0, 0.0])


def test_comparison_record():
    ref = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]])
    moved = ref.copy()
    moved[2, 1] = 0.3
    c = compare_curves(moved, ref, scale=3.0)
    assert c.max_pointwise == pytest.approx(0.3) and c.max_pointwise_index == 2
    assert c.max_pointwise_relative == pytest.approx(0.1)
    assert c.hausdorff == pytest.approx(0.3)
    assert c.mean_pointwise == pytest.approx(0.075)
    assert set(c.to_json()) >= {"hausdorff", "hausdorff_relative", "max_pointwise", "scale"}


def test_bad_inputs_are_case_errors():
    a = np.zeros((3, 2))
    with pytest.raises(sd.CaseError, match="correspond"):
        compare_curves(a, np.zeros((4, 2)))
    with pytest.raises(sd.CaseError, match="scale"):
        compare_curves(a, a, scale=0.0)
    with pytest.raises(sd.CaseError, match="at least 2"):
        hausdorff_distance(np.zeros((1, 2)), a)
    with pytest.raises(sd.CaseError, match="finite"):
        hausdorff_distance(np.array([[0.0, np.nan], [1.0, 1.0]]), a)
