"""``sectiondeform convert`` on assemblies: case JSON <-> DXF <-> SVG, options, refusals."""

from __future__ import annotations

import json

import pytest

ezdxf = pytest.importorskip("ezdxf")

from sectiondeform.cli import main  # noqa: E402
from sectiondeform.io.case import load_case  # noqa: E402
from sectiondeform.laws import AreaRatio  # noqa: E402

from io_helpers import CASES_DIR, same_curve  # noqa: E402

STRIP = CASES_DIR / "v2" / "two-layer-strip.json"


def test_convert_json_dxf_svg_json(tmp_path):
    case = load_case(STRIP)
    assert main(["convert", str(STRIP), str(tmp_path / "a.dxf")]) == 0
    assert main(["convert", str(tmp_path / "a.dxf"), str(tmp_path / "a.svg")]) == 0
    assert main(["convert", str(tmp_path / "a.svg"), str(tmp_path / "a.json")]) == 0
    assert json.loads((tmp_path / "a.json").read_text())["format"] == "section-case/2"
    back = load_case(tmp_path / "a.json")
    assert [b.name for b in back.bodies] == [b.name for b in case.bodies]
    assert [b.law for b in back.bodies] == [b.law for b in case.bodies]
    assert [b.material for b in back.bodies] == [b.material for b in case.bodies]
    for a, b in zip(case.bodies, back.bodies):
        assert a.lower.to_json() == b.lower.to_json()
        assert same_curve(a.upper, b.upper) < 1e-5  # the JSON's chains join arcs to vertices rounded to 1e-6
    assert same_curve(case.target, back.target) < 1e-9


def test_convert_contour_drawing_with_area_ratio_and_units(tmp_path, capsys):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    msp.add_line((0, 0), (100, 0), dxfattribs={"layer": "SUPPORT"})
    msp.add_arc((50, -200), 206.0, 60, 120, dxfattribs={"layer": "TARGET"})
    msp.add_lwpolyline([(0, 0), (100, 0), (100, 4), (0, 4)], close=True, dxfattribs={"layer": "BODY-backing"})
    msp.add_lwpolyline([(0, 4), (100, 4), (100, 12, 0.3), (90, 17), (10, 17), (0, 12)], format="xy", close=True,
                       dxfattribs={"layer": "BODY-cover"})
    doc.saveas(tmp_path / "layup.dxf")
    out = tmp_path / "layup.json"
    assert main(["convert", str(tmp_path / "layup.dxf"), str(out), "--area-ratio", "0.9", "--units", "cm"]) == 0
    case = load_case(out)
    assert case.units == "cm" and [b.law for b in case.bodies] == [AreaRatio(0.9)] * 2
    assert case.bodies[1].lower.to_json() == {"polyline": [[0.0, 0.4], [10.0, 0.4]]}
    assert "lower curve from" in capsys.readouterr().out


def test_convert_refusals_leave_no_file(tmp_path, capsys):
    assert main(["convert", str(STRIP), str(tmp_path / "a.dxf")]) == 0
    capsys.readouterr()
    out = tmp_path / "b.json"
    assert main(["convert", str(tmp_path / "a.dxf"), str(out), "--split", "0,0", "100,0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "--split" in err and "several bodies" in err and not out.exists()
    assert main(["convert", str(STRIP), str(out), "--area-ratio", "0.9"]) == 2
    err = capsys.readouterr().err.strip()
    assert "each body's law" in err and not out.exists()
    assert main(["convert", str(tmp_path / "a.dxf"), str(out), "--layers", "lower=BASE"]) == 2
    assert "--layers" in capsys.readouterr().err and not out.exists()


def test_convert_keeps_stored_laws_unless_told(tmp_path):
    assert main(["convert", str(STRIP), str(tmp_path / "a.dxf")]) == 0
    assert main(["convert", str(tmp_path / "a.dxf"), str(tmp_path / "b.json"), "--area-ratio", "1.0"]) == 0
    assert [b.law for b in load_case(tmp_path / "b.json").bodies] == [AreaRatio(1.0)] * 2


def test_deform_an_assembly_to_dxf_svg_and_meshes(tmp_path, capsys):
    meshio = pytest.importorskip("meshio")
    out = tmp_path / "r.dxf"
    argv = ["deform", str(STRIP), "-o", str(out), "--mesh-out", str(tmp_path / "f.vtu"),
            "--initial-mesh-out", str(tmp_path / "i.msh")]
    assert main(argv) == 0
    layers = {layer.dxf.name for layer in ezdxf.readfile(out).layers}
    assert {"SUPPORT", "TARGET", "DEFORMED-cover-UPPER", "INITIAL-backing-LOWER", "MESH-FINAL-backing"} <= layers
    assert set(meshio.read(tmp_path / "i.msh").field_data) == {"backing", "cover"}
    assert main(["deform", str(STRIP), "-o", str(tmp_path / "r.svg")]) == 0
    assert 'id="DEFORMED-backing-UPPER"' in (tmp_path / "r.svg").read_text()
    assert main(["deform", str(STRIP), "-o", str(tmp_path / "r.vtu"), "--fields"]) == 0  # each body's fields, its cells
    vtu = meshio.read(tmp_path / "r.vtu")
    cells = sum(len(c.data) for c in vtu.cells)
    assert sum(len(v) for v in vtu.cell_data["geometric_J"]) == cells and "pressure" not in vtu.cell_data


def test_case_json_naming_an_assembly_drawing(tmp_path):
    """Curves from a CAD contour drawing, laws and materials per body from the JSON."""
    doc = ezdxf.new("R2010")
    msp = doc.modelspace()
    msp.add_line((0, 0), (100, 0), dxfattribs={"layer": "SUPPORT"})
    msp.add_line((0, -2), (100, -2), dxfattribs={"layer": "TARGET"})
    msp.add_lwpolyline([(0, 0), (100, 0), (100, 4), (0, 4)], close=True, dxfattribs={"layer": "BODY-backing"})
    msp.add_lwpolyline([(0, 4), (100, 4), (50, 14)], close=True, dxfattribs={"layer": "BODY-cover"})
    doc.saveas(tmp_path / "layup.dxf")
    (tmp_path / "case.json").write_text(json.dumps({
        "format": "section-case/2", "name": "layup", "drawing": {"file": "layup.dxf"},
        "bodies": [{"name": "cover", "law": {"area_ratio": 0.9}},
                   {"name": "backing", "law": {"area_ratio": 0.95}, "material": {"shear_modulus": 3.0}}],
        "options": {"chordal_error": 0.05},
    }))
    from sectiondeform.io import read_case

    case = read_case(tmp_path / "case.json")
    assert [b.name for b in case.bodies] == ["cover", "backing"]
    assert [b.law for b in case.bodies] == [AreaRatio(0.9), AreaRatio(0.95)]
    assert case.bodies[1].material_data == {"shear_modulus": 3.0}
    assert case.options.chordal_error == 0.05 and case.name == "layup"
    assert case.bodies[0].lower.to_json() == {"polyline": [[0.0, 4.0], [100.0, 4.0]]}
    out = tmp_path / "r.json"
    assert main(["deform", str(tmp_path / "case.json"), "-o", str(out)]) == 0
    data = json.loads((tmp_path / "case.json").read_text())
    data["bodies"].append({"name": "tread", "law": {"area_ratio": 1.0}})
    (tmp_path / "bad.json").write_text(json.dumps(data))
    with pytest.raises(Exception) as exc:
        read_case(tmp_path / "bad.json")
    assert "'tread'" in str(exc.value) and "BODY-tread" in str(exc.value)
    data["bodies"][2] = {"name": "cover", "lower": {"polyline": [[0, 0], [1, 0]]}}
    (tmp_path / "bad.json").write_text(json.dumps(data))
    with pytest.raises(Exception) as exc:
        read_case(tmp_path / "bad.json")
    assert str(exc.value).startswith("bodies[2].lower:")


def test_deform_a_law_less_assembly_drawing_with_area_ratio(tmp_path):
    doc = ezdxf.new("R2010")
    msp = doc.modelspace()
    msp.add_line((0, 0), (100, 0), dxfattribs={"layer": "SUPPORT"})
    msp.add_line((0, -2), (100, -2), dxfattribs={"layer": "TARGET"})
    msp.add_lwpolyline([(0, 0), (100, 0), (100, 4), (0, 4)], close=True, dxfattribs={"layer": "BODY-backing"})
    msp.add_lwpolyline([(0, 4), (100, 4), (50, 14)], close=True, dxfattribs={"layer": "BODY-cover"})
    doc.saveas(tmp_path / "layup.dxf")
    out = tmp_path / "r.json"
    assert main(["deform", str(tmp_path / "layup.dxf"), "--area-ratio", "0.9", "-o", str(out)]) == 0
    for body in json.loads(out.read_text())["bodies"]:
        assert body["area"]["final"] == pytest.approx(0.9 * body["area"]["initial"], rel=1e-9)
    assert main(["deform", str(tmp_path / "layup.dxf"), "-o", str(tmp_path / "s.json")]) == 2  # no law anywhere
    assert not (tmp_path / "s.json").exists()
