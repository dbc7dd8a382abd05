"""The finite-element reference with the rubber models of sectiondeform.materials.

A block bonded on a flat target stretched by s, with the area law r = s², has
the homogeneous solution F = diag(s, s, 1/s²) (free top and sides): for s > 1
an equibiaxial stretch in the section's plane, for s < 1 a uniaxial one
along the out-of-plane axis. Its out-of-plane Cauchy stress follows from the
incompressible nominal stresses of materials/homogeneous.py, derived there
from W(Ī₁, Ī₂) independently of the solver.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import sectiondeform as sd

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.io.case import case_from_dict  # noqa: E402
from sectiondeform.materials import MooneyRivlin, NeoHookean, Yeoh  # noqa: E402
from sectiondeform.materials.homogeneous import nominal_stress  # noqa: E402
from sectiondeform.reference import solve_reference  # noqa: E402

from conftest import CASES_DIR  # noqa: E402

RUBBERS = [
    NeoHookean(0.8, bulk_to_shear=1e5),
    MooneyRivlin(0.3, 0.08, bulk_to_shear=1e5),
    Yeoh(0.25, -0.01, 0.002, bulk_to_shear=1e5),
]
IDS = ["neo-hookean", "mooney-rivlin", "yeoh"]


def block(width=10.0, height=3.0, stretch=1.0, target=None, ratio=None):
    top = [[x, height] for x in np.linspace(width, 0.0, 6)]
    return sd.case_from_dict({
        "format": "section-case/1", "name": "block",
        "lower": {"polyline": [[0.0, 0.0], [width, 0.0]]},
        "upper": {"polyline": [[width, 0.0]] + top + [[0.0, 0.0]]},
        "target": target or {"polyline": [[0.0, 0.0], [stretch * width, 0.0]]},
        "law": {"area_ratio": stretch**2 if ratio is None else ratio},
    })


def out_of_plane_stress(material, s: float) -> float:
    """σ₃₃ of F = diag(s, s, 1/s²) with σ₁₁ = σ₂₂ = 0, from the homogeneous tests."""
    if s > 1.0:  # equibiaxial λ = s in the plane: the lab's σ = s P_eq in the plane, shifted by −s P_eq
        return -s * float(nominal_stress(material, "equibiaxial", [s])[0])
    lam = s**-2  # uniaxial λ = 1/s² out of plane: σ₃₃ = λ P_u
    return lam * float(nominal_stress(material, "uniaxial", [lam])[0])


@pytest.mark.parametrize("s", [1.25, 0.85])
@pytest.mark.parametrize("material", RUBBERS, ids=IDS)
def test_homogeneous_stretch_gives_the_stress_of_the_homogeneous_tests(material, s):
    ref = solve_reference(block(stretch=s), material=material, mesh_size=0.5)
    np.testing.assert_allclose(ref.mesh.points, s * ref.initial_mesh.points, atol=1e-4 * 3.0)
    sigma = ref.cauchy
    expected = out_of_plane_stress(material, s)
    assert abs(expected) > 0.1 * material.shear_modulus
    np.testing.assert_allclose(sigma[:, 2, 2], expected, rtol=1e-3)
    assert np.abs(sigma[:, :2, :2]).max() < 1e-3 * abs(expected)
    assert ref.bodies[0].material == material and ref.summary()["bodies"][0]["material"]["model"] == material.model


@pytest.mark.parametrize("material", RUBBERS[1:], ids=IDS[1:])
def test_the_shape_of_one_body_does_not_depend_on_the_scale_of_its_moduli(material):
    arc = {"arc": {"center": [5.0, 9.0], "radius": 10.0, "start_deg": -120.0, "end_deg": -60.0}}
    case = block(target=arc, ratio=0.9)
    material = material.scaled(1.0)  # bulk_to_shear 1e5 kept
    base = solve_reference(case, material=material, mesh_size=0.4)
    scaled = solve_reference(case, material=material.scaled(7.0), mesh_size=0.4)
    np.testing.assert_allclose(scaled.bodies[0].upper, base.bodies[0].upper, atol=1e-8 * 3.0)
    np.testing.assert_allclose(scaled.pressure, 7.0 * base.pressure, atol=1e-6 * np.abs(base.pressure).max())
    assert scaled.strain_energy == pytest.approx(7.0 * base.strain_energy, rel=1e-7)


def test_bulk_modulus_in_mpa_scales_with_the_constants_too():
    """κ given directly (MPa): scaling c10, c20, c30 and κ together by 7 keeps the shape."""
    case = block(stretch=1.1, target={"polyline": [[0.0, 0.0], [4.0, 1.0], [11.0, 0.0]]}, ratio=0.9)
    rubber = Yeoh(0.3, 0.02, 0.001, bulk_modulus=60.0)  # κ / μ₀ = 100
    base = solve_reference(case, material=rubber, mesh_size=0.5)
    same = solve_reference(case, material=rubber.scaled(7.0), mesh_size=0.5)
    np.testing.assert_allclose(same.bodies[0].upper, base.bodies[0].upper, atol=1e-8 * 3.0)
    assert same.bodies[0].material.bulk_modulus == pytest.approx(420.0)


def test_material_from_the_case_format_object():
    case = block(stretch=1.1)
    obj = {"model": "mooney-rivlin", "c10": 0.3, "c01": 0.08, "bulk_to_shear": 2000}
    a = solve_reference(case, material=obj, mesh_size=0.5)
    b = solve_reference(case, material=MooneyRivlin(0.3, 0.08, bulk_to_shear=2000.0), mesh_size=0.5)
    np.testing.assert_array_equal(a.bodies[0].upper, b.bodies[0].upper)
    assert a.bodies[0].bulk_to_shear == pytest.approx(2000.0) and a.bodies[0].material.shear_modulus == pytest.approx(0.76)
    # Without one, the default neo-Hookean rubber of the first version.
    c = solve_reference(case, mesh_size=0.5)
    assert c.bodies[0].material == NeoHookean(1.0, bulk_to_shear=1000.0)


def test_refusals_name_the_field():
    case = block()
    with pytest.raises(sd.CaseError, match=r"material\.bulk_to_shear: the reference is a nearly incompressible"):
        solve_reference(case, material=NeoHookean(1.0, bulk_to_shear=10.0))
    with pytest.raises(sd.CaseError, match=r"material\.c10: must be > 0"):
        solve_reference(case, material={"model": "yeoh", "c10": -1.0, "c20": 0.0, "c30": 0.0})
    with pytest.raises(sd.CaseError, match="material: expected a rubber"):
        solve_reference(case, material=2.0)


def test_each_body_of_several_takes_its_own_material_field_in_errors():
    data = json.loads((CASES_DIR / "v2" / "two-layer-strip.json").read_text())
    data["bodies"][1]["material"] = {"shear_modulus": 1.0, "bulk_to_shear": 10.0}
    with pytest.raises(sd.CaseError, match=r"^bodies\[1\]\.material\.bulk_to_shear: the reference is a nearly") as err:
        solve_reference(case_from_dict(data))
    assert "\n" not in str(err.value)


def test_the_closed_form_neo_hookean_and_the_general_path_agree():
    """The default rubber runs the first version's closed form; Mooney–Rivlin with c01 = 0 is the same rubber, run generally."""
    arc = {"arc": {"center": [5.0, 9.0], "radius": 10.0, "start_deg": -120.0, "end_deg": -60.0}}
    case = block(target=arc, ratio=0.9)
    a = solve_reference(case, material=NeoHookean(1.4, bulk_to_shear=500.0), mesh_size=0.4)
    b = solve_reference(case, material=MooneyRivlin(0.7, 0.0, bulk_to_shear=500.0), mesh_size=0.4)
    np.testing.assert_allclose(a.bodies[0].upper, b.bodies[0].upper, atol=1e-10 * 3.0)
    np.testing.assert_allclose(a.cauchy, b.cauchy, atol=1e-9)
    assert a.iterations == b.iterations
