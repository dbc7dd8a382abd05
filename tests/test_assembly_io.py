"""Assemblies (section-case/2) in DXF and SVG: layers in and out, contours split on their foundations, refusals."""

from __future__ import annotations

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

from sectiondeform.errors import CaseError, SectionDeformError  # noqa: E402
from sectiondeform.io import read_case, write_case  # noqa: E402
from sectiondeform.io.case import case_from_dict  # noqa: E402
from sectiondeform.io.dxf import _add_curve  # noqa: E402
from sectiondeform.laws import AreaRatio  # noqa: E402
from sectiondeform.problem import Problem  # noqa: E402

from io_helpers import same_curve, shared_case  # noqa: E402

STRIP = "v2/two-layer-strip"


def plain_assembly(**changes) -> Problem:
    """Two stacked polyline bodies on a straight support, a polyline target: every coordinate exact in a drawing."""
    data = {
        "format": "section-case/2", "name": "blocks", "units": "mm",
        "support": {"polyline": [[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]]},
        "target": {"polyline": [[0.0, 0.5], [10.0, -0.25], [20.0, 0.5]]},
        "bodies": [
            {"name": "base", "lower": {"polyline": [[0.0, 0.0], [20.0, 0.0]]},
             "upper": {"polyline": [[20.0, 0.0], [20.0, 2.0], [13.3, 2.0], [0.1, 2.0], [0.0, 0.0]]},
             "law": {"area_ratio": 0.95}, "material": {"shear_modulus": 3.0, "bulk_to_shear": 500.0}},
            {"name": "Top Layer", "lower": {"polyline": [[0.1, 2.0], [13.3, 2.0], [20.0, 2.0]]},
             "upper": {"polyline": [[20.0, 2.0], [18.0, 5.5], [2.0, 5.5], [0.1, 2.0]]},
             "law": {"area_ratio": 0.875}},
        ],
        "options": {"chordal_error": 0.01, "contact_tolerance": 1e-5},
    }
    data.update(changes)
    return case_from_dict(data)


def new_doc():
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    return doc, doc.modelspace()


# ---------------------------------------------------------------- round trips


@pytest.mark.parametrize("ext", [".dxf", ".svg"])
def test_polyline_assembly_round_trip_is_exact(tmp_path, ext):
    case = plain_assembly()
    write_case(tmp_path / f"a{ext}", case)
    back = read_case(tmp_path / f"a{ext}")
    assert isinstance(back, Problem) and back.dialect == "section-case/2"
    assert back == case  # every curve, law, material, option and the name, to the bit
    assert [b.name for b in back.bodies] == ["base", "Top Layer"]


@pytest.mark.parametrize("ext", [".dxf", ".svg"])
def test_shared_strip_round_trip(tmp_path, ext):
    case = shared_case(STRIP)
    write_case(tmp_path / f"a{ext}", case)
    back = read_case(tmp_path / f"a{ext}")
    assert [b.name for b in back.bodies] == [b.name for b in case.bodies]
    assert [b.law for b in back.bodies] == [b.law for b in case.bodies]
    assert [b.material for b in back.bodies] == [b.material for b in case.bodies]
    assert back.options == case.options and back.name == case.name and back.units == case.units
    # Polylines come back exactly; the cover's upper chains arcs with polylines whose vertices the
    # JSON rounds to 1e-6, and chaining moves those ends onto the arcs: within the chordal error.
    for a, b in zip(case.bodies, back.bodies):
        assert a.lower.to_json() == b.lower.to_json()
        assert [p.kind for p in a.upper.parts()] == [p.kind for p in b.upper.parts()]
        assert same_curve(a.upper, b.upper) < 1e-6 < case.options.chordal_error
    assert case.bodies[0].upper.to_json() == back.bodies[0].upper.to_json()
    assert back.support.to_json() == case.support.to_json()
    assert same_curve(back.target, case.target) < 1e-9
    if ext == ".dxf":
        assert back.target.to_json() == case.target.to_json()


def test_revolution_round_trip(tmp_path):
    case = shared_case("v2/tread-on-drum")
    for ext in (".dxf", ".svg"):
        write_case(tmp_path / f"a{ext}", case)
        back = read_case(tmp_path / f"a{ext}")
        assert back.revolution == case.revolution
        assert [b.law for b in back.bodies] == [b.law for b in case.bodies]
        for a, b in zip(case.bodies, back.bodies):
            assert same_curve(a.lower, b.lower) < 1e-5 and same_curve(a.upper, b.upper) < 1e-5  # the JSON rounds to 1e-6


def test_axis_layer_gives_the_revolution(tmp_path):
    case = shared_case("v2/tread-on-drum")
    write_case(tmp_path / "a.dxf", case)
    doc = ezdxf.readfile(tmp_path / "a.dxf")
    (axis,) = doc.modelspace().query("LWPOLYLINE[layer=='AXIS']")
    axis.set_points([(0, -260), (5, -260)], format="xy")
    doc.saveas(tmp_path / "b.dxf")
    back = read_case(tmp_path / "b.dxf")
    assert back.revolution.axis == ((0.0, -260.0), (5.0, -260.0))
    assert all(b.law.axis == back.revolution.axis for b in back.bodies)


def test_units_option_scales_everything(tmp_path):
    case = plain_assembly()
    write_case(tmp_path / "a.dxf", case)
    back = read_case(tmp_path / "a.dxf", units="cm")
    assert back.units == "cm" and back.options.contact_tolerance == pytest.approx(1e-6)
    for a, b in zip(case.bodies, back.bodies):
        assert np.allclose(b.upper.at_fractions(np.linspace(0, 1, 9)), 0.1 * a.upper.at_fractions(np.linspace(0, 1, 9)))


# ---------------------------------------------------------------- contours


def contour_drawing(path, case: Problem, order=None, layer=lambda b: f"BODY-{b.name}"):
    """Each body of ``case`` drawn as one closed contour (its lower then upper curve) on its own layer, no stored data."""
    doc, msp = new_doc()
    _add_curve(msp, case.support, "SUPPORT", 1e-3)
    _add_curve(msp, case.target, "TARGET", 1e-3)
    for i in order or range(len(case.bodies)):
        b = case.bodies[i]
        _add_curve(msp, b.lower, layer(b), 1e-3)
        _add_curve(msp, b.upper, layer(b), 1e-3)
    doc.saveas(path)


@pytest.mark.parametrize("order", [(0, 1), (1, 0)])
def test_contours_find_the_lower_curves(tmp_path, order):
    case = plain_assembly()
    contour_drawing(tmp_path / "c.dxf", case, order)
    report = []
    back = read_case(tmp_path / "c.dxf", law=AreaRatio(0.9), report=report)
    assert sorted(b.name for b in back.bodies) == ["Top Layer", "base"]
    for b in back.bodies:
        a = next(x for x in case.bodies if x.name == b.name)
        assert b.lower.to_json() == a.lower.to_json()  # found on the support / on the base, same points, same way
        assert same_curve(b.upper, a.upper) == 0.0
        assert b.law == AreaRatio(0.9)
    assert back.layout.foundations[[b.name for b in back.bodies].index("Top Layer")] != ()
    assert any("lower curve from (0.1, 2) to (20, 2)" in line for line in report)


def test_contour_with_arcs_splits_exactly(tmp_path):
    """The cover of the shared strip, drawn as one closed contour with its fillet arcs, on the backing's contour."""
    case = shared_case(STRIP)
    contour_drawing(tmp_path / "c.dxf", case)
    back = read_case(tmp_path / "c.dxf", law=AreaRatio(0.9))
    for a, b in zip(case.bodies, back.bodies):
        assert a.lower.to_json() == b.lower.to_json()
        assert [p.kind for p in a.upper.parts()] == [p.kind for p in b.upper.parts()]
        assert same_curve(a.upper, b.upper) < 1e-6


def test_contour_lower_ending_inside_an_arc_cuts_the_arc(tmp_path):
    """A half disc lying on a support shorter than its base... the contact ends inside the arc of a rounded corner."""
    doc, msp = new_doc()
    msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "SUPPORT"})
    msp.add_line((0, -1), (10, -1), dxfattribs={"layer": "TARGET"})
    # a body whose base is an arc of radius 50 sagging onto the support... instead: base line + quarter arc
    msp.add_line((2, 0), (8, 0), dxfattribs={"layer": "BODY-bead"})
    msp.add_arc((8, 2), 2, 270, 360, dxfattribs={"layer": "BODY-bead"})
    msp.add_line((10, 2), (2, 2), dxfattribs={"layer": "BODY-bead"})
    msp.add_line((2, 2), (2, 0), dxfattribs={"layer": "BODY-bead"})
    doc.saveas(tmp_path / "c.dxf")
    back = read_case(tmp_path / "c.dxf", law=AreaRatio(1.0))
    (b,) = back.bodies
    assert b.lower.to_json() == {"polyline": [[2.0, 0.0], [8.0, 0.0]]}  # the arc only touches the support at its start
    assert [p.kind for p in b.upper.parts()] == ["arc", "polyline"]


def test_side_by_side_bodies(tmp_path):
    """Two blocks on the support sharing a side: the first found rests on the support, the other runs up the side."""
    doc, msp = new_doc()
    msp.add_line((0, 0), (20, 0), dxfattribs={"layer": "SUPPORT"})
    msp.add_line((0, -1), (20, -1), dxfattribs={"layer": "TARGET"})
    msp.add_lwpolyline([(0, 0), (10, 0), (10, 5), (0, 5)], close=True, dxfattribs={"layer": "BODY-left"})
    msp.add_lwpolyline([(10, 0), (20, 0), (20, 5), (10, 5)], close=True, dxfattribs={"layer": "BODY-right"})
    msp.add_line((0, -9), (20, -9), dxfattribs={"layer": "Dims"})
    doc.saveas(tmp_path / "c.dxf")
    report = []
    back = read_case(tmp_path / "c.dxf", law=AreaRatio(0.9), report=report)
    assert "ignored: 1 entity not used by the case: 1 on layer Dims" in report
    left, right = back.bodies
    assert left.lower.to_json() == {"polyline": [[0.0, 0.0], [10.0, 0.0]]}
    assert right.lower.to_json() == {"polyline": [[10.0, 5.0], [10.0, 0.0], [20.0, 0.0]]}
    assert back.layout.foundations == ((), (0,)) and back.layout.on_support == (True, True)


def test_mixed_forms(tmp_path):
    """One body on BODY-x-LOWER/-UPPER, the other as a contour resting on it."""
    case = plain_assembly()
    doc, msp = new_doc()
    _add_curve(msp, case.support, "SUPPORT", 1e-3)
    _add_curve(msp, case.target, "TARGET", 1e-3)
    top, base = case.bodies[1], case.bodies[0]
    _add_curve(msp, top.lower, "BODY-top", 1e-3)
    _add_curve(msp, top.upper, "BODY-top", 1e-3)
    _add_curve(msp, base.lower, "BODY-base-LOWER", 1e-3)
    _add_curve(msp, base.upper, "BODY-base-UPPER", 1e-3)
    doc.saveas(tmp_path / "c.dxf")
    back = read_case(tmp_path / "c.dxf", law=AreaRatio(0.9))
    assert [b.name for b in back.bodies] == ["top", "base"]
    assert back.bodies[0].lower.to_json() == top.lower.to_json()


def test_svg_group_per_body(tmp_path):
    """An SVG with each body a group named BODY-<name> holding its outline (y down, px units)."""
    svg = """<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="10mm" viewBox="0 0 20 10">
      <path id="SUPPORT" d="M0,10 L20,10"/><path class="target" d="M0,11 L20,11"/>
      <g id="BODY-base"><path d="M0,10 L20,10 L20,8 L0,8 Z"/></g>
      <g id="BODY-cap"><path d="M0,8 L20,8 L10,2 Z"/></g>
    </svg>"""
    (tmp_path / "c.svg").write_text(svg)
    back = read_case(tmp_path / "c.svg", law=AreaRatio(0.9))
    base, cap = back.bodies
    assert base.lower.to_json() == {"polyline": [[0.0, -10.0], [20.0, -10.0]]}
    assert cap.lower.to_json() == {"polyline": [[0.0, -8.0], [20.0, -8.0]]}
    assert back.layout.foundations == ((), (0,))


# ---------------------------------------------------------------- refusals


def one_line(exc) -> str:
    text = str(exc.value)
    assert "\n" not in text
    return text


def test_refusals(tmp_path):
    def drawing(*adds, name="c.dxf"):
        doc, msp = new_doc()
        for layer, pts in adds:
            msp.add_lwpolyline(pts, close=layer.startswith("BODY-") and not layer.endswith(("LOWER", "UPPER", "LOWR")),
                               dxfattribs={"layer": layer})
        doc.saveas(tmp_path / name)
        return tmp_path / name

    sup = ("SUPPORT", [(0, 0), (10, 0)])
    tgt = ("TARGET", [(0, -1), (10, -1)])
    box = ("BODY-box", [(0, 0), (10, 0), (10, 2), (0, 2)])
    floating = ("BODY-cloud", [(0, 5), (10, 5), (10, 6), (0, 6)])
    with pytest.raises(CaseError) as exc:
        read_case(drawing(sup, tgt, box, floating), law=AreaRatio(1))
    assert "BODY-cloud" in one_line(exc) and "no lower curve found" in str(exc.value) and "gap 3" in str(exc.value)
    with pytest.raises(CaseError) as exc:
        read_case(drawing(sup, tgt, ("BODY-box-LOWER", [(0, 0), (10, 0)]), ("BODY-box-LOWR", [(10, 0), (5, 3), (0, 0)])),
                  law=AreaRatio(1))
    assert "BODY-box-LOWR" in one_line(exc) and "did you mean BODY-box-UPPER" in str(exc.value)
    with pytest.raises(CaseError) as exc:
        read_case(drawing(sup, tgt, ("BODY-box-LOWER", [(0, 0), (10, 0)])), law=AreaRatio(1))
    assert "BODY-box-UPPER" in one_line(exc) and "not found" in str(exc.value)
    with pytest.raises(CaseError) as exc:
        read_case(drawing(("SUPORT", [(0, 0), (10, 0)]), tgt, box), law=AreaRatio(1))
    assert "no layer SUPPORT (did you mean SUPORT?)" in one_line(exc)
    with pytest.raises(CaseError) as exc:
        read_case(drawing(sup, tgt, box), law=None)
    assert "'box'" in one_line(exc) and "stores no law" in str(exc.value)
    with pytest.raises(CaseError) as exc:
        read_case(drawing(sup, tgt, box), law=AreaRatio(1), split=((0, 0), (10, 0)))
    assert one_line(exc).startswith("split:")
    with pytest.raises(CaseError) as exc:
        read_case(drawing(sup, tgt, box, ("BODY-box-LOWER", [(0, 0), (10, 0)])), law=AreaRatio(1))
    assert "BODY-box" in one_line(exc) and "either as one closed contour" in str(exc.value)
    with pytest.raises(CaseError) as exc:
        read_case(drawing(sup, tgt, box, ("LOWER", [(0, 0), (10, 0)])), law=AreaRatio(1))
    assert "layer LOWER" in one_line(exc)
    # A body touching its foundations in two separate stretches (a bridge over a gap in the support).
    bridge = ("BODY-bridge", [(0, 0), (3, 0), (3, 1), (7, 1), (7, 0), (10, 0), (10, 2), (0, 2)])
    with pytest.raises(CaseError) as exc:
        read_case(drawing(("SUPPORT", [(0, 0), (10, 0)]), tgt, bridge), law=AreaRatio(1))
    assert "BODY-bridge" in one_line(exc) and "2 separate stretches" in str(exc.value)
    # The assembly's own checks still run: an overhang into the air is refused naming the gap.
    with pytest.raises(SectionDeformError) as exc:
        read_case(drawing(sup, tgt, ("BODY-a-LOWER", [(0, 0), (12, 0)]), ("BODY-a-UPPER", [(12, 0), (0, 2), (0, 0)])),
                  law=AreaRatio(1))
    assert "rests on nothing" in one_line(exc)


def test_names_that_cannot_be_layers(tmp_path):
    bad = plain_assembly()
    renamed = bad.replace(bodies=(bad.bodies[0], bad.bodies[1].__class__(**{**bad.bodies[1].__dict__, "name": "a/b"})))
    with pytest.raises(CaseError) as exc:
        write_case(tmp_path / "a.dxf", renamed)
    assert one_line(exc).startswith("bodies[1].name:")
    assert not (tmp_path / "a.dxf").exists()
    write_case(tmp_path / "a.svg", renamed)  # an SVG id may hold it
    assert read_case(tmp_path / "a.svg").bodies[1].name == "a/b"
    twins = bad.replace(bodies=(bad.bodies[0], bad.bodies[1].__class__(**{**bad.bodies[1].__dict__, "name": "BASE"})))
    with pytest.raises(CaseError) as exc:
        write_case(tmp_path / "b.svg", twins)
    assert "only by case" in one_line(exc)


# ---------------------------------------------------------------- results and meshes


@pytest.fixture(scope="module")
def strip_result():
    from sectiondeform.deform import Deformer

    case = shared_case(STRIP)
    return case, Deformer(case).deform()


def test_result_dxf_one_layer_per_body(tmp_path, strip_result):
    from sectiondeform.io import write_result

    case, result = strip_result
    write_result(tmp_path / "r.dxf", result, case=case)
    msp = ezdxf.readfile(tmp_path / "r.dxf").modelspace()
    for b in result.bodies:
        for state, lower, upper in (("DEFORMED", b.lower, b.upper), ("INITIAL", b.initial_lower, b.initial_upper)):
            for side, pts in (("LOWER", lower), ("UPPER", upper)):
                (e,) = msp.query(f"LWPOLYLINE[layer=='{state}-{b.name}-{side}']")
                assert np.array_equal(np.array(e.get_points("xy")), pts)
        for which, mesh in (("FINAL", b.final_mesh), ("INITIAL", b.initial_mesh)):
            cells = msp.query(f"LWPOLYLINE[layer=='MESH-{which}-{b.name}']")
            assert len(cells) == len(mesh.cells)
    (support,) = msp.query("LWPOLYLINE[layer=='SUPPORT']")
    assert np.array_equal(np.array(support.get_points("xy"))[[0, -1]], np.vstack(case.support.ends))
    # A result drawing is not a case: reading it says there is no body.
    with pytest.raises(CaseError) as exc:
        read_case(tmp_path / "r.dxf", law=AreaRatio(1))
    assert "no body" in one_line(exc)


def test_result_svg_groups(tmp_path, strip_result):
    import xml.etree.ElementTree as ET

    from sectiondeform.io import write_result

    case, result = strip_result
    write_result(tmp_path / "r.svg", result)
    ids = {g.get("id") for g in ET.parse(tmp_path / "r.svg").getroot().iter("{http://www.w3.org/2000/svg}g")}
    for b in result.bodies:
        assert {f"DEFORMED-{b.name}-LOWER", f"DEFORMED-{b.name}-UPPER", f"INITIAL-{b.name}-UPPER",
                f"MESH-FINAL-{b.name}", f"MESH-INITIAL-{b.name}"} <= ids
    assert "SUPPORT" not in ids  # only drawn when the case is given


def test_result_dxf_splines_follow_each_bodys_deformed_curves(tmp_path, strip_result):
    import shapely

    from sectiondeform.io import write_result

    case, result = strip_result
    tol = 1e-3
    write_result(tmp_path / "s.dxf", result, spline=True, chordal_error=tol)
    msp = ezdxf.readfile(tmp_path / "s.dxf").modelspace()
    for b in result.bodies:
        for side, pts in (("LOWER", b.lower), ("UPPER", b.upper)):
            (e,) = msp.query(f"SPLINE[layer=='DEFORMED-{b.name}-{side}']")
            curve = shapely.LineString([(p[0], p[1]) for p in e.construction_tool().flattening(tol / 100)])
            assert shapely.distance(shapely.points(pts), curve).max() <= 1.01 * tol
        assert not msp.query(f"LWPOLYLINE[layer=='DEFORMED-{b.name}-LOWER']")


@pytest.mark.parametrize("ext", [".vtu", ".vtk", ".msh"])
def test_mesh_tags_each_body(tmp_path, strip_result, ext):
    meshio = pytest.importorskip("meshio")
    from sectiondeform.io import write_result

    case, result = strip_result
    write_result(tmp_path / f"r{ext}", result)
    m = meshio.read(tmp_path / f"r{ext}")
    body = np.concatenate(m.cell_data["body"])
    element = np.concatenate(m.cell_data["element"])
    cells = np.concatenate([c.data for c in m.cells])
    finals = [b.final_mesh for b in result.bodies]
    assert np.array_equal(body, np.repeat([1, 2], [len(f.cells) for f in finals]))
    assert np.array_equal(element, np.concatenate([np.arange(len(f.cells)) for f in finals]))
    # Each element's corners are its body's own nodes, at the body's final coordinates.
    offsets = np.cumsum([0] + [len(f.points) for f in finals])
    for k, f in enumerate(finals):
        mine = cells[body == k + 1]
        assert mine.min() >= offsets[k] and mine.max() < offsets[k + 1]
        assert np.allclose(m.points[mine, :2], f.points[f.cells], rtol=0, atol=1e-12)
        assert np.allclose(m.point_data["displacement"][offsets[k]:offsets[k + 1], :2],
                           f.points - result.bodies[k].initial_mesh.points, rtol=0, atol=1e-12)
    if ext == ".msh":
        assert {k: v.tolist() for k, v in m.field_data.items()} == {"backing": [1, 2], "cover": [2, 2]}
        assert np.array_equal(np.concatenate(m.cell_data["gmsh:physical"]), body)


def test_mesh_inp_element_sets(tmp_path, strip_result):
    meshio = pytest.importorskip("meshio")
    from sectiondeform.io.meshes import write_mesh

    case, result = strip_result
    write_mesh(tmp_path / "r.inp", result, "initial")
    text = (tmp_path / "r.inp").read_text()
    assert "ELSET=backing" in text.replace(" ", "") or "ELSET=BACKING" in text.upper().replace(" ", "")
    m = meshio.read(tmp_path / "r.inp")
    assert len(m.points) == sum(len(b.initial_mesh.points) for b in result.bodies)


# ---------------------------------------------------------------- property: stacks of boxes


def test_stacked_boxes_any_drawing_order_any_start_any_direction():
    """Nested boxes stacked on a support, drawn as closed contours in any order, from any corner, either way:
    each body's lower curve is exactly its bottom edge, left to right, and it rests on the box below.
    """
    import tempfile
    from pathlib import Path

    from hypothesis import given, settings
    from hypothesis import strategies as st

    @settings(max_examples=8, deadline=None)
    @given(st.lists(st.tuples(st.integers(0, 3), st.integers(0, 3), st.integers(1, 4)), min_size=1, max_size=4),
           st.randoms(use_true_random=False))
    def check(layers, rnd):
        boxes, x0, x1, y = [], 0, 40, 0
        for left, right, height in layers:
            x0, x1 = x0 + left, x1 - right
            boxes.append((x0, x1, y, y + height))
            y += height
        doc, msp = new_doc()
        msp.add_line((-5, 0), (45, 0), dxfattribs={"layer": "SUPPORT"})
        msp.add_line((-5, -1), (45, -1), dxfattribs={"layer": "TARGET"})
        order = list(range(len(boxes)))
        rnd.shuffle(order)
        for i in order:
            a, b, lo, hi = boxes[i]
            corners = [(a, lo), (b, lo), (b, hi), (a, hi)]
            k = rnd.randrange(4)
            corners = corners[k:] + corners[:k]
            if rnd.random() < 0.5:
                corners = corners[::-1]
            msp.add_lwpolyline(corners, close=True, dxfattribs={"layer": f"BODY-b{i}"})
        with tempfile.TemporaryDirectory() as tmp:
            doc.saveas(Path(tmp) / "s.dxf")
            case = read_case(Path(tmp) / "s.dxf", law=AreaRatio(0.9))
        assert [b.name for b in case.bodies] == [f"b{i}" for i in order]
        for body in case.bodies:
            i = int(body.name[1:])
            a, b, lo, hi = boxes[i]
            assert body.lower.to_json() == {"polyline": [[float(a), float(lo)], [float(b), float(lo)]]}
            assert body.upper.to_json() == {"polyline": [[float(b), float(lo)], [float(b), float(hi)],
                                                         [float(a), float(hi)], [float(a), float(lo)]]}
            found = case.layout.foundations[case.bodies.index(body)]
            assert [case.bodies[j].name for j in found] == ([] if i == 0 else [f"b{i - 1}"])

    check()


def test_contact_ending_inside_a_segment(tmp_path):
    """A block overhanging the end of the support: its lower curve stops where the support does (to the sampling
    step, 1/1024 of the drawing's diagonal), the overhang is free.
    """
    doc, msp = new_doc()
    msp.add_line((-2, 0), (6, 0), dxfattribs={"layer": "SUPPORT"})
    msp.add_line((-2, -1), (6, -1), dxfattribs={"layer": "TARGET"})
    msp.add_lwpolyline([(10, 2), (0, 2), (0, 0), (10, 0)], close=True, dxfattribs={"layer": "BODY-block"})
    doc.saveas(tmp_path / "c.dxf")
    (b,) = read_case(tmp_path / "c.dxf", law=AreaRatio(0.9)).bodies
    lower = b.lower.vertices
    step = np.hypot(12, 2) / 1024
    assert lower.shape == (2, 2) and lower[0].tolist() == [0.0, 0.0]
    assert lower[1, 1] == 0.0 and 6 - step <= lower[1, 0] <= 6
    assert np.array_equal(b.upper.vertices[0], lower[1]) and b.upper.vertices[1].tolist() == [10.0, 0.0]
