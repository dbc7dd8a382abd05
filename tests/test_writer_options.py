"""Result writers take only their own keywords: a misspelt or foreign option is an error, nothing is written."""

from __future__ import annotations

import pytest

import sectiondeform as sd
from sectiondeform.errors import CaseError
from sectiondeform.io import write_result


@pytest.fixture(scope="module")
def result():
    return sd.Deformer(sd.load_case(sd.example_case_path())).deform()


@pytest.mark.parametrize(("ext", "key"), [(".svg", "spline"), (".svg", "meshes"), (".dxf", "splin"), (".json", "mesh"), (".vtu", "meshes")])
def test_unknown_writer_option_is_refused_and_nothing_written(tmp_path, result, ext, key):
    if ext in (".dxf", ".vtu"):
        pytest.importorskip("ezdxf" if ext == ".dxf" else "meshio")
    path = tmp_path / f"r{ext}"
    with pytest.raises(CaseError, match=f"^{key}: not an option of the \\{ext} result writer") as err:
        write_result(path, result, **{key: True})
    assert "\n" not in str(err.value)
    assert not path.exists()


@pytest.mark.parametrize(("ext", "options"), [(".json", {"meshes": False}), (".svg", {}), (".dxf", {"spline": True, "chordal_error": 0.01})])
def test_known_writer_options_are_taken(tmp_path, result, ext, options):
    if ext == ".dxf":
        pytest.importorskip("ezdxf")
    path = tmp_path / f"r{ext}"
    write_result(path, result, **options)
    assert path.stat().st_size > 0
