"""Meshes through meshio: VTU, VTK, MSH, XDMF, INP re-read with numbering kept."""

from __future__ import annotations

import numpy as np
import pytest

meshio = pytest.importorskip("meshio")

from sectiondeform.deform import Deformer  # noqa: E402
from sectiondeform.errors import CaseError  # noqa: E402
from sectiondeform.io import write_result  # noqa: E402
from sectiondeform.io.meshes import write_mesh  # noqa: E402

from io_helpers import shared_case  # noqa: E402


@pytest.fixture(scope="module")
def result():
    return Deformer(shared_case("paper-example")).deform()


@pytest.mark.parametrize("ext", [".vtu", ".vtk", ".msh", ".xdmf", ".inp"])
def test_final_mesh_round_trip(tmp_path, result, ext):
    path = tmp_path / f"final{ext}"
    write_result(path, result)
    mesh = meshio.read(path)
    assert np.allclose(mesh.points[:, :2], result.final_mesh.points, atol=1e-12)
    assert mesh.cells[0].type == "quad"
    assert np.array_equal(mesh.cells[0].data, result.final_mesh.cells)
    if ext != ".inp":
        assert np.allclose(mesh.point_data["initial"][:, :2], result.initial_mesh.points)
        assert np.allclose(mesh.point_data["displacement"][:, :2], result.final_mesh.points - result.initial_mesh.points)


def test_initial_mesh_and_bad_extension(tmp_path, result):
    write_mesh(tmp_path / "initial.vtu", result, "initial")
    mesh = meshio.read(tmp_path / "initial.vtu")
    assert np.allclose(mesh.points[:, :2], result.initial_mesh.points)
    with pytest.raises(CaseError, match="unknown mesh format"):
        write_mesh(tmp_path / "x.stl", result)
    assert not (tmp_path / "x.stl").exists()
