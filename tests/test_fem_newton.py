"""The solver's fast paths answer as the slow ones: sparse axisymmetric products, the reused column order."""

import numpy as np
import pytest
from scipy.sparse.linalg import splu

from sectiondeform.fem.axisymmetric import AxisymmetricNeoHooke
from sectiondeform.fem.elements import geometry
from sectiondeform.fem.neohooke import MixedNeoHooke, Pattern
from sectiondeform.fem.newton import NewtonSolver

from conftest import one_body_mesh

BOX = np.array([[1, 0], [5, 0], [5, 2], [1, 2]], float)  # one unit off the axis x = 0


@pytest.fixture(scope="module")
def ring():
    m = one_body_mesh(BOX, np.array([0]), 0.7)
    ph = AxisymmetricNeoHooke(m.cells, m.nodes, geometry(m.nodes, m.cells), [0.0, 0.0], [1.0, 0.0], 200.0, 1.0, 0.3)
    return m, ph


def _state(m, rng, noise=0.04):
    return np.concatenate((m.nodes.ravel() + rng.normal(0, noise, 2 * len(m.nodes)), rng.normal(0, 0.3, m.n_vertices)))


def test_axisymmetric_sparse_residual_is_the_sum_of_the_element_residuals(ring):
    m, ph = ring
    z = _state(m, np.random.default_rng(1))
    f = ph.fields(z, 1.3)
    pat = Pattern(ph.edofs, len(z), np.zeros(0, np.int64))
    assert np.allclose(ph.residual(f), pat.vector(ph.element_residuals(f)), rtol=0, atol=1e-12 * np.abs(ph.residual(f)).max())


def test_axisymmetric_hoop_stretch_is_the_distance_ratio_at_the_quadrature_points(ring):
    m, ph = ring
    z = _state(m, np.random.default_rng(2))
    f = ph.fields(z, 1.0)
    x = z[: 2 * len(m.nodes)].reshape(-1, 2)[m.cells]  # (E, 6, 2)
    at_q = np.einsum("qa,eai->eqi", ph.values, x)
    assert np.allclose(f.hoop, at_q[..., 0] / ph.radius, rtol=1e-13, atol=0)


def test_axisymmetric_tangent_is_the_derivative_of_the_residual(ring):
    m, ph = ring
    rng = np.random.default_rng(3)
    z, s = _state(m, rng), 1.2
    pat = Pattern(ph.edofs, len(z), np.array([0, 1]))
    kff = pat.matrix_ff(ph.element_matrices(ph.fields(z, s))).toarray()
    dz = rng.normal(0, 1, len(pat.free))
    eps = 1e-6
    zp, zm = z.copy(), z.copy()
    zp[pat.free] += eps * dz
    zm[pat.free] -= eps * dz
    fd = (ph.residual(ph.fields(zp, s)) - ph.residual(ph.fields(zm, s)))[pat.free] / (2 * eps)
    assert np.allclose(fd, kff @ dz, rtol=1e-6, atol=1e-6 * np.abs(fd).max())


@pytest.mark.parametrize("spec", ["COLAMD", "MMD_AT_PLUS_A"])
def test_later_factorisations_reuse_the_first_order_and_solve_the_same_system(spec):
    m = one_body_mesh(np.array([[0, 0], [4, 0], [4, 2], [0, 2]], float), np.array([0]), 0.5)
    ph = MixedNeoHooke(m.cells, len(m.nodes), geometry(m.nodes, m.cells), 500.0)
    fixed = (2 * np.flatnonzero(np.isclose(m.nodes[:, 1], 0.0))[:, None] + np.arange(2)).ravel()
    pat = Pattern(ph.edofs, 2 * len(m.nodes) + m.n_vertices, fixed)
    solver = NewtonSolver(ph, pat, 2.0, permc_spec=spec)
    rng = np.random.default_rng(5)
    z0 = np.concatenate((m.nodes.ravel(), np.zeros(m.n_vertices)))
    first = solver.tangent(ph.fields(z0, 1.0))
    z = _state(m, rng, 0.02)
    f = ph.fields(z, 1.1)
    later = solver.tangent(f)
    assert type(later.lu).__name__ == "_Ordered" and type(first.lu).__name__ == "SuperLU"
    kff = pat.matrix_ff(ph.element_matrices(f))
    fresh = splu(kff, permc_spec=spec, diag_pivot_thresh=0.01, options={"SymmetricMode": True})
    assert later.lu.lu.L.nnz + later.lu.lu.U.nnz == fresh.L.nnz + fresh.U.nnz  # the same fill: the same order
    rhs = rng.normal(0, 1, (kff.shape[0], 3))
    for k in range(3):
        x = later.solve(rhs[:, k])
        assert np.allclose(kff @ x, rhs[:, k], rtol=0, atol=1e-9 * np.abs(rhs[:, k]).max())
        assert np.allclose(x, fresh.solve(rhs[:, k]), rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("offset", [(-1e5, 2e5), (3e3, -7e3)])
def test_the_union_mesh_of_a_small_body_far_off_is_its_mesh_at_the_origin_moved(offset):
    """A 0.06 mm body at 1e5 mm: meshed about its own point (it used to loop in Qhull's lost digits)."""
    from sectiondeform.fem.union_mesh import union_mesh

    ring = np.array([[0.0, 0.0], [0.0625, 0.0], [0.0139, 0.0031], [0.006, 0.0031]])
    here = union_mesh([ring], [np.array([0, 1])], 0.0008, 1e-12)
    there = union_mesh([ring + offset], [np.array([0, 1])], 0.0008, 1e-12)
    assert there.cells.shape == here.cells.shape and there.nodes.shape == here.nodes.shape
    a, b = here.nodes, np.round(there.nodes - offset, 9)  # the same nodes, in whatever order Qhull gave
    assert np.allclose(a[np.lexsort(np.round(a, 9).T)], b[np.lexsort(b.T)], rtol=0, atol=1e-9)
    corners = there.nodes[there.cells[:, :3]] - offset
    e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    areas = 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    x, y = ring.T
    assert areas.min() > 0 and np.isclose(areas.sum(), 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)), rtol=1e-9)


def test_a_thin_sliver_factorises_with_little_fill():
    """The column order keeps a thin one-body sliver sparse (the minimum-degree order filled it 25 times more).

    tests/data/fuzz-found/hang-fem-assembly-element-matrices-183.json meshes to 16,240 unknowns; its first
    tangent in SuperLU's ``MMD_AT_PLUS_A`` order had 37.0 M entries in L and U (2,277 per unknown, 8 s of
    factorisation), in COLAMD order 1.45 M (89 per unknown).
    """
    from pathlib import Path

    import sectiondeform as sd

    path = Path(__file__).parent / "data" / "fuzz-found" / "hang-fem-assembly-element-matrices-183.json"
    prepared = sd.Deformer(sd.load_case(path), "hyperelastic").prepared
    n = len(prepared.solver.pattern.free)
    lu = prepared.reference.tangent.lu
    assert n > 12_000
    assert lu.L.nnz + lu.U.nnz < 200 * n
