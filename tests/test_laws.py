"""Laws: the area ratio's arithmetic, its JSON round trip and its one-line refusals."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.errors import CaseError
from sectiondeform.laws import RATIO_RANGE, AreaRatio, law_from_json, law_roots


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


root = st.floats(-10, 10).filter(lambda r: abs(r) > 1e-3)


@settings(max_examples=200, deadline=None)
@given(roots=st.lists(root, min_size=1, max_size=3, unique=True).filter(
           lambda rs: all(abs(a - b) > 1e-2 for i, a in enumerate(rs) for b in rs[i + 1:])),
       lead=st.floats(0.1, 10) | st.floats(-10, -0.1), wanted=st.floats(-5, 5))
def test_law_roots_are_the_roots_the_polynomial_was_built_from(roots, lead, wanted):
    """q(k) - wanted = lead * prod(k - r): the real roots come back, each to round-off (simple roots)."""
    c = lead * np.polynomial.polynomial.polyfromroots(roots)
    c[0] += wanted  # q(k) = wanted exactly at the roots
    got = sorted(law_roots(c, wanted))
    assert len(got) == len(roots)
    scale = 1.0 + max(abs(r) for r in roots)
    assert np.allclose(got, sorted(roots), rtol=0, atol=1e-7 * scale)


def test_law_roots_of_a_quadratic_keep_the_small_root_without_cancellation():
    # k² + 1e8 k - 1 = 0: the small root is 1e-8 to 16 digits, which the textbook formula loses
    (small,) = [k for k in law_roots([-1.0, 1e8, 1.0], 0.0) if abs(k) < 1]
    assert small == pytest.approx(1e-8, rel=1e-15)
    assert law_roots([1.0, 0.0, 1.0], 0.0) == []  # k² + 1 = 0: no real root
    assert law_roots([2.0], 1.0) == []  # a constant: none
