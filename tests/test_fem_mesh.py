"""The hyperelastic model's mesher on one body: exact cover, every corner a node, valid elements, contour located.

(Several bodies sharing pieces: ``tests/test_union_mesh.py``.)
"""

import numpy as np
import pytest
import shapely

import sectiondeform as sd
from sectiondeform.fem.elements import geometry

from conftest import SHARED_CASES, one_body_mesh

# An L-shape with a re-entrant corner at (4, 2) and a groove.
L_SHAPE = np.array([[0, 0], [10, 0], [10, 2], [6, 2], [6, 1], [5, 1], [5, 2], [4, 2], [4, 6], [0, 6]], float)


@pytest.mark.parametrize("h", [0.5, 1.0, 3.0])
def test_l_shape_is_covered_exactly_with_every_corner_a_node(h):
    m = one_body_mesh(L_SHAPE, np.array([0]), h)
    g = geometry(m.nodes, m.cells)
    assert g.weight.sum() == pytest.approx(shapely.Polygon(L_SHAPE).area, rel=1e-12)
    assert g.detj_ratio.min() > 0.2
    for c in L_SHAPE:
        assert np.hypot(*(m.nodes[: m.n_vertices] - c).T).min() < 1e-12


@pytest.mark.parametrize("h", [0.5, 1.0])
def test_every_contour_point_is_the_image_of_the_undeformed_nodes(h):
    """The contour is located on the mesh's boundary edges: the undeformed nodes give back every contour point."""
    ring = np.array([[0, 0], [10, 0], [10, 3], [7, 3.5], [3, 3.5], [0, 3]], float)
    m = one_body_mesh(ring, np.array([0, 1]), h)
    np.testing.assert_allclose(m.vertex_weights @ m.nodes, m.points, atol=1e-12)
    assert len(m.points) == len(ring)


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
@pytest.mark.parametrize("n", [2, 4, 8])
def test_shared_sections_mesh_with_positive_elements(path, n):
    sec = sd.build_section(sd.load_case(path))
    m = one_body_mesh(sec.contour, np.array([0, len(sec.lower) - 1]), sec.thickness / n)
    g = geometry(m.nodes, m.cells)
    assert g.detj_ratio.min() > 0.2
    assert g.weight.sum() == pytest.approx(sec.area, rel=2e-3)
    # A and B are nodes.
    for end in (sec.lower[0], sec.lower[-1]):
        assert np.hypot(*(m.nodes[: m.n_vertices] - end).T).min() < 1e-12
