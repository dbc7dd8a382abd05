import json

import pytest

import sectiondeform as sd
from sectiondeform.errors import CaseError
from sectiondeform.io.json import write_case

from conftest import SHARED_CASES, box_case


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_read_write_read_is_identity(path, tmp_path):
    case = sd.load_case(path)
    out = tmp_path / "case.json"
    write_case(out, case)
    again = sd.load_case(out)
    assert sd.case_to_dict(again) == sd.case_to_dict(case)
    # and the deformation of both is the same
    assert sd.deform(again).upper.tolist() == sd.deform(case).upper.tolist()


@pytest.mark.parametrize(
    "mutate, field",
    [
        (lambda d: d.pop("lower"), "lower: missing"),
        (lambda d: d.pop("law"), "law: missing"),
        (lambda d: d.update(format="section-case/9"), "format: expected 'section-case/1'"),
        (lambda d: d.update(law={"area_ratio": 0}), "law.area_ratio: must be a finite number > 0"),
        (lambda d: d.update(law={"area_ratio": -0.5}), "law.area_ratio"),
        (lambda d: d.update(law={"area_ratio": "0.8"}), "law.area_ratio"),
        (lambda d: d.update(law={"volume": 1}), "law: unknown law 'volume'"),
        (lambda d: d.update(options={"model": "magic"}), "options.model: unknown model 'magic'"),
        (lambda d: d.update(options={"chordal_error": -1}), "options.chordal_error: must be a finite number > 0"),
        (lambda d: d.update(options=[1]), "options: expected an object"),
        (lambda d: d.update(upper={"circle": 1}), "upper: unknown curve kind 'circle'"),
        (lambda d: d.update(target={"polyline": [[0, 0], [0, 0]]}), "target.polyline: the curve has zero length"),
        (lambda d: d.update(name=3), "name: expected a string"),
    ],
)
def test_bad_case_fields(mutate, field):
    d = box_case()
    mutate(d)
    with pytest.raises(CaseError) as info:
        sd.case_from_dict(d)
    assert str(info.value).startswith(field)
    assert "\n" not in str(info.value)


def test_load_case_reports_json_errors(tmp_path):
    p = tmp_path / "bad.json"
    p.write_text('{"lower": [1, 2,, 3]}')
    with pytest.raises(CaseError, match=r"not valid JSON: .* line 1"):
        sd.load_case(p)
    with pytest.raises(CaseError, match="cannot read the case file"):
        sd.load_case(tmp_path / "missing.json")
    p.write_text(json.dumps([1, 2]))
    with pytest.raises(CaseError, match="case: expected a JSON object"):
        sd.load_case(p)
