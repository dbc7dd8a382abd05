"""Invariants of the paper's model: identity, rigid motion, area law, valid meshes, order."""


import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import sectiondeform as sd
from sectiondeform.curves import Polyline
from sectiondeform.errors import LawError, MeshError
from sectiondeform.laws import AreaRatio
from sectiondeform.models.paper import scale_roots

from conftest import SHARED_CASES, Outcomes, box_case, chord_offset, rigid


def _identity_case(case):
    """The case with the target equal to the lower curve and ratio 1."""
    return case.replace(target=case.lower, law=AreaRatio(1.0))


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_identity_gives_back_the_section(path):
    case = _identity_case(sd.load_case(path))
    r = sd.deform(case)
    size = np.hypot(*np.ptp(r.initial_contour, axis=0))
    assert np.abs(r.upper - r.initial_upper).max() <= chord_offset(r) + 1e-9 * size
    assert np.abs(r.lower - r.initial_lower).max() <= 1e-9 * size
    assert r.info.height_scale == pytest.approx(1.0, abs=1e-4)  # the exact area, not the polygon's: k off 1 by the chords' missed area


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
@pytest.mark.parametrize("angle, shift", [(30.0, (5.0, -2.0)), (-135.0, (100.0, 40.0))])
def test_rigid_motion_of_the_target_moves_the_section_rigidly(path, angle, shift):
    case = _identity_case(sd.load_case(path))
    deformer = sd.Deformer(case)
    same = deformer.deform()
    moved = rigid(deformer.section.lower, angle, shift)
    r = deformer.deform(moved)
    size = deformer.section.size
    assert np.abs(r.upper - rigid(same.upper, angle, shift)).max() <= 1e-9 * size
    assert r.relative_error == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_shared_cases_meet_the_law_with_valid_meshes(path):
    case = sd.load_case(path)
    r = sd.deform(case)
    assert abs(r.relative_error) <= 1e-9
    assert r.quality.initial.jacobian_min > 0 and r.quality.final.jacobian_min > 0
    assert len(r.upper) == len(r.initial_upper)
    assert np.allclose(r.upper[0], r.lower[-1]) and np.allclose(r.upper[-1], r.lower[0])
    # the lower curve lands on the target, arc-length fractions preserved
    deformer = sd.Deformer(case)
    assert np.allclose(r.lower, case.target.at_fractions(deformer.section.fractions), atol=1e-12)
    assert np.allclose(r.lower[[0, -1]], [case.target.start, case.target.end], atol=1e-9)


def test_area_law_and_valid_mesh_for_bent_targets():
    """A 40 x 12 block with a domed top on a parabolic target of any bend, stretch, rotation."""
    outcomes = Outcomes()

    @settings(max_examples=40, deadline=None)
    @given(
        ratio=st.floats(0.5, 1.5),
        sagitta=st.floats(-12.0, 12.0),
        stretch=st.floats(0.8, 1.25),
        angle=st.floats(-180, 180),
    )
    def check(ratio, sagitta, stretch, angle):
        x = np.linspace(40, 0, 21)
        top = np.column_stack((x, 12 + 3 * np.sin(np.pi * x / 40)))
        upper = [[40.0, 0.0]] + top.tolist() + [[0.0, 0.0]]
        xt = np.linspace(0, 40 * stretch, 41)
        yt = sagitta * (1 - (2 * xt / xt[-1] - 1) ** 2)
        target = rigid(np.column_stack((xt, yt)), angle, (3.0, -7.0))
        case = sd.case_from_dict(box_case(40, 12, upper=upper, target={"polyline": target.tolist()}, ratio=ratio))
        try:
            r = sd.deform(case)
        except (MeshError, LawError, sd.GeometryError) as exc:
            # a refusal must be a clear one-line error, never a silent bad result
            assert "\n" not in str(exc)
            outcomes.refused(type(exc).__name__)
            return
        assert abs(r.relative_error) <= 1e-9
        assert r.quality.final.jacobian_min > 0
        assert len(r.upper) == len(upper)
        outcomes.checked()

    check()
    outcomes.assert_mostly_checked(at_least=20, max_refused_fraction=0.5)


def test_re_deformation_reuses_the_section():
    case = sd.load_case(sd.example_case_path())
    deformer = sd.Deformer(case)
    first = deformer.deform()
    mesh = deformer.prepared.bodies[0].initial_mesh
    for sag in (0.0, 5.0, 10.0):
        x = np.linspace(0, 110, 23)
        t = Polyline(np.column_stack((x, sag * (1 - (2 * x / 110 - 1) ** 2))))
        r = deformer.deform(t)
        assert r.initial_mesh is mesh
        assert abs(r.relative_error) <= 1e-9
    assert np.array_equal(deformer.deform().upper, first.upper)


def test_reversed_straight_target_is_a_half_turn():
    case = sd.case_from_dict(box_case(10, 4, ratio=1.0))
    deformer = sd.Deformer(case)
    r = deformer.deform(deformer.section.lower[::-1].copy())
    assert np.allclose(r.upper, rigid(r.initial_upper, 180.0, (10.0, 0.0)), atol=1e-12)


def test_sharp_target_fold_is_reported():
    case = sd.case_from_dict(box_case(20, 10, ratio=1.0))
    deformer = sd.Deformer(case)
    n = len(deformer.section.lower)
    s = deformer.section.fractions
    # a hairpin: the target goes out and comes back 0.1 apart
    hairpin = np.where(s[:, None] < 0.5, np.column_stack((40 * s, 0 * s)), np.column_stack((40 * (1 - s), 0.1 + 0 * s)))
    assert len(hairpin) == n  # one node per lower node: the node-array path
    with pytest.raises((MeshError, LawError, sd.GeometryError)) as info:
        deformer.deform(hairpin)
    assert "\n" not in str(info.value)  # one line
    # the refusal leaves the prepared state as it was: the next deformation is a fresh one's
    again, fresh = deformer.deform(), sd.Deformer(case).deform()
    assert np.array_equal(again.contour, fresh.contour)


def test_the_height_scale_is_the_positive_root_nearest_the_guess():
    # the rectangle [0, 1] x [0, k]: its area is k
    sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]])
    up = np.array([[0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [0.0, 1.0]])
    assert scale_roots(AreaRatio(2.0).coefficients(sq, up), 2.0, 1.0) == pytest.approx([2.0], rel=1e-15)
    assert scale_roots(AreaRatio(2.0).coefficients(sq, up), -1.0, 1.0) == []  # a negative area: no positive scale
    # 3k - k² = 2 has the roots 1 and 2: the nearer the guess first
    assert scale_roots([0.0, 3.0, -1.0], 2.0, 1.8) == pytest.approx([2.0, 1.0], rel=1e-15)


def test_mushroom_section_with_far_overhangs():
    """A cap five times wider than its foot: the base is prolonged by virtual columns."""
    upper = [[2, 0], [2, 1], [7, 1.2], [7, 4], [-5, 4], [-5, 1.2], [0, 1], [0, 0]]
    case = sd.case_from_dict(box_case(2, 4, upper=upper, ratio=0.8,
                                      target={"arc": {"center": [1, 5], "radius": 5, "start_deg": -101.5, "end_deg": -78.5}}))
    deformer = sd.Deformer(case)
    assert min(deformer.prepared.bodies[0].quality.virtual_columns) > 0
    r = deformer.deform()
    assert abs(r.relative_error) <= 1e-9 and r.quality.final.jacobian_min > 0
    ident = deformer.deform(deformer.section.lower, law=AreaRatio(1.0))
    assert np.abs(ident.upper - ident.initial_upper).max() < 1e-12  # polylines: the exact area is the polygon's
    moved = deformer.deform(rigid(deformer.section.lower, 70, (1, 2)), law=AreaRatio(1.0))
    assert np.abs(moved.upper - rigid(ident.initial_upper, 70, (1, 2))).max() < 1e-12


def test_preview_of_the_paper_model_is_the_full_deformation():
    deformer = sd.Deformer(sd.load_case(sd.example_case_path()))
    x = np.linspace(0, 110, 23)
    t = Polyline(np.column_stack((x, 4 * (1 - (2 * x / 110 - 1) ** 2))))
    assert np.array_equal(deformer.preview(t).upper, deformer.deform(t).upper)


def test_laws_met_in_turn_give_the_results_of_a_fresh_deformer():
    """The initial quantity kept per law (a drag asks it at every move) changes no result, bit for bit.

    Twenty ratios, more than are kept, then the first ones again: each result equals that of a new
    deformer that never saw another law.
    """
    case = sd.load_case(sd.example_case_path())
    deformer = sd.Deformer(case)
    x = np.linspace(0, 110, 23)
    t = Polyline(np.column_stack((x, 4 * (1 - (2 * x / 110 - 1) ** 2))))
    ratios = [0.6 + 0.025 * i for i in range(20)]
    for ratio in ratios + ratios[:3]:
        got = deformer.preview(t, AreaRatio(ratio))
        fresh = sd.Deformer(case).deform(t, AreaRatio(ratio))
        assert np.array_equal(got.contour, fresh.contour) and np.array_equal(got.final_mesh.points, fresh.final_mesh.points)
        assert got.area_final == fresh.area_final
    # the initial quantity is the curves' exact one, kept once whatever the ratio
    assert deformer.stack.initial_quantity(0, AreaRatio(0.7)) == AreaRatio(0.7).curve_quantity((case.bodies[0].lower, case.bodies[0].upper))


def test_fine_mesh_on_a_tightly_curved_target():
    """Four times finer elements than the default on the S-curve: the normal field needs more smoothing."""
    case = sd.load_case(SHARED_CASES[[p.stem for p in SHARED_CASES].index("thick-block-s-curve")])
    case = case.replace(options=case.options.replace(refine=4))
    r = sd.deform(case)
    assert abs(r.relative_error) <= 1e-9 and r.quality.final.jacobian_min > 0


@pytest.mark.parametrize("model", ["paper", "hyperelastic"])
def test_a_long_straight_upper_segment_follows_a_tight_arc_as_if_split(model):
    """A 200 x 5 strip given by its four corners deforms onto a tight arc as the strip with its top split in 40."""
    arc = {"arc": {"center": [100, 60], "radius": 60, "start_deg": -170, "end_deg": -10}}
    corners = sd.Deformer(sd.case_from_dict(box_case(200, 5, target=arc)), model=model).deform()
    top = [[200 - 5 * i, 5.0] for i in range(41)]
    split = sd.Deformer(sd.case_from_dict(box_case(200, 5, upper=[[200, 0]] + top + [[0, 0]], target=arc)),
                        model=model).deform()
    for r in (corners, split):
        assert abs(r.relative_error) <= 1e-9
    assert len(corners.upper) == 4 and len(corners.contour) > 40  # one image per corner, the outline between them
    gap = shapely.hausdorff_distance(shapely.Polygon(corners.contour), shapely.Polygon(split.contour))
    assert gap <= 0.05 * 5.0


def test_section_in_a_right_angled_corner():
    """An L-shaped section on an L-shaped support, moved rigidly and shrunk: the layers turn the corner."""
    case = sd.case_from_dict(box_case(30, 4, upper=[[30, 0], [30, 4], [4, 4], [4, 10], [0, 10]], ratio=0.95))
    d = sd.case_to_dict(case)
    d["lower"] = {"polyline": [[0, 10], [0, 0], [30, 0]]}
    d["target"] = {"polyline": rigid(d["lower"]["polyline"], 10, (1, -1)).tolist()}
    r = sd.deform(sd.case_from_dict(d))
    assert abs(r.relative_error) <= 1e-9 and r.quality.initial.jacobian_min > 0 and r.quality.final.jacobian_min > 0
