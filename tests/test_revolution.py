"""Bodies of revolution: Pappus volumes, the volume law in the paper model, refusals.

Volumes are checked against computations that do not go through
:mod:`sectiondeform.pappus`: closed forms (a rectangle sweeps an annular
cylinder), GEOS's area and centroid (shapely), and a numerical integration
over thin strips parallel to the axis.
"""

import json
import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.cli import main
from sectiondeform.curves import Polyline
from sectiondeform.deform import deform
from sectiondeform.errors import CaseError, GeometryError, LawError
from sectiondeform.io.case import case_from_dict
from sectiondeform.laws import AreaRatio, VolumeRatio, law_from_json
from sectiondeform.models.paper import scale_roots
from sectiondeform.pappus import first_moment, moment_coefficients, volume

from conftest import CASES_DIR

DRUM = CASES_DIR / "v2" / "tread-on-drum.json"
X_AXIS = ((0.0, 0.0), (1.0, 0.0))


def pappus_by_geos(contour, axis=X_AXIS):
    """Volume of revolution from shapely's area and centroid (the axis turned onto the x axis)."""
    (x0, y0), (x1, y1) = axis
    angle = math.atan2(y1 - y0, x1 - x0)
    c, s = math.cos(-angle), math.sin(-angle)
    p = np.asarray(contour) - (x0, y0)
    rotated = np.column_stack((c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]))
    poly = shapely.Polygon(rotated)
    return 2 * math.pi * poly.area * abs(poly.centroid.y)


def one_body(lower, upper, law, target=None, axis=X_AXIS, support=None):
    """A one-body ``section-case/2`` of revolution (the body resting on the support)."""
    support = lower if support is None else support
    return {
        "format": "section-case/2",
        "support": {"polyline": [list(p) for p in support]},
        "target": {"polyline": [list(p) for p in (target if target is not None else support)]},
        "revolution": {"axis": [list(p) for p in axis]},
        "bodies": [{"name": "ring", "lower": {"polyline": [list(p) for p in lower]},
                    "upper": {"polyline": [list(p) for p in upper]}, "law": law}],
    }


def rectangle(x0, x1, y0, y1):
    """Lower edge and upper path of a rectangle resting on y = y0 (counter-clockwise)."""
    return [(x0, y0), (x1, y0)], [(x1, y0), (x1, y1), (x0, y1), (x0, y0)]


# -- Pappus --------------------------------------------------------------------


@pytest.mark.parametrize("x0, x1, y0, y1", [(0, 3, 2, 5), (-1, 1, 0, 1), (10, 10.5, 100, 130)])
def test_a_rectangle_sweeps_an_annular_cylinder(x0, x1, y0, y1):
    ring = np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], dtype=float)
    exact = math.pi * (x1 - x0) * (y1**2 - y0**2)  # pi (R_out² - R_in²) x length
    assert volume(ring, X_AXIS) == pytest.approx(exact, rel=1e-13)
    assert volume(ring[::-1], X_AXIS) == pytest.approx(exact, rel=1e-13)  # orientation does not matter
    # 2 pi R A with R the centroid's distance; the axis drawn the other way changes only the sign of Q
    assert first_moment(ring, ((1.0, 0.0), (0.0, 0.0))) == pytest.approx(-(x1 - x0) * (y1 - y0) * 0.5 * (y0 + y1))


def test_a_non_convex_polygon_about_a_tilted_axis_against_strip_integration():
    ell = np.array([(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (0, 3)], dtype=float) + (6.0, 2.0)
    axis = ((0.0, -1.0), (2.0, 0.0))
    # Numerical integration: the polygon in the axis frame cut into thin strips parallel to the axis.
    e = np.array([2.0, 1.0]) / math.sqrt(5.0)
    nu = np.array([-e[1], e[0]])
    rel = ell - axis[0]
    frame = shapely.Polygon(np.column_stack((rel @ e, rel @ nu)))
    lo, hi = frame.bounds[1], frame.bounds[3]
    edges = np.linspace(lo, hi, 4001)
    big = 1e3
    strips = shapely.intersection(frame, shapely.box(-big, edges[:-1], big, edges[1:]))
    areas = shapely.area(strips)
    ys = np.array([g.centroid.y if not g.is_empty else 0.0 for g in strips])
    numeric = 2 * math.pi * abs((areas * ys).sum())
    midpoint = 2 * math.pi * abs((areas * 0.5 * (edges[1:] + edges[:-1])).sum())  # O(h²) quadrature
    assert volume(ell, axis) == pytest.approx(numeric, rel=1e-12)
    assert volume(ell, axis) == pytest.approx(midpoint, rel=1e-6)
    assert volume(ell, axis) == pytest.approx(pappus_by_geos(ell, axis), rel=1e-12)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(-5, 5), st.floats(-5, 5)), min_size=3, max_size=8),
       st.lists(st.tuples(st.floats(-2, 2), st.floats(-2, 2)), min_size=3, max_size=8),
       st.floats(0.0, 3.0))
def test_the_moment_cubic_matches_the_moment_of_the_polygon_at_every_k(fixed, moving, k):
    n = min(len(fixed), len(moving))
    f, g = np.array(fixed[:n]), np.array(moving[:n])
    axis = ((0.3, -7.0), (1.1, -6.5))
    c = moment_coefficients(f, g, axis)
    scale = 1.0 + np.abs(f).max() + np.abs(g).max()
    assert np.polynomial.polynomial.polyval(k, c) == pytest.approx(first_moment(f + k * g, axis), abs=1e-10 * scale**4)


def test_scale_roots_of_a_cubic_are_exact_and_nearest_first():
    # (k - 0.5)(k - 2)(k + 1) = k³ - 1.5k² - 1.5k + 1
    roots = scale_roots([1.0, -1.5, -1.5, 1.0], 0.0, 1.8)
    assert roots == pytest.approx([2.0, 0.5], abs=1e-15)
    assert scale_roots([1.0, 0.0, 0.0, 1.0], 0.5, 1.0) == []  # k³ + 1 = 0.5 has no positive root


# -- the law -------------------------------------------------------------------


def test_volume_ratio_law_reads_and_writes_its_key_and_needs_an_axis():
    law = law_from_json({"volume_ratio": 0.98}, axis=X_AXIS)
    assert law == VolumeRatio(0.98, X_AXIS) and law.to_json() == {"volume_ratio": 0.98}
    assert law_from_json({"volume_ratio": 0.98}).axis is None  # an extruded body's growth
    with pytest.raises(CaseError, match="law.volume_ratio: must be between"):
        VolumeRatio(200.0)
    with pytest.raises(LawError, match="volume_ratio sets the volume, not the area"):
        VolumeRatio(1.0, X_AXIS).target_area(1.0)
    assert AreaRatio(0.8).target(10.0) == pytest.approx(8.0)


def test_the_tread_on_drum_deforms_with_each_volume_exact():
    problem = case_from_dict(json.loads(DRUM.read_text()))
    result = deform(problem)
    ratios = {"undertread": 1.0, "tread": 0.98}
    drum = ((0.0, -250.0), (1.0, -250.0))
    def sampled(case_body, n):
        # the volume of the curves themselves: polylines by their vertices, arcs by n points (error ~ 1/n^2)
        return pappus_by_geos(np.concatenate([
            p.vertices if isinstance(p, Polyline) else p.at_fractions(np.linspace(0.0, 1.0, n))
            for c in (case_body.lower, case_body.upper) for p in c.parts()]), drum)  # a gap between pieces: its chord

    for body, case_body in zip(result.bodies, problem.bodies):
        v0 = (4.0 * sampled(case_body, 1 << 12) - sampled(case_body, 1 << 11)) / 3.0  # extrapolated
        v1 = pappus_by_geos(body.contour, drum)
        assert body.volume_initial == pytest.approx(v0, rel=1e-11)
        assert abs(v1 - ratios[body.name] * body.volume_initial) <= 1e-9 * v0
        assert abs(body.relative_error) <= 1e-9 and body.measure == "volume"
        data = body.to_json(meshes=False)
        assert set(data["volume"]) == {"initial", "target", "final", "relative_error"}
        assert set(data["area"]) == {"initial", "final"}  # the law sets the volume, not the area
    # the incompressible undertread moved outwards: area x centroid radius kept
    under = result.body("undertread")
    r0 = shapely.Polygon(under.initial_contour).centroid.y + 250
    r1 = shapely.Polygon(under.contour).centroid.y + 250
    assert under.area_final * r1 == pytest.approx(under.area_initial * r0, rel=1e-9)
    assert under.area_final < under.area_initial


def test_the_cli_writes_the_volumes_of_the_tread_on_drum(tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["deform", str(DRUM), "-o", str(out), "--no-meshes"]) == 0
    data = json.loads(out.read_text())
    assert data["format"] == "section-result/2"
    assert all(abs(b["volume"]["relative_error"]) <= 1e-9 for b in data["bodies"])
    assert "volume" in capsys.readouterr().out


def test_area_laws_in_a_revolution_case_carry_the_volume_without_target():
    data = json.loads(DRUM.read_text())
    data["bodies"][0]["law"] = {"area_ratio": 0.9}
    result = deform(case_from_dict(data))
    under = result.body("undertread").to_json(meshes=False)
    assert set(under["volume"]) == {"initial", "final"} and under["area"]["target"] == pytest.approx(405.0)


@pytest.mark.parametrize("shift", [0.0, 5.0, 40.0, -20.0])
def test_an_incompressible_rectangle_moved_radially_keeps_area_times_radius(shift):
    """Rectangle w x h on a flat support at radius R moved rigidly to R + shift: heights k h with
    w k h (R + shift + k h / 2) = w h (R + h / 2), a quadratic solved by hand.
    """
    w, h, radius = 10.0, 2.0, 50.0
    lower, upper = rectangle(0.0, w, radius, radius + h)
    target = [(0.0, radius + shift), (w, radius + shift)]
    result = deform(case_from_dict(one_body(lower, upper, {"volume_ratio": 1.0}, target)))
    body = result.bodies[0]
    r1 = radius + shift
    k = (-r1 + math.sqrt(r1**2 + 2 * h * (radius + h / 2))) / h
    top = body.upper[1:3]  # the images of the two top corners
    assert top[:, 1] == pytest.approx(r1 + k * h, abs=1e-9)
    c0 = shapely.Polygon(body.initial_contour).centroid.y
    c1 = shapely.Polygon(body.contour).centroid.y
    assert body.area_final / body.area_initial == pytest.approx(c0 / c1, rel=1e-9)
    if shift:
        assert (body.area_final < body.area_initial) == (shift > 0)
    else:
        assert body.area_final == pytest.approx(body.area_initial, rel=1e-12)


sections = st.tuples(
    st.floats(2.0, 30.0),  # width
    st.floats(0.05, 0.4),  # height over width
    st.floats(20.0, 300.0),  # distance of the base from the axis
    st.floats(0.6, 1.6),  # volume ratio
    st.floats(-0.3, 0.3),  # turn of the target, radians
    st.floats(-4.0, 4.0),  # radial move of the target
    st.floats(0.0, 0.4),  # bulge of the upper curve, fraction of the height
)


@settings(max_examples=25, deadline=None)
@given(sections)
def test_the_volume_law_holds_to_1e_9_on_generated_sections_and_targets(params):
    w, h, radius, ratio, turn, move, bulge = params
    h *= w
    lower = [(0.0, radius), (w, radius)]
    xs = np.linspace(w, 0.0, 7)
    top = radius + h * (1.0 + bulge * np.sin(np.pi * xs / w))
    upper = [(w, radius)] + [(float(x), float(y)) for x, y in zip(xs, top)] + [(0.0, radius)]
    c, s = math.cos(turn), math.sin(turn)
    target = [(0.0, radius + move), (w * c, radius + move + w * s)]
    case = one_body(lower, upper, {"volume_ratio": ratio}, target)
    body = deform(case_from_dict(case)).bodies[0]
    v0 = pappus_by_geos(body.initial_contour)
    assert abs(pappus_by_geos(body.contour) - ratio * v0) <= 1e-9 * ratio * v0


def test_the_physical_root_is_taken_when_the_body_grows_towards_the_axis():
    """A strip hanging from a support at radius 10 towards the axis: V(k) = 2 pi w k h (10 - k h / 2)
    rises to its largest value when the strip reaches the axis, then falls; of the two roots the one
    short of the axis is taken, and a volume beyond the largest is refused naming the body.
    """
    w, h, radius = 4.0, 2.0, 10.0
    lower = [(w, radius), (0.0, radius)]  # drawn right to left: the body lies below, towards the axis
    upper = [(0.0, radius), (0.0, radius - h), (w, radius - h), (w, radius)]
    v0 = 2 * math.pi * w * h * (radius - h / 2)
    # 1.7: the smaller root k = 1.89 is within the paper model's height scale [0.5, 2] (2.5 gives k = 3.42, refused);
    # the other root, 8.11, lies beyond the axis.
    body = deform(case_from_dict(one_body(lower, upper, {"volume_ratio": 1.7}))).bodies[0]
    kh = radius - math.sqrt(radius**2 - 2 * 1.7 * v0 / (2 * math.pi * w))  # the smaller root of the quadratic
    assert body.info.height_scale == pytest.approx(kh / h, rel=1e-9)
    assert body.upper[1:3, 1] == pytest.approx(radius - kh, abs=1e-9)
    assert (body.contour[:, 1] >= 0).all()
    with pytest.raises(LawError, match=r"^bodies\[0\] 'ring': law: no height scale gives the volume"):
        deform(case_from_dict(one_body(lower, upper, {"volume_ratio": 3.0})))


# -- refusals ------------------------------------------------------------------


def test_a_volume_law_without_revolution_is_a_growth_of_version_2_only():
    data = json.loads(DRUM.read_text())
    del data["revolution"]
    law = case_from_dict(data).bodies[0].law
    assert law.axis is None and law.measure == "area" and law.growth == law.ratio
    v1 = {"format": "section-case/1", "lower": {"polyline": [[0, 0], [1, 0]]},
          "upper": {"polyline": [[1, 0], [1, 1], [0, 1], [0, 0]]}, "target": {"polyline": [[0, 0], [1, 0]]},
          "law": {"volume_ratio": 1.0}}
    with pytest.raises(CaseError, match=r"^format: section-case/1 holds one body .* growth"):
        case_from_dict(v1)


def test_bodies_on_both_sides_of_the_axis_or_crossed_by_it_are_refused():
    lower, upper = rectangle(0.0, 4.0, -1.0, 1.0)
    with pytest.raises(GeometryError, match=r"^bodies\[0\] 'ring': the revolution axis crosses it"):
        case_from_dict(one_body(lower, upper, {"volume_ratio": 1.0}))
    data = json.loads(DRUM.read_text())
    data["revolution"]["axis"] = [[0, 8], [1, 8]]  # between the undertread and the tread's top
    with pytest.raises(GeometryError, match=r"^bodies\[1\] 'tread': the revolution axis crosses it"):
        case_from_dict(data)
    data["revolution"]["axis"] = [[0, 3], [1, 3]]  # along the shared line: undertread below, tread above
    with pytest.raises(GeometryError, match=r"^bodies\[1\] 'tread': it lies on the other side of the revolution axis"):
        case_from_dict(data)


def test_a_target_that_brings_the_body_across_the_axis_is_refused():
    lower, upper = rectangle(0.0, 4.0, 1.0, 2.0)
    target = [(0.0, -1.0), (4.0, -1.0)]  # the support moved to the other side of the axis
    with pytest.raises(GeometryError, match=r"^bodies\[0\] 'ring': result: the deformed body crosses the revolution axis"):
        deform(case_from_dict(one_body(lower, upper, {"area_ratio": 1.0}, target)))


