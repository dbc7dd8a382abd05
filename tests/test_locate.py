import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.spatial import Delaunay

from sectiondeform.errors import LocateError
from sectiondeform.layers import structured_quads
from sectiondeform.locate import bilinear_weights, inverse_bilinear, locate, place


def _wavy_mesh(nx=8, ny=5):
    x, y = np.meshgrid(np.linspace(0, 8, nx + 1), np.linspace(0, 5, ny + 1))
    pts = np.column_stack(((x + 0.2 * np.sin(y)).ravel(), (y + 0.3 * np.sin(x)).ravel()))
    return pts, structured_quads(ny, nx + 1)


@settings(max_examples=60, deadline=None)
@given(arrays(np.float64, (4, 2), elements=st.floats(-0.2, 0.2)), arrays(np.float64, (5, 2), elements=st.floats(0, 1)))
def test_inverse_bilinear_inverts_the_map(jitter, local):
    quad = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float) + jitter
    x = bilinear_weights(local) @ quad
    back = inverse_bilinear(np.broadcast_to(quad, (5, 4, 2)), x)
    assert np.allclose(back, local, atol=1e-9)


def test_locate_then_place_returns_the_points():
    pts, quads = _wavy_mesh()
    rng = np.random.default_rng(0)
    local = rng.random((500, 2))
    el = rng.integers(0, len(quads), 500)
    x = np.einsum("pk,pkd->pd", bilinear_weights(local), pts[quads[el]])
    loc = locate(pts, quads, x)
    assert np.allclose(place(pts, loc), x, atol=1e-12)


def test_nodes_and_edges_are_located():
    pts, quads = _wavy_mesh()
    edge_mid = 0.5 * (pts[quads[:, 0]] + pts[quads[:, 1]])
    x = np.vstack((pts, edge_mid))
    loc = locate(pts, quads, x)
    assert np.allclose(place(pts, loc), x, atol=1e-12)
    assert np.all((loc.local >= 0) & (loc.local <= 1))


def test_agrees_with_delaunay_oracle_on_a_rectangle_grid():
    x, y = np.meshgrid(np.arange(5.0), np.arange(4.0))
    pts = np.column_stack((x.ravel(), y.ravel()))
    quads = structured_quads(3, 5)
    rng = np.random.default_rng(1)
    q = rng.random((300, 2)) * [4, 3]
    loc = locate(pts, quads, q)
    # for a unit grid the element is floor(x) + 4 * floor(y)
    assert np.array_equal(loc.elements, (np.floor(q[:, 0]) + 4 * np.floor(q[:, 1])).astype(int))
    assert Delaunay(pts).find_simplex(q).min() >= 0


def test_point_outside_is_named():
    pts, quads = _wavy_mesh()
    with pytest.raises(LocateError, match=r"point 1 at \[50.0, 50.0\] lies in no element"):
        locate(pts, quads, np.array([[1.0, 1.0], [50.0, 50.0]]))
