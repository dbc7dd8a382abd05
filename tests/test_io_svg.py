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


def _svg(body: str, root: str = 'width="100mm" height="100mm" viewBox="0 0 100 100"') -> str:
    return f'<svg xmlns="http://www.w3.org/2000/svg" {root}>{body}</svg>'


SECTION = ('<path id="lower" d="M0,0 L10,0"/><path id="upper" d="M10,0 L10,-5 L0,-5 L0,0"/>'
           '<path id="target" d="M0,0 L10,0"/>')


@pytest.mark.parametrize("body, message", [
    ('<g transform="matrix(nan,0,0,1,0,0)">' + SECTION + "</g>", "<g> transform"),
    ('<g transform="scale(1e400)">' + SECTION + "</g>", "<g> transform"),
    ('<g transform="matrix(1,0,0,1)">' + SECTION + "</g>", "<g> transform"),
    (SECTION.replace("L10,-5 L0,-5", "L10,-5 x,-5"), "id='upper' d: cannot read 'x,-5"),
    (SECTION.replace("L10,-5 L0,-5", "L10,-5 L0,1e999"), "id='upper' d: a number is not finite"),
    (SECTION.replace('d="M0,0 L10,0"/><path id="upper"', 'd="M0,0 A5,5 0 x 1 10,0"/><path id="upper"'),
     "id='lower' d: cannot read 'x"),
    (SECTION + '<polyline class="extra" points="0,0 1,1 2"/>', "points: 5 numbers"),
    (SECTION + '<polyline class="extra" points="0,0 1,nan"/>', "points: cannot read 'nan'"),
    (SECTION + '<line class="extra" x1="abc" y1="0" x2="1" y2="1"/>', "x1: 'abc' is not a finite number"),
    (SECTION.replace('d="M0,0 L10,0"/><path id="upper"', 'd="M0,0 L1e300,0"/><path id="upper"'),
     "coordinates must be finite numbers"),
], ids=["nan-matrix", "infinite-scale", "short-matrix", "letter-in-path", "infinite-number", "letter-in-arc-flag",
        "odd-points", "nan-points", "letter-attribute", "overflow-after-units"])
def test_a_damaged_svg_is_one_line_naming_the_element(tmp_path, body, message):
    """Each damage, before: IndexError, ValueError, a silently shortened path, or NaN coordinates."""
    path = tmp_path / "bad.svg"
    path.write_text(_svg(body))
    with pytest.raises(CaseError) as info:
        read_case(path, law=AreaRatio(0.8))
    assert message in str(info.value) and "\n" not in str(info.value)


def test_an_ellipse_too_fine_to_flatten_is_refused_before_any_point_is_computed(tmp_path):
    """129 bytes that took 3.2 GB and 28 s: a 1e-6 viewBox makes the chordal error 1e-10 for a radius of 1e5."""
    import time
    import tracemalloc

    path = tmp_path / "e.svg"
    path.write_text(_svg('<ellipse id="upper" rx="100000" ry="1"/>', 'viewBox="0 0 1e-6 1e-6"'))
    tracemalloc.start()
    t0 = time.process_time()
    try:
        with pytest.raises(CaseError, match=r"<ellipse> #1 id='upper': [0-9.e+]+ points needed, more than the bound "
                                            r"200000; .*--chordal-error"):
            read_case(path, law=AreaRatio(0.8))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert time.process_time() - t0 < 2.0 and peak < 20e6


def test_an_ellipse_within_the_bound_is_still_flattened_within_the_chordal_error(tmp_path):
    path = tmp_path / "e.svg"
    path.write_text(_svg(SECTION + '<ellipse class="extra" cx="50" cy="50" rx="40" ry="10"/>'))
    from sectiondeform.io.svg import read_drawing

    drawing = read_drawing(path, chordal_error=1e-3)
    ellipse = [p.curve for p in drawing.pieces if "EXTRA" in p.tags][0]
    pts = ellipse.vertices
    # Every chord's midpoint lies within the chordal error of the ellipse (in mm: 1 user unit = 1 mm here).
    mid = 0.5 * (pts[1:] + pts[:-1]) - [50, -50]
    r = np.hypot(mid[:, 0] / 40, mid[:, 1] / 10)
    assert np.all(r <= 1.0) and np.all((1.0 - r) * 10 <= 1e-3 * 1.01)


BULB = ('<path id="lower" d="M0,0 L20,0"/><path id="upper" d="M20,0 L20,-10 A10,10 0 0 0 0,-10 L0,0"/>'
        '<path id="target" d="M0,0 L20,0"/>')


def test_an_svg_hole_is_read_and_other_shapes_reported(tmp_path):
    """A <circle id="hole"> inside the section was dropped without a word (the area 46 % too large), then refused."""
    path = tmp_path / "seal.svg"
    path.write_text(_svg(BULB + '<circle id="hole" cx="10" cy="-10" r="6"/>'))
    report = []
    (body,) = read_case(path, law=AreaRatio(0.9), report=report).bodies
    assert len(body.holes) == 1 and body.holes[0].green() == pytest.approx(36 * np.pi, rel=1e-12)
    assert "read 1 hole in body 'seal' (id/class hole: <circle> #4 id='hole')" in report
    path.write_text(_svg(BULB + '<circle id="hole" cx="60" cy="-10" r="6"/><rect class="frame" x="-50" y="-80" '
                                'width="200" height="130"/><line x1="0" y1="5" x2="20" y2="5"/>'))
    report = []
    assert read_case(path, law=AreaRatio(0.9), report=report).bodies[0].holes == ()
    assert "ignored: 3 entities not used by the case: 1 on id/class frame, 1 on id/class hole, 1 without an id " \
           "or class" in report


def test_an_svg_contour_across_the_section_s_is_one_line_naming_it(tmp_path):
    path = tmp_path / "seal.svg"
    path.write_text(_svg(BULB + '<circle id="hole" cx="20" cy="-10" r="3"/>'))
    with pytest.raises(CaseError, match=r"^id/class hole: <circle> #4 id='hole': a closed contour crossing or touching "
                                        r"the contour of body 'seal' near \(") as err:
        read_case(path, law=AreaRatio(0.9))
    assert "\n" not in str(err.value)


def test_an_svg_body_s_holes_path_gives_one_hole_per_subpath(tmp_path):
    """A writer puts a body's holes in one path BODY-<name>-HOLE, a subpath each; they read back one hole each."""
    from sectiondeform.io.case import case_from_dict
    from sectiondeform.problem import V2

    data = {"format": V2, "support": {"polyline": [[0, 0], [20, 0]]}, "target": {"polyline": [[0, 0], [20, 0]]},
            "bodies": [{"name": "s", "lower": {"polyline": [[0, 0], [20, 0]]},
                        "upper": {"polyline": [[20, 0], [20, 10], [0, 10], [0, 0]]}, "law": {"area_ratio": 0.9},
                        "holes": [{"arc": {"center": [5, 5], "radius": 2, "start_deg": 0, "end_deg": 360}},
                                  {"polyline": [[12, 3], [16, 3], [16, 7], [12, 7], [12, 3]]}]}]}
    case = case_from_dict(data)
    write_case(tmp_path / "c.svg", case)
    text = (tmp_path / "c.svg").read_text()
    assert text.count('id="BODY-s-HOLE"') == 1
    again = read_case(tmp_path / "c.svg")
    assert sorted(abs(h.green()) for h in again.bodies[0].holes) == pytest.approx([4 * np.pi, 16.0], rel=1e-12)
