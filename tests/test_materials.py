"""Rubber models: derivatives against finite differences, the reference solver's neo-Hookean, JSON, measures."""

import math

import numpy as np
import pytest

from sectiondeform.errors import CaseError, MeshError, SectionDeformError
from sectiondeform.materials import MooneyRivlin, NeoHookean, Yeoh, gradient_3d, material_from_json
from sectiondeform.materials.homogeneous import nominal_stress, unstable_modes
from sectiondeform.materials.measures import max_principal_strain, pressure, principal_stretches, von_mises

MATERIALS = [
    NeoHookean(1.3, bulk_to_shear=20.0),
    MooneyRivlin(0.3, 0.2, bulk_modulus=8.0),
    MooneyRivlin(0.4, -0.05, bulk_to_shear=50.0),
    Yeoh(0.3, -0.02, 0.004, bulk_modulus=6.0),
]


def _gradients(seed, n=5, size=0.3):
    rng = np.random.default_rng(seed)
    F = np.eye(3) + size * rng.standard_normal((n, 3, 3))
    F[np.linalg.det(F) < 0, :, 0] *= -1.0  # keep det F > 0
    return F


def _fd(fun, F, h=1e-6):
    out = []
    for k in range(3):
        for l in range(3):
            dF = np.zeros((3, 3))
            dF[k, l] = h
            out.append((fun(F + dF) - fun(F - dF)) / (2 * h))
    d = np.stack(out, axis=-1)
    return d.reshape(d.shape[:-1] + (3, 3))


@pytest.mark.parametrize("material", MATERIALS, ids=lambda m: repr(m))
@pytest.mark.parametrize("volumetric", [True, False])
def test_stress_is_the_derivative_of_the_energy_and_tangent_of_the_stress(material, volumetric):
    F = _gradients(1)
    P = material.first_piola(F, volumetric)
    A = material.tangent(F, volumetric)
    P_fd = _fd(lambda G: material.energy(G, volumetric), F)
    A_fd = _fd(lambda G: material.first_piola(G, volumetric), F)
    assert np.abs(P - P_fd).max() <= 1e-7 * np.abs(P).max()
    assert np.abs(A - A_fd).max() <= 1e-7 * np.abs(A).max()
    # Major symmetry of a hyperelastic tangent.
    assert np.allclose(A, np.einsum("...ijkl->...klij", A), atol=1e-12 * np.abs(A).max())


@pytest.mark.parametrize("material", MATERIALS, ids=lambda m: repr(m))
def test_undeformed_state_is_stress_free_with_the_initial_shear_modulus(material):
    I = np.eye(3)
    assert np.abs(material.first_piola(I)).max() < 1e-14
    assert abs(float(material.energy(I))) < 1e-14
    # Small simple shear: tau = mu0 * gamma.
    gamma = 1e-6
    F = I.copy()
    F[0, 1] = gamma
    assert material.cauchy(F)[0, 1] == pytest.approx(material.shear_modulus * gamma, rel=1e-5)
    # Small volume change: p = -kappa dV/V.
    eps = 1e-7
    assert pressure(material.cauchy((1 + eps) * I)) == pytest.approx(-material.kappa * 3 * eps, rel=1e-5)


def test_neo_hookean_matches_the_reference_solver():
    from sectiondeform.reference.solver import neo_hookean

    mu, kappa, lz = 0.7, 350.0, 1.15
    F3 = _gradients(7, n=6, size=0.2)
    F2 = F3[:, :2, :2]
    F2[np.linalg.det(F2) < 0, :, 0] *= -1.0
    F = gradient_3d(F2, lz)
    J = np.linalg.det(F)
    grad_u = np.moveaxis(F2 - np.eye(2), 0, -1)  # the solver's layout: (2, 2, points)
    ref = neo_hookean(grad_u, lz, kappa * (J - 1.0), mu, kappa)
    mat = NeoHookean(mu, bulk_modulus=kappa)
    assert np.allclose(mat.energy(F), ref["psi_mixed"], rtol=1e-12, atol=1e-12)
    assert np.allclose(np.moveaxis(mat.first_piola(F)[:, :2, :2], 0, -1), ref["P"], rtol=1e-12, atol=1e-12)
    # The solver's tangent is at fixed pressure; with p = kappa (J - 1) eliminated,
    # dP/dF gains dP/dp x dp/dF = (J F^-T) x (kappa J F^-T).
    Fit = ref["dPdp"]
    A_ref = ref["A"] + kappa * np.einsum("ij...,kl...->ijkl...", Fit, Fit)
    A = np.moveaxis(mat.tangent(F)[:, :2, :2, :2, :2], 0, -1)
    assert np.allclose(A, A_ref, rtol=1e-10, atol=1e-10 * np.abs(A_ref).max())


def test_measures_on_a_homogeneous_isochoric_stretch():
    # F = diag(2, 0.8, 0.625), J = 1; neo-Hookean mu = 1: sigma = dev(B), B = diag(4, 0.64, 0.390625).
    F = np.diag([2.0, 0.8, 0.625])
    sigma = NeoHookean(1.0).cauchy(F)
    mean = (4.0 + 0.64 + 0.390625) / 3.0
    assert np.allclose(np.diag(sigma), [4.0 - mean, 0.64 - mean, 0.390625 - mean], atol=1e-12)
    assert np.allclose(sigma - np.diag(np.diag(sigma)), 0.0, atol=1e-14)
    assert abs(float(pressure(sigma))) < 1e-12
    # von Mises from the principal differences 3.36, 0.249375, 3.609375.
    vm = math.sqrt((3.36**2 + 0.249375**2 + 3.609375**2) / 2.0)
    assert float(von_mises(sigma)) == pytest.approx(vm, rel=1e-12)
    assert principal_stretches(F).tolist() == pytest.approx([2.0, 0.8, 0.625])
    assert float(max_principal_strain(F)) == pytest.approx(1.0)
    assert float(max_principal_strain(F, "log")) == pytest.approx(math.log(2.0))
    assert float(max_principal_strain(F, "green")) == pytest.approx(1.5)


def test_measures_on_a_homogeneous_dilatation_and_a_rotation():
    m = MooneyRivlin(0.3, 0.1, bulk_modulus=100.0)
    F = 1.1 * np.eye(3)
    sigma = m.cauchy(F)
    assert float(pressure(sigma)) == pytest.approx(-100.0 * (1.331 - 1.0), rel=1e-12)
    assert float(von_mises(sigma)) < 1e-12
    # Rotating the deformed body leaves stretches and invariant stresses alone.
    c, s = math.cos(0.7), math.sin(0.7)
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    G = _gradients(3, n=4)
    for a, b in ((G, R @ G),):
        assert np.allclose(principal_stretches(a), principal_stretches(b))
        assert np.allclose(von_mises(m.cauchy(a)), von_mises(m.cauchy(b)))
        assert np.allclose(pressure(m.cauchy(a)), pressure(m.cauchy(b)))


def test_gradient_with_an_inverted_point_is_refused():
    F = np.stack([np.eye(3), np.diag([1.0, 1.0, -1.0])])
    with pytest.raises(MeshError, match="inverted"):
        NeoHookean().first_piola(F)


@pytest.mark.parametrize("material", [NeoHookean(0.8), MooneyRivlin(0.3, 0.1), Yeoh(0.3, -0.01, 0.002)], ids=repr)
@pytest.mark.parametrize("mode", ["uniaxial", "equibiaxial", "planar"])
def test_analytic_homogeneous_stress_matches_the_stress_tensor(material, mode):
    lam = np.linspace(0.5, 4.0, 15)
    one = np.ones_like(lam)
    diag = {"uniaxial": (lam, lam**-0.5, lam**-0.5), "equibiaxial": (lam, lam, lam**-2),
            "planar": (lam, one, 1 / lam)}[mode]
    F = np.zeros((lam.size, 3, 3))
    for i in range(3):
        F[:, i, i] = diag[i]
    # Incompressible: sigma = sigma_iso - q I, q such that the free direction 3 has no stress.
    sigma = material.first_piola(F, volumetric=False) @ np.swapaxes(F, -1, -2)
    expected = (sigma[:, 0, 0] - sigma[:, 2, 2]) / lam
    assert np.allclose(nominal_stress(material, mode, lam), expected, rtol=1e-12, atol=1e-14)


def test_stability_check():
    assert unstable_modes(NeoHookean(1.0), 8.0) == []
    assert unstable_modes(Yeoh(0.2, 0.01, 0.001), 8.0) == []
    # Mooney-Rivlin with c01 < 0: equibiaxial P = 2 (l - l^-5)(c10 + l^2 c01) peaks before l = 2.
    lines = unstable_modes(MooneyRivlin(0.2, -0.05), 4.0)
    assert any(line.startswith("equibiaxial: unstable beyond stretch") for line in lines)
    beyond = float([line for line in lines if line.startswith("equibiaxial")][0].split()[-1])
    assert 1.0 < beyond < 2.0


# -- the case format's material object ---------------------------------------------------------------

def test_material_json_forms_and_round_trip():
    assert material_from_json({}) == NeoHookean(1.0)
    assert material_from_json({}).kappa == 1000.0
    assert material_from_json({"shear_modulus": 2.5}, default_bulk_to_shear=500.0).kappa == 1250.0
    assert material_from_json({"shear_modulus": 2.5, "bulk_to_shear": 100}, default_bulk_to_shear=500.0).kappa == 250.0
    for m in (NeoHookean(0.4, bulk_to_shear=2000.0), MooneyRivlin(0.2, 0.05, bulk_modulus=900.0),
              Yeoh(0.2, -0.001, 3e-5), NeoHookean(0.5, bulk_modulus=1e3)):
        obj = m.to_json()
        assert material_from_json(obj) == m
        assert material_from_json(obj).kappa == m.kappa
    assert "model" not in NeoHookean().to_json()
    assert material_from_json({"model": "neo-hookean", "shear_modulus": 3}) == NeoHookean(3.0)
    assert MooneyRivlin(0.2, 0.05).shear_modulus == pytest.approx(0.5)
    assert Yeoh(0.2, 0.0, 0.0).shear_modulus == pytest.approx(0.4)


@pytest.mark.parametrize("obj, where", [
    ({"model": "mooney-rivlin", "c10": -0.1, "c01": 0.2}, "bodies[1].material.c10: must be > 0"),
    ({"model": "mooney-rivlin", "c10": 0.1, "c01": -0.2}, "bodies[1].material.c01: the initial shear modulus"),
    ({"model": "mooney-rivlin", "c10": 0.1}, "bodies[1].material.c01: missing"),
    ({"model": "yeoh", "c10": 0.1, "c20": 0.0, "c03": 0.0}, "bodies[1].material.c03: unknown key for a yeoh material; did you mean c30?"),
    ({"model": "yeo", "c10": 1}, "bodies[1].material.model: unknown material model 'yeo'; did you mean yeoh?"),
    ({"shear_modulus": 0}, "bodies[1].material.shear_modulus: must be > 0"),
    ({"shear_modulus": True}, "bodies[1].material.shear_modulus: expected a number"),
    ({"shear_modulus": "1"}, "bodies[1].material.shear_modulus: expected a number"),
    ({"shear_modulus": 1, "bulk_modulus": 10, "bulk_to_shear": 10}, "bodies[1].material.bulk_modulus: give bulk_modulus or bulk_to_shear"),
    ({"shear_modulus": 1, "bulk_to_shear": -1}, "bodies[1].material.bulk_to_shear: must be a finite number > 0"),
    ({"model": "yeoh", "c10": 0.1, "c20": float("nan"), "c30": 0}, "bodies[1].material.c20: expected a finite number"),
    ([1.0], "bodies[1].material: expected an object"),
])
def test_material_json_errors_name_the_field(obj, where):
    with pytest.raises(CaseError) as info:
        material_from_json(obj, "bodies[1].material")
    msg = str(info.value)
    assert msg.startswith(where), msg
    assert "\n" not in msg
    assert isinstance(info.value, SectionDeformError)


def test_materials_are_frozen_and_hashable():
    m = Yeoh(0.2, -0.001, 3e-5)
    with pytest.raises(AttributeError):
        m.c10 = 1.0
    assert {m: 1}[Yeoh(0.2, -0.001, 3e-5)] == 1
    assert m.scaled(2.0).c20 == pytest.approx(-0.002)


@pytest.mark.parametrize("material", [NeoHookean(0.7), MooneyRivlin(0.4, 0.2), Yeoh(0.5, -0.05, 0.01)],
                         ids=["neo-hookean", "mooney-rivlin", "yeoh"])
def test_the_plane_tangent_is_the_in_plane_block_of_the_full_one(material):
    """For F = diag(F2, lz) the in-plane block of dP/dF needs the in-plane blocks only: the same numbers, to rounding."""
    rng = np.random.default_rng(3)
    F = np.zeros((40, 3, 3))
    F[:, :2, :2] = np.eye(2) + 0.3 * rng.normal(size=(40, 2, 2))
    F[:, 2, 2] = 0.8 + 0.4 * rng.random(40)
    F = F[np.linalg.det(F) > 0.1]
    for volumetric in (False, True):
        full = material.tangent(F, volumetric=volumetric)[..., :2, :2, :2, :2]
        np.testing.assert_allclose(material.tangent(F, volumetric=volumetric, plane=True), full, rtol=1e-12, atol=1e-12)
