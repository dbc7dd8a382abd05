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
  outside, integrated by ``quad``; of two bonded layers, σr continuous
  across their interface and the pressure jumping there.

Bodies stacked and bonded each have their own pressure field (continuous
within a body, free to jump across the interface), so stacked bodies of
different rubbers in a homogeneous state per body hold it exactly.
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

from sectiondeform.cli import main
from sectiondeform.deform import Deformer
from sectiondeform.errors import CaseError
from sectiondeform.field_plot import field_values
from sectiondeform.io.case import case_from_dict
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
    """Blocks side by side on the support, apart, each with its material and the area law of out-of-plane stretch ``lz``."""
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
    result = Deformer(case_from_dict(side_by_side_case([material], lz))).deform()
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


def stacked_case(materials, stretches):
    """Blocks stacked and bonded on the support, each with its material and the area law of its out-of-plane stretch."""
    bodies = []
    for i, (material, lz) in enumerate(zip(materials, stretches)):
        lower, upper = block(0.0, i * HEIGHT)
        bodies.append({"name": f"layer{i}", "lower": {"polyline": lower}, "upper": {"polyline": upper},
                       "law": {"area_ratio": 1.0 / lz}, "material": material})
    return {"format": "section-case/2", "name": "stack", "units": "mm",
            "support": {"polyline": [[0, 0], [WIDTH, 0]]}, "target": {"polyline": [[0, 0], [LAM * WIDTH, 0]]},
            "bodies": bodies, "options": {"model": "hyperelastic", "newton_tolerance": 1e-10}}


@pytest.mark.parametrize("rubbers", [
    [(0.5, 0.0, 1000.0), (1.5, 0.0, 3000.0)],  # neo-Hookean, shear moduli 1 and 3, same κ/μ: one stretch for both
    [(0.3, 0.12, 500.0), (1.5, 0.0, 6000.0)],  # Mooney–Rivlin under neo-Hookean, other κ/μ: each its own stretch
])
def test_stacked_blocks_of_different_rubbers_hold_each_ones_exact_state_with_the_pressure_jumping_between(rubbers):
    """Each block in its own free state F = diag(λ, λ, λz_b) (σxx = σyy = 0): bonded, the stack is in equilibrium.

    The in-plane stretches agree at the interface and neither block pulls
    on the other, so the exact solution is homogeneous per body; its
    pressure jumps at the interface (in the ratio of the moduli for
    neo-Hookean blocks of one κ/μ). A pressure field continuous across the
    interface cannot hold it (nodes 2.8e-2 of a layer off it, pressures
    0.5–0.9 % off, measured before the pressure was split per body).
    """
    states = [homogeneous(*r) for r in rubbers]
    materials = [{"model": "mooney-rivlin", "c10": c10, "c01": c01, "bulk_to_shear": kappa / (2 * (c10 + c01))}
                 for c10, c01, kappa in rubbers]
    result = Deformer(case_from_dict(stacked_case(materials, [lz for lz, _ in states]))).deform()
    z = result.state.state.z
    interface = []
    for b, (body, data, (lz, sigma)) in enumerate(zip(result.bodies, result.to_json(fields=True)["bodies"], states)):
        X = body.initial_mesh.points
        assert np.abs(body.final_mesh.points - LAM * X).max() <= 1e-9 * HEIGHT  # the homogeneous state, exactly
        np.testing.assert_allclose(data["fields"]["principal_stretches"], np.tile([LAM, LAM, lz], (len(data["fields"]["J"]), 1)), rtol=1e-9)
        pressure, vm = pressure_and_von_mises(sigma)
        np.testing.assert_allclose(data["fields"]["pressure"], pressure, rtol=1e-7)
        np.testing.assert_allclose(data["fields"]["von_mises_stress"], vm, rtol=1e-7)
        # the body's own pressure unknowns at its corners on the interface (the mean stress, −pressure)
        corners = body.initial_mesh.cells[:, :3]
        on = np.abs(X[corners, 1] - HEIGHT) <= 1e-9 * HEIGHT
        assert on.sum() >= 2 * WIDTH / HEIGHT
        dofs = result.state.pressure_dofs[b][on]
        np.testing.assert_allclose(z[dofs], -pressure, rtol=1e-7)
        interface.append((dofs, X[corners[on]], pressure))
    (soft, x_soft, p_soft), (stiff, x_stiff, p_stiff) = interface
    assert not np.intersect1d(soft, stiff).size  # each body its own unknowns at the shared vertices
    assert np.array_equal(np.unique(x_soft, axis=0), np.unique(x_stiff, axis=0))  # ... of the same vertices
    assert abs(p_stiff - p_soft) > 0.1 * abs(p_soft)  # a real jump
    if rubbers[0][1] == 0.0 and rubbers[0][2] / rubbers[0][0] == rubbers[1][2] / rubbers[1][0]:
        assert z[stiff].mean() / z[soft].mean() == pytest.approx(rubbers[1][0] / rubbers[0][0], rel=1e-7)


def test_stacked_blocks_keep_their_exact_state_through_a_warm_start_and_a_preview():
    """From the solved stack, onto the same target: the warm start and the drag preview stay on the exact state.

    The warm start carries the state with each body's pressure unknowns
    (the pressure written is still each body's closed form); the preview
    steps from it with its factorisation.
    """
    lz, sigma = homogeneous(0.5, 0.0, 1000.0)
    pressure = pressure_and_von_mises(sigma)[0]
    deformer = Deformer(case_from_dict(stacked_case([{"shear_modulus": 1.0}, {"shear_modulus": 3.0}], [lz, lz])))
    cold = deformer.deform()
    warm, preview = deformer.deform(start=cold), deformer.preview(start=cold)
    assert warm.bodies[0].info.warm_start and warm.state.state.z.shape == cold.state.state.z.shape
    for result in (warm, preview):
        for body in result.bodies:
            assert np.abs(body.final_mesh.points - LAM * body.initial_mesh.points).max() <= 1e-9 * HEIGHT
    for data, mu in zip(warm.to_json(fields=True)["bodies"], (1.0, 3.0)):
        np.testing.assert_allclose(data["fields"]["pressure"], mu * pressure, rtol=1e-7)


def test_an_assemblys_stress_can_be_plotted_and_the_paper_models_cannot(tmp_path):
    lz, sigma = homogeneous(0.5, 0.0, 1000.0)
    case = side_by_side_case([{"shear_modulus": 1.0}, {"shear_modulus": 3.0}], lz)
    result = Deformer(case_from_dict(case)).deform()
    kind, (soft, stiff) = field_values(result, "pressure")
    assert kind == "mechanical"
    np.testing.assert_allclose(stiff, 3.0 * pressure_and_von_mises(sigma)[0], rtol=1e-7)
    pytest.importorskip("matplotlib")
    src, fig = tmp_path / "blocks.json", tmp_path / "p.png"
    src.write_text(json.dumps(case))
    assert main(["deform", str(src), "-o", str(tmp_path / "r.json"), "--plot", str(fig), "--plot-field", "pressure"]) == 0
    assert fig.stat().st_size > 1000
    paper = Deformer(case_from_dict(case), model="paper").deform()
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
    result = Deformer(case_from_dict(case)).deform()
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
    result = Deformer(case_from_dict(case)).deform()
    mechanics = result_mechanics(result)[0]
    assert mechanics.growth == pytest.approx(v)
    fields = result.to_json(fields=True)["bodies"][0]["fields"]
    np.testing.assert_allclose(fields["J"], v, rtol=1e-8)
    assert np.abs(fields["von_mises_stress"]).max() < 1e-7 and np.abs(fields["pressure"]).max() < 1e-7


def test_two_stacked_rings_of_different_rubbers_grown_alike_are_stress_free():
    """Two blocks of revolution, bonded, of different rubbers, both grown by v: the homothety about the axis, exactly."""
    radius, w, h, v = 20.0, 6.0, 3.0, 1.2
    g = v ** (1.0 / 3.0)
    rubbers = [{"shear_modulus": 1.0}, {"model": "yeoh", "c10": 1.5, "c20": -0.05, "c30": 0.01, "bulk_to_shear": 300.0}]
    bodies = []
    for i, material in enumerate(rubbers):
        y0, y1 = radius + i * h, radius + (i + 1) * h
        bodies.append({"name": f"ring{i}", "lower": {"polyline": [[0, y0], [w, y0]]},
                       "upper": {"polyline": [[w, y0], [w, y1], [0, y1], [0, y0]]},
                       "law": {"volume_ratio": v}, "material": material})
    case = {"format": "section-case/2", "name": "grow", "support": {"polyline": [[0, radius], [w, radius]]},
            "target": {"polyline": [[0, g * radius], [g * w, g * radius]]}, "revolution": {"axis": [[0, 0], [1, 0]]},
            "bodies": bodies, "options": {"model": "hyperelastic", "newton_tolerance": 1e-10}}
    result = Deformer(case_from_dict(case)).deform()
    for body, data in zip(result.bodies, result.to_json(fields=True)["bodies"]):
        assert np.abs(body.final_mesh.points - g * body.initial_mesh.points).max() <= 1e-9 * h
        np.testing.assert_allclose(data["fields"]["J"], v, rtol=1e-8)
        assert np.abs(data["fields"]["von_mises_stress"]).max() < 1e-7 and np.abs(data["fields"]["pressure"]).max() < 1e-7


def two_layer_ring_case(moduli, length, through):
    """The thick ring of ``ring_case`` split at mid-wall into two bonded layers of neo-Hookean shear ``moduli``."""
    mid = A + T / 2
    case = ring_case(1.0, length=length, through=through)
    layers = []
    for i, (y0, y1) in enumerate(((A, mid), (mid, A + T))):
        top = [[x, y1] for x in np.linspace(length, 0.0, 13)]
        layers.append({"name": f"layer{i}", "lower": {"polyline": [[0.0, y0], [length, y0]]},
                       "upper": {"polyline": [[length, y0]] + top + [[0.0, y0]]}, "law": {"volume_ratio": 1.0},
                       "material": {"shear_modulus": moduli[i], "bulk_to_shear": 1e5}})
    case["bodies"] = layers
    return case


def two_layer_ring_pressure_errors(moduli=(1.0, 3.0), length=48 * T, through=2.0, medians=None):
    """Per layer of ``two_layer_ring_case``, the largest pressure error within one wall of the middle over the largest pressure.

    ``medians``, a list, receives each layer's median exact pressure there.
    """
    result = Deformer(case_from_dict(two_layer_ring_case(moduli, length, through))).deform()
    outer = math.sqrt(GROW**2 + (A + T) ** 2 - A**2)
    r_mid = math.sqrt(GROW**2 + (A + T / 2) ** 2 - A**2)

    def hoop(rho):  # λθ at the current radius rho: r² − a² = R² − A²
        return rho / math.sqrt(rho * rho - GROW**2 + A**2)

    def term(rho, mu):
        return mu * (hoop(rho) ** 2 - hoop(rho) ** -2) / rho

    def radial(r):  # σr at the current radius r, zero outside, continuous across the interface
        if r >= r_mid:
            return -quad(term, r, outer, args=(moduli[1],))[0]
        return -quad(term, r, r_mid, args=(moduli[0],))[0] - quad(term, r_mid, outer, args=(moduli[1],))[0]

    errors, exact = [], []
    for body, mechanics, mu in zip(result.bodies, result_mechanics(result), moduli):
        fields = result_fields(body.initial_mesh, body.final_mesh, "hyperelastic", 1.0, result.axis, mechanics)[1]
        X = element_centres(body.initial_mesh)
        mid = np.abs(X[:, 0] - length / 2) <= T
        expected = []
        for R in X[mid, 1]:
            r = math.sqrt(GROW**2 + R * R - A * A)
            lt, lr = r / R, R / r
            sr = radial(r)
            expected.append(-np.mean([sr, sr + mu * (lt * lt - lr * lr), sr + mu * (1.0 - lr * lr)]))
        expected = np.array(expected)
        errors.append(np.abs(fields["pressure"][mid] - expected).max())
        exact.append(expected)
    scale = max(np.abs(e).max() for e in exact)
    if medians is not None:
        medians.extend(float(np.median(e)) for e in exact)
    return [e / scale for e in errors]


def test_a_thick_ring_of_two_bonded_layers_has_the_closed_form_pressure_jumping_at_their_interface():
    """A soft inner layer (μ = 1) under a stiff outer one (μ = 3), expanded radially, incompressible.

    σr is continuous across the interface, σθ − σr = μ (λθ² − λr²) and
    σz − σr = μ (1 − λr²) jump with μ: the pressure jumps (by about 6.5×
    here). Far from the free ends (within one wall of the middle of a ring
    48 walls long: a stiff shell on a soft layer feels its ends further
    than one material does), 2 elements through each layer. Measured:
    within 1.2e-4 of the largest pressure in both layers, next to the
    interface too; a pressure continuous across the interface misses by
    0.15 (inner) and 0.34 (outer).
    """
    medians = []
    errors = two_layer_ring_pressure_errors(medians=medians)
    assert medians[1] / medians[0] > 5.0  # the exact pressure jumps at the interface
    assert max(errors) < 5e-4
