"""The hyperelastic model: invariants, area law, warm starts, preview, accuracy and convergence."""


import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import sectiondeform as sd
from sectiondeform.errors import ConvergenceError
from sectiondeform.laws import AreaRatio

from conftest import SHARED_CASES, box_case, chord_offset, rigid


def _with(case, **options):
    return case.replace(options=case.options.replace(**options))


def _identity_case(case):
    return case.replace(target=case.lower, law=AreaRatio(1.0))


def _hausdorff(a, b, T):
    """(mean, max) distance between two upper polylines, relative to T."""
    la, lb = shapely.LineString(a), shapely.LineString(b)
    pts = shapely.points(shapely.get_coordinates(shapely.segmentize(la, T / 50)))
    mean = float(np.mean(shapely.distance(pts, lb)))
    return mean / T, shapely.hausdorff_distance(la, lb, densify=0.05) / T


@pytest.fixture(scope="module")
def fine_truth():
    """Fine solutions (12 elements through the thickness) of each shared case, cached."""
    cache = {}

    def get(path):
        if path not in cache:
            case = _with(sd.load_case(path), elements_through_thickness=12)
            cache[path] = sd.Deformer(case, model="hyperelastic").deform()
        return cache[path]

    return get


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_identity_gives_back_the_section(path):
    r = sd.Deformer(_identity_case(sd.load_case(path)), model="hyperelastic").deform()
    size = np.hypot(*np.ptp(r.initial_contour, axis=0))
    assert np.abs(r.upper - r.initial_upper).max() <= chord_offset(r) + 1e-9 * size
    assert r.info.newton_full == 0


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
@pytest.mark.parametrize("angle, shift", [(30.0, (5.0, -2.0)), (-135.0, (100.0, 40.0))])
def test_rigid_motion_of_the_target_moves_the_section_rigidly(path, angle, shift):
    deformer = sd.Deformer(_identity_case(sd.load_case(path)), model="hyperelastic")
    same = deformer.deform()
    r = deformer.deform(rigid(deformer.section.lower, angle, shift))
    size = deformer.section.size
    assert np.abs(r.upper - rigid(same.upper, angle, shift)).max() <= 1e-9 * size


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_area_law_exact_and_every_upper_point_mapped_in_order(path):
    case = sd.load_case(path)
    deformer = sd.Deformer(case, model="hyperelastic")
    r = deformer.deform()
    assert abs(r.area_final - r.area_target) <= 1e-12 * r.area_target
    sec = deformer.section
    characteristic = sec.upper[sec.characteristic_index]
    assert r.upper.shape == characteristic.shape
    nodes = deformer.target_nodes()
    assert np.array_equal(r.upper[0], nodes[-1]) and np.array_equal(r.upper[-1], nodes[0])
    # In order: each point stays nearest its own image's neighbours (no swaps), the contour is simple.
    assert shapely.LinearRing(np.concatenate((nodes, r.upper[1:-1]))).is_simple
    step = np.hypot(*np.diff(r.upper, axis=0).T)
    assert step.max() <= 3.0 * np.hypot(*np.diff(characteristic, axis=0).T).max()
    assert r.info.area_correction < 0.02
    assert r.final_mesh.kind == "triangle6"


@settings(max_examples=8, deadline=None)
@given(
    angle=st.floats(-180, 180),
    dx=st.floats(-50, 50),
    ratio=st.floats(0.8, 1.2),
    bend=st.floats(-0.3, 0.3),
)
def test_area_law_on_bent_moved_targets(angle, dx, ratio, bend):
    # A box bonded to an arc-like polyline of curvature ``bend`` / width, moved rigidly.
    s = np.linspace(0.0, 1.0, 21)
    pts = np.column_stack((10 * s, 10 * bend * (s - 0.5) ** 2))
    target = rigid(pts, angle, (dx, 0.0))
    case = sd.case_from_dict(box_case(10.0, 4.0, {"polyline": target.tolist()}, ratio))
    r = sd.Deformer(case, model="hyperelastic").deform()
    assert abs(r.area_final - r.area_target) <= 1e-12 * r.area_target


def test_warm_start_matches_a_cold_solve():
    case = sd.load_case(SHARED_CASES[0])
    deformer = sd.Deformer(case, model="hyperelastic")
    nodes = deformer.target_nodes()
    first = deformer.deform(target_nodes=nodes)
    moved = nodes + 0.02 * deformer.section.thickness * np.sin(np.linspace(0, np.pi, len(nodes)))[:, None] * [0, 1]
    warm = deformer.deform(target_nodes=moved, start=first)
    assert warm.info.warm_start and warm.info.factorisations <= 1
    cold = sd.Deformer(case, model="hyperelastic").deform(target_nodes=moved)
    assert np.abs(warm.upper - cold.upper).max() <= 1e-5 * deformer.section.thickness


def test_preview_is_close_for_a_small_drag_and_meets_the_law():
    case = sd.load_case(SHARED_CASES[0])
    deformer = sd.Deformer(case, model="hyperelastic")
    nodes = deformer.target_nodes()
    first = deformer.deform(target_nodes=nodes)
    T = deformer.section.thickness
    moved = nodes + 0.02 * T * np.sin(np.linspace(0, np.pi, len(nodes)))[:, None] * [0, 1]
    preview = deformer.preview(target_nodes=moved, start=first)
    exact = sd.Deformer(case, model="hyperelastic").deform(target_nodes=moved)
    assert preview.info.preview
    assert np.abs(preview.upper - exact.upper).max() <= 2e-3 * T
    area = abs(sd.section.polygon_area(preview.contour))
    assert area == pytest.approx(exact.area_target, rel=1e-12) and preview.area_final == pytest.approx(area, rel=1e-12)


def test_preview_before_any_solve_is_rigid_exact():
    case = _identity_case(sd.load_case(SHARED_CASES[0]))
    deformer = sd.Deformer(case, model="hyperelastic")
    same = deformer.deform()
    moved = rigid(deformer.section.lower, 40.0, (3.0, 1.0))
    p = deformer.preview(moved)
    assert np.abs(p.upper - rigid(same.upper, 40.0, (3.0, 1.0))).max() <= 1e-9 * deformer.section.size


def test_impossible_target_raises_instead_of_returning():
    # A hairpin target: the section would have to fold through itself.
    case = sd.case_from_dict(box_case(10.0, 4.0, {"polyline": [[0.0, 0.0], [5.0, 0.0], [0.0, 0.2]]}, 1.0))
    with pytest.raises(ConvergenceError, match="did not converge"):
        sd.Deformer(case, model="hyperelastic").deform()


def test_severe_squeeze_warns_about_the_area_correction():
    case = sd.case_from_dict(box_case(10.0, 4.0, {"polyline": [[0.0, 0.0], [0.5, 0.0]]}, 1.0))
    try:
        r = sd.Deformer(case, model="hyperelastic").deform()
    except sd.MeshError as exc:  # a squeeze this severe may turn P2 triangles over: refused, never returned
        assert "inverted" in str(exc)
    else:
        assert any("area correction" in w for w in r.warnings)


def test_options_are_checked():
    with pytest.raises(sd.CaseError, match="elements_through_thickness"):
        sd.Deformer(_with(sd.load_case(SHARED_CASES[0]), elements_through_thickness=-1), model="hyperelastic")


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_default_mesh_agrees_with_a_fine_solution(path, fine_truth):
    fine = fine_truth(path)
    r = sd.Deformer(sd.load_case(path), model="hyperelastic").deform()
    T = r.area_initial / sd.build_section(sd.load_case(path)).lower_length
    mean, worst = _hausdorff(r.upper, fine.upper, T)
    assert mean <= 0.01 and worst <= 0.015


def test_shape_error_converges_as_the_mesh_is_refined(fine_truth):
    path = [p for p in SHARED_CASES if "thick" in p.stem][0]
    fine = fine_truth(path)
    case = sd.load_case(path)
    T = sd.build_section(case).thickness
    ns = np.array([2.0, 3.0, 4.0, 6.0])
    errors = [
        _hausdorff(sd.Deformer(_with(case, elements_through_thickness=n), model="hyperelastic").deform().upper, fine.upper, T)[1]
        for n in ns
    ]
    slope = np.polyfit(np.log(1.0 / ns), np.log(errors), 1)[0]
    assert slope > 1.0
    assert errors[-1] < errors[0]


def test_clockwise_section_gives_the_same_shape_as_its_counter_clockwise_twin():
    arc = {"center": [5.0, -20.0], "radius": 20.0, "start_deg": 104.0, "end_deg": 76.0}
    ccw = sd.case_from_dict(box_case(10.0, 4.0, {"arc": arc}, 0.9))
    cw_dict = box_case(10.0, 4.0, {"arc": {**arc, "start_deg": 76.0, "end_deg": 104.0}}, 0.9)
    cw_dict["lower"] = {"polyline": [[10.0, 0.0], [0.0, 0.0]]}
    cw_dict["upper"] = {"polyline": [[0.0, 0.0], [0.0, 4.0], [10.0, 4.0], [10.0, 0.0]]}
    d_cw = sd.Deformer(sd.case_from_dict(cw_dict), model="hyperelastic")
    assert d_cw.section.orientation == -1
    a = sd.Deformer(ccw, model="hyperelastic").deform().upper
    b = d_cw.deform().upper
    assert np.abs(a[::-1] - b).max() <= 1e-9 * 10.0
