"""The height-change warning counts only what a uniform map of the motion does not give.

A ring of rubber (a rectangular tread section on a drum of revolution)
moved radially outward under an incompressible volume law thins exactly as
the closed form says: the annulus between R and R + t of axial width w has
the volume pi ((R + t)^2 - R^2) w, so on the radius R1 its thickness is
t1 = sqrt(R1^2 + 2 R t + t^2) - R1. The paper model gives it to rounding;
its height scale k = t1 / t (-22 % for a 30 % larger radius) is the
motion's, not a distortion, and must not be warned. The law's own area
change (a box on its own base) still is, and so is a bend that changes the
heights.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.applicability import HEIGHT_CHANGE_LIMIT, extent_warnings, uniform_height_scale

from conftest import box_case

R, T, W = 100.0, 10.0, 30.0


def ring_case(r1: float, ratio: float = 1.0) -> dict:
    """A W x T tread on a drum of radius R (the axis at y = -R), its support moved out to the radius r1."""
    return {
        "format": "section-case/2", "name": "ring", "units": "mm",
        "support": {"polyline": [[0.0, 0.0], [W, 0.0]]},
        "target": {"polyline": [[0.0, r1 - R], [W, r1 - R]]},
        "revolution": {"axis": [[0.0, -R], [1.0, -R]]},
        "bodies": [{"name": "tread", "lower": {"polyline": [[0.0, 0.0], [W, 0.0]]},
                    "upper": {"polyline": [[W, 0.0], [W, T], [0.0, T], [0.0, 0.0]]},
                    "law": {"volume_ratio": ratio}}],
        "options": {"model": "paper"},
    }


def ring_thickness(r1: float, ratio: float = 1.0) -> float:
    """The closed form: the annulus on the radius r1 holding ``ratio`` times the volume of the initial one."""
    return math.sqrt(r1 * r1 + ratio * (2.0 * R * T + T * T)) - r1


def _height_warnings(result):
    return [w for w in result.warnings if "heights change by" in w]


@pytest.mark.parametrize("grow", [1.3, 1.1, 0.8, 2.0])
def test_a_ring_moved_from_its_axis_is_exact_and_not_warned(grow):
    r1 = grow * R
    result = sd.deform(sd.case_from_dict(ring_case(r1)))
    upper = np.asarray(result.bodies[0].upper)
    t1 = ring_thickness(r1)
    assert np.abs(upper[1:3, 1] - (r1 - R + t1)).max() < 1e-9 * R
    k = result.bodies[0].info.height_scale
    assert k == pytest.approx(t1 / T, rel=1e-12)
    if grow == 1.3:
        assert abs(k - 1.0) > 2 * HEIGHT_CHANGE_LIMIT  # -22 %: the case of the false alarm
    assert result.bodies[0].info.uniform_height_scale == pytest.approx(k, rel=1e-9)
    assert _height_warnings(result) == []


def test_the_laws_own_change_on_a_ring_is_still_warned():
    r1 = 1.3 * R
    result = sd.deform(sd.case_from_dict(ring_case(r1, ratio=0.8)))
    assert np.asarray(result.bodies[0].upper)[1, 1] == pytest.approx(r1 - R + ring_thickness(r1, 0.8), abs=1e-9 * R)
    (warning,) = _height_warnings(result)
    change = float(re.search(r"heights change by ([-+][\d.]+) %", warning).group(1))
    info = result.bodies[0].info
    assert change == pytest.approx(100.0 * (info.height_scale / info.uniform_height_scale - 1.0), abs=0.05)
    assert change == pytest.approx(-20.0, abs=1.0)  # the law's 0.8, whatever the move


@pytest.mark.parametrize("stretch", [1.3, 0.8])
def test_a_box_stretched_along_its_base_keeps_its_area_exactly_and_is_not_warned(stretch):
    # k = 1 / s exactly: the uniform map of a body that keeps its area on a base s times as long.
    target = {"polyline": [[0.0, 0.0], [10.0 * stretch, 0.0]]}
    result = sd.deform(sd.case_from_dict(box_case(target=target)))
    assert result.info.height_scale == pytest.approx(1.0 / stretch, rel=1e-12)
    assert _height_warnings(result) == []


def test_a_bend_that_changes_the_heights_is_still_warned():
    # A thick box on a convex arc: the layers' offsets gain area, the heights shrink beyond the uniform map's.
    box = box_case(width=10.0, height=4.0)
    target = {"arc": {"center": [5.0, -6.0], "radius": math.hypot(5.0, 6.0),
                      "start_deg": math.degrees(math.atan2(6.0, -5.0)), "end_deg": math.degrees(math.atan2(6.0, 5.0))}}
    result = sd.deform(sd.case_from_dict({**box, "target": target}))
    info = result.info
    assert abs(info.height_scale / info.uniform_height_scale - 1.0) > HEIGHT_CHANGE_LIMIT
    assert len(_height_warnings(result)) == 1


def test_the_figure_is_k_over_the_uniform_scale():
    assert extent_warnings(0.78, (1.0, 1.0), 1.0, uniform_scale=0.78) == []
    (w,) = extent_warnings(0.78, (1.0, 1.0), 1.0, uniform_scale=1.0)
    assert "-22 %" in w
    assert uniform_height_scale(10.0, 10.0, 1.0, 1.0) == 1.0
