"""Deformer contracts: same inputs give the same bits, any curve is a target, leaks and flips are reported."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.curves import Arc, Polyline

from conftest import SHARED_CASES, box_case


def _bent(deformer, amount):
    nodes = deformer.target_nodes()
    s = deformer.section.fractions
    return nodes + amount * deformer.section.thickness * np.sin(np.pi * s)[:, None] * [0.0, 1.0]


def test_hyperelastic_answer_does_not_depend_on_call_history():
    case = sd.load_case(SHARED_CASES[0])
    deformer = sd.Deformer(case, model="hyperelastic")
    a, b = _bent(deformer, 0.03), _bent(deformer, -0.05)
    first = deformer.deform(target_nodes=a)
    deformer.deform(target_nodes=b)
    deformer.preview(target_nodes=b)
    again = deformer.deform(target_nodes=a)
    fresh = sd.Deformer(case, model="hyperelastic").deform(target_nodes=a)
    assert np.array_equal(first.upper, again.upper) and np.array_equal(first.upper, fresh.upper)
    assert np.array_equal(first.final_mesh.points, fresh.final_mesh.points)
    assert not first.info.warm_start


def test_warm_start_is_an_argument_and_lands_near_the_cold_answer():
    case = sd.load_case(SHARED_CASES[0])
    deformer = sd.Deformer(case, model="hyperelastic")
    a, b = _bent(deformer, 0.03), _bent(deformer, 0.04)
    warm = deformer.deform(target_nodes=b, start=deformer.deform(target_nodes=a))
    cold = deformer.deform(target_nodes=b)
    assert warm.info.warm_start and not cold.info.warm_start
    assert np.abs(warm.upper - cold.upper).max() <= 1e-5 * deformer.section.thickness


def test_one_prepared_section_serves_several_threads():
    case = sd.load_case(SHARED_CASES[0])
    deformer = sd.Deformer(case, model="hyperelastic")
    targets = [_bent(deformer, x) for x in (0.02, -0.02, 0.04, -0.04)]
    alone = [deformer.deform(target_nodes=t).upper for t in targets]
    with ThreadPoolExecutor(2) as pool:
        together = list(pool.map(lambda t: deformer.deform(target_nodes=t).upper, targets * 2))
    for i, up in enumerate(together):
        assert np.array_equal(up, alone[i % 4])


def test_a_polyline_target_of_any_node_count_is_a_curve():
    deformer = sd.Deformer(sd.case_from_dict(box_case()))
    straight = np.array([[0.0, 0.0], [3.0, 0.0], [10.0, 0.0]])  # 3 nodes, not one per lower node
    r = deformer.deform(straight)
    assert np.allclose(r.lower, deformer.section.lower, atol=1e-12)
    assert np.array_equal(deformer.deform(Polyline(straight)).upper, r.upper)


def test_target_nodes_must_have_one_node_per_lower_node():
    deformer = sd.Deformer(sd.case_from_dict(box_case()))
    with pytest.raises(sd.CaseError, match="^target_nodes: expected"):
        deformer.deform(target_nodes=[[0.0, 0.0], [10.0, 0.0], [11.0, 0.0]] * 7)
    with pytest.raises(sd.CaseError, match="either target or target_nodes"):
        deformer.deform([[0, 0], [1, 0]], target_nodes=deformer.section.lower)


def _quarter_arc(length):
    r = 2.0 * length / np.pi
    return Arc(np.array([0.0, -r]), r, 90.0, 0.0)  # from (0, 0) clockwise, length ``length``


def test_a_target_the_section_was_not_sampled_for_is_reported_with_its_deviation():
    deformer = sd.Deformer(sd.case_from_dict(box_case(40.0, 4.0, chordal_error=1e-3)))  # sampled for a straight target
    arc = _quarter_arc(40.0)
    tol = deformer.section.chordal_error
    deviation = deformer.target_deviation(arc)
    # independent: the sagitta of the longest chord (the element step) on this radius
    steps = np.diff(deformer.section.fractions) * arc.length
    sagitta = arc.radius * (1 - np.cos(steps.max() / (2 * arc.radius)))
    assert deviation == pytest.approx(sagitta, rel=1e-6)
    r = deformer.deform(arc)
    assert deviation > 1.5 * tol
    assert any(f"strays {deviation:.3g}" in w and "prepare again on a case with this target" in w for w in r.warnings)
    # on its own case, the same arc is resolved: no warning
    own = sd.Deformer(sd.case_from_dict(box_case(40.0, 4.0, arc.to_json(), chordal_error=1e-3)))
    assert own.target_deviation() <= 1.5 * own.section.chordal_error
    # no sampling warning (the 4-point box's upper chord on this arc does get a height-scale warning)
    assert not [w for w in own.deform().warnings if w.startswith("target:")]


def test_the_case_own_target_gives_no_sampling_warning():
    for path in SHARED_CASES:
        d = sd.Deformer(sd.load_case(path))
        assert d.target_deviation() <= 1.5 * d.section.chordal_error


def test_a_lower_curve_drawn_the_other_way_is_refused_with_the_fix():
    d = box_case()
    d["lower"] = {"polyline": [[10.0, 0.0], [0.0, 0.0]]}
    d["upper"] = {"polyline": [[0.0, 0.0], [0.0, 4.0], [10.0, 4.0], [10.0, 0.0]]}
    case = sd.case_from_dict(d)
    for model in ("paper", "hyperelastic"):
        with pytest.raises(sd.GeometryError, match="reverse the lower curve or the target"):
            sd.Deformer(case, model=model).deform()
    # drawn the same way as the target, the same outline deforms
    d["target"] = {"polyline": [[10.0, 0.0], [0.0, 0.0]]}
    r = sd.deform(sd.case_from_dict(d))
    assert r.contour[:, 1].min() >= -1e-9


def test_the_paper_example_figures_are_unchanged():
    r = sd.deform(sd.load_case(sd.example_case_path()))
    assert round(r.area_initial) == 4379 and round(r.area_final, 1) == 3503.2


def test_a_half_turned_target_near_the_reversed_lower_curve_is_flagged_not_refused():
    """A half turn of the support on purpose cannot be told from a drawing error: a warning, not a refusal."""
    d = box_case()
    a = np.radians(166.0)  # lower (0, 0)-(10, 0) turned by 166 degrees about the origin, then moved by 10 in x
    d["target"] = {"polyline": [[10.0, 0.0], [10.0 + 10.0 * np.cos(a), 10.0 * np.sin(a)]]}
    r = sd.deform(sd.case_from_dict(d))
    assert any("turned over" in w for w in r.warnings)
    # a rigid motion: the section turns with its support, area kept
    assert abs(r.relative_error) <= 1e-9
