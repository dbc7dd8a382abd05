"""The command line, run in-process: outputs, exit status 2 and no file on bad input."""

import json

import pytest

from sectiondeform.cli import main

from conftest import SHARED_CASES, box_case


def _write(tmp_path, obj, name="case.json"):
    p = tmp_path / name
    p.write_text(obj if isinstance(obj, str) else json.dumps(obj))
    return p


@pytest.mark.parametrize("path", SHARED_CASES, ids=[p.stem for p in SHARED_CASES])
def test_deform_writes_the_result_format(path, tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["deform", str(path), "-o", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["format"] == "section-result/1"
    assert set(r["area"]) == {"initial", "target", "final", "relative_error"}
    assert abs(r["area"]["relative_error"]) <= 1e-9
    # The contour is the lower points, then the upper side back to the start, densified between the
    # images of the characteristic points ("upper"), which it passes through in order.
    contour, lower, upper = r["contour"], r["lower"], r["upper"]
    assert len(contour) >= len(lower) + len(upper) - 2
    assert contour[:len(lower)] == lower and upper[0] == lower[-1] and upper[-1] == lower[0]
    back = contour[len(lower) - 1:] + contour[:1]
    at = [back.index(p) for p in upper]
    assert at[0] == 0 and at[-1] == len(back) - 1 and at == sorted(set(at))
    mesh = r["meshes"]["final"]
    assert len(mesh["cells"]) == mesh["layers"] * mesh["columns"]
    assert "relative error" in capsys.readouterr().out


def test_deform_with_plot_and_overrides(tmp_path):
    out, fig = tmp_path / "r.json", tmp_path / "f.svg"
    case = _write(tmp_path, box_case(20, 5))
    assert main(["deform", str(case), "-o", str(out), "--plot", str(fig), "--area-ratio", "0.7"]) == 0
    r = json.loads(out.read_text())
    assert r["area"]["target"] == pytest.approx(70.0)
    assert fig.read_text().lstrip().startswith("<?xml")


def test_demo_prints_the_paper_figures_and_one_time(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["demo", "-o", "demo.json"]) == 0
    text = capsys.readouterr().out
    assert "4379 mm² -> 3503.2 mm²" in text
    assert text.count("re-deformation") == 1  # one re-deformation time, not two
    assert sorted(p.name for p in tmp_path.iterdir()) == ["demo.json"]  # no figure unless asked


def test_demo_figure_where_asked(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.chdir(tmp_path)
    assert main(["demo", "--plot", "fig.svg"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig.svg"]


def test_bench_times_a_users_case_and_writes_nothing(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = tmp_path / "box.json"
    case.write_text(json.dumps(box_case()))
    assert main(["bench", str(case), "--repeat", "3"]) == 0
    out = capsys.readouterr().out
    for line in ("prepare", "re-deformation"):
        (row,) = [r for r in out.splitlines() if r.strip().startswith(line)]
        assert float(row.split()[1]) > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["box.json"]
    assert main(["bench", str(case), "--repeat", "0"]) == 2


BAD = [
    ("{not json", "not valid JSON"),
    (dict(box_case(), lower={"spline": []}), "lower: unknown curve kind 'spline'"),
    ({k: v for k, v in box_case().items() if k != "target"}, "target: missing"),
    (box_case(upper=[[10, 1], [10, 4], [0, 4], [0, 0]]), "upper: starts at"),
    (box_case(upper=[[10, 0], [10, 4], [-2, -1], [0, 0]]), "crosses itself"),
    (json.dumps(box_case()).replace('[10.0, 4.0]', '[10.0, NaN]', 1), "coordinates must be finite"),
    (box_case(ratio=-0.8), "law.area_ratio: must be a finite number > 0"),
    (box_case(target={"polyline": [[1, 1], [1, 1]]}), "target.polyline: the curve has zero length"),
    (dict(box_case(), options={"model": "fast"}), "options.model: unknown model"),
]


@pytest.mark.parametrize("case, message", BAD, ids=[m.split(":")[0][:20] for _, m in BAD])
def test_bad_input_exits_2_with_one_line_and_no_output(case, message, tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["deform", str(_write(tmp_path, case)), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err
    assert len(err.splitlines()) == 1
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == ["case.json"]


def test_unknown_output_format_and_missing_file(tmp_path, capsys):
    case = _write(tmp_path, box_case())
    assert main(["deform", str(case), "-o", str(tmp_path / "r.xyz")]) == 2
    assert "unknown output format '.xyz'" in capsys.readouterr().err
    assert main(["deform", str(tmp_path / "nope.json"), "-o", str(tmp_path / "r.json")]) == 2
    assert "cannot read the case file" in capsys.readouterr().err


def test_help_on_every_command(capsys):
    from sectiondeform.cli import build_parser

    parser = build_parser()
    names = parser._subparsers._group_actions[0].choices
    assert {"deform", "demo"} <= set(names)
    for name in names:
        with pytest.raises(SystemExit) as info:
            main([name, "--help"])
        assert info.value.code == 0
        assert "usage: sectiondeform" in capsys.readouterr().out


@pytest.mark.parametrize("extra", [["--plot", "fig.gif"], ["--mesh-out", "m.stl"]])
def test_bad_secondary_output_writes_nothing(extra, tmp_path, capsys):
    case = _write(tmp_path, box_case())
    out = tmp_path / "r.json"
    args = ["deform", str(case), "-o", str(out)] + [str(tmp_path / a) if "." in a else a for a in extra]
    assert main(args) == 2
    assert "unknown" in capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == ["case.json"]


def test_missing_output_folder_is_one_line(tmp_path, capsys):
    case = _write(tmp_path, box_case())
    assert main(["deform", str(case), "-o", str(tmp_path / "no" / "r.json")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--output: the folder" in err and len(err.splitlines()) == 1
    assert [p.name for p in tmp_path.iterdir()] == ["case.json"]


V2_CASES = SHARED_CASES[0].parent / "v2"


def test_deform_prints_each_body_and_writes_the_version_2_result(tmp_path, capsys):
    out = tmp_path / "r.json"
    case = V2_CASES / "two-layer-strip.json"
    assert main(["deform", str(case), "-o", str(out), "--no-meshes"]) == 0
    r = json.loads(out.read_text())
    laws = [b["law"]["area_ratio"] for b in json.loads(case.read_text())["bodies"]]
    assert r["format"] == "section-result/2" and "meshes" not in r["bodies"][0]
    for body, ratio in zip(r["bodies"], laws):
        assert body["area"]["final"] == pytest.approx(ratio * body["area"]["initial"], rel=1e-9)
    text = capsys.readouterr().out
    assert "2 bodies" in text and "  backing\n" in text and "  cover\n" in text and text.count("relative error") == 2


def test_area_ratio_on_several_bodies_is_one_line_naming_the_option(tmp_path, capsys):
    from argparse import Namespace

    from sectiondeform.commands._common import apply_overrides
    from sectiondeform.errors import CaseError
    from sectiondeform.io.case import load_case
    from sectiondeform.laws import AreaRatio

    problem = load_case(V2_CASES / "two-layer-strip.json")
    with pytest.raises(CaseError) as exc:
        apply_overrides(problem, Namespace(area_ratio=0.9))
    assert str(exc.value).startswith("--area-ratio: the case has 2 bodies") and "\n" not in str(exc.value)
    same = problem.replace(bodies=tuple(b.__class__(b.name, b.lower, b.upper, AreaRatio(0.9)) for b in problem.bodies))
    assert apply_overrides(same, Namespace(area_ratio=0.9)) == same  # a drawing's reader gave every body that law
    one = load_case(SHARED_CASES[0])
    assert apply_overrides(one, Namespace(area_ratio=0.7)).law == AreaRatio(0.7)
