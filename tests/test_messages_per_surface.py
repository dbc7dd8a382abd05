"""Each surface names an option in its own words: the library by its key, the command line by its flag.

Library messages name an option as ``option KEY`` (``option simplify``,
``option snap at 0.5``), never in Python syntax (``simplify=TOL``,
``layers={lower: NAME}``, ``split=(A, B)``); the command line writes each
in its spelling (``--simplify TOL``, ``--layers ROLE=NAME,...``,
``--split XA,YA XB,YB``) from one table, ``commands._common.OPTION_FLAGS``.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from sectiondeform.cli import main
from sectiondeform.commands._common import OPTION_FLAGS
from sectiondeform.curves import Polyline
from sectiondeform.errors import CaseError, spelled
from sectiondeform.io.drawing import case_from_drawing
from sectiondeform.io.pieces import Drawing, Piece
from sectiondeform.laws import AreaRatio

PYTHON_SYNTAX = re.compile(r"\b[a-z_]+=(\{|\(|[A-Z]{2,}\b|-?\d)|Deformer|AreaRatio\(")


def _refusal(**options) -> str:
    gap = Drawing([Piece(Polyline([[0, 0], [10, 0]]), frozenset({"CONTOUR"}), "a"),
                   Piece(Polyline([[10, 0.5], [0, 0.5]]), frozenset({"CONTOUR"}), "b")], "mm", 1.0, {}, Path("g.svg"))
    with pytest.raises(CaseError) as info:
        case_from_drawing(gap, **options)
    return str(info.value)


@pytest.mark.parametrize("options, key", [
    (dict(split=((1, 0), (9, 0)), target_arc=0.0, law=AreaRatio(0.9)), "close_gap"),
    (dict(law=AreaRatio(0.9), target_arc=0.0), "split"),
])
def test_the_library_names_the_key_without_python_syntax(options, key):
    message = _refusal(**options)
    assert f"option {key}" in message and not PYTHON_SYNTAX.search(message), message
    assert "--" not in message


def _svg_box(path: Path) -> Path:
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 20 20">'
                    '<path id="CONTOUR" d="M 0 0 L 10 0 L 10 4 L 0 4 Z" fill="none" stroke="black"/></svg>')
    return path


@pytest.mark.parametrize("args, flag", [
    ([], "--split XA,YA XB,YB"),                                          # one contour, no split points
    (["--split", "-1,-30", "9,0", "--target-arc", "0"], "--split-tol D"),  # split point far from the contour
    (["--layers", "lower=BASE", "--target-arc", "0"], "--layers ROLE=NAME,..."),
])
def test_the_command_line_spells_the_flag(tmp_path, capsys, args, flag):
    pytest.importorskip("svgelements")
    out = tmp_path / "o.json"
    assert main(["convert", str(_svg_box(tmp_path / "c.svg")), str(out), "--area-ratio", "0.9", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and not out.exists()
    assert flag in err or flag.split()[0] + ":" in err, err
    assert "option " not in err and not PYTHON_SYNTAX.search(err), err


def test_one_table_spells_every_key_and_a_value():
    names = dict(OPTION_FLAGS)
    assert spelled("x: allow it with option snap at 0.505 or option close_gap at 1", names) == \
        "x: allow it with --snap 0.505 or --close-gap 1"
    assert spelled("simplify: must be > 0", names) == "--simplify: must be > 0"
    assert spelled("give option simplify", names) == "give --simplify TOL"
    assert spelled("option unknown stays", names) == "option unknown stays"


CASES = Path(__file__).parent / "data" / "cases"


def test_a_refusal_naming_the_model_is_spelled_by_each_surface(tmp_path, capsys):
    """The paper model refuses rigid parts naming the model: as a key in Python, a flag in the shell, a label on the page."""
    import sectiondeform as sd
    from sectiondeform.app.server import one_line

    case = CASES / "v2" / "bumper-under-plate.json"
    with pytest.raises(sd.SectionDeformError) as info:
        sd.deform(sd.load_case(case), model="paper")
    message = str(info.value)
    assert "option model at hyperelastic" in message and "--" not in message
    assert main(["deform", str(case), "--model", "paper", "-o", str(tmp_path / "r.json")]) == 2
    err = capsys.readouterr().err
    assert "(--model hyperelastic" in err or "use --model hyperelastic" in err, err
    assert "option model" not in err and not (tmp_path / "r.json").exists()
    page = one_line(message)
    assert "use model hyperelastic" in page and "option" not in page and "--" not in page


@pytest.mark.parametrize("law, message", [({"area_ratio": -0.5}, "bodies[1].law.area_ratio: must be"),
                                          ({"volume_ratio": 0}, "bodies[1].law.volume_ratio: must be")])
def test_a_bad_law_of_one_body_names_the_body(law, message):
    import json

    import sectiondeform as sd

    case = json.loads((CASES / "v2" / "two-layer-strip.json").read_text())
    case["bodies"][1]["law"] = law
    with pytest.raises(CaseError) as info:
        sd.case_from_dict(case)
    assert str(info.value).startswith(message)


def test_a_bad_area_ratio_on_the_command_line_names_the_option(tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["deform", str(CASES / "paper-example.json"), "--area-ratio", "-0.5", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == "sectiondeform deform: error: --area-ratio: must be a finite number > 0, got -0.5"
    assert not out.exists()


def test_a_misspelt_option_gets_the_nearest_one(capsys):
    with pytest.raises(SystemExit) as info:
        main(["deform", str(CASES / "paper-example.json"), "--area-ration", "0.8", "-o", "r.json"])
    assert info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "did you mean --area-ratio?" in err[0]


def test_another_commands_option_is_named_as_such_not_suggested_as_itself(capsys):
    with pytest.raises(SystemExit) as info:
        main(["deform", str(CASES / "paper-example.json"), "-o", "r.json", "--quiet"])
    assert info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--quiet is an option of " in err[0] and "sweep" in err[0] and "did you mean" not in err[0]


def test_an_output_that_is_a_folder_is_named_as_one(tmp_path, capsys):
    assert main(["deform", str(CASES / "paper-example.json"), "-o", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.endswith(f"--output: {str(tmp_path)!r} is a folder; give a file in it, such as {str(tmp_path / 'out.json')!r}")
    assert list(tmp_path.iterdir()) == []
