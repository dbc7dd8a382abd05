"""Mixed neo-Hookean assembly: consistent tangent, stress-free states, frame indifference; a pressure per body."""

import numpy as np
import pytest

from sectiondeform.fem.axisymmetric import AxisymmetricNeoHooke, AxisymmetricRubber
from sectiondeform.fem.elements import geometry
from sectiondeform.fem.neohooke import MixedNeoHooke, Pattern
from sectiondeform.fem.rubber import MixedRubber
from sectiondeform.fem.union_mesh import body_pressure_cells, union_mesh
from sectiondeform.materials import MooneyRivlin, NeoHookean

from conftest import one_body_mesh

BOX = np.array([[0, 0], [4, 0], [4, 2], [0, 2]], float)


@pytest.fixture(scope="module")
def problem():
    m = one_body_mesh(BOX, np.array([0]), 1.0)
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


# --- one pressure field per body -----------------------------------------------------------


def _stack():
    """Two stacked boxes of one union mesh, 4 x 1 each, above the axis y = -1."""
    low = np.array([[0, 0], [4, 0], [4, 1], [0, 1]], float)
    return union_mesh([low, low + [0.0, 1.0]], [np.array([0, 1])] * 2, 0.6, 1e-9)


def _physics(kind, m):
    geom = geometry(m.nodes, m.cells)
    rubbers = [NeoHookean(1.0, bulk_modulus=40.0), MooneyRivlin(1.2, 0.6, bulk_modulus=300.0)]
    if kind == "plane":
        return MixedNeoHooke(m.cells, len(m.nodes), geom, 40.0 * np.array([1.0, 3.0])[m.body], np.array([1.0, 3.0])[m.body],
                             m.pressure_cells)
    if kind == "plane rubber":
        return MixedRubber(m.cells, len(m.nodes), geom, rubbers, m.body, np.array([0.1, -0.2])[m.body], m.pressure_cells)
    if kind == "revolution":
        return AxisymmetricNeoHooke(m.cells, m.nodes, geom, [0.0, -1.0], [0.0, 1.0], np.array([40.0, 120.0])[m.body],
                                    np.array([1.0, 3.0])[m.body], np.array([0.1, -0.1])[m.body], m.pressure_cells)
    return AxisymmetricRubber(m.cells, m.nodes, geom, [0.0, -1.0], [0.0, 1.0], rubbers, m.body,
                              np.array([0.1, -0.1])[m.body], m.pressure_cells)


@pytest.mark.parametrize("kind", ["plane", "plane rubber", "revolution", "revolution rubber"])
def test_a_pressure_per_body_keeps_the_tangent_the_derivative_of_the_residual(kind):
    m = _stack()
    ph = _physics(kind, m)
    assert m.n_pressures > m.n_vertices and ph.edofs.max() == 2 * len(m.nodes) + m.n_pressures - 1
    rng = np.random.default_rng(5)
    z = np.concatenate((m.nodes.ravel() + rng.normal(0, 0.03, 2 * len(m.nodes)), rng.normal(0, 0.3, m.n_pressures)))
    lz = 1.3
    pat = Pattern(ph.edofs, len(z), np.array([0, 1]))
    f = ph.fields(z, lz)
    assert np.allclose(pat.vector(ph.element_residuals(f)), ph.residual(f), atol=1e-12)
    kff = pat.matrix_ff(ph.element_matrices(f)).toarray()
    dz = rng.normal(0, 1, len(pat.free))
    eps = 1e-6
    zp, zm = z.copy(), z.copy()
    zp[pat.free] += eps * dz
    zm[pat.free] -= eps * dz
    fd = (ph.residual(ph.fields(zp, lz)) - ph.residual(ph.fields(zm, lz)))[pat.free] / (2 * eps)
    assert np.allclose(fd, kff @ dz, rtol=1e-6, atol=1e-6 * np.abs(fd).max())


def test_a_pressure_per_body_is_read_per_body_and_the_one_field_is_the_default(problem):
    m = _stack()
    ph = _physics("plane", m)
    # one pressure per body: 1 in the lower body, 3 in the upper, at every point of each, the interface too
    p = np.zeros(m.n_pressures)
    p[m.pressure_cells[m.body == 1]] = 3.0
    p[m.pressure_cells[m.body == 0]] = 1.0  # would overwrite the upper body's at shared vertices if they were one
    f = ph.fields(np.concatenate((m.nodes.ravel(), p)), 1.0)
    np.testing.assert_array_equal(f.p[m.body == 0], 1.0)
    np.testing.assert_allclose(f.p[m.body == 1], 3.0, rtol=1e-15)
    # without pressure_cells, one field on the corner nodes (the single-body problem), bit for bit
    single, ph0 = problem
    again = MixedNeoHooke(single.cells, len(single.nodes), ph0.geom, 50.0, pressure_cells=single.cells[:, :3])
    assert np.array_equal(again.edofs, ph0.edofs) and again.n_pressures == single.n_vertices
    assert np.array_equal(body_pressure_cells(single.cells, np.zeros(len(single.cells), np.int64), single.n_vertices)[0],
                          single.cells[:, :3])
