"""The coarse mesher: exact cover, corners as nodes, boundary bookkeeping, valid elements."""

import numpy as np
import pytest
import shapely

import sectiondeform as sd
from sectiondeform.fem.elements import geometry
from sectiondeform.fem.mesh import coarse_mesh

from conftest import SHARED_CASES

# An L-shape with a re-entrant corner at (4, 2) and a groove.
L_SHAPE = np.array([[0, 0], [10, 0], [10, 2], [6, 2], [6, 1], [5, 1], [5, 2], [4, 2], [4, 6], [0, 6]], float)


@pytest.mark.parametrize("h", [0.5, 1.0, 3.0])
def test_l_shape_is_covered_exactly_with_every_corner_a_node(h):
    m = coarse_mesh(L_SHAPE, np.array([0]), h)
    g = geometry(m.nodes, m.cells)
    assert g.weight.sum() == pytest.approx(shapely.Polygon(L_SHAPE).area, rel=1e-12)
    assert g.detj_ratio.min() > 0.2
    corners = m.nodes[: m.n_boundary]
    for c in L_SHAPE:
        assert np.hypot(*(corners - c).T).min() < 1e-12


def test_boundary_edges_follow_the_contour_in_order():
    m = coarse_mesh(L_SHAPE, np.array([0]), 1.0)
    assert np.all(np.diff(m.boundary_s) > 0)
    cell, loc, direction = m.boundary_edges.T
    ends = np.array([[0, 1], [1, 2], [2, 0]])[loc]
    a = m.cells[cell, ends[:, 0]]
    b = m.cells[cell, ends[:, 1]]
    j = np.arange(m.n_boundary)
    first = np.where(direction > 0, a, b)
    second = np.where(direction > 0, b, a)
    assert np.array_equal(first, j) and np.array_equal(second, (j + 1) % m.n_boundary)


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
@pytest.mark.parametrize("n", [2, 4, 8])
def test_shared_sections_mesh_with_positive_elements(path, n):
    sec = sd.build_section(sd.load_case(path))
    m = coarse_mesh(sec.contour, np.array([0, len(sec.lower) - 1]), sec.thickness / n)
    g = geometry(m.nodes, m.cells)
    assert g.detj_ratio.min() > 0.2
    assert g.weight.sum() == pytest.approx(sec.area, rel=2e-3)
    # A and B are nodes.
    assert np.hypot(*(m.nodes[: m.n_boundary] - sec.lower[-1]).T).min() < 1e-12
    assert m.nodes[0] == pytest.approx(sec.lower[0])
