"""Point location in a quad mesh: against independent oracles, and the two search paths against each other."""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.spatial import Delaunay

import sectiondeform.locate as locate_module
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
    # Oracle: scipy's Delaunay triangle holding each point. On a unit grid every Delaunay
    # triangle is half of one cell, so the cell holding its centroid is the point's element.
    tri = Delaunay(pts)
    simplex = tri.find_simplex(q)
    assert simplex.min() >= 0
    centroid = pts[tri.simplices[simplex]].mean(axis=1)
    oracle = (np.floor(centroid[:, 0]) + 4 * np.floor(centroid[:, 1])).astype(int)
    assert np.array_equal(loc.elements, oracle)


def _covering_quads(pts, quads, x, tol=1e-9):
    """Oracle by shapely: for each point, the set of elements whose polygon covers it."""
    polys = shapely.polygons(pts[quads])
    tree = shapely.STRtree(polys)
    pairs = tree.query(shapely.points(x), predicate="dwithin", distance=tol)
    covering = [set() for _ in range(len(x))]
    for i, el in pairs.T:
        covering[i].add(int(el))
    return covering


@pytest.mark.parametrize("n", [50, 5000])
def test_element_found_covers_the_point_by_shapely(n):
    pts, quads = _wavy_mesh()
    inside = shapely.union_all(shapely.polygons(pts[quads]))
    rng = np.random.default_rng(n)
    cand = rng.random((4 * n, 2)) * [8.5, 5.5] - [0.2, 0.0]
    x = cand[shapely.contains_xy(inside, cand[:, 0], cand[:, 1])][:n]
    assert len(x) == n
    loc = locate(pts, quads, x)
    covering = _covering_quads(pts, quads, x)
    assert all(int(e) in c for e, c in zip(loc.elements, covering))


def test_bucket_grid_and_box_scan_agree(monkeypatch):
    """The two search paths (bucket grid for many points, box scan for few) give the same location."""
    pts, quads = _wavy_mesh()
    rng = np.random.default_rng(5)
    local = rng.random((400, 2))
    el = rng.integers(0, len(quads), 400)
    x = np.einsum("pk,pkd->pd", bilinear_weights(local), pts[quads[el]])
    x = np.vstack((x, pts))  # nodes too, shared by up to four elements
    monkeypatch.setattr(locate_module, "FEW_PAIRS", -1)  # always the bucket grid
    buckets = locate(pts, quads, x)
    monkeypatch.setattr(locate_module, "FEW_PAIRS", 10**12)  # always the box scan
    boxes = locate(pts, quads, x)
    np.testing.assert_allclose(place(pts, buckets), place(pts, boxes), atol=1e-12)
    interior = slice(0, 400)  # strictly inside one element: the same element, the same local coordinates
    strict = np.all((local > 1e-6) & (local < 1 - 1e-6), axis=1)
    assert np.array_equal(buckets.elements[interior][strict], boxes.elements[interior][strict])
    np.testing.assert_allclose(buckets.local[interior][strict], boxes.local[interior][strict], atol=1e-10)


def test_point_outside_is_named():
    pts, quads = _wavy_mesh()
    with pytest.raises(LocateError, match=r"point 1 at \[50.0, 50.0\] lies in no element"):
        locate(pts, quads, np.array([[1.0, 1.0], [50.0, 50.0]]))
