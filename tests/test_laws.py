"""Laws: the area ratio's arithmetic, its JSON round trip and its one-line refusals."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.errors import CaseError
from sectiondeform.laws import RATIO_RANGE, AreaRatio, law_from_json


@settings(max_examples=100, deadline=None)
@given(ratio=st.floats(*RATIO_RANGE), area=st.floats(1e-6, 1e9))
def test_area_ratio_scales_the_area_and_round_trips(ratio, area):
    law = AreaRatio(ratio)
    assert law.target_area(area) == pytest.approx(ratio * area, rel=1e-15)
    assert law.area_ratio(area) == pytest.approx(ratio, rel=1e-12)
    back = law_from_json(law.to_json())
    assert back == law and hash(back) == hash(law)


@pytest.mark.parametrize("bad", [0.0, -0.8, math.inf, math.nan, True, "0.8", None, RATIO_RANGE[1] * 1.01, RATIO_RANGE[0] / 1.01])
def test_bad_ratio_is_one_line_naming_the_field(bad):
    with pytest.raises(CaseError) as info:
        AreaRatio(bad)
    assert str(info.value).startswith("law.area_ratio") and "\n" not in str(info.value)
