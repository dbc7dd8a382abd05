"""Det J of six-node triangles, against values derived by hand."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.verify import det_j_p2

# reference triangle, corners then mid-nodes of edges 0-1, 1-2, 2-0
_REF = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]])
_CELL = np.arange(6)[None]

coord = st.floats(-10, 10, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(st.tuples(coord, coord, coord, coord, coord, coord))
def test_straight_sided_triangle_has_det_j_twice_its_signed_area(m):
    # an affine image x = A xi + b: det J = det A everywhere, = twice the signed area
    a = np.array([[m[0], m[1]], [m[2], m[3]]])
    pts = _REF @ a.T + np.array([m[4], m[5]])
    det = det_j_p2(pts, _CELL)
    assert det.shape[0] == 1
    np.testing.assert_allclose(det, np.linalg.det(a), atol=1e-9 * (1 + np.abs(a).max() ** 2))


def test_many_cells_each_get_their_own_values():
    scales = np.array([1.0, 2.0, -1.0])  # the third is mirrored: inverted
    pts = np.concatenate([_REF * np.array([s, 1.0]) for s in scales])
    cells = np.arange(18).reshape(3, 6)
    det = det_j_p2(pts, cells)
    np.testing.assert_allclose(det, np.repeat(scales[:, None], det.shape[1], axis=1))


def test_a_mid_node_pulled_across_the_opposite_corner_inverts_part_of_the_element():
    # det J along edge 0-1 at xi: 1 + 4 (m - 1/2) (1 - 2 xi) for mid-node 3 at (m, 0) —
    # negative at a corner once m leaves (1/4, 3/4)
    pts = _REF.copy()
    pts[3] = [0.9, 0.0]
    det = det_j_p2(pts, _CELL)
    assert det.min() < 0 < det.max()
    pts[3] = [0.7, 0.0]
    assert (det_j_p2(pts, _CELL) > 0).all()
