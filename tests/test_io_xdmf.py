"""XDMF meshes with their fields: one file, read back by meshio, the same cell data as the result's."""

from __future__ import annotations

import json

import numpy as np
import pytest

meshio = pytest.importorskip("meshio")
pytest.importorskip("h5py")  # meshio's XDMF writer imports it even for inline data
pytest.importorskip("skfem")

from sectiondeform.deform import Deformer  # noqa: E402
from sectiondeform.io import write_result  # noqa: E402
from sectiondeform.io.case import case_from_dict  # noqa: E402
from sectiondeform.io.meshes import split_components, write_mesh  # noqa: E402

from conftest import data_case_path  # noqa: E402
from io_helpers import shared_case  # noqa: E402


def _whole(cell_data: dict, name: str) -> np.ndarray:
    return np.concatenate([np.asarray(b) for b in cell_data[name]])


def test_a_hyperelastic_result_in_xdmf_carries_its_stresses_as_the_json_does(tmp_path):
    case = json.loads(data_case_path("paper-example").read_text())
    case["options"] = {**case.get("options", {}), "model": "hyperelastic"}
    result = Deformer(case_from_dict(case)).deform()
    out, xdmf = tmp_path / "r.json", tmp_path / "final.xdmf"
    write_result(out, result, fields=True)
    write_mesh(xdmf, result, "final", fields=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["final.xdmf", "r.json"]  # no HDF5 file beside it
    fields = json.loads(out.read_text())["fields"]
    mesh = meshio.read(xdmf)
    assert mesh.cells[0].type == "triangle6" and len(mesh.cells[0].data) == len(fields["J"])
    for name in ("pressure", "von_mises_stress", "J", "max_principal_strain"):
        np.testing.assert_allclose(_whole(mesh.cell_data, name), fields[name], rtol=1e-12, atol=1e-300)
    # three stretches are a vector, the nine strains a full tensor: both kept whole
    np.testing.assert_allclose(_whole(mesh.cell_data, "principal_stretches"), fields["principal_stretches"], rtol=1e-12)
    assert _whole(mesh.cell_data, "green_lagrange_strain").shape == (len(fields["J"]), 9)
    assert float(np.median(fields["pressure"])) != 0.0  # a field that could differ


def test_an_assemblys_bodies_are_one_block_tagged_by_body_with_each_bodys_fields(tmp_path):
    case = json.loads(data_case_path("v2/two-layer-strip").read_text())
    case["options"] = {**case.get("options", {}), "model": "hyperelastic"}
    result = Deformer(case_from_dict(case)).deform()
    path = tmp_path / "strip.xdmf"
    write_mesh(path, result, "final", fields=True)
    mesh = meshio.read(path)
    assert len(mesh.cells) == 1  # a Mixed topology of quadratic triangles is not readable: one block
    body = _whole(mesh.cell_data, "body")
    bodies = result.to_json(fields=True)["bodies"]
    for k, b in enumerate(bodies, start=1):
        np.testing.assert_allclose(_whole(mesh.cell_data, "pressure")[body == k], b["fields"]["pressure"], rtol=1e-12)
    points = np.concatenate([b.final_mesh.points for b in result.bodies])
    np.testing.assert_allclose(mesh.points[:, :2], points, atol=1e-12)


def test_the_paper_models_two_component_fields_are_split_for_xdmf(tmp_path):
    result = Deformer(shared_case("paper-example")).deform()
    path = tmp_path / "paper.xdmf"
    write_mesh(path, result, "final", fields=True)
    names = set(meshio.read(path).cell_data)
    assert {"layer_stretch_0", "layer_stretch_1"} <= names and "layer_stretch" not in names


def test_split_components_keeps_the_widths_a_format_carries():
    data = {"s": np.zeros(4), "v": np.zeros((4, 3)), "t6": np.zeros((4, 6)), "two": np.ones((4, 2))}
    assert sorted(split_components(data, "xdmf")) == ["s", "t6", "two_0", "two_1", "v"]
    assert sorted(split_components(data, "gmsh")) == ["s", "t6_0", "t6_1", "t6_2", "t6_3", "t6_4", "t6_5", "two_0", "two_1", "v"]
    assert sorted(split_components(data, "vtu")) == sorted(data)
