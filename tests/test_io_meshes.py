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


def test_an_abaqus_mesh_reaches_calculix_as_meant(tmp_path, result):
    """CalculiX reads the first 20 characters of a real only: every coordinate must fit, to 13 digits."""
    for which, mesh in (("final", result.final_mesh), ("initial", result.initial_mesh)):
        path = tmp_path / f"{which}.inp"
        write_mesh(path, result, which)
        lines = path.read_text().splitlines()
        start = next(i for i, line in enumerate(lines) if line.upper().startswith("*NODE"))
        rows = []
        for line in lines[start + 1:]:
            if line.startswith("*"):
                break
            fields = [f.strip() for f in line.split(",")]
            assert all(len(f) <= 20 for f in fields[1:]), line
            rows.append([float(f[:20]) for f in fields[1:3]])  # what CalculiX keeps of each field
        np.testing.assert_allclose(np.array(rows), mesh.points, rtol=1e-12, atol=1e-12 * np.abs(mesh.points).max())
