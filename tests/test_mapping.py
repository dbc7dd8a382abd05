"""Point mapping helpers of the hyperelastic model: the rigid fit (the law's offset: tests/test_assembly_hyperelastic.py)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from sectiondeform.fem.mapping import rigid_fit

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
