"""Every refusal of an assembly case: one line naming the bodies and the place."""

import json

import pytest

from sectiondeform.cli import main
from sectiondeform.errors import CaseError, GeometryError
from sectiondeform.io.case import case_from_dict

from conftest import CASES_DIR

STRIP = CASES_DIR / "v2" / "two-layer-strip.json"
DRUM = CASES_DIR / "v2" / "tread-on-drum.json"


def poly(*pts):
    return {"polyline": [list(p) for p in pts]}


def body(name, lower, upper, ratio=1.0):
    return {"name": name, "lower": poly(*lower), "upper": poly(*upper), "law": {"area_ratio": ratio}}


def case(*bodies, support=((0, 0), (4, 0))):
    return {"format": "section-case/2", "support": poly(*support), "target": poly(*support), "bodies": list(bodies)}


BASE = body("base", [(0, 0), (2, 0)], [(2, 0), (2, 1), (0, 1), (0, 0)])


def refused(data, error=GeometryError):
    with pytest.raises(error) as info:
        case_from_dict(data)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_a_lower_curve_resting_on_nothing_gives_the_gap_and_its_place():
    lifted = body("lid", [(0, 1.5), (2, 1.5)], [(2, 1.5), (1, 2.5), (0, 1.5)])
    message = refused(case(BASE, lifted))
    assert "bodies[1] 'lid'" in message and "rests on nothing" in message and "gap 0.5" in message


def test_overlapping_interiors_give_the_overlap_area():
    hanging = body("drop", [(0, 1), (2, 1)], [(2, 1), (1, 0.5), (0, 1)])  # lies under its lower curve, inside base
    message = refused(case(BASE, hanging))
    assert "'base'" in message and "'drop'" in message and "overlap (area 0.5" in message


def test_bodies_resting_on_each_other_in_a_cycle_are_refused():
    a = body("a", [(0, 0), (1, 0), (1, 1)], [(1, 1), (0, 1), (0, 0)])  # runs up the side it shares with b
    b = body("b", [(0, 1), (1, 1)], [(1, 1), (1, 0), (2, 0), (2, 2), (0, 2), (0, 1)])  # rests on a's top
    message = refused(case(a, b))
    assert "cycle" in message and "'a'" in message and "'b'" in message


def test_a_shared_piece_in_both_upper_curves_is_refused():
    left = body("left", [(0, 0), (1, 0)], [(1, 0), (1, 1), (0, 1), (0, 0)])
    right = body("right", [(1, 0), (2, 0)], [(2, 0), (2, 1), (1, 1), (1, 0)])
    message = refused(case(left, right))
    assert "upper curves share a piece of length 1" in message and "'left'" in message and "'right'" in message


def test_a_shared_piece_in_both_lower_curves_is_refused():
    above = body("above", [(0, 0), (2, 0)], [(2, 0), (2, 1), (0, 1), (0, 0)])
    below = body("below", [(3, 0), (1, 0)], [(1, 0), (1, -1), (3, -1), (3, 0)])
    message = refused(case(above, below))
    assert "lower curves share a piece of length 1" in message


def test_duplicate_names_are_refused():
    message = refused(case(BASE, body("base", [(0, 1), (2, 1)], [(2, 1), (1, 2), (0, 1)])), CaseError)
    assert message.startswith("bodies[1].name") and "bodies[0]" in message


def test_unknown_keys_name_the_nearest_known_one():
    data = json.loads(STRIP.read_text())
    data["bodys"] = data.pop("bodies")
    assert "did you mean bodies?" in refused(data, CaseError)
    data = json.loads(STRIP.read_text())
    data["bodies"][1]["materail"] = data["bodies"][1].pop("material")
    assert refused(data, CaseError).startswith("bodies[1].materail: unknown key; did you mean material?")
    data = json.loads(STRIP.read_text())
    data["bodies"][0]["material"]["shear_modulus"] = -1
    assert refused(data, CaseError).startswith("bodies[0].material.shear_modulus")


def test_a_revolution_axis_crossing_a_body_or_given_by_one_point_is_refused():
    data = json.loads(DRUM.read_text())
    data["revolution"]["axis"] = [[0, 10], [1, 10]]  # through the tread
    message = refused(data)
    assert message.startswith("bodies[1] 'tread': the revolution axis crosses it")
    data = json.loads(DRUM.read_text())
    data["revolution"]["axis"] = [[0, 0], [0, 0]]
    assert refused(data, CaseError).startswith("revolution.axis")


def test_cli_deforms_an_assembly_to_section_result_2(tmp_path, capsys):
    out, fig = tmp_path / "r.json", tmp_path / "r.png"
    assert main(["deform", str(STRIP), "-o", str(out), "--plot", str(fig), "--no-meshes"]) == 0
    data = json.loads(out.read_text())
    assert data["format"] == "section-result/2" and [b["name"] for b in data["bodies"]] == ["backing", "cover"]
    assert "meshes" not in data["bodies"][0]
    assert fig.stat().st_size > 0
    assert "cover" in capsys.readouterr().out


@pytest.mark.parametrize("extra", [["--area-ratio", "0.9"]])
def test_cli_refusals_on_assemblies_exit_2_and_write_nothing(tmp_path, capsys, extra):
    out = tmp_path / "r.json"
    extra = [str(tmp_path / e) if e.endswith(".vtu") else e for e in extra]
    assert main(["deform", str(STRIP), "-o", str(out), *extra]) == 2
    assert not out.exists() and list(tmp_path.iterdir()) == []
    assert len(capsys.readouterr().err.strip().splitlines()) == 1



def test_a_target_of_zero_length_is_named_as_for_one_body():
    import numpy as np

    from sectiondeform.deform import Deformer

    deformer = Deformer(case_from_dict(json.loads((CASES_DIR / "v2" / "two-layer-strip.json").read_text())))
    for nodes in (np.array([[1.0, 1.0], [1.0, 1.0]]), np.array([[1.0, 1.0], [1.0 + 1e-13, 1.0]])):
        with pytest.raises(CaseError, match=r"^target: the target has zero length$"):
            deformer.deform(nodes)
