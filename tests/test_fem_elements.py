"""Taylor-Hood P2 triangle: shape functions, quadrature, geometry."""

import numpy as np
import pytest

from sectiondeform.fem.elements import QUAD_POINTS, QUAD_WEIGHTS, geometry, p1_values, p2_gradients, p2_values

NODES = np.array([[0, 0], [1, 0], [0, 1], [0.5, 0], [0.5, 0.5], [0, 0.5]])


def test_p2_is_a_nodal_basis_with_partition_of_unity():
    assert np.allclose(p2_values(NODES), np.eye(6))
    pts = np.random.default_rng(1).random((20, 2)) * 0.5
    assert np.allclose(p2_values(pts).sum(axis=1), 1.0)
    assert np.allclose(p2_gradients(pts).sum(axis=1), 0.0)
    assert np.allclose(p1_values(pts).sum(axis=1), 1.0)


def test_p2_gradients_match_finite_differences():
    pts = np.array([[0.2, 0.3], [0.6, 0.1]])
    eps = 1e-7
    fd = np.stack([(p2_values(pts + eps * e) - p2_values(pts - eps * e)) / (2 * eps) for e in np.eye(2)], axis=2)
    assert np.allclose(fd, p2_gradients(pts), atol=1e-7)


@pytest.mark.parametrize("i, j", [(0, 0), (2, 1), (4, 0), (1, 3), (2, 2)])
def test_quadrature_is_exact_to_degree_four(i, j):
    # int over the reference triangle of x^i y^j = i! j! / (i + j + 2)!
    from math import factorial

    exact = factorial(i) * factorial(j) / factorial(i + j + 2)
    x, y = QUAD_POINTS.T
    assert np.dot(QUAD_WEIGHTS, x**i * y**j) == pytest.approx(exact, rel=1e-12)


def test_isoparametric_area_of_a_curved_edge():
    # A quarter disc of radius 1 by one P2 triangle: the curved edge's area is the quadratic's.
    s = np.sqrt(0.5)
    nodes = np.array([[0, 0], [1, 0], [0, 1], [0.5, 0], [s, s], [0, 0.5]])
    g = geometry(nodes, np.arange(6)[None])
    # Area under the parabola through (1,0), (s,s), (0,1) plus the triangle: 1/2 + 2/3 (sagitta * chord).
    sagitta = np.hypot(s - 0.5, s - 0.5)
    assert g.weight.sum() == pytest.approx(0.5 + 2.0 / 3.0 * sagitta * np.sqrt(2.0), rel=1e-12)
