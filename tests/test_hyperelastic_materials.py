"""The hyperelastic model with the rubbers of sectiondeform.materials (Mooney–Rivlin, Yeoh).

The homogeneous test: a block bonded on a flat target stretched by s, with
the area law r = s², has the homogeneous solution F = diag(s, s, 1/s²) (free
top and sides); its out-of-plane Cauchy stress follows from the
incompressible nominal stresses of materials/homogeneous.py, derived there
from W(Ī₁, Ī₂) independently of the finite elements.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely

import sectiondeform as sd
from sectiondeform.deform import Deformer
from sectiondeform.fem.elements import geometry
from sectiondeform.fem.neohooke import MixedNeoHooke, Pattern
from sectiondeform.fem.rubber import MixedRubber
from sectiondeform.io.case import case_from_dict
from sectiondeform.materials import MooneyRivlin, NeoHookean, Yeoh, gradient_3d
from sectiondeform.materials.homogeneous import nominal_stress
from sectiondeform.problem import V2

from conftest import CASES_DIR, one_body_mesh

RUBBERS = [MooneyRivlin(0.3, 0.08, bulk_to_shear=1e5), Yeoh(0.25, -0.01, 0.002, bulk_to_shear=1e5)]
IDS = ["mooney-rivlin", "yeoh"]


def _block_mesh(size=0.7):
    ring = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 3.0], [0.0, 3.0]])
    mesh = one_body_mesh(ring, np.array([0, 1]), size)
    return mesh, geometry(mesh.nodes, mesh.cells)


def _perturbed(mesh, seed=0, amount=0.01):
    rng = np.random.default_rng(seed)
    n = len(mesh.nodes)
    return np.concatenate((mesh.nodes.ravel() + amount * rng.standard_normal(2 * n), 0.3 * rng.standard_normal(mesh.n_vertices)))


def _block(width=10.0, height=3.0, stretch=1.0, target=None):
    top = [[x, height] for x in np.linspace(width, 0.0, 6)]
    return sd.case_from_dict({
        "format": "section-case/1", "name": "block",
        "lower": {"polyline": [[0.0, 0.0], [width, 0.0]]},
        "upper": {"polyline": [[width, 0.0]] + top + [[0.0, 0.0]]},
        "target": target or {"polyline": [[0.0, 0.0], [stretch * width, 0.0]]},
        "law": {"area_ratio": stretch**2},
    })


def _place(case, material, through=4.0):
    """The one-body ``case`` of ``material`` solved by the hyperelastic model: its section, deformer and result."""
    data = sd.case_to_dict(case.replace(dialect=V2))
    data["bodies"][0]["material"] = material.to_json()
    data["options"] = {**data.get("options", {}), "model": "hyperelastic", "elements_through_thickness": through}
    deformer = Deformer(case_from_dict(data))
    return deformer.section, deformer, deformer.deform()


# -- the physics ------------------------------------------------------------------------------------

def test_neo_hookean_through_the_materials_agrees_with_the_closed_form():
    mesh, geom = _block_mesh()
    e = len(mesh.cells)
    body = (mesh.nodes[mesh.cells[:, :3]].mean(axis=1)[:, 1] > 1.5).astype(int)  # two materials
    rubbers = [NeoHookean(1.0, bulk_to_shear=1000.0), NeoHookean(3.0, bulk_modulus=500.0)]
    closed = MixedNeoHooke(mesh.cells, len(mesh.nodes), geom, np.array([r.kappa for r in rubbers])[body],
                           np.array([r.shear_modulus for r in rubbers])[body])
    general = MixedRubber(mesh.cells, len(mesh.nodes), geom, rubbers, body)
    z = _perturbed(mesh)
    fc, fg = closed.fields(z, 1.1), general.fields(z, 1.1)
    scale = np.abs(closed.residual(fc)).max()
    assert np.abs(closed.residual(fc) - general.residual(fg)).max() <= 1e-10 * scale
    assert np.abs(closed.element_residuals(fc) - general.element_residuals(fg)).max() <= 1e-10 * scale
    kc, kg = closed.element_matrices(fc), general.element_matrices(fg)
    assert kc.shape == kg.shape == (e, 15, 15)
    assert np.abs(kc - kg).max() <= 1e-10 * np.abs(kc).max()


@pytest.mark.parametrize("material", RUBBERS + [MooneyRivlin(0.4, -0.05), Yeoh(1.2, 0.3, 0.05)],
                         ids=IDS + ["mooney-rivlin-negative-c01", "yeoh-stiffening"])
def test_tangent_is_the_derivative_of_the_residual(material):
    mesh, geom = _block_mesh()
    body = np.arange(len(mesh.cells)) % 2
    ln_stretch = np.where(body == 0, 0.1, -0.2)  # a different out-of-plane stretch per material
    phys = MixedRubber(mesh.cells, len(mesh.nodes), geom, [material, material.scaled(4.0)], body, ln_stretch)
    z = _perturbed(mesh, seed=1)
    ke = phys.element_matrices(phys.fields(z, 1.3))
    assert np.abs(ke - ke.transpose(0, 2, 1)).max() <= 1e-12 * np.abs(ke).max()
    K = Pattern(phys.edofs, len(z), np.array([], np.int64)).matrix_ff(ke)
    dz = np.random.default_rng(2).standard_normal(len(z))
    h = 1e-6
    fd = (phys.residual(phys.fields(z + h * dz, 1.3)) - phys.residual(phys.fields(z - h * dz, 1.3))) / (2 * h)
    assert np.abs(K @ dz - fd).max() <= 1e-7 * np.abs(fd).max()


def test_the_undeformed_state_is_stress_free_and_an_inverted_one_is_refused():
    mesh, geom = _block_mesh()
    phys = MixedRubber(mesh.cells, len(mesh.nodes), geom, [RUBBERS[1]])
    z = np.concatenate((mesh.nodes.ravel(), np.zeros(mesh.n_vertices)))
    assert np.abs(phys.residual(phys.fields(z, 1.0))).max() < 1e-13
    flipped = z.copy()
    flipped[: 2 * len(mesh.nodes)] = (mesh.nodes * [1.0, -1.0]).ravel()
    assert phys.fields(flipped, 1.0) is None


# -- the model ----------------------------------------------------------------------------------------

def _out_of_plane_stress(material, s: float) -> float:
    """σ₃₃ of F = diag(s, s, 1/s²) with σ₁₁ = σ₂₂ = 0, from the homogeneous tests."""
    if s > 1.0:  # equibiaxial λ = s in the plane: σ₃₃ = −s P_eq(s)
        return -s * float(nominal_stress(material, "equibiaxial", [s])[0])
    lam = s**-2  # uniaxial λ = 1/s² out of plane: σ₃₃ = λ P_u(λ)
    return lam * float(nominal_stress(material, "uniaxial", [lam])[0])


@pytest.mark.parametrize("s", [1.25, 0.85])
@pytest.mark.parametrize("material", RUBBERS, ids=IDS)
def test_homogeneous_stretch_gives_the_stress_of_the_homogeneous_tests(material, s):
    section, _, placement = _place(_block(stretch=s), material)
    np.testing.assert_allclose(placement.final_mesh.points, s * placement.initial_mesh.points, atol=1e-4 * 3.0)
    f = placement.state.state.fields
    lz = f.J / f.det
    F3 = gradient_3d(f.F, lz)
    P_iso = material.first_piola(F3, volumetric=False)
    sigma33 = P_iso[..., 2, 2] * lz / f.J + f.p  # Cauchy: (P_iso + p J F^-T) F^T / J
    expected = _out_of_plane_stress(material, s)
    assert abs(expected) > 0.1 * material.shear_modulus
    np.testing.assert_allclose(sigma33, expected, rtol=1e-3)
    np.testing.assert_allclose(lz, 1.0 / s**2, rtol=1e-12)


@pytest.mark.parametrize("material", RUBBERS, ids=IDS)
def test_the_shape_of_one_body_does_not_depend_on_the_scale_of_its_moduli(material):
    arc = {"arc": {"center": [5.0, 9.0], "radius": 10.0, "start_deg": -120.0, "end_deg": -60.0}}
    case = _block(target=arc)
    section, _, base = _place(case, material)
    _, _, scaled = _place(case, material.scaled(7.0))
    bent = np.abs(base.upper - section.upper[section.characteristic_index]).max()  # result.upper: the characteristic points
    assert bent > 0.1 * section.thickness  # a real deformation
    assert np.abs(scaled.upper - base.upper).max() <= 1e-9 * section.thickness
    _, _, nh = _place(case, NeoHookean(material.shear_modulus, bulk_to_shear=1e5))
    assert np.abs(nh.upper - base.upper).max() > 1e-6 * section.thickness  # the model matters (1.8e-5 T, 5e-5 T)


# -- assemblies ------------------------------------------------------------------------------------------

STRIP = CASES_DIR / "v2" / "two-layer-strip.json"


def _strip(materials, stretch=1.2):
    data = json.loads(STRIP.read_text())
    data["options"] = {**data.get("options", {}), "model": "hyperelastic", "elements_through_thickness": 2.0}
    data["target"] = {"polyline": [[0.0, 0.0], [100.0 * stretch, 0.0]]}
    for body, material in zip(data["bodies"], materials):
        body["law"] = {"area_ratio": 1.0}
        body["material"] = material.to_json()
    return Deformer(case_from_dict(data)).deform()


def _top_stretch(result):
    """Length of the cover's deformed upper curve over its initial length."""
    cover = result.bodies[1]
    length = lambda p: float(np.hypot(*np.diff(p, axis=0).T).sum())  # noqa: E731
    return length(cover.upper) / length(cover.initial_upper)


def test_an_assembly_depends_on_the_ratio_of_its_moduli_and_the_stiffer_body_deforms_less():
    # The support stretches by 1.2; both bodies keep their area. A stiff cover resists the stretch its
    # backing pulls it into: its top stretches less; on a stiff backing it follows the support more.
    mr, yeoh = RUBBERS[0], RUBBERS[1]
    equal = _top_stretch(_strip([mr, yeoh.scaled(mr.shear_modulus / yeoh.shear_modulus)]))
    stiff_cover = _top_stretch(_strip([mr, yeoh.scaled(20.0 * mr.shear_modulus / yeoh.shear_modulus)]))
    stiff_backing = _top_stretch(_strip([mr.scaled(20.0), yeoh.scaled(mr.shear_modulus / yeoh.shear_modulus)]))
    assert 1.0 < stiff_cover < equal < stiff_backing < 1.2 + 1e-9
    both_scaled = _top_stretch(_strip([mr.scaled(7.0), yeoh.scaled(7.0 * mr.shear_modulus / yeoh.shear_modulus)]))
    assert both_scaled == pytest.approx(equal, abs=1e-7)


def test_an_assembly_with_a_mooney_rivlin_body_meets_each_law():
    result = _strip([NeoHookean(1.0), MooneyRivlin(0.4, 0.1)])
    for body in result.bodies:
        assert body.area_final == pytest.approx(body.area_target, rel=1e-9)


# -- against the reference ----------------------------------------------------------------------------

def _distance(a, b, T):
    return shapely.hausdorff_distance(shapely.LineString(a), shapely.LineString(b), densify=0.05) / T


@pytest.mark.parametrize("material", RUBBERS, ids=IDS)
def test_the_thick_block_is_as_close_to_the_reference_as_the_neo_hookean_model(material):
    pytest.importorskip("skfem")
    pytest.importorskip("triangle")
    from sectiondeform.reference import solve_reference

    case = sd.load_case(CASES_DIR / "thick-block-s-curve.json")
    section, _, placement = _place(case, material)
    ref = solve_reference(case, material=material)
    d = _distance(placement.upper, ref.bodies[0].upper, section.thickness)
    assert d < 0.012  # the neo-Hookean model: 0.9 % of T (docs/validation.md)


def test_an_unstable_rubber_is_named_as_such_not_blamed_on_the_mesh():
    """Yeoh with c20 = -0.5 loses stability beyond an equibiaxial stretch of 1.12: Newton finds no equilibrium.

    It was reported as "Newton stopped at its bound ... try a lower elements_through_thickness".
    """
    from sectiondeform.errors import ConvergenceError
    from sectiondeform.laws import AreaRatio
    from sectiondeform.materials.homogeneous import unstable_modes

    unstable = Yeoh(0.5, -0.5, 0.0, bulk_to_shear=1e3)
    assert "equibiaxial: unstable beyond stretch 1.12" in unstable_modes(unstable, 1.5)
    case = _block(stretch=1.3).replace(law=AreaRatio(1.0))
    with pytest.raises(ConvergenceError, match=r"^hyperelastic: the rubber \(yeoh, c10 = 0\.5, c20 = -0\.5, c30 = 0\) "
                                               r"is unstable beyond stretch 1\.12 \(equibiaxial\)") as info:
        _place(case, unstable)
    assert "elements_through_thickness" not in str(info.value)
    # The same target with a stable rubber of the same initial modulus is solved.
    _, _, placement = _place(case, Yeoh(0.5, 0.0, 0.0, bulk_to_shear=1e3))
    assert np.isfinite(placement.upper).all()
