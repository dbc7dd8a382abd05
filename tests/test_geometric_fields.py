"""The paper model's geometric fields: per element, in the result JSON and in VTU files read back by meshio.

On a homogeneous stretch the fields are known by hand: a rectangle on a flat
support whose target is the support stretched by ``lam``, under the area
ratio ``r``, keeps its columns straight and scales its height by
``k = r / lam``; every element is stretched by ``lam`` along the layers and
``k`` up the columns, its corner Jacobians by ``r``.
"""

import json

import meshio
import numpy as np
import pytest

from sectiondeform.cli import main
from sectiondeform.deform import Deformer
from sectiondeform.errors import CaseError
from sectiondeform.io.case import case_from_dict
from sectiondeform.io.meshes import to_meshio, write_mesh

LAM, RATIO = 1.25, 0.8
WIDTH, HEIGHT = 10.0, 2.0


def stretch_case():
    return {
        "format": "section-case/1",
        "lower": {"polyline": [[0, 0], [WIDTH, 0]]},
        "upper": {"polyline": [[WIDTH, 0], [WIDTH, HEIGHT], [0, HEIGHT], [0, 0]]},
        "target": {"polyline": [[0, 0], [LAM * WIDTH, 0]]},
        "law": {"area_ratio": RATIO},
    }


@pytest.fixture(scope="module")
def result():
    return Deformer(case_from_dict(stretch_case())).deform()


def test_the_fields_of_a_homogeneous_stretch_in_a_vtu_file_match_the_hand_calculation(result, tmp_path):
    path = tmp_path / "final.vtu"
    write_mesh(path, result, "final", fields=True)
    mesh = meshio.read(path)
    m = len(result.final_mesh.cells)
    layer, height = mesh.cell_data["layer_stretch"][0], mesh.cell_data["height_stretch"][0]
    ratio, jac = mesh.cell_data["corner_jacobian_ratio"][0], mesh.cell_data["corner_jacobians"][0]
    assert layer.shape == (m, 2) and ratio.shape == (m, 4)
    np.testing.assert_allclose(layer, LAM, rtol=1e-12)
    np.testing.assert_allclose(height, RATIO / LAM, rtol=1e-12)
    np.testing.assert_allclose(ratio, RATIO, rtol=1e-12)
    # a corner Jacobian of a rectangle is its area: initial width x height of the element, times r
    p = result.initial_mesh.points[result.initial_mesh.cells[0]]
    w0, h0 = np.ptp(p[:, 0]), np.ptp(p[:, 1])
    assert jac[0] == pytest.approx([RATIO * w0 * h0] * 4, rel=1e-12)


def test_the_fields_are_in_the_result_json_only_when_asked(result):
    assert "fields" not in result.to_json(meshes=False)
    fields = result.to_json(meshes=False, fields=True)["fields"]
    assert fields["kind"] == "geometric" and fields["location"] == "cell" and "not mechanical" in fields["note"]
    assert np.allclose(fields["layer_stretch"], LAM)


def test_the_cli_writes_the_fields_to_json_and_meshes(tmp_path):
    case = tmp_path / "case.json"
    case.write_text(json.dumps(stretch_case()))
    out, vtu = tmp_path / "r.json", tmp_path / "m.vtu"
    assert main(["deform", str(case), "-o", str(out), "--fields", "--mesh-out", str(vtu)]) == 0
    assert np.allclose(json.loads(out.read_text())["fields"]["height_stretch"], RATIO / LAM)
    assert np.allclose(meshio.read(vtu).cell_data["corner_jacobian_ratio"][0], RATIO)
    assert main(["deform", str(case), "-o", str(out)]) == 0
    assert "fields" not in json.loads(out.read_text())


def test_extra_mesh_data_must_have_one_row_per_node_or_element(result):
    m, n = len(result.final_mesh.cells), len(result.final_mesh.points)
    mesh = to_meshio(result, point_data={"t": np.arange(n, dtype=float)}, cell_data={"s": np.ones((m, 3))})
    assert mesh.cell_data["s"][0].shape == (m, 3) and mesh.point_data["t"].shape == (n,)
    with pytest.raises(CaseError, match=r"^s: expected one row per element"):
        to_meshio(result, cell_data={"s": np.ones(m + 1)})
