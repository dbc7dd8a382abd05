"""Strain fields per element (principal stretches, J, Green-Lagrange strain) in meshes read back with meshio.

Every expected value is worked out by hand for a homogeneous deformation:
the paper model stretching a rectangle along a flat target (stretch lam along
the layers, r / lam across them, out of plane 1), an affine map of the
hyperelastic model's P2 mesh (F = Q diag(a, b), out of plane its lambda_z),
and a rectangle of revolution moved away from its axis (hoop stretch r / R).
"""

import dataclasses
import json
import math

import meshio
import numpy as np
import pytest

from sectiondeform.cli import main
from sectiondeform.deform import Deformer, deform
from sectiondeform.io.case import case_from_dict
from sectiondeform.io.meshes import write_mesh
from sectiondeform.models.base import MeshData
from sectiondeform.strain_fields import element_gradients

LAM, RATIO = 1.25, 0.8
WIDTH, HEIGHT = 10.0, 2.0


def stretch_case(model="paper"):
    return {
        "format": "section-case/1",
        "lower": {"polyline": [[0, 0], [WIDTH, 0]]},
        "upper": {"polyline": [[WIDTH, 0], [WIDTH, HEIGHT], [0, HEIGHT], [0, 0]]},
        "target": {"polyline": [[0, 0], [LAM * WIDTH, 0]]},
        "law": {"area_ratio": RATIO},
        "options": {"model": model},
    }


def cell(mesh, name):
    return mesh.cell_data[name][0]


def test_the_paper_models_homogeneous_stretch_gives_the_exact_geometric_strains_in_vtu(tmp_path):
    result = Deformer(case_from_dict(stretch_case())).deform()
    path = tmp_path / "final.vtu"
    write_mesh(path, result, "final", fields=True)
    mesh = meshio.read(path)
    m = len(result.final_mesh.cells)
    k = RATIO / LAM  # the height scale: the columns stay straight
    np.testing.assert_allclose(cell(mesh, "geometric_principal_stretches"), np.tile([LAM, 1.0, k], (m, 1)), rtol=1e-12)
    np.testing.assert_allclose(cell(mesh, "geometric_J"), RATIO, rtol=1e-12)
    green = np.diag([(LAM**2 - 1) / 2, (k**2 - 1) / 2, 0.0]).ravel()
    np.testing.assert_allclose(cell(mesh, "geometric_green_lagrange_strain"), np.tile(green, (m, 1)), atol=1e-12)
    np.testing.assert_allclose(cell(mesh, "geometric_max_principal_strain"), LAM - 1.0, rtol=1e-12)
    assert "J" not in mesh.cell_data  # the paper model's strains are never written as mechanical ones


def test_an_affine_map_of_the_hyperelastic_mesh_gives_its_stretches_and_j_in_vtu(tmp_path):
    result = Deformer(case_from_dict(stretch_case("hyperelastic"))).deform()
    lz = result.info.out_of_plane_stretch
    assert lz == pytest.approx(1 / RATIO)
    a, b, turn = 1.3, 0.7, 0.4
    q = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
    affine = q @ np.diag([a, b])
    moved = MeshData(result.initial_mesh.points @ affine.T + [3.0, -1.0], result.initial_mesh.cells, "triangle6")
    path = tmp_path / "affine.vtu"
    body = dataclasses.replace(result.only(), final_mesh=moved)
    write_mesh(path, dataclasses.replace(result, bodies=(body,)), "final", fields=True)
    mesh = meshio.read(path)
    m = len(result.initial_mesh.cells)
    np.testing.assert_allclose(cell(mesh, "principal_stretches"), np.tile(sorted([a, b, lz], reverse=True), (m, 1)),
                               rtol=1e-10)
    np.testing.assert_allclose(cell(mesh, "J"), a * b * lz, rtol=1e-10)
    green = np.diag([(a * a - 1) / 2, (b * b - 1) / 2, (lz * lz - 1) / 2]).ravel()  # Q drops out of F^T F
    np.testing.assert_allclose(cell(mesh, "green_lagrange_strain"), np.tile(green, (m, 1)), atol=1e-10)
    np.testing.assert_allclose(cell(mesh, "max_principal_strain"), max(a, b, lz) - 1, rtol=1e-10)
    # neo-Hookean, shear modulus 1: deviatoric Cauchy stress J^(-5/3) dev(B), B with eigenvalues a^2, b^2, lz^2
    squares = np.array([a * a, b * b, lz * lz])
    dev = squares - squares.mean()
    vm = (a * b * lz) ** (-5 / 3) * math.sqrt(1.5 * np.sum(dev**2))
    np.testing.assert_allclose(cell(mesh, "von_mises_stress"), vm, rtol=1e-9)


def test_the_hyperelastic_solution_is_nearly_incompressible_and_labelled_mechanical(tmp_path):
    case = tmp_path / "case.json"
    case.write_text(json.dumps(stretch_case("hyperelastic")))
    out = tmp_path / "r.json"
    assert main(["deform", str(case), "-o", str(out), "--fields", "--no-meshes"]) == 0
    fields = json.loads(out.read_text())["fields"]
    assert fields["kind"] == "mechanical" and fields["location"] == "cell"
    # bulk modulus 1000 x the shear modulus: J within 1 % of 1 in nearly every element; only the
    # elements at the ends of the bonded edge (stress singularities of the coarse mesh) reach a few %
    off = np.abs(np.asarray(fields["J"]) - 1.0)
    assert np.median(off) < 0.01 and np.quantile(off, 0.95) < 0.01 and off.max() < 0.1
    assert not any(name.startswith("geometric") for name in fields)


def test_the_hoop_stretch_of_a_rectangle_moved_away_from_its_axis():
    """A w x h rectangle at distance R from the axis y = 0, moved rigidly to R + s with volume ratio 1:
    heights k h by Pappus (a quadratic solved by hand); an element centred at height Y goes to
    R + s + k (Y - R): F = diag(1, k, (R + s + k (Y - R)) / Y).
    """
    w, h, radius, shift = 10.0, 2.0, 50.0, 5.0
    case = {
        "format": "section-case/2",
        "support": {"polyline": [[0, radius], [w, radius]]},
        "target": {"polyline": [[0, radius + shift], [w, radius + shift]]},
        "revolution": {"axis": [[0, 0], [1, 0]]},
        "bodies": [{"name": "ring", "lower": {"polyline": [[0, radius], [w, radius]]},
                    "upper": {"polyline": [[w, radius], [w, radius + h], [0, radius + h], [0, radius]]},
                    "law": {"volume_ratio": 1.0}}],
    }
    data = deform(case_from_dict(case)).to_json(fields=True)
    body = data["bodies"][0]
    r1 = radius + shift
    k = (-r1 + math.sqrt(r1**2 + 2 * h * (radius + h / 2))) / h
    initial = body["meshes"]["initial"]
    y = np.asarray(initial["points"])[np.asarray(initial["cells"])][:, :, 1].mean(axis=1)
    y = y[y < radius + h]  # elements inside the body (the layered mesh may reach beyond it)
    hoop = (r1 + k * (y - radius)) / y
    fields = body["fields"]
    assert fields["kind"] == "geometric"
    stretches = np.asarray(fields["geometric_principal_stretches"])[: len(y)]
    np.testing.assert_allclose(np.sort(stretches, axis=1), np.sort(np.column_stack((np.ones_like(y), np.full_like(y, k),
                                                                                    hoop)), axis=1), rtol=1e-9)
    np.testing.assert_allclose(np.asarray(fields["geometric_J"])[: len(y)], k * hoop, rtol=1e-9)


def test_gmsh_files_take_the_fields_split_into_components(tmp_path):
    result = Deformer(case_from_dict(stretch_case())).deform()
    path = tmp_path / "final.msh"
    write_mesh(path, result, "final", fields=True)
    mesh = meshio.read(path)
    assert {"corner_jacobians_0", "corner_jacobians_3", "layer_stretch_1"} <= set(mesh.cell_data)
    np.testing.assert_allclose(cell(mesh, "layer_stretch_0"), LAM, rtol=1e-12)
    assert cell(mesh, "geometric_green_lagrange_strain").shape[1] == 9


def test_element_gradients_of_linear_triangles_and_quads_are_exact_for_affine_maps():
    rng = np.random.default_rng(3)
    pts = rng.uniform(0, 1, (4, 2)) + [[0, 0], [2, 0], [2, 2], [0, 2]]
    affine = np.array([[1.2, 0.3], [-0.1, 0.9]])
    for kind, cells in (("quad", np.array([[0, 1, 2, 3]])), ("triangle", np.array([[0, 1, 2], [0, 2, 3]]))):
        f = element_gradients(MeshData(pts, cells, kind), MeshData(pts @ affine.T, cells, kind))
        np.testing.assert_allclose(f, np.broadcast_to(affine, f.shape), rtol=1e-12)


def test_an_assemblys_bodies_carry_the_stresses_of_their_own_rubbers(tmp_path):
    # the two-layer strip: backing shear modulus 3, cover 1 (MPa). Neo-Hookean von Mises stress from the
    # written principal stretches alone: mu J^(-5/3) sqrt(3/2 |dev(lambda^2)|^2)
    from pathlib import Path

    strip = json.loads((Path(__file__).parent / "data" / "cases" / "v2" / "two-layer-strip.json").read_text())
    result = deform(case_from_dict(strip), model="hyperelastic")
    for body, mu in zip(result.to_json(fields=True)["bodies"], (3.0, 1.0)):
        fields = body["fields"]
        assert fields["kind"] == "mechanical" and "MPa" in fields["note"]
        lam = np.asarray(fields["principal_stretches"])
        squares = lam**2
        dev = squares - squares.mean(axis=1, keepdims=True)
        vm = mu * np.prod(lam, axis=1) ** (-5 / 3) * np.sqrt(1.5 * np.sum(dev**2, axis=1))
        np.testing.assert_allclose(fields["von_mises_stress"], vm, rtol=1e-9)
        assert len(fields["pressure"]) == len(vm) and np.all(np.isfinite(fields["pressure"]))
