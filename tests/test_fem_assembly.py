"""Mixed neo-Hookean assembly: consistent tangent, stress-free states, frame indifference."""

import numpy as np
import pytest

from sectiondeform.fem.assembly import MixedNeoHooke, Pattern
from sectiondeform.fem.elements import geometry
from sectiondeform.fem.mesh import coarse_mesh

BOX = np.array([[0, 0], [4, 0], [4, 2], [0, 2]], float)


@pytest.fixture(scope="module")
def problem():
    m = coarse_mesh(BOX, np.array([0]), 1.0)
    ph = MixedNeoHooke(m.cells, len(m.nodes), geometry(m.nodes, m.cells), 50.0)
    return m, ph


def _state(m, rng, noise=0.05):
    return np.concatenate((m.nodes.ravel() + rng.normal(0, noise, 2 * len(m.nodes)), rng.normal(0, 0.3, m.n_vertices)))


def test_tangent_is_the_derivative_of_the_residual(problem):
    m, ph = problem
    rng = np.random.default_rng(3)
    z, lz = _state(m, rng), 1.15
    pat = Pattern(ph.edofs, len(z), np.array([0, 1]))
    f = ph.fields(z, lz)
    kff = pat.matrix_ff(ph.element_matrices(f)).toarray()
    free = pat.free
    dz = rng.normal(0, 1, len(free))
    eps = 1e-6
    zp, zm = z.copy(), z.copy()
    zp[free] += eps * dz
    zm[free] -= eps * dz
    fd = (ph.residual(ph.fields(zp, lz)) - ph.residual(ph.fields(zm, lz)))[free] / (2 * eps)
    assert np.allclose(fd, kff @ dz, rtol=1e-6, atol=1e-6 * np.abs(fd).max())
    assert np.allclose(kff, kff.T, atol=1e-12)


def test_element_and_global_residuals_agree(problem):
    m, ph = problem
    z = _state(m, np.random.default_rng(4))
    f = ph.fields(z, 0.9)
    pat = Pattern(ph.edofs, len(z), np.zeros(0, np.int64))
    assert np.allclose(pat.vector(ph.element_residuals(f)), ph.residual(f), atol=1e-12)


@pytest.mark.parametrize("angle", [0.0, 0.7, -2.5])
def test_rigid_motions_are_stress_free(problem, angle):
    m, ph = problem
    q = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    z = np.concatenate(((m.nodes @ q.T + [3.0, -1.0]).ravel(), np.zeros(m.n_vertices)))
    assert np.abs(ph.residual(ph.fields(z, 1.0))).max() < 1e-12


def test_inverted_state_is_reported(problem):
    m, ph = problem
    z = np.concatenate(((m.nodes * [-1.0, 1.0]).ravel(), np.zeros(m.n_vertices)))
    assert ph.fields(z, 1.0) is None
