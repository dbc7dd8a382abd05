"""Hertz's contact of a rounded rubber part on a rigid plate, plane and of revolution (hyperelastic model).

For a small squeeze the contact is Hertz's: the half-width ``a`` and the
peak pressure under a line load ``P`` (per unit length) on a cylinder of
radius ``R`` (plane strain, incompressible: ``E* = 4 mu``) are
``a = sqrt(4 P R / (pi E*))`` and ``p_max = 2 P / (pi a)``; the contact
radius under a load ``P`` on a sphere is ``a = (3 P R / (4 E*))^(1/3)``.
Each is computed from the force the model reports, so only the shape of the
contact is checked against the closed form. The bodies here are a half
cylinder and a hemisphere bonded on their flat face, whose far side does
not matter while ``a`` is small against ``R``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.io.case import case_from_dict
from sectiondeform.pappus import signed_distance

R, MU = 8.0, 0.8
E_STAR = 4.0 * MU
BUMPER = Path(__file__).parent / "data" / "cases" / "v2" / "bumper-under-plate.json"


def _half_cylinder(squeeze: float, through: int) -> dict:
    case = json.loads(BUMPER.read_text())
    part = case["rigid"][0]
    start = np.array(part["contour"]["polyline"]) + [0.0, 1.2]  # the plate's start: touching the top
    part["contour"]["polyline"] = (start - [0.0, squeeze]).tolist()
    part["travel"] = [0.0, -squeeze]
    case["options"] = {"model": "hyperelastic", "elements_through_thickness": through, "bulk_to_shear": 1000}
    return case


def _hemisphere(squeeze: float, through: int, axis=((0, 0), (0, 1))) -> dict:
    return {"format": "section-case/2", "name": "hemisphere", "units": "mm",
            "support": {"polyline": [[0, 0], [R, 0]]}, "target": {"polyline": [[0, 0], [R, 0]]},
            "revolution": {"axis": [list(p) for p in axis]},
            "bodies": [{"name": "ball", "lower": {"polyline": [[0, 0], [R, 0]]},
                        "upper": {"chain": [{"arc": {"center": [0, 0], "radius": R, "start_deg": 0, "end_deg": 90}},
                                            {"polyline": [[0, R], [0, 0]]}]},
                        "law": {"volume_ratio": 1.0}, "material": {"shear_modulus": MU}}],
            "rigid": [{"name": "plate", "travel": [0, -squeeze], "friction": 0.0,
                       "contour": {"polyline": [[-1, R - squeeze], [12, R - squeeze], [12, R + 3], [-1, R + 3],
                                                [-1, R - squeeze]]}}],
            "options": {"model": "hyperelastic", "elements_through_thickness": through, "bulk_to_shear": 1000}}


def test_a_half_cylinder_pressed_on_a_plate_has_hertz_contact():
    part = sd.deform(case_from_dict(_half_cylinder(0.1, 16))).rigid[0]
    load = part.force[1]
    a = math.sqrt(4.0 * load * R / (math.pi * E_STAR))
    assert part.length == pytest.approx(2.0 * a, rel=0.05)  # 1.5715 against 1.5149 mm
    assert part.pressure_max == pytest.approx(2.0 * load / (math.pi * a), rel=0.02)  # 0.1519 against 0.1515 MPa


@pytest.mark.parametrize("squeeze, through", [(0.1, 8), (0.3, 16)])
def test_a_hemisphere_pressed_on_a_plate_has_hertz_contact_radius(squeeze, through):
    result = sd.deform(case_from_dict(_hemisphere(squeeze, through)))
    part = result.rigid[0]
    load = abs(part.force[1])  # the whole ring's force, N
    a = (3.0 * load * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    assert part.length == pytest.approx(a, rel=0.01)  # the contact runs from the axis: its length is the radius


def test_a_solid_body_of_revolution_keeps_its_points_on_the_axis():
    """Its points on the axis stay there; before, it was refused: "the deformed body crosses the revolution axis"."""
    case = _hemisphere(0.3, 8)
    body = sd.deform(case_from_dict(case)).bodies[0]
    start = signed_distance(np.array([[0.0, 0.0], [0.0, R]]), case["revolution"]["axis"])
    assert np.all(start == 0)
    on_axis = np.abs(body.initial_contour[:, 0]) <= 1e-9
    assert on_axis.sum() >= 3
    assert np.abs(body.contour[on_axis, 0]).max() <= 1e-12 * R  # interpolated between nodes held at exactly 0
    assert body.contour[:, 0].min() >= -1e-12 * R


def test_a_body_on_an_oblique_axis_is_refused_in_one_line():
    c, s = math.cos(0.3), math.sin(0.3)
    case = _hemisphere(0.1, 4)
    rot = np.array([[c, -s], [s, c]])

    def turn(points):
        return (np.asarray(points, float) @ rot.T).tolist()

    case["revolution"]["axis"] = turn([[0, 0], [0, 1]])
    for key in ("support", "target"):
        case[key]["polyline"] = turn(case[key]["polyline"])
    body = case["bodies"][0]
    body["lower"]["polyline"] = turn(body["lower"]["polyline"])
    arc, line = body["upper"]["chain"]
    arc["arc"]["start_deg"] += math.degrees(0.3)
    arc["arc"]["end_deg"] += math.degrees(0.3)
    line["polyline"] = turn(line["polyline"])
    part = case["rigid"][0]
    part["contour"]["polyline"] = turn(part["contour"]["polyline"])
    part["travel"] = turn([part["travel"]])[0]
    with pytest.raises(sd.CaseError, match=r"^revolution\.axis: .*draw it along x or y") as info:
        sd.deform(case_from_dict(case))
    assert "\n" not in str(info.value)
