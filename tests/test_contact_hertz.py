"""Hertz's contact of rubber and a rigid part, plane and of revolution (hyperelastic model; incompressible, so ``E* = 4 mu``).

A rigid cylinder indenting a wide, deep block (plane strain): from the force
per length ``P`` the model computes, the contact half-width
``a = sqrt(4 P R / (pi E*))`` and the peak pressure ``p0 = 2 P / (pi a)``.
A rigid sphere indenting a large block of revolution by ``d``: the contact
radius ``a = sqrt(R d)`` and the force ``F = 4/3 E* sqrt(R) d^1.5``. A rubber
hemisphere pressed on a rigid plate: the contact radius under the force
``P`` it reports, ``a = (3 P R / (4 E*))^(1/3)`` (the hemisphere is bonded on
its flat face at ``R`` from the contact, not a half-space; in three
dimensions the field decays fast enough that its contact radius is Hertz's
within 1 % here). The blocks are refined under the contact by nested
inserts of the same rubber (``tests/contact_cases.py``), one more than the
default here, so that the contact spans several elements.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from contact_cases import LEVELS, indentation_problem  # noqa: E402

import sectiondeform as sd
from sectiondeform.io.case import case_from_dict
from sectiondeform.pappus import signed_distance

R, MU = 8.0, 0.8
E_STAR = 4.0 * MU


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


FINE = (*LEVELS, (0.12, 0.06))
"""The block's levels with one insert more: elements of R / 133 under the contact."""


def test_a_cylinder_indenting_a_half_space_has_hertz_width_and_peak():
    """Plane: a cylinder (R) indents a block 20 R wide and 10 R deep by R / 200 (a / R = 0.04).

    Measured: the width +1.6 %, the peak +1.1 % of Hertz's for the force the model reports (its mesh, over 400
    vertices, is not halved under the cylinder by default; halved, −0.04 % and +4.8 %: the node-wise pressure wiggles
    by about 5 % from node to node over the 20 elements across, and the peak reported is the largest).
    """
    part = sd.deform(indentation_problem(0.005, False, radius=1.0, through=4, levels=FINE)).rigid[0]
    load = abs(part.force[1])  # per unit length, shear modulus 1
    a = math.sqrt(4.0 * load * 1.0 / (math.pi * 4.0))
    assert a < 0.1
    assert part.length == pytest.approx(2.0 * a, rel=0.03)  # the contact runs across: its length is the width
    assert part.pressure_max == pytest.approx(2.0 * load / (math.pi * a), rel=0.05)


def test_a_sphere_indenting_a_block_of_revolution_needs_hertz_force_and_radius():
    """A rigid sphere (R) indents a block of revolution 20 R wide and 10 R deep by d = R / 200.

    Measured: the force −0.3 % of 4/3 E* sqrt(R) d^1.5, the contact radius +1.4 % of sqrt(R d).
    """
    depth, radius = 0.005, 1.0
    part = sd.deform(indentation_problem(depth, True, radius=radius, through=4, levels=FINE)).rigid[0]
    force = abs(part.force[1])
    assert force == pytest.approx(4.0 / 3.0 * 4.0 * math.sqrt(radius) * depth**1.5, rel=0.03)
    assert part.length == pytest.approx(math.sqrt(radius * depth), rel=0.03)


@pytest.mark.parametrize("squeeze, through, tolerance", [(0.1, 8, 0.03), (0.3, 16, 0.01)])
def test_a_hemisphere_pressed_on_a_plate_has_hertz_contact_radius(squeeze, through, tolerance):
    """Measured: +2.2 % at 8 elements through (the contact about two of the elements halved under the plate; the
    length's resolution is a fraction of an element: −0.2 % on the mesh not halved), +0.05 % at 16 (not halved by
    default: over 400 vertices).
    """
    result = sd.deform(case_from_dict(_hemisphere(squeeze, through)))
    part = result.rigid[0]
    load = abs(part.force[1])  # the whole ring's force, N
    a = (3.0 * load * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    assert part.length == pytest.approx(a, rel=tolerance)  # the contact runs from the axis: its length is the radius


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
