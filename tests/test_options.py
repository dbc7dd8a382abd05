"""Options, cases and figures as types: checked once, immutable, hashable, round trips equal."""

import dataclasses
import json

import pytest

import sectiondeform as sd
from sectiondeform.models import MODEL_NAMES, get_model, model_options_types
from sectiondeform.models.base import MeshQuality
from sectiondeform.options import Options, options_from_json

from conftest import SHARED_CASES, box_case


def test_a_typo_names_the_nearest_option():
    with pytest.raises(sd.CaseError, match=r"^options\.chordal_eror: unknown option; did you mean chordal_error\?"):
        options_from_json({"chordal_eror": 0.01})


def test_unknown_option_far_from_any_lists_the_known_ones():
    with pytest.raises(sd.CaseError, match=r"options\.zzz: unknown option; use one of model"):
        options_from_json({"zzz": 1})


def test_user_keys_are_carried_through_unread():
    o = options_from_json({"x-color": "red", "extra": {"batch": [1, 2]}, "refine": 2})
    assert o.user_data == {"x-color": "red", "extra": {"batch": [1, 2]}}
    assert options_from_json(o.to_json()) == o


def test_an_option_of_any_model_is_accepted_and_read_by_that_model_only():
    case = sd.case_from_dict(box_case(bulk_to_shear=500.0))
    assert case.options.for_model("hyperelastic").bulk_to_shear == 500.0
    assert case.options.for_model("paper").to_json() == {}
    assert sd.Deformer(case, model="paper").deform().area_final > 0


def test_every_model_declares_a_frozen_options_type_with_defaults():
    for name, t in model_options_types().items():
        assert get_model(name).options_type is t
        o = t()
        assert dataclasses.is_dataclass(o) and o.to_json() == {}
        for key in t.keys():
            with pytest.raises(dataclasses.FrozenInstanceError):
                setattr(o, key, 1.0)


@pytest.mark.parametrize("value", [0, -1, float("nan"), "2", True, 10**400])
@pytest.mark.parametrize("key", ["chordal_error", "element_size", "refine", "contact_tolerance", "bulk_to_shear",
                                 "elements_through_thickness", "newton_tolerance"])
def test_every_number_option_must_be_finite_and_positive(key, value):
    with pytest.raises(sd.CaseError, match=f"^options.{key}: "):
        options_from_json({key: value})


def test_model_names_come_from_the_registry():
    assert set(MODEL_NAMES) == set(model_options_types())
    with pytest.raises(sd.CaseError, match="did you mean hyperelastic"):
        options_from_json({"model": "hyperelastc"})


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_two_loads_are_equal_and_hash_alike_and_a_round_trip_is_equal(path):
    a, b = sd.load_case(path), sd.load_case(path)
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1
    assert sd.case_from_dict(sd.case_to_dict(a)) == a
    assert sd.case_from_dict(json.loads(json.dumps(sd.case_to_dict(a)))) == a


def test_case_and_options_are_immutable():
    case = sd.case_from_dict(box_case(refine=2))
    with pytest.raises(dataclasses.FrozenInstanceError):
        case.options.refine = 3
    with pytest.raises(dataclasses.FrozenInstanceError):
        case.name = "x"
    assert case.options.replace(refine=3).refine == 3.0 and case.options.refine == 2.0


def test_cases_that_differ_are_unequal():
    a = sd.case_from_dict(box_case())
    assert a != sd.case_from_dict(box_case(ratio=0.9))
    assert a != sd.case_from_dict(box_case(refine=2))
    assert Options() == options_from_json({}) == options_from_json({"refine": 1})


def test_quality_and_info_are_types_whose_json_keys_are_the_result_format():
    r = sd.deform(sd.case_from_dict(box_case()))
    q = r.quality
    assert isinstance(q.initial, MeshQuality) and q.initial.layers >= 1
    j = r.to_json()["quality"]
    assert {"layers", "columns", "elements", "element_size", "jacobian_min", "jacobian_max", "virtual_columns",
            "final_jacobian_min", "final_jacobian_max"} <= set(j)
    assert j["final_jacobian_min"] == q.final.jacobian_min
    assert set(r.to_json()["info"]) == {"height_scale", "normal_smoothing", "bend_change", "overhang", "stretch_min",
                                        "stretch_max", "aspect_change", "uniform_height_scale"}
    h = sd.Deformer(sd.case_from_dict(box_case()), model="hyperelastic").deform()
    assert h.quality.initial.layers is None and h.quality.initial.nodes > 0
    assert {"newton_full", "warm_start", "area_correction"} <= set(h.to_json()["info"])
    assert "final_area_stretch_min" in h.to_json()["quality"]
