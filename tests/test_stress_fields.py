"""The hyperelastic model's stresses per element: von Mises stress and pressure, against closed forms.

Every expected value is derived here by hand, independently of the code's
materials (which go through the invariants' derivatives):

* a block stretched equibiaxially in its plane, F = diag(λ, λ, λz): its
  lower edge bonded to a target λ times as long, the law's out-of-plane
  stretch λz chosen so that the nearly incompressible solution is exactly
  homogeneous (σxx = σyy = 0 and the mixed constraint J − 1 = p / κ, a
  scalar equation solved by ``brentq``). Principal Cauchy stresses of an
  isotropic rubber W(Ī₁, Ī₂): the deviator of 2/J [(W₁ + Ī₁ W₂) b̄ − W₂ b̄²]
  (b̄ = J^(-2/3) λᵢ²) plus the mean stress;
* a thick ring of revolution expanded radially (incompressible, no axial
  motion far from its ends): σθ − σr = 2 (λθ² − λr²)(W₁ + λz² W₂) and
  σz − σr = 2 (λz² − λr²)(W₁ + λθ² W₂), dσr/dr = (σθ − σr) / r, σr = 0
  outside, integrated by ``quad``.
"""

from __future__ import annotations

import json
import math

import meshio
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from test_hyperelastic_revolution import GROW, A, T, ring_case

from sectiondeform.assembly import assembly_from_dict
from sectiondeform.assembly_deform import AssemblyDeformer
from sectiondeform.case import case_from_dict
from sectiondeform.cli import main
from sectiondeform.deform import Deformer
from sectiondeform.errors import CaseError
from sectiondeform.field_plot import field_values
from sectiondeform.io.meshes import write_mesh
from sectiondeform.strain_fields import STRESS_NOTES, element_centres, result_fields, result_mechanics

LAM, WIDTH, HEIGHT = 1.2, 10.0, 2.0


def principal_cauchy(stretches, c10, c01, mean):
    """Principal Cauchy stresses of W = c10 (Ī₁ − 3) + c01 (Ī₂ − 3) with the mean stress ``mean``."""
    lam = np.asarray(stretches, dtype=np.float64)
    J = float(np.prod(lam))
    b = J ** (-2.0 / 3.0) * lam * lam
    i1 = b.sum()
    s = 2.0 / J * ((c10 + c01 * i1) * b - c01 * b * b)
    return s - s.mean() + mean


def homogeneous(c10, c01, kappa):
    """(λz, principal stresses) of the block's homogeneous state: σxx = σyy = 0, J − 1 = mean / κ."""
    def constraint(lz):
        mean = -principal_cauchy((LAM, LAM, lz), c10, c01, 0.0)[0]  # σxx = 0
        return LAM * LAM * lz - 1.0 - mean / kappa

    lz = brentq(constraint, 0.3, 1.5, xtol=1e-15)
    mean = -principal_cauchy((LAM, LAM, lz), c10, c01, 0.0)[0]
    return lz, principal_cauchy((LAM, LAM, lz), c10, c01, mean)


def pressure_and_von_mises(sigma):
    s = sigma - sigma.mean()
    return -sigma.mean(), math.sqrt(1.5 * float(s @ s))


def block(x0=0.0, y0=0.0):
    return ([[x0, y0], [x0 + WIDTH, y0]],
            [[x0 + WIDTH, y0], [x0 + WIDTH, y0 + HEIGHT], [x0, y0 + HEIGHT], [x0, y0]])


def one_body_case(lz):
    lower, upper = block()
    return {"format": "section-case/1", "name": "block", "lower": {"polyline": lower}, "upper": {"polyline": upper},
            "target": {"polyline": [[0, 0], [LAM * WIDTH, 0]]}, "law": {"area_ratio": 1.0 / lz},
            "options": {"model": "hyperelastic", "newton_tolerance": 1e-10}}


def side_by_side_case(materials, lz, gap=2.0):
    """Blocks side by side on the support, apart, each with its material and the area law of out-of-plane stretch ``lz``.

    Apart, not bonded to each other: the coarse model's pressure field is
    continuous across a bonded interface, so two bonded bodies of different
    moduli cannot hold the exact homogeneous state (whose pressure jumps
    there; see docs/hyperelastic.md).
    """
    bodies = []
    for i, material in enumerate(materials):
        lower, upper = block(i * (WIDTH + gap), 0.0)
        bodies.append({"name": f"block{i}", "lower": {"polyline": lower}, "upper": {"polyline": upper},
                       "law": {"area_ratio": 1.0 / lz}, "material": material})
    length = len(materials) * (WIDTH + gap) - gap
    return {"format": "section-case/2", "name": "blocks", "units": "mm",
            "support": {"polyline": [[0, 0], [length, 0]]}, "target": {"polyline": [[0, 0], [LAM * length, 0]]},
            "bodies": bodies, "options": {"model": "hyperelastic", "newton_tolerance": 1e-10}}


# --- one body, relative modulus ------------------------------------------------------------------


def test_a_homogeneous_equibiaxial_block_has_the_hand_pressure_and_von_mises_in_json_and_vtu(tmp_path):
    lz, sigma = homogeneous(0.5, 0.0, 1000.0)  # the model's rubber: shear modulus 1, bulk 1000
    assert sigma[0] == pytest.approx(0.0, abs=1e-15) and sigma[2] < 0  # squeezed out of the plane: compressed
    pressure, vm = pressure_and_von_mises(sigma)
    assert pressure > 0 and vm == pytest.approx(abs(sigma[2]), rel=1e-12)  # positive in compression
    src = tmp_path / "case.json"
    src.write_text(json.dumps(one_body_case(lz)))
    out, vtu = tmp_path / "r.json", tmp_path / "final.vtu"
    assert main(["deform", str(src), "-o", str(out), "--fields", "--mesh-out", str(vtu)]) == 0
    fields = json.loads(out.read_text())["fields"]
    assert fields["kind"] == "mechanical" and fields["note"] == STRESS_NOTES[True] and "shear modulus" in fields["note"]
    np.testing.assert_allclose(fields["principal_stretches"], np.tile([LAM, LAM, lz], (len(fields["J"]), 1)), rtol=1e-9)
    np.testing.assert_allclose(fields["pressure"], pressure, rtol=1e-7)
    np.testing.assert_allclose(fields["von_mises_stress"], vm, rtol=1e-7)
    mesh = meshio.read(vtu)
    np.testing.assert_allclose(mesh.cell_data["pressure"][0], pressure, rtol=1e-7)
    np.testing.assert_allclose(mesh.cell_data["von_mises_stress"][0], vm, rtol=1e-7)


def test_the_pressure_is_the_solutions_field_not_kappa_times_j_minus_one():
    """With a soft bulk modulus both agree to the constraint's own form; the field is what is written."""
    lz, sigma = homogeneous(0.5, 0.0, 20.0)
    case = one_body_case(lz)
    case["options"]["bulk_to_shear"] = 20.0
    result = Deformer(case_from_dict(case)).deform()
    mechanics = result_mechanics(result)[0]
    assert mechanics.relative and mechanics.material.shear_modulus == 1.0
    fields = result_fields(result.initial_mesh, result.final_mesh, "hyperelastic", lz, mechanics=mechanics)[1]
    np.testing.assert_allclose(fields["pressure"], pressure_and_von_mises(sigma)[0], rtol=1e-7)
    np.testing.assert_allclose(fields["pressure"], -20.0 * (fields["J"] - 1.0), rtol=1e-7)  # J − 1 = p / κ here


def test_a_drag_preview_has_strains_but_no_pressure():
    lz, _ = homogeneous(0.5, 0.0, 1000.0)
    deformer = Deformer(case_from_dict(one_body_case(lz)))
    solved = deformer.deform()
    preview = deformer.preview(start=solved) if hasattr(deformer, "preview") else None
    if preview is None:
        pytest.skip("no preview on this deformer")
    fields = preview.to_json(fields=True)["fields"]
    assert "J" in fields and "pressure" not in fields
    with pytest.raises(CaseError, match=r"^--plot-field: no pressure for a drag preview"):
        field_values(preview, "pressure")


# --- assemblies: each body's rubber, in its unit --------------------------------------------------


def test_a_mooney_rivlin_body_has_the_hand_stresses_in_its_units_in_json_and_vtu(tmp_path):
    c10, c01 = 0.3, 0.12  # MPa
    kappa = 1000.0 * 2.0 * (c10 + c01)
    lz, sigma = homogeneous(c10, c01, kappa)
    pressure, vm = pressure_and_von_mises(sigma)
    material = {"model": "mooney-rivlin", "c10": c10, "c01": c01}
    result = AssemblyDeformer(assembly_from_dict(side_by_side_case([material], lz))).deform()
    body = result.to_json(fields=True)["bodies"][0]
    assert body["fields"]["note"] == STRESS_NOTES[False]
    np.testing.assert_allclose(body["fields"]["principal_stretches"][0], [LAM, LAM, lz], rtol=1e-9)
    np.testing.assert_allclose(body["fields"]["pressure"], pressure, rtol=1e-7)
    np.testing.assert_allclose(body["fields"]["von_mises_stress"], vm, rtol=1e-7)
    # not the neo-Hookean rubber of the same initial shear modulus: the test tells them apart
    nh_pressure, nh_vm = pressure_and_von_mises(homogeneous(c10 + c01, 0.0, kappa)[1])
    assert abs(nh_vm - vm) > 1e-3 * vm
    path = tmp_path / "stack.vtu"
    write_mesh(path, result, "final", fields=True)
    mesh = meshio.read(path)
    np.testing.assert_allclose(mesh.cell_data["pressure"][0], pressure, rtol=1e-7)
    np.testing.assert_allclose(mesh.cell_data["von_mises_stress"][0], vm, rtol=1e-7)


def test_two_bodies_of_different_moduli_carry_stresses_in_their_ratio(tmp_path):
    """Both homogeneous with the same stretches (same bulk-to-shear ratio): stresses scale with the modulus."""
    lz, sigma = homogeneous(0.5, 0.0, 1000.0)
    pressure, vm = pressure_and_von_mises(sigma)
    src = tmp_path / "blocks.json"
    src.write_text(json.dumps(side_by_side_case([{"shear_modulus": 1.0}, {"shear_modulus": 3.0}], lz)))
    out, vtu = tmp_path / "r.json", tmp_path / "r.vtu"
    assert main(["deform", str(src), "-o", str(out), "--fields", "--mesh-out", str(vtu)]) == 0
    soft, stiff = (b["fields"] for b in json.loads(out.read_text())["bodies"])
    for fields, mu in ((soft, 1.0), (stiff, 3.0)):
        np.testing.assert_allclose(fields["pressure"], mu * pressure, rtol=1e-7)
        np.testing.assert_allclose(fields["von_mises_stress"], mu * vm, rtol=1e-7)
    assert np.median(stiff["pressure"]) / np.median(soft["pressure"]) == pytest.approx(3.0, rel=1e-7)
    mesh = meshio.read(vtu)  # each body's cells tagged with its number (meshio reads the blocks back as one)
    body = np.concatenate(mesh.cell_data["body"])
    written = np.concatenate(mesh.cell_data["pressure"])
    assert [(body == k).sum() for k in (1, 2)] == [len(soft["J"]), len(stiff["J"])]
    np.testing.assert_allclose(written[body == 1], pressure, rtol=1e-7)
    np.testing.assert_allclose(written[body == 2], 3.0 * pressure, rtol=1e-7)


def test_an_assemblys_stress_can_be_plotted_and_the_paper_models_cannot(tmp_path):
    lz, sigma = homogeneous(0.5, 0.0, 1000.0)
    case = side_by_side_case([{"shear_modulus": 1.0}, {"shear_modulus": 3.0}], lz)
    result = AssemblyDeformer(assembly_from_dict(case)).deform()
    kind, (soft, stiff) = field_values(result, "pressure")
    assert kind == "mechanical"
    np.testing.assert_allclose(stiff, 3.0 * pressure_and_von_mises(sigma)[0], rtol=1e-7)
    pytest.importorskip("matplotlib")
    src, fig = tmp_path / "blocks.json", tmp_path / "p.png"
    src.write_text(json.dumps(case))
    assert main(["deform", str(src), "-o", str(tmp_path / "r.json"), "--plot", str(fig), "--plot-field", "pressure"]) == 0
    assert fig.stat().st_size > 1000
    paper = AssemblyDeformer(assembly_from_dict(case), model="paper").deform()
    with pytest.raises(CaseError, match=r"^--plot-field: pressure is a stress and the paper model has no material"):
        field_values(paper, "pressure")


# --- bodies of revolution -------------------------------------------------------------------------


@pytest.mark.parametrize("material, c10, c01", [
    ({"shear_modulus": 1.0, "bulk_to_shear": 1e5}, 0.5, 0.0),
    ({"model": "mooney-rivlin", "c10": 0.3, "c01": 0.2, "bulk_to_shear": 1e5}, 0.3, 0.2),
])
def test_a_thick_ring_expanded_radially_has_the_closed_form_pressure_and_von_mises(material, c10, c01):
    """Far from the free ends (within one wall of the middle of a ring 24 walls long), incompressible, v = 1.

    Measured: pressure within 3e-4 (neo-Hookean) and 6e-4 (Mooney–Rivlin)
    of its largest value, von Mises within 7e-4, at 4 elements through the wall.
    """
    case = ring_case(1.0)
    case["bodies"][0]["material"] = material
    length = 24 * T
    result = AssemblyDeformer(assembly_from_dict(case)).deform()
    body, mechanics = result.bodies[0], result_mechanics(result)[0]
    assert mechanics.growth == 1.0 and not mechanics.relative
    fields = result_fields(body.initial_mesh, body.final_mesh, "hyperelastic", 1.0, result.axis, mechanics)[1]
    X = element_centres(body.initial_mesh)
    mid = np.abs(X[:, 0] - length / 2) <= T
    outer = math.sqrt(GROW**2 + (A + T) ** 2 - A**2)

    def hoop(rho):  # λθ at the current radius rho: r² − a² = R² − A²
        return rho / math.sqrt(rho * rho - GROW**2 + A**2)

    expected = []
    for R in X[mid, 1]:
        r = math.sqrt(GROW**2 + R * R - A * A)
        lt, lr = r / R, R / r
        sr = -quad(lambda rho: 2.0 * (hoop(rho) ** 2 - hoop(rho) ** -2) * (c10 + c01) / rho, r, outer)[0]
        sigma = np.array([sr, sr + 2.0 * (lt * lt - lr * lr) * (c10 + c01), sr + 2.0 * (1.0 - lr * lr) * (c10 + c01 * lt * lt)])
        expected.append(pressure_and_von_mises(sigma))
    expected = np.array(expected)
    scale = np.abs(expected).max(axis=0)
    assert np.abs(fields["pressure"][mid] - expected[:, 0]).max() < 2e-3 * scale[0]
    assert np.abs(fields["von_mises_stress"][mid] - expected[:, 1]).max() < 2e-3 * scale[1]
    assert (fields["pressure"][mid] < 0).all()  # stretched around its hoop: tension, a negative pressure


def test_a_grown_body_of_revolution_is_stress_free():
    """A free block of revolution grown by v about the axis (a homothety from a point of it): no stress."""
    radius, w, h, v = 20.0, 6.0, 3.0, 1.2
    g = v ** (1.0 / 3.0)
    upper = [[w, radius], [w, radius + h], [0, radius + h], [0, radius]]
    case = {"format": "section-case/2", "name": "grow", "support": {"polyline": [[0, radius], [w, radius]]},
            "target": {"polyline": [[0, g * radius], [g * w, g * radius]]}, "revolution": {"axis": [[0, 0], [1, 0]]},
            "bodies": [{"name": "b", "lower": {"polyline": [[0, radius], [w, radius]]}, "upper": {"polyline": upper},
                        "law": {"volume_ratio": v}, "material": {"model": "yeoh", "c10": 0.4, "c20": -0.01, "c30": 0.002}}],
            "options": {"model": "hyperelastic", "newton_tolerance": 1e-10}}
    result = AssemblyDeformer(assembly_from_dict(case)).deform()
    mechanics = result_mechanics(result)[0]
    assert mechanics.growth == pytest.approx(v)
    fields = result.to_json(fields=True)["bodies"][0]["fields"]
    np.testing.assert_allclose(fields["J"], v, rtol=1e-8)
    assert np.abs(fields["von_mises_stress"]).max() < 1e-7 and np.abs(fields["pressure"]).max() < 1e-7
