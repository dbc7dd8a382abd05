import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.errors import GeometryError
from sectiondeform.section import polygon_area

from conftest import box_case


def test_box_section_figures():
    s = sd.build_section(sd.case_from_dict(box_case(10, 4)))
    assert s.area == pytest.approx(40.0, rel=1e-14)
    assert s.orientation == 1
    assert s.thickness == pytest.approx(4.0)
    assert np.allclose(s.lower[[0, -1]], [[0, 0], [10, 0]])
    # the straight lower curve is split so that no step exceeds T / 4
    assert np.diff(s.fractions).max() * 10 <= 1.0 + 1e-9
    assert s.upper.tolist() == [[10, 0], [10, 4], [0, 4], [0, 0]]


def test_clockwise_section_is_accepted():
    d = box_case()
    d["lower"] = {"polyline": [[10, 0], [0, 0]]}
    d["upper"] = {"polyline": [[0, 0], [0, 4], [10, 4], [10, 0]]}
    d["target"] = d["lower"]
    s = sd.build_section(sd.case_from_dict(d))
    assert s.orientation == -1 and s.area == pytest.approx(40.0)
    r = sd.deform(sd.case_from_dict(d))
    assert np.allclose(r.upper, s.upper, atol=1e-12)


def test_target_bends_are_resolved_in_the_lower_discretisation():
    d = box_case(100, 20, target={"arc": {"center": [50, 100], "radius": 100, "start_deg": -120, "end_deg": -60}})
    s = sd.build_section(sd.case_from_dict(d))
    case = sd.case_from_dict(d)
    nodes = case.target.at_fractions(s.fractions)
    # the target polyline through the image of the lower nodes stays within the chordal error
    mid = case.target.at_fractions(0.5 * (s.fractions[1:] + s.fractions[:-1]))
    chord_mid = 0.5 * (nodes[1:] + nodes[:-1])
    assert np.hypot(*(mid - chord_mid).T).max() <= s.chordal_error * 1.01


def test_polygon_matches_exact_curve_area():
    c = sd.load_case(sd.example_case_path())
    s = sd.build_section(c)
    assert s.curve_area == pytest.approx(4379.0, abs=0.01)
    assert abs(s.area - s.curve_area) <= 1e-5 * s.curve_area


@pytest.mark.parametrize(
    "upper, message",
    [
        ([[10, 0.5], [10, 4], [0, 4], [0, 0]], "upper: starts at .* from the lower curve's end B"),
        ([[10, 0], [10, 4], [0, 4], [0, 1]], "upper: ends at .* from the lower curve's start A"),
        ([[10, 0], [0, 4], [10, 4], [0, 0]], "crosses itself"),
        ([[10, 0], [10, 4], [-2, -1], [0, 0]], r"crosses itself \(lower edge 0 meets upper edge"),
        ([[10, 0], [5, 0.0], [0, 0]], "crosses itself|enclose no area"),
    ],
)
def test_bad_sections(upper, message):
    with pytest.raises(GeometryError, match=message) as info:
        sd.build_section(sd.case_from_dict(box_case(upper=upper)))
    assert "\n" not in str(info.value)


def test_polygon_area_sign():
    sq = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    assert polygon_area(sq) == 1.0 and polygon_area(sq[::-1]) == -1.0
