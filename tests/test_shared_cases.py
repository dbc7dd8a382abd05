"""The cases kept in tests/data, checked against independently derived figures.

Nothing here was recorded from the program's output: the exact area of the
curves is recomputed from a fine sampling of the curves with shapely, the
initial (polygon) area is bounded by the chordal error, and the law and the
mesh validity are invariants. The paper's own figures are 4379 mm² -> 3503 mm².
"""

import numpy as np
import pytest
import shapely

import sectiondeform as sd

from conftest import SHARED_CASES


def fine_area(case, n=40001):
    """Area enclosed by lower (A -> B) then upper (B -> A), sampled at n equal arc-length fractions each."""
    s = np.linspace(0.0, 1.0, n)
    ring = np.vstack((case.lower.at_fractions(s), case.upper.at_fractions(s)[1:-1]))
    return shapely.Polygon(ring).area


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_areas_law_and_mesh_validity(path):
    case = sd.load_case(path)
    deformer = sd.Deformer(case)
    r = deformer.deform()
    sec = deformer.section
    # the curves' exact area against a 40 000-point polygon of the same curves
    assert sec.curve_area == pytest.approx(fine_area(case), rel=1e-6)
    # the polygon of characteristic points misses the curves by at most the chordal error along their length
    assert abs(r.area_initial - sec.curve_area) <= sec.chordal_error * (case.lower.length + case.upper.length)
    # the initial area reported is the curves' exact one; the final one is the area of the contour returned
    assert r.area_initial == pytest.approx(fine_area(case), rel=1e-6)
    assert r.area_final == pytest.approx(shapely.Polygon(r.contour).area, rel=1e-12)
    # the law
    assert r.area_target == pytest.approx(case.law.ratio * r.area_initial, rel=1e-15)
    assert abs(r.relative_error) <= 1e-9
    assert shapely.Polygon(r.contour).is_valid
    # the contour ends on the target: its first and last lower points are the target's ends
    np.testing.assert_allclose(r.lower[[0, -1]], np.array([case.target.start, case.target.end]), atol=1e-9)
    assert r.quality.initial.jacobian_min > 0 and r.quality.final.jacobian_min > 0


def test_paper_example_figures():
    r = sd.deform(sd.load_case(sd.example_case_path()))
    # the paper's figures: 4379 mm² reduced by 20 % to 3503 mm² (0.8 x 4379 = 3503.2)
    assert round(r.area_initial) == 4379
    assert r.area_final == pytest.approx(0.8 * r.area_initial, rel=1e-12)
    assert round(r.area_final, 1) == 3503.2
    # the paper's method lost 0.1 %; this one meets the law to rounding error
    assert abs(r.relative_error) < 1e-12
    # symmetric case, symmetric result about the axis x = 55
    mirrored = np.column_stack((110 - r.upper[::-1, 0], r.upper[::-1, 1]))
    assert np.abs(mirrored - r.upper).max() < 1e-6
