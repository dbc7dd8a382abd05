"""The convert command and deform with CAD input and output, in-process."""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("ezdxf")
pytest.importorskip("meshio")

from sectiondeform.cli import main  # noqa: E402
from sectiondeform.io.case import load_case  # noqa: E402

from io_helpers import CASES_DIR, same_curve, shared_case  # noqa: E402


def test_convert_json_dxf_svg_json(tmp_path):
    case = shared_case("paper-example")
    src = CASES_DIR / "paper-example.json"
    assert main(["convert", str(src), str(tmp_path / "c.dxf")]) == 0
    assert main(["convert", str(tmp_path / "c.dxf"), str(tmp_path / "c.svg")]) == 0
    assert main(["convert", str(tmp_path / "c.svg"), str(tmp_path / "c.json")]) == 0
    back = load_case(tmp_path / "c.json")
    for key in ("lower", "upper", "target"):
        assert same_curve(getattr(case, key), getattr(back, key)) < 1e-6
    assert back.law == case.law


def test_deform_dxf_to_dxf_with_meshes(tmp_path, capsys):
    src = CASES_DIR / "paper-example.json"
    assert main(["convert", str(src), str(tmp_path / "profile.dxf")]) == 0
    out = tmp_path / "deformed.dxf"
    argv = ["deform", str(tmp_path / "profile.dxf"), "--area-ratio", "0.8", "-o", str(out),
            "--mesh-out", str(tmp_path / "f.vtu"), "--initial-mesh-out", str(tmp_path / "i.inp"), "--dxf-spline"]
    assert main(argv) == 0
    assert out.exists() and (tmp_path / "f.vtu").exists() and (tmp_path / "i.inp").exists()
    assert main(["deform", str(src), "-o", str(tmp_path / "r.json")]) == 0
    ref = json.loads((tmp_path / "r.json").read_text())
    assert main(["deform", str(tmp_path / "profile.dxf"), "-o", str(tmp_path / "d.json")]) == 0
    got = json.loads((tmp_path / "d.json").read_text())
    assert np.abs(np.array(got["contour"]) - np.array(ref["contour"])).max() < 1e-8


def test_case_json_naming_a_drawing(tmp_path):
    case = shared_case("paper-example")
    from sectiondeform.io import read_case, write_case

    write_case(tmp_path / "profile.dxf", case)
    (tmp_path / "case.json").write_text(json.dumps({
        "format": "section-case/1", "name": "from-drawing", "law": {"area_ratio": 0.7},
        "drawing": {"file": "profile.dxf", "layers": {"lower": "LOWER"}},
    }))
    got = read_case(tmp_path / "case.json")
    assert got.name == "from-drawing" and got.law.ratio == 0.7
    assert same_curve(got.upper, case.upper) < 1e-9
    out = tmp_path / "r.vtu"
    assert main(["deform", str(tmp_path / "case.json"), "-o", str(out)]) == 0 and out.exists()


def test_bad_option_values_exit_2(tmp_path, capsys):
    src = CASES_DIR / "paper-example.json"
    assert main(["convert", str(src), str(tmp_path / "c.dxf")]) == 0
    assert main(["deform", str(tmp_path / "c.dxf"), "--snap", "-1", "-o", str(tmp_path / "x.dxf")]) == 2
    assert main(["convert", str(src), str(tmp_path / "c.stl")]) == 2
    assert not (tmp_path / "x.dxf").exists() and not (tmp_path / "c.stl").exists()
