"""The paper model's warning when the law changes the section's heights by more than the limit."""

import re

import pytest

import sectiondeform as sd
from sectiondeform.applicability import HEIGHT_CHANGE_LIMIT, HEIGHT_SCALE_LIMITS, extent_refusal

from conftest import box_case, data_case_path


def _height_warnings(result):
    return [w for w in result.warnings if "heights change by" in w]


@pytest.mark.parametrize("ratio", [0.8, 0.85, 1.15])
def test_a_box_on_its_own_base_warns_with_the_height_change_it_gets(ratio):
    # Straight base onto the same straight target: the columns keep their widths, so the
    # heights alone carry the area change, k = r exactly.
    r = sd.deform(sd.case_from_dict(box_case(ratio=ratio)))
    assert r.info.height_scale == pytest.approx(ratio, rel=1e-9)
    (w,) = _height_warnings(r)
    change = float(re.search(r"heights change by ([-+][\d.]+) %", w).group(1))
    assert change == pytest.approx(100.0 * (ratio - 1.0), abs=0.05)
    assert "hyperelastic" in w and "\n" not in w


@pytest.mark.parametrize("ratio", [0.95, 1.0, 1.05])
def test_a_small_height_change_does_not_warn(ratio):
    assert _height_warnings(sd.deform(sd.case_from_dict(box_case(ratio=ratio)))) == []


def test_the_grooved_tread_is_flagged_and_the_paper_example_is_not():
    """The calibration's two sides (docs/reliability.md): 13 % of its height off the reference, and 5 %."""
    tread = sd.deform(sd.load_case(data_case_path("grooved-tread")))
    assert abs(tread.info.height_scale - 1.0) > HEIGHT_CHANGE_LIMIT and len(_height_warnings(tread)) == 1
    example = sd.deform(sd.load_case(data_case_path("paper-example")))
    assert abs(example.info.height_scale - 1.0) <= HEIGHT_CHANGE_LIMIT and _height_warnings(example) == []


@pytest.mark.parametrize("k", [HEIGHT_SCALE_LIMITS[0] - 0.01, HEIGHT_SCALE_LIMITS[1] + 0.01])
def test_beyond_the_height_scale_limits_a_refusal_not_a_warning(k):
    assert "height scale k" in extent_refusal(k, 1.0) and extent_refusal(1.0, 1.0) is None
