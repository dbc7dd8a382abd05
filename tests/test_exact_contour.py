"""The deformed contour within the chordal error, and laws exact against the curves given.

A long straight upper edge between two characteristic points does not stay
a straight chord on a bent target: the contour has the points between them
(``upper`` keeps one image per characteristic point). The initial area or
volume is the curves' own, in closed form (arcs), by Gauss quadrature
(B-splines); the law holds to 1e-9 against it. Every expected value below
is derived by hand.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

import sectiondeform as sd
from sectiondeform import Arc, AreaRatio, BSpline, Deformer, Polyline, Problem
from sectiondeform.io.case import case_from_dict
from sectiondeform.pappus import curve_moment

MODELS = ["paper", "hyperelastic"]


def bent_block(width, height, radius):
    """A width x height block drawn by its 4 corners, its lower edge onto an arc of ``radius`` (centre below), area kept."""
    half = math.degrees(0.5 * width / radius)
    target = Arc(np.array([0.5 * width, -radius]), radius, 90.0 + half, 90.0 - half)  # A' left, B' right, length width
    return Problem.single(Polyline([[0, 0], [width, 0]]), Polyline([[width, 0], [width, height], [0, height], [0, 0]]),
                          target, AreaRatio(1.0))


def thickness_on_ray(result, centre, direction):
    """Length of the deformed section cut by the ray from ``centre`` along ``direction``, units."""
    ray = shapely.LineString([centre, np.asarray(centre) + 1e4 * np.asarray(direction)])
    return shapely.Polygon(result.contour).intersection(ray).length


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("width, height, radius", [(200.0, 10.0, 500.0), (100.0, 10.0, 60.0)])
def test_a_block_drawn_by_its_corners_bent_on_an_arc_keeps_its_thickness(model, width, height, radius):
    """Bent at constant area and lower length, a block of area w h becomes an annular sector of angle w / R:
    (R + t)² = R² + 2 w h / (w / R), so t = 9.902 mm for 200 x 10 on R = 500 (not the 6.5 of a straight chord).
    """
    result = Deformer(bent_block(width, height, radius), model).deform()
    t = math.sqrt(radius**2 + 2.0 * height * radius) - radius
    mid = thickness_on_ray(result, (0.5 * width, -radius), (0.0, 1.0))
    assert mid == pytest.approx(t, rel=0.03)
    assert len(result.upper) == 4 and len(result.contour) > 40  # one image per corner; the outline between them
    assert abs(result.area_final - width * height) <= 1e-9 * width * height
    assert not any("split it" in w or "elements_through_thickness" in w for w in result.warnings)


@pytest.mark.parametrize("model", MODELS)
def test_a_tread_drawn_by_four_points_on_a_crowned_drum_keeps_its_crown(model):
    """A 10 mm tread (4 points) shaped onto a crown of radius 150 at constant area: thickness at the crown
    sqrt(R² + 2 t R) - R = 9.68 mm (a straight chord would leave about 2.5).
    """
    width, height, radius = 160.0, 10.0, 150.0
    result = Deformer(bent_block(width, height, radius), model).deform()
    crown = thickness_on_ray(result, (0.5 * width, -radius), (0.0, 1.0))
    assert crown == pytest.approx(math.sqrt(radius**2 + 2.0 * height * radius) - radius, rel=0.03)


def test_a_half_disc_on_its_diameter_keeps_the_exact_area_under_its_law():
    r = 7.0
    half_disc = Problem.single(Polyline([[-r, 0.0], [r, 0.0]]), Arc(np.zeros(2), r, 0.0, 180.0),
                               Polyline([[-r, 0.0], [r, 0.0]]), AreaRatio(0.9))
    for model in MODELS:
        body = Deformer(half_disc, model).deform().bodies[0]
        assert body.area_initial == pytest.approx(math.pi * r * r / 2.0, rel=1e-14)
        assert abs(body.area_final - 0.9 * math.pi * r * r / 2.0) <= 1e-9 * body.area_final


@pytest.mark.parametrize("model", MODELS)
def test_a_torus_section_keeps_its_exact_pappus_volume(model):
    """A half-disc of radius r on a flat support at R from the axis: V = 2 pi (pi r² / 2) (R + 4 r / (3 pi))."""
    r, big = 4.0, 12.0
    case = {
        "format": "section-case/2", "support": {"polyline": [[-r, big], [r, big]]},
        "target": {"polyline": [[-r, big + 1.0], [r, big + 1.0]]},
        "revolution": {"axis": [[0.0, 0.0], [1.0, 0.0]]},
        "bodies": [{"name": "half-torus", "lower": {"polyline": [[-r, big], [r, big]]},
                    "upper": {"arc": {"center": [0.0, big], "radius": r, "start_deg": 0.0, "end_deg": 180.0}},
                    "law": {"volume_ratio": 1.0}}],
    }
    body = Deformer(case_from_dict(case), model).deform().bodies[0]
    exact = 2.0 * math.pi * (math.pi * r * r / 2.0) * (big + 4.0 * r / (3.0 * math.pi))
    assert body.volume_initial == pytest.approx(exact, rel=1e-13)
    assert abs(body.volume_final - exact) <= 1e-9 * exact


def test_exact_moments_of_the_curve_kinds():
    """Polyline, arc and B-spline pieces against closed forms: -1/2 integral of y² dx and Pappus's moment."""
    parabola = BSpline(2, np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 1.0]]))  # y = x², x from 0 to 1
    assert parabola.moment_x() == pytest.approx(-0.1, rel=1e-14)  # -1/2 integral of x^4
    assert parabola.green() == pytest.approx(1.0 / 6.0, rel=1e-14)
    disc = [Arc(np.array([0.0, 5.0]), 2.0, -90.0, 90.0), Arc(np.array([0.0, 5.0]), 2.0, 90.0, 270.0)]
    assert curve_moment(disc, ((0.0, 0.0), (1.0, 0.0))) == pytest.approx(math.pi * 4.0 * 5.0, rel=1e-14)
    # the same disc about an oblique axis through the origin: distance of the centre (0, 5) is 5 cos 30°
    axis = ((0.0, 0.0), (math.cos(math.radians(30.0)), math.sin(math.radians(30.0))))
    assert curve_moment(disc, axis) == pytest.approx(math.pi * 4.0 * 5.0 * math.cos(math.radians(30.0)), rel=1e-13)
    square = [Polyline([[0.0, 1.0], [2.0, 1.0], [2.0, 3.0], [0.0, 3.0], [0.0, 1.0]])]
    assert curve_moment(square, ((0.0, 0.0), (1.0, 0.0))) == pytest.approx(4.0 * 2.0, rel=1e-15)


def test_a_gap_between_pieces_counts_as_its_chord():
    """Pieces that miss each other by rounding: the area is the closed polygon's, not the open curves' sum."""
    square = (Polyline([[0.0, 0.0], [1.0, 0.0]]), Polyline([[1.0, 1e-7], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]]))
    assert AreaRatio(1.0).curve_quantity(square) == pytest.approx(1.0, rel=1e-15)
    assert sd.curves.closed_parts(square)[1].to_json() == {"polyline": [[1.0, 0.0], [1.0, 1e-7]]}
