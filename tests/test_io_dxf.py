"""DXF reading and writing: every entity kind, chaining, units, errors, the real seal scan."""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

from sectiondeform.cli import main  # noqa: E402
from sectiondeform.deform import Deformer  # noqa: E402
from sectiondeform.errors import CaseError, SectionDeformError  # noqa: E402
from sectiondeform.io import read_case, write_case, write_result  # noqa: E402
from sectiondeform.io.case import load_case  # noqa: E402
from sectiondeform.laws import AreaRatio  # noqa: E402
from sectiondeform.section import polygon_area  # noqa: E402

from io_helpers import SEAL, same_curve, shared_case  # noqa: E402

HOLLOW = Path(__file__).parent / "data" / "cases" / "v2" / "hollow-on-arc.json"


def new_doc(units=4):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = units
    return doc, doc.modelspace()


def section_doc(shuffle_seed=None, reverse=False, units=4):
    """A 100 x 40 section: LINE base, upper made of every entity kind, ARC target.

    Upper from B (100, 0): LINE up, LWPOLYLINE with a bulge (half circle of
    radius 5 bulging right), SPLINE across the top, POLYLINE down, ELLIPSE
    quarter from (0, 30) to (-7.5, 15), LINE to A (0, 0).
    """
    doc, msp = new_doc(units)
    L, U, T = {"layer": "LOWER"}, {"layer": "UPPER"}, {"layer": "TARGET"}
    ents = []
    ents.append(lambda: msp.add_line((0, 0), (100, 0), dxfattribs=L))
    ents.append(lambda: msp.add_line((100, 0), (100, 10), dxfattribs=U))
    # bulge +1: half circle from (100, 10) to (100, 20), counter-clockwise, bulging to +x
    ents.append(lambda: msp.add_lwpolyline([(100, 10, 1.0), (100, 20, 0.0), (100, 30, 0.0)], format="xyb", dxfattribs=U))
    ents.append(lambda: msp.add_open_spline([(100, 30), (90, 45), (60, 40), (40, 40)], degree=3, dxfattribs=U))
    ents.append(lambda: msp.add_polyline2d([(40, 40), (20, 40)], dxfattribs=U))
    ents.append(lambda: msp.add_arc((20, 30), 10, 90, 180, dxfattribs=U))
    ents.append(lambda: msp.add_ellipse((0, 15), major_axis=(0, 15), ratio=0.5, start_param=0, end_param=math.pi / 2, dxfattribs=U))
    ents.append(lambda: msp.add_line((10, 30), (0, 30), dxfattribs=U))
    order = list(range(len(ents)))
    if shuffle_seed is not None:
        random.Random(shuffle_seed).shuffle(order)
    for i in order:
        ents[i]()
    msp.add_arc((50, 200), 200, 255, 285, dxfattribs=T)
    return doc


def fix_section(doc):
    """Close the ELLIPSE end to A with a LINE (the ellipse ends at (-7.5, 15))."""
    doc.modelspace().add_line((-7.5, 15), (0, 0), dxfattribs={"layer": "UPPER"})
    return doc


@pytest.mark.parametrize("seed", [None, 1, 7])
def test_every_entity_kind_shuffled(tmp_path, seed):
    doc = fix_section(section_doc(seed))
    if seed is not None:  # reverse some pieces too: re-add LINEs the other way
        msp = doc.modelspace()
        for e in list(msp.query("LINE[layer=='UPPER']")):
            s, t = e.dxf.start, e.dxf.end
            e.dxf.start, e.dxf.end = t, s
    path = tmp_path / "profile.dxf"
    doc.saveas(path)
    report = []
    case = read_case(path, law=AreaRatio(0.8), report=report)
    assert case.units == "mm"
    assert np.allclose(case.lower.start, [0, 0]) and np.allclose(case.lower.end, [100, 0])
    assert np.allclose(case.upper.start, [100, 0]) and np.allclose(case.upper.end, [0, 0])
    kinds = {p.kind for p in case.upper.pieces}
    assert {"polyline", "arc", "bspline"} <= kinds
    # The bulge became an exact half circle of radius 5 centred at (100, 15), bulging to +x.
    arcs = [p for p in case.upper.pieces if p.kind == "arc" and abs(p.radius - 5) < 1e-12]
    assert arcs and np.allclose(arcs[0].center, [100, 15])
    assert arcs[0].at_fractions(np.array([0.5]))[0][0] == pytest.approx(105.0)
    # Target runs A' -> B' the same way as A -> B.
    assert case.target.start[0] < case.target.end[0]
    result = Deformer(case).deform()
    assert result.area_final == pytest.approx(0.8 * result.area_initial, rel=1e-9)


def test_rational_spline_becomes_polyline_within_chordal_error(tmp_path):
    doc, msp = new_doc()
    msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "LOWER"})
    w = math.sqrt(0.5)  # exact quarter circles as rational quadratics
    spline = msp.add_rational_spline([(10, 0), (10, 10), (0, 10)], [1, w, 1], degree=2, dxfattribs={"layer": "UPPER"})
    msp.add_line((0, 10), (0, 0), dxfattribs={"layer": "UPPER"})
    msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "TARGET"})
    doc.saveas(tmp_path / "r.dxf")
    case = read_case(tmp_path / "r.dxf", law=AreaRatio(0.9), chordal_error=1e-4)
    assert case.upper.kind == "polyline"  # the flattened spline and the LINE, merged
    arc = case.upper.vertices[:-1]
    assert np.allclose(np.hypot(*arc.T), 10.0, atol=1e-9)  # vertices on the exact circle
    # chord midpoints within the chordal error
    mids = 0.5 * (arc[1:] + arc[:-1])
    assert (10.0 - np.hypot(*mids.T)).max() <= 1e-4 + 1e-12
    assert spline.dxf.flags  # it really was rational


def test_units_from_insunits_and_conversion(tmp_path):
    doc = fix_section(section_doc(units=5))  # centimetres
    doc.saveas(tmp_path / "cm.dxf")
    case = read_case(tmp_path / "cm.dxf", law=AreaRatio(0.8))
    assert case.units == "cm"
    mm = read_case(tmp_path / "cm.dxf", law=AreaRatio(0.8), units="mm")
    assert mm.units == "mm"
    assert same_curve(mm.upper, type(case.upper)(tuple(p for p in case.upper.pieces))) > 0  # moved
    assert mm.lower.length == pytest.approx(10 * case.lower.length)
    assert np.allclose(mm.upper.at_fractions(np.linspace(0, 1, 50)), 10 * case.upper.at_fractions(np.linspace(0, 1, 50)))


@pytest.mark.parametrize("name", ["paper-example", "grooved-tread", "thick-block-s-curve"])
def test_case_round_trip_and_same_deformation(tmp_path, name):
    case = shared_case(name)
    write_case(tmp_path / "c.dxf", case)
    back = read_case(tmp_path / "c.dxf")
    for key in ("lower", "upper", "target"):
        assert same_curve(getattr(case, key), getattr(back, key)) < 1e-9
    assert back.law == case.law and back.name == case.name and back.options == case.options
    r0, r1 = Deformer(case).deform(), Deformer(back).deform()
    assert r0.contour.shape == r1.contour.shape
    assert np.abs(r0.contour - r1.contour).max() < 1e-8


def test_result_dxf_reread_gives_same_points(tmp_path):
    result = Deformer(shared_case("paper-example")).deform()
    write_result(tmp_path / "r.dxf", result)
    doc = ezdxf.readfile(tmp_path / "r.dxf")
    msp = doc.modelspace()
    (deformed,) = msp.query("LWPOLYLINE[layer=='DEFORMED']")
    assert np.array_equal(np.array(deformed.get_points("xy")), result.contour)
    (initial,) = msp.query("LWPOLYLINE[layer=='INITIAL']")
    assert np.array_equal(np.array(initial.get_points("xy")), result.initial_contour)
    cells = msp.query("LWPOLYLINE[layer=='MESH_FINAL']")
    assert len(cells) == len(result.final_mesh.cells)
    first = np.array(cells[0].get_points("xy"))
    assert np.array_equal(first, result.final_mesh.points[result.final_mesh.cells[0]])
    assert len(msp.query("LWPOLYLINE[layer=='MESH_INITIAL']")) == len(result.initial_mesh.cells)
    assert doc.header["$INSUNITS"] == 4


def test_result_dxf_spline_within_chordal_error(tmp_path):
    result = Deformer(shared_case("paper-example")).deform()
    write_result(tmp_path / "s.dxf", result, spline=True, chordal_error=0.01)
    doc = ezdxf.readfile(tmp_path / "s.dxf")
    splines = doc.modelspace().query("SPLINE[layer=='DEFORMED']")
    assert len(splines) == 2
    curve = np.array([tuple(p)[:2] for p in splines[1].construction_tool().flattening(1e-4)])
    import shapely

    d = shapely.distance(shapely.points(result.upper), shapely.LineString(curve))
    assert d.max() < 0.01 + 1e-4


def bad_drawings():
    def missing(msp):
        msp.add_line((0, 0), (1, 0), dxfattribs={"layer": "LOWER"})

    def gap(msp):
        msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "LOWER"})
        msp.add_line((10, 0), (10, 5), dxfattribs={"layer": "UPPER"})
        msp.add_line((10, 5.5), (0, 5), dxfattribs={"layer": "UPPER"})
        msp.add_line((0, 5), (0, 0), dxfattribs={"layer": "UPPER"})

    def branch(msp):
        msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "LOWER"})
        msp.add_line((10, 0), (10, 5), dxfattribs={"layer": "UPPER"})
        msp.add_lwpolyline([(10, 5), (0, 5), (0, 0)], dxfattribs={"layer": "UPPER"})
        msp.add_line((10, 5), (5, 8), dxfattribs={"layer": "UPPER"})

    def gap_free(msp):
        msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "LOWER"})
        msp.add_lwpolyline([(10, 0), (10, 5), (0, 5), (0, 0)], dxfattribs={"layer": "UPPER"})
        msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "TARGET"})

    def zero(msp):
        gap_free(msp)
        msp.add_line((3, 5), (3, 5), dxfattribs={"layer": "UPPER"})

    def unsupported(msp):
        gap_free(msp)
        msp.add_solid([(0, 0), (1, 0), (1, 1)], dxfattribs={"layer": "UPPER"})

    def nan(msp):
        gap_free(msp)
        msp.add_line((10, 5), (float("nan"), 7), dxfattribs={"layer": "UPPER"})

    def all_collapsed(msp):  # a far stray piece makes the default join tolerance larger than the section
        gap_free(msp)
        msp.add_line((0, 0), (1e8, 1e8), dxfattribs={"layer": "STRAY"})

    return {
        "missing": (missing, "'UPPER' not found"),
        "gap": (gap, "nearest gap is 0.5"),
        "branch": (branch, "branch at (10, 5)"),
        "zero": (zero, "zero-length LINE"),
        "unsupported": (unsupported, "unsupported entity SOLID"),
        "nan": (nan, "coordinates must be finite numbers"),
        "all_collapsed": (all_collapsed, "every piece is shorter than twice the join tolerance"),
    }


@pytest.mark.parametrize("kind", sorted(bad_drawings()))
def test_bad_drawing_one_clear_error(tmp_path, capsys, kind):
    build, message = bad_drawings()[kind]
    doc, msp = new_doc()
    build(msp)
    doc.saveas(tmp_path / "bad.dxf")
    with pytest.raises(CaseError) as info:
        read_case(tmp_path / "bad.dxf", law=AreaRatio(0.8))
    assert message in str(info.value)
    out = tmp_path / "out.dxf"
    assert main(["deform", str(tmp_path / "bad.dxf"), "--area-ratio", "0.8", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0]
    assert not out.exists() and not list(tmp_path.glob(".out*"))


def test_an_ellipse_too_fine_to_flatten_is_refused_before_any_point_is_computed(tmp_path):
    from sectiondeform.io.dxf import read_drawing

    doc, msp = new_doc()
    msp.add_ellipse((5, 5), major_axis=(1e5, 0), ratio=1e-3, dxfattribs={"layer": "UPPER"})
    doc.saveas(tmp_path / "e.dxf")
    with pytest.raises(CaseError, match=r"layer UPPER: ELLIPSE \(handle \w+\): [0-9.e+]+ points needed, more than "
                                        r"the bound 200000; .*--chordal-error"):
        read_drawing(tmp_path / "e.dxf", chordal_error=1e-9)
    assert len(read_drawing(tmp_path / "e.dxf", chordal_error=1e-2).pieces) == 1


TRUNCATED_HEADER = "0\nSECTION\n2\nHEADER\n"
EMPTY_NUMBER = "0\nSECTION\n2\nHEADER\n9\n$EXTMIN\n10\n\n20\n0.0\n0\nENDSEC\n0\nEOF\n"


@pytest.mark.parametrize("text", [TRUNCATED_HEADER, EMPTY_NUMBER, "0\nSECTION\n2\n", "\xff\xfe0\n"],
                         ids=["truncated", "empty-number", "cut-in-a-tag", "binary"])
def test_a_damaged_dxf_file_is_one_clear_error(tmp_path, capsys, text):
    path = tmp_path / "bad.dxf"
    path.write_text(text, encoding="latin-1")
    with pytest.raises(CaseError, match="DXF file"):
        read_case(path, law=AreaRatio(0.8))
    assert main(["convert", str(path), str(tmp_path / "out.json")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bad.dxf: " in err[0] and "DXF file" in err[0]
    assert not (tmp_path / "out.json").exists()


def test_no_law_and_no_target_errors(tmp_path):
    doc, msp = new_doc()
    msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "LOWER"})
    msp.add_lwpolyline([(10, 0), (10, 5), (0, 5), (0, 0)], dxfattribs={"layer": "UPPER"})
    doc.saveas(tmp_path / "p.dxf")
    with pytest.raises(CaseError, match="stores no law"):
        read_case(tmp_path / "p.dxf", target_arc=1.0)
    with pytest.raises(CaseError, match="no target"):
        read_case(tmp_path / "p.dxf", law=AreaRatio(0.8))
    case = read_case(tmp_path / "p.dxf", law=AreaRatio(0.8), target_arc=1.0)
    assert case.target.length == pytest.approx(10.0)
    mid = case.target.at_fractions(np.array([0.5]))[0]
    assert np.allclose(mid, [5, 0])
    assert case.target.start[1] == pytest.approx(1.0, rel=1e-9) and case.target.start[0] < case.target.end[0]


def test_chaining_5600_shuffled_lines_gives_the_ring(tmp_path):
    n = 5600
    t = np.linspace(0, 2 * np.pi, n + 1)
    ring = np.column_stack((20 + 5 * np.cos(t), 5 * np.sin(t)))
    ring[-1] = ring[0]
    doc, msp = new_doc()
    order = np.random.default_rng(3).permutation(n)
    for i in order:
        a, b = ring[i], ring[i + 1]
        if i % 3 == 0:
            a, b = b, a
        msp.add_line(tuple(a), tuple(b))
    doc.saveas(tmp_path / "ring.dxf")
    from sectiondeform.io.chaining import one_chain
    from sectiondeform.io.dxf import read_drawing

    drawing = read_drawing(tmp_path / "ring.dxf")
    path, report = one_chain(drawing.pieces, "layer 0", 1e-9, closed=True)  # its time: benchmarks/run.py
    assert path.closed and len(path.curve.vertices) == n + 1
    assert abs(polygon_area(path.curve.vertices[:-1])) == pytest.approx(25 * np.pi, rel=1e-5)


def test_real_seal_scan_read_and_deformed(tmp_path, capsys):
    # Figures from the scan's own description (tests/data/real): 5,632 LINEs in mm; the left
    # section is a 1,983-point polygon of 6.7 x 6.5 mm, area about 27.6 mm² once its 2.08 mm
    # unscanned gap is closed; its chains meet across a 0.019 mm gap; the base lies at y = 0 to 0.5.
    opts = dict(bbox=(-21, -1, -12, 10), snap=0.05, close_gap=2.5, split=((-19.6, 0.0), (-18.4, 0.0)),
                simplify=0.01, target_arc=0.05, law=AreaRatio(0.8))
    case = read_case(SEAL, **opts)  # its time: benchmarks/run.py
    assert case.units == "mm"
    ring = np.vstack((case.lower.vertices, case.upper.vertices[1:-1]))
    width, height = np.ptp(ring, axis=0)
    assert width == pytest.approx(6.7, abs=0.1) and height == pytest.approx(6.5, abs=0.1)
    # the lower curve runs between the two split points, on the base
    np.testing.assert_allclose([case.lower.start[0], case.lower.end[0]], [-19.6, -18.4], atol=0.05)
    assert np.all((case.lower.vertices[:, 1] > -0.1) & (case.lower.vertices[:, 1] < 0.6))
    chord = float(np.hypot(*(case.lower.end - case.lower.start)))
    assert chord <= case.lower.length <= 1.2 * chord  # a nearly flat base
    assert abs(polygon_area(ring)) == pytest.approx(27.6, abs=0.1)
    # Without --close-gap the drawing is refused, naming the gap.
    with pytest.raises(CaseError, match="not closed: a gap of 2.08"):
        read_case(SEAL, **{**opts, "close_gap": 0.0})
    out = tmp_path / "seal.dxf"
    argv = ["deform", str(SEAL), "--bbox=-21,-1,-12,10", "--snap", "0.05", "--close-gap", "2.5",
            "--split", "-19.6,0", "-18.4,0", "--simplify", "0.01", "--target-arc", "0.05",
            "--area-ratio", "0.8", "--model", "hyperelastic", "-o", str(out)]
    assert main(argv) == 0, capsys.readouterr().err
    doc = ezdxf.readfile(out)
    assert len(doc.modelspace().query("LWPOLYLINE[layer=='DEFORMED']")) == 1


def bulb_seal(hole_center=(10.0, 10.0)):
    """A bulb seal 20 wide: a 10-high block under a half disc of radius 10, with a hole of radius 6 on HOLE."""
    doc, msp = new_doc()
    msp.add_line((0, 0), (20, 0), dxfattribs={"layer": "LOWER"})
    msp.add_line((20, 0), (20, 10), dxfattribs={"layer": "UPPER"})
    msp.add_arc((10, 10), 10, 0, 180, dxfattribs={"layer": "UPPER"})
    msp.add_line((0, 10), (0, 0), dxfattribs={"layer": "UPPER"})
    msp.add_line((0, 0), (20, 0), dxfattribs={"layer": "TARGET"})
    msp.add_circle(hole_center, 6, dxfattribs={"layer": "HOLE"})
    return doc, msp


def test_a_hole_on_a_layer_nobody_reads_is_read_as_the_section_s_hole(tmp_path, capsys):
    """Read without its hole the seal's area was 46 % too large, without a word; then the hole was refused."""
    doc, _ = bulb_seal()
    doc.saveas(tmp_path / "seal.dxf")
    report = []
    case = read_case(tmp_path / "seal.dxf", law=AreaRatio(0.9), report=report)
    (body,) = case.bodies
    assert case.dialect == "section-case/2" and len(body.holes) == 1  # the paper's one-body dialect has no holes
    assert body.lower.to_json() == case.support.to_json()
    assert body.holes[0].green() == pytest.approx(36 * math.pi, rel=1e-12)
    assert "read 1 hole in body 'seal' (layer HOLE: CIRCLE #5 (handle 34, layer HOLE))" in report
    assert not [line for line in report if line.startswith("ignored")]
    assert main(["convert", str(tmp_path / "seal.dxf"), str(tmp_path / "out.json"), "--area-ratio", "0.9"]) == 0
    assert "read 1 hole in body 'seal'" in capsys.readouterr().out
    out = json.loads((tmp_path / "out.json").read_text())
    assert out["bodies"][0]["holes"] == [{"arc": {"center": [10.0, 10.0], "radius": 6.0, "start_deg": 0.0, "end_deg": 360.0}}]


def test_entities_not_used_are_reported_with_their_layers(tmp_path, capsys):
    doc, msp = bulb_seal(hole_center=(60.0, 10.0))  # beside the section: no hole
    msp.add_lwpolyline([(-50, -50), (150, -50), (150, 80), (-50, 80)], close=True, dxfattribs={"layer": "BORDER"})
    msp.add_text("seal", dxfattribs={"layer": "NOTES"})
    doc.saveas(tmp_path / "seal.dxf")
    report = []
    case = read_case(tmp_path / "seal.dxf", law=AreaRatio(0.9), report=report)
    assert polygon_area(np.vstack((case.lower.characteristic_points(1e-3), case.upper.characteristic_points(1e-3)))) \
        == pytest.approx(200 + 50 * math.pi, rel=1e-4)
    assert "ignored: 3 entities not used by the case: 1 on layer BORDER, 1 on layer HOLE, 1 on layer NOTES " \
           "(annotation: TEXT)" in report
    assert main(["convert", str(tmp_path / "seal.dxf"), str(tmp_path / "out.json"), "--area-ratio", "0.9"]) == 0
    assert "ignored: 3 entities not used by the case" in capsys.readouterr().out


def test_a_drawing_whose_every_entity_is_used_reports_nothing_ignored(tmp_path):
    doc = fix_section(section_doc())
    doc.saveas(tmp_path / "s.dxf")
    report = []
    read_case(tmp_path / "s.dxf", law=AreaRatio(0.9), report=report)
    assert not [line for line in report if line.startswith("ignored")]


def two_bodies(hole_center=None):
    """Two 20 x 5 blocks on a support: ``base`` on BODY-base-LOWER/-UPPER, ``top`` a contour on BODY-top."""
    doc, msp = new_doc()
    msp.add_line((0, 0), (20, 0), dxfattribs={"layer": "SUPPORT"})
    msp.add_line((0, -1), (20, -1), dxfattribs={"layer": "TARGET"})
    msp.add_line((0, 0), (20, 0), dxfattribs={"layer": "BODY-base-LOWER"})
    msp.add_lwpolyline([(20, 0), (20, 5), (0, 5), (0, 0)], dxfattribs={"layer": "BODY-base-UPPER"})
    msp.add_lwpolyline([(0, 5), (20, 5), (20, 10), (0, 10)], close=True, dxfattribs={"layer": "BODY-top"})
    if hole_center is not None:
        msp.add_circle(hole_center, 2, dxfattribs={"layer": "HOLE"})
    return doc, msp


def test_a_hole_in_a_drawing_of_bodies_is_read_as_the_hole_of_the_body_round_it(tmp_path):
    doc, _ = two_bodies((10, 7.5))
    doc.saveas(tmp_path / "layup.dxf")
    report = []
    problem = read_case(tmp_path / "layup.dxf", law=AreaRatio(0.9), report=report)
    base, top = problem.bodies
    assert base.holes == () and len(top.holes) == 1 and top.holes[0].green() == pytest.approx(4 * math.pi, rel=1e-12)
    assert "read 1 hole in body 'top' (layer HOLE: CIRCLE #5 (handle 34, layer HOLE))" in report
    # the body's area less the hole's, as the deformer counts it
    assert Deformer(problem).deform().bodies[1].area_initial == pytest.approx(100 - 4 * math.pi, rel=1e-9)


@pytest.mark.parametrize("center", [(10, 5), (19, 7.5), (10, 12)], ids=["across-the-interface", "across-a-side",
                                                                        "touching-the-top"])
def test_a_closed_contour_crossing_or_touching_a_body_is_one_line_naming_its_layer_and_entity(tmp_path, capsys, center):
    doc, _ = two_bodies(center)
    doc.saveas(tmp_path / "layup.dxf")
    with pytest.raises(CaseError, match=r"^layer HOLE: CIRCLE #5 \(handle 34, layer HOLE\): a closed contour crossing "
                                        r"or touching the contour of body '(base|top)' near"):
        read_case(tmp_path / "layup.dxf", law=AreaRatio(0.9))
    assert main(["convert", str(tmp_path / "layup.dxf"), str(tmp_path / "out.json"), "--area-ratio", "0.9"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "CIRCLE #5 (handle 34, layer HOLE): a closed contour crossing" in err[0]
    assert not (tmp_path / "out.json").exists()


def test_holes_on_a_body_s_hole_layer_and_inside_its_contour_layer(tmp_path):
    """BODY-<name>-HOLE holds a body's holes; on BODY-<name>, the contours inside the outer one are its holes."""
    doc, msp = two_bodies()
    msp.add_circle((5, 7.5), 1, dxfattribs={"layer": "BODY-top"})
    msp.add_lwpolyline([(13, 1), (17, 1), (17, 4), (13, 4)], close=True, dxfattribs={"layer": "BODY-base-HOLE"})
    msp.add_circle((5, 2.5), 1, dxfattribs={"layer": "BODY-base-HOLE"})
    doc.saveas(tmp_path / "layup.dxf")
    report = []
    base, top = read_case(tmp_path / "layup.dxf", law=AreaRatio(0.9), report=report).bodies
    assert sorted(abs(h.green()) for h in base.holes) == pytest.approx([math.pi, 12.0], rel=1e-12)
    assert [abs(h.green()) for h in top.holes] == pytest.approx([math.pi], rel=1e-12)
    ring = np.vstack((top.lower.characteristic_points(1e-3), top.upper.characteristic_points(1e-3)[1:-1]))
    assert polygon_area(ring) == pytest.approx(100.0, rel=1e-12)  # the outer contour stays the body's
    assert any(line.startswith("read 2 holes in body 'base'") for line in report)
    assert any(line.startswith("read 1 hole in body 'top' (layer BODY-top:") for line in report)


@pytest.mark.parametrize("hole, message", [
    (lambda msp: msp.add_lwpolyline([(13, 1), (17, 1), (17, 4)], dxfattribs={"layer": "BODY-base-HOLE"}),
     r"^layer BODY-base-HOLE: LWPOLYLINE #5 \(handle \w+, layer BODY-base-HOLE\) is part of an open curve from "
     r"\(1[37], 1\) to \(1[37], [14]\); a hole is a closed contour"),
    (lambda msp: msp.add_circle((40, 2.5), 1, dxfattribs={"layer": "BODY-base-HOLE"}),
     r"^layer BODY-base-HOLE: CIRCLE #5 \(handle \w+, layer BODY-base-HOLE\): it lies outside the body's contour"),
    (lambda msp: msp.add_circle((10, 2.5), 1, dxfattribs={"layer": "BODY-nobody-HOLE"}),
     r"^layer BODY-nobody-HOLE: holes of body 'nobody', which is not drawn"),
], ids=["open", "outside", "no-body"])
def test_a_bad_hole_layer_is_one_line_naming_it(tmp_path, hole, message):
    doc, msp = two_bodies()
    hole(msp)
    doc.saveas(tmp_path / "layup.dxf")
    with pytest.raises(SectionDeformError, match=message) as err:
        read_case(tmp_path / "layup.dxf", law=AreaRatio(0.9))
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("suffix", [".dxf", ".svg"])
def test_the_hollow_profile_round_trips_through_a_drawing_with_its_hole(tmp_path, suffix):
    """Case JSON -> drawing -> case -> drawing -> case: the same hole (to 1e-9) and the same area less the hole."""
    case = load_case(HOLLOW)
    first = tmp_path / f"a{suffix}"
    write_case(first, case)
    once = read_case(first)
    write_case(tmp_path / f"b{suffix}", once)
    twice = read_case(tmp_path / f"b{suffix}")
    (hole,) = case.bodies[0].holes
    for again in (once, twice):
        (h,) = again.bodies[0].holes
        assert h.green() == pytest.approx(hole.green(), rel=1e-12)
        pts = h.at_fractions(np.linspace(0.0, 1.0, 97))
        assert np.abs(np.hypot(*(pts - [12.0, 6.5]).T) - 4.0).max() < 1e-9  # every point on the drawn circle
        assert same_curve(again.bodies[0].upper, case.bodies[0].upper) < 1e-9
    # the deformer's area is the contour's less the hole's, as for the case JSON
    areas = [Deformer(p).deform().bodies[0].area_initial for p in (case, twice)]
    assert areas[1] == pytest.approx(areas[0], rel=1e-9) and areas[0] == pytest.approx(288 - 16 * math.pi, rel=1e-9)


@pytest.mark.parametrize("model", ["paper", "hyperelastic"])
def test_a_written_result_draws_the_holes_before_and_after(tmp_path, model):
    case = load_case(HOLLOW)
    result = Deformer(case, model=model).deform()
    write_result(tmp_path / "r.dxf", result, case=case)
    msp = ezdxf.readfile(tmp_path / "r.dxf").modelspace()
    body = result.bodies[0]
    for layer, ring in (("INITIAL-profile-HOLE", body.initial_holes[0]), ("DEFORMED-profile-HOLE", body.holes[0])):
        (e,) = msp.query(f"LWPOLYLINE[layer=='{layer}']")
        assert e.closed and np.array_equal(np.array(e.get_points("xy")), ring)


def test_entities_a_drawing_of_bodies_does_not_use_are_reported_with_their_layers(tmp_path, capsys):
    doc, msp = two_bodies(hole_center=(60, 5))  # beside the bodies: no hole
    msp.add_lwpolyline([(-50, -50), (150, -50), (150, 80), (-50, 80)], close=True, dxfattribs={"layer": "BORDER"})
    msp.add_line((0, -9), (20, -9), dxfattribs={"layer": "Dims"})
    msp.add_text("layup", dxfattribs={"layer": "NOTES"})
    doc.saveas(tmp_path / "layup.dxf")
    report = []
    problem = read_case(tmp_path / "layup.dxf", law=AreaRatio(0.9), report=report)
    assert [b.name for b in problem.bodies] == ["base", "top"]
    for body in problem.bodies:  # each read solid
        ring = np.vstack((body.lower.characteristic_points(1e-3), body.upper.characteristic_points(1e-3)))
        assert abs(polygon_area(ring)) == pytest.approx(100.0)
    assert "ignored: 4 entities not used by the case: 1 on layer BORDER, 1 on layer Dims, 1 on layer HOLE, " \
           "1 on layer NOTES (annotation: TEXT)" in report
    assert main(["convert", str(tmp_path / "layup.dxf"), str(tmp_path / "out.json"), "--area-ratio", "0.9"]) == 0
    assert "ignored: 4 entities not used by the case" in capsys.readouterr().out


def test_a_drawing_of_bodies_whose_every_entity_is_used_reports_nothing_ignored(tmp_path):
    doc, _ = two_bodies()
    doc.saveas(tmp_path / "layup.dxf")
    report = []
    read_case(tmp_path / "layup.dxf", law=AreaRatio(0.9), report=report)
    assert not [line for line in report if line.startswith("ignored")]


@pytest.mark.parametrize("suffix", [".dxf", ".svg"])
def test_the_public_hollow_profile_through_the_command_line_deforms_as_its_case_json(tmp_path, capsys, suffix):
    """Convert JSON -> drawing, then deform the drawing with both models: the hole is read, the areas are the JSON's."""
    drawing = tmp_path / f"hollow{suffix}"
    assert main(["convert", str(HOLLOW), str(drawing)]) == 0
    for model in ("paper", "hyperelastic"):
        assert main(["deform", str(HOLLOW), "-o", str(tmp_path / "j.json"), "--model", model]) == 0
        assert main(["deform", str(drawing), "-o", str(tmp_path / "d.json"), "--model", model]) == 0
        assert "read 1 hole in body 'profile'" in capsys.readouterr().out
        ref, got = (json.loads((tmp_path / f"{n}.json").read_text())["bodies"][0] for n in "jd")
        for key in ("initial", "final"):
            assert got["area"][key] == pytest.approx(ref["area"][key], rel=1e-9)
        assert got["area"]["initial"] == pytest.approx(288 - 16 * math.pi, rel=1e-9)


def test_a_drawing_s_holes_are_scaled_with_its_units(tmp_path):
    write_case(tmp_path / "h.dxf", load_case(HOLLOW))
    (hole,) = read_case(tmp_path / "h.dxf", units="cm").bodies[0].holes
    assert hole.green() == pytest.approx(math.pi * 0.4**2, rel=1e-12)


def test_a_hole_drawn_on_the_upper_curve_s_layer_is_read_as_a_hole(tmp_path):
    """On UPPER beside the upper curve, the hole made the layer 'form 2 separate chains', refused."""
    doc, msp = bulb_seal(hole_center=(60.0, 10.0))
    msp.add_circle((10, 10), 6, dxfattribs={"layer": "UPPER"})
    doc.saveas(tmp_path / "seal.dxf")
    report = []
    (body,) = read_case(tmp_path / "seal.dxf", law=AreaRatio(0.9), report=report).bodies
    assert [h.green() for h in body.holes] == pytest.approx([36 * math.pi], rel=1e-12)
    assert polygon_area(np.vstack((body.lower.vertices, body.upper.characteristic_points(1e-3)[1:-1]))) \
        == pytest.approx(200 + 50 * math.pi, rel=1e-4)  # the upper curve without the hole
    assert any(line.startswith("read 1 hole in body 'seal' (layer UPPER: CIRCLE #6") for line in report)
    doc, msp = two_bodies()
    msp.add_circle((10, 2.5), 1, dxfattribs={"layer": "BODY-base-UPPER"})
    doc.saveas(tmp_path / "layup.dxf")
    base, top = read_case(tmp_path / "layup.dxf", law=AreaRatio(0.9)).bodies
    assert [h.green() for h in base.holes] == pytest.approx([math.pi], rel=1e-12) and top.holes == ()
