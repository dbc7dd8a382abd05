"""Strict inputs: every bad number or file is one CaseError line, never another exception."""

import json
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.checks import COORDINATE_LIMIT
from sectiondeform.io import read_case

from conftest import box_case

FUZZ = Path(__file__).parent / "data" / "fuzz-found"
# The fuzz-found inputs broken at the JSON level (numbers too large for a float, deep nesting, not UTF-8).
FUZZ_FILES = sorted(p for p in FUZZ.glob("*.json")
                    if any(k in p.name for k in ("overflowerror-case", "overflowerror-curves", "overflowerror-laws",
                                                 "recursionerror", "unicodedecodeerror")))


def _one_line_case_error(call):
    with pytest.raises(sd.CaseError) as info:
        call()
    text = str(info.value)
    assert "\n" not in text and text
    return text


def test_fuzz_fixtures_are_present():
    assert len(FUZZ_FILES) == 9  # a missing fixture is a failure, not a skip


@pytest.mark.parametrize("path", FUZZ_FILES, ids=[p.stem for p in FUZZ_FILES])
@pytest.mark.parametrize("reader", [sd.load_case, read_case], ids=["load_case", "read_case"])
def test_fuzz_found_inputs_give_one_line_case_errors(path, reader):
    _one_line_case_error(lambda: reader(path))


@pytest.mark.parametrize(
    "mutate, field",
    [
        (lambda d: d["lower"].update(polyline=[["0", "0"], [10, 0]]), "lower.polyline[0]"),
        (lambda d: d["lower"].update(polyline=[[0, 0], [10**400, 0]]), "lower.polyline[1]"),
        (lambda d: d["lower"].update(polyline=[[0, 0], [True, 0]]), "lower.polyline[1]"),
        (lambda d: d["upper"].update(polyline=[[10, 0], [10, 1e308], [0, 4], [0, 0]]), "upper.polyline[1]"),
        (lambda d: d.update(law={"area_ratio": 10**400}), "law.area_ratio"),
        (lambda d: d.update(law={"area_ratio": 1e-9}), "law.area_ratio"),
        (lambda d: d.update(law={"area_ratio": 1e9}), "law.area_ratio"),
        (lambda d: d.update(options={"chordal_error": 10**400}), "options.chordal_error"),
        (lambda d: d.update(options={"chordal_error": "0.1"}), "options.chordal_error"),
        (lambda d: d.update(options={"element_size": 1e300}), "options.element_size"),
        (lambda d: d.update(options={"refine": 1e6}), "options.refine"),
        (lambda d: d.update(options={"bulk_to_shear": float("inf")}), "options.bulk_to_shear"),
        (lambda d: d.update(target={"arc": {"center": [0, 0], "radius": 10**400, "start_deg": 0, "end_deg": 90}}),
         "target.arc.radius"),
        (lambda d: d.update(target={"arc": {"center": [0, 0], "radius": 2e9, "start_deg": 0, "end_deg": 90}}),
         "target.arc.radius"),
        (lambda d: d.update(lowr={"polyline": [[0, 0], [1, 0]]}), "lowr: unknown key; did you mean lower?"),
    ],
)
def test_bad_numbers_and_keys_are_one_line_errors(mutate, field):
    d = box_case()
    mutate(d)
    text = _one_line_case_error(lambda: sd.case_from_dict(json.loads(json.dumps(d))))
    assert text.startswith(field)


def test_note_x_keys_and_extra_are_accepted_at_the_top_level():
    d = box_case()
    d.update({"note": "a box", "x-origin": {"cad": "v2"}, "extra": [1, 2]})
    assert sd.case_from_dict(d) == sd.case_from_dict(box_case())


def test_coordinates_beyond_the_limit_are_refused_and_within_accepted():
    d = box_case()
    big = 0.5 * COORDINATE_LIMIT
    d["lower"]["polyline"] = [[big, 0.0], [big + 10.0, 0.0]]
    d["upper"]["polyline"] = [[big + 10.0, 0.0], [big + 10.0, 4.0], [big, 4.0], [big, 0.0]]
    d["target"] = {"polyline": d["lower"]["polyline"]}
    assert sd.case_from_dict(d).lower.length == pytest.approx(10.0)
    d["lower"]["polyline"][0][0] = -2 * COORDINATE_LIMIT
    _one_line_case_error(lambda: sd.case_from_dict(d))


def test_numpy_warnings_never_escape(recwarn):
    deformer = sd.Deformer(sd.case_from_dict(box_case()))
    deformer.deform(target_nodes=deformer.section.lower * [1.0, 1.0])
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]


def test_not_utf8_and_deep_nesting_name_the_file(tmp_path):
    bad = tmp_path / "latin1.json"
    bad.write_bytes('{"name": "µ"}'.encode("latin-1"))
    assert "not UTF-8" in _one_line_case_error(lambda: sd.load_case(bad))
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100000 + "]" * 100000)
    assert "nests too deeply" in _one_line_case_error(lambda: sd.load_case(deep))


def test_non_finite_target_array_is_refused():
    deformer = sd.Deformer(sd.case_from_dict(box_case()))
    _one_line_case_error(lambda: deformer.deform(np.array([[0.0, 0.0], [np.nan, 0.0]])))
