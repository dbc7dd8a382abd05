"""Point mapping helpers of the hyperelastic model: rigid fit, interpolation, area correction."""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from sectiondeform.fem.mapping import correct_area, interpolation_matrix, rigid_fit

from conftest import rigid


@settings(max_examples=60, deadline=None)
@given(
    pts=arrays(np.float64, (6, 2), elements=st.floats(-10, 10)),
    angle=st.floats(-179, 179),
    shift=arrays(np.float64, (2,), elements=st.floats(-50, 50)),
)
def test_rigid_fit_recovers_a_rigid_motion(pts, angle, shift):
    pts = pts + np.arange(12.0).reshape(6, 2) * [1.0, 0.3]  # not all on one point
    q, t = rigid_fit(pts, rigid(pts, angle, shift))
    a = np.radians(angle)
    np.testing.assert_allclose(q, [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]], atol=1e-9)
    np.testing.assert_allclose(t, shift, atol=1e-8)
    assert np.linalg.det(q) == pytest.approx(1.0)


@settings(max_examples=60, deadline=None)
@given(n=st.integers(2, 30), at=st.lists(st.floats(0, 1), min_size=1, max_size=20))
def test_interpolation_rows_are_partitions_of_unity_and_exact_on_lines(n, at):
    fractions = np.sort(np.concatenate(([0.0, 1.0], np.linspace(0, 1, n)[1:-1] ** 1.5)))
    at = np.array(at)
    w = interpolation_matrix(at, fractions)
    assert np.all(w >= 0) and np.allclose(w.sum(axis=1), 1.0)
    assert np.allclose(w @ (3 * fractions - 2), 3 * at - 2)  # linear data interpolated exactly


@pytest.mark.parametrize("wanted", [30.0, 40.0, 55.0])
def test_correct_area_meets_the_area_and_keeps_the_ends(wanted):
    lower = np.column_stack((np.linspace(0, 10, 11), np.zeros(11)))
    x = np.linspace(10, 0, 21)
    upper = np.vstack(([10.0, 0.0], np.column_stack((x, 4 + np.sin(x))), [0.0, 0.0]))  # from B to A
    new, offset = correct_area(lower, upper, wanted)
    ring = np.vstack((lower, new[1:-1]))
    assert shapely.Polygon(ring).area == pytest.approx(wanted, rel=1e-9)
    np.testing.assert_array_equal(new[[0, -1]], upper[[0, -1]])
    before = shapely.Polygon(np.vstack((lower, upper[1:-1]))).area
    assert np.sign(offset) == np.sign(wanted - before)
