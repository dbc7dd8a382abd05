"""The paper model's applicability and extent warnings, and distances read against the section's height."""

import math
import re

import numpy as np
import pytest
import shapely

import sectiondeform as sd
from sectiondeform.applicability import BEND_LIMIT, HEIGHT_SCALE_LIMITS, OVERHANG_LIMIT
from sectiondeform.compare import hausdorff_distance, section_height
from sectiondeform.errors import MeshError

from conftest import box_case, data_case_path


def _number(pattern: str, text: str) -> float:
    m = re.search(pattern, text)
    assert m, f"{pattern!r} not in {text!r}"
    return float(m.group(1))


def _warnings(result, prefix):
    return [w for w in result.warnings if w.startswith(prefix)]


def test_no_warning_on_the_paper_example():
    r = sd.deform(sd.load_case(data_case_path("paper-example")))
    assert r.warnings == ()


def test_overhang_warns_with_its_ratio_and_names_the_hyperelastic_model():
    # A cap 8 wide on a foot 2 wide: 3 beyond each end; height = |(5, 3) - (2, 0)| = sqrt(18).
    upper = [[2.0, 0.0], [2.0, 1.0], [5.0, 1.0], [5.0, 3.0], [-3.0, 3.0], [-3.0, 1.0], [0.0, 1.0], [0.0, 0.0]]
    r = sd.deform(sd.case_from_dict(box_case(width=2.0, upper=upper)))
    (w,) = _warnings(r, "applicability")
    ratio = _number(r"overhangs its lower curve by ([\d.]+) x its height", w)
    assert ratio == pytest.approx(3.0 / math.sqrt(18.0), abs=0.006)
    assert ratio > OVERHANG_LIMIT
    assert 'option model at hyperelastic' in w


def _bent_box(radius, width=60.0, height=20.0):
    """A box ``width`` x ``height`` on a straight base, bent onto an arc of ``radius`` (> 0: towards the section)."""
    half = math.degrees(0.5 * width / abs(radius))
    centre, start, end = ([30.0, radius], -90.0 - half, -90.0 + half) if radius > 0 else ([30.0, radius], 90.0 + half, 90.0 - half)
    target = {"arc": {"center": centre, "radius": abs(radius), "start_deg": start, "end_deg": end}}
    return sd.case_from_dict(box_case(width=width, height=height, target=target))


def test_a_thick_section_on_a_bent_target_warns_with_height_over_radius():
    # Bent away from the section: the layers open out, the paper model places them and warns.
    radius, height = -40.0, 20.0
    r = sd.deform(_bent_box(radius, height=height))
    (w,) = _warnings(r, "applicability")
    bend = _number(r"bends the base by ([\d.]+) rad", w)
    assert bend == pytest.approx(height / abs(radius), rel=0.03)
    assert bend > BEND_LIMIT and 'option model at hyperelastic' in w


def test_a_thick_section_bent_towards_itself_is_refused_naming_the_hyperelastic_model():
    # Bent towards the section by the same height over radius: the top layer, at radius 40 - 20, is
    # half as long as the base, so an element's aspect changes beyond ASPECT_LIMIT: refused, not a warning.
    with pytest.raises(MeshError, match=r"aspect ratio changes [\d.]+-fold .*beyond what the paper model can mean; "
                                        r"refused: .*hyperelastic") as info:
        sd.deform(_bent_box(40.0))
    assert "\n" not in str(info.value)


def test_a_gentle_bend_does_not_warn():
    r = sd.deform(sd.case_from_dict(box_case(width=60.0, height=5.0, target={
        "arc": {"center": [30.0, 100.0], "radius": 100.0, "start_deg": -90.0 - 17.19, "end_deg": -90.0 + 17.19}})))
    assert _warnings(r, "applicability") == []


def test_a_short_target_under_a_long_lower_curve_warns_with_the_figures():
    # Straight lower curve 90 long onto a straight target 0.45 x as long: columns stay upright, the
    # widths shrink by s = 0.45, so the heights grow k = r / s (area k s A0 = r A0) and an element's
    # aspect changes k / s = r / s² = 3.46-fold, within ASPECT_LIMIT: warnings with the figures.
    case = sd.load_case(data_case_path("grooved-tread"))
    s, ratio = 0.45, 0.7
    r = sd.Deformer(case).deform(np.array([[45.0 - 45.0 * s, 0.0], [45.0 + 45.0 * s, 0.0]]), law=sd.AreaRatio(ratio))
    assert r.info.height_scale == pytest.approx(ratio / s, rel=1e-9)
    text = " ".join(_warnings(r, "result"))
    assert _number(r"k = ([\d.]+)", text) == pytest.approx(ratio / s, abs=0.005)  # shown to 3 digits
    lo = _number(r"stretched by ([\d.]+) to", text)
    hi = _number(r"stretched by [\d.]+ to ([\d.]+)", text)
    assert lo == pytest.approx(s, rel=1e-2) and hi == pytest.approx(s, rel=1e-2)


def test_a_much_shorter_target_is_refused_with_its_height_scale():
    # Onto a target 9 times shorter: k = 9 r = 8.1, beyond HEIGHT_SCALE_LIMITS: refused with the figure.
    case = sd.load_case(data_case_path("grooved-tread"))
    with pytest.raises(MeshError) as info:
        sd.Deformer(case).deform(np.array([[40.0, 0.0], [50.0, 0.0]]))
    message = str(info.value)
    assert "\n" not in message and 'option model at hyperelastic' in message
    assert _number(r"height scale k = ([\d.]+)", message) == pytest.approx(9.0 * case.law.ratio, rel=1e-2)
    assert _number(r"height scale k = ([\d.]+)", message) > HEIGHT_SCALE_LIMITS[1]


def test_section_height_matches_shapely():
    rng = np.random.default_rng(3)
    lower = np.column_stack((np.linspace(0.0, 10.0, 7), rng.normal(0.0, 0.5, 7)))
    upper = rng.uniform(-5.0, 15.0, (40, 2))
    expected = max(shapely.LineString(lower).distance(shapely.Point(p)) for p in upper)
    assert section_height(lower, upper) == pytest.approx(expected, rel=1e-12)


def test_hausdorff_in_units_matches_shapely():
    rng = np.random.default_rng(5)
    t = np.linspace(0.0, np.pi, 30)
    a = np.column_stack((10.0 * np.cos(t), 6.0 * np.sin(t)))
    b = a + rng.normal(0.0, 0.3, a.shape)
    exact = shapely.hausdorff_distance(shapely.LineString(a), shapely.LineString(b), densify=1e-3)
    assert hausdorff_distance(a, b) == pytest.approx(exact, abs=2e-3 * 31.0)


def test_validation_reports_the_distance_in_units_and_over_the_height():
    pytest.importorskip("skfem")
    from sectiondeform.reference.validation import validate

    case = sd.load_case(data_case_path("grooved-tread"))
    v = validate(case, model="paper", fast_runs=1)
    report = v.to_json()
    expected_height = max(shapely.LineString(v.fast.initial_lower).distance(shapely.Point(p)) for p in v.fast.initial_upper)
    assert report["height"] == pytest.approx(expected_height, rel=1e-12)
    ref_upper = v.reference.bodies[0].upper
    exact = shapely.hausdorff_distance(shapely.LineString(v.fast.upper), shapely.LineString(ref_upper), densify=1e-3)
    assert v.bodies[0].shape.hausdorff == pytest.approx(exact, rel=1e-2)
    assert report["hausdorff_over_height"] == pytest.approx(v.bodies[0].shape.hausdorff / expected_height)
    assert report["thickness"] == pytest.approx(v.fast.area_initial / case.lower.length)
    assert any("of the height" in line for line in v.lines())
