"""SVG reading and writing: path segments, ids and classes, y flip, document units, round trips."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("svgelements")

from sectiondeform.deform import Deformer  # noqa: E402
from sectiondeform.errors import CaseError  # noqa: E402
from sectiondeform.io import read_case, write_case, write_result  # noqa: E402
from sectiondeform.laws import AreaRatio  # noqa: E402

from io_helpers import same_curve, shared_case  # noqa: E402

SVG = """<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="100mm" viewBox="0 0 100 50">
<g transform="translate(0,50)">
 <path id="lower" d="M 10,0 L 90,0"/>
 <path class="upper outline" d="M 90,0 C 90,-20 70,-30 60,-30 Q 50,-35 40,-30 A 10,10 0 0 1 20,-30 L 10,0"/>
 <polyline class="target" points="10,0 50,5 90,0"/>
 <text>ignored</text>
</g>
</svg>"""


def test_path_segments_units_and_flip(tmp_path):
    (tmp_path / "p.svg").write_text(SVG)
    case = read_case(tmp_path / "p.svg", law=AreaRatio(0.8))
    assert case.units == "mm"
    # 1 user unit = 2 mm, y flipped: SVG (10, 50) -> (20, -100) mm
    assert np.allclose(case.lower.start, [20, -100]) and np.allclose(case.lower.end, [180, -100])
    kinds = [p.kind for p in case.upper.pieces]
    assert kinds.count("bspline") == 2 and "arc" in kinds
    cubic = [p for p in case.upper.pieces if p.kind == "bspline" and p.degree == 3][0]
    assert cubic.knots.tolist() == [0, 0, 0, 0, 1, 1, 1, 1]
    arc = [p for p in case.upper.pieces if p.kind == "arc"][0]
    assert arc.radius == pytest.approx(20.0) and np.allclose(arc.center, [60, -40])
    # sweep-flag 1 is clockwise on screen: from right to left through the screen's bottom,
    # so in the flipped frame the arc dips towards the base: its middle at y = -60
    assert arc.at_fractions(np.array([0.5]))[0][1] == pytest.approx(-60.0)
    assert case.target.kind == "polyline" and np.allclose(case.target.vertices[1], [100, -110])
    result = Deformer(case).deform()
    assert result.area_final == pytest.approx(0.8 * result.area_initial, rel=1e-9)


@pytest.mark.parametrize("name", ["paper-example", "grooved-tread", "thick-block-s-curve"])
def test_case_round_trip(tmp_path, name):
    case = shared_case(name)
    write_case(tmp_path / "c.svg", case)
    back = read_case(tmp_path / "c.svg")
    for key in ("lower", "upper", "target"):
        assert same_curve(getattr(case, key), getattr(back, key)) < 1e-6
    assert back.law == case.law and back.units == case.units
    r0, r1 = Deformer(case).deform(), Deformer(back).deform()
    assert r1.area_final == pytest.approx(r0.area_final, rel=1e-8)


def test_result_svg_is_valid_and_holds_the_contour(tmp_path):
    import xml.etree.ElementTree as ET

    result = Deformer(shared_case("paper-example")).deform()
    write_result(tmp_path / "r.svg", result)
    root = ET.parse(tmp_path / "r.svg").getroot()
    ids = {g.get("id") for g in root.iter("{http://www.w3.org/2000/svg}g")}
    assert ids == {"initial", "mesh-initial", "target", "mesh-final", "deformed"}
    # the deformed group reads back as a closed contour through the result's points
    from sectiondeform.io.svg import read_drawing

    pieces = [p for p in read_drawing(tmp_path / "r.svg").pieces if "DEFORMED" in p.tags]
    starts = np.array([p.curve.vertices[0] for p in pieces])  # one piece per segment, closing one last
    assert np.abs(starts - result.contour).max() < 1e-9


def test_missing_id_names_what_exists(tmp_path):
    (tmp_path / "p.svg").write_text(SVG.replace('id="lower"', 'id="base"'))
    with pytest.raises(CaseError, match="'LOWER' not found .*BASE"):
        read_case(tmp_path / "p.svg", law=AreaRatio(0.8))
    case = read_case(tmp_path / "p.svg", law=AreaRatio(0.8), layers={"lower": "base"})
    assert case.lower.length == pytest.approx(160.0)
