"""``sectiondeform validate``: report, figure, progress, exit status 2 and no file on bad input."""

from __future__ import annotations

import json
import sys

import pytest

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.cli import main  # noqa: E402

from conftest import CASES_DIR, box_case  # noqa: E402

GROOVED = CASES_DIR / "grooved-tread.json"


def _write(tmp_path, obj, name="case.json"):
    p = tmp_path / name
    p.write_text(obj if isinstance(obj, str) else json.dumps(obj))
    return p


def test_report_figure_and_progress(tmp_path, capsys):
    report, fig = tmp_path / "report.json", tmp_path / "overlay.png"
    assert main(["validate", str(GROOVED), "-o", str(report), "--plot", str(fig), "--mesh-size", "0.3"]) == 0
    out, err = capsys.readouterr()
    assert "Hausdorff" in out and "speed ratio" in out and "wrote" in out
    assert "reference: load 100.0%" in err  # progress on stderr
    r = json.loads(report.read_text())
    assert r["format"] == "section-validation/1"
    T = r["thickness"]
    assert T == pytest.approx(1804.0 / 90.0)
    s = r["shape"]
    assert s["hausdorff_relative"] == pytest.approx(s["hausdorff"] / T)
    assert s["hausdorff"] <= s["max_pointwise"] + 1e-9
    # The paper's method is not the physics on this tread: a few to a few tens of % of T apart.
    assert 0.03 < s["hausdorff_relative"] < 0.4
    assert abs(r["fast"]["area_relative_error"]) < 1e-9
    assert abs(r["reference"]["area_relative_error"]) < 1e-3  # compressibility only (bulk/shear 1000)
    assert r["reference"]["solver"]["bulk_to_shear"] == 1000.0
    assert len(r["fast"]["upper"]) == len(r["reference"]["upper"]) == len(r["pointwise_distance"]) == 18
    assert r["speed_ratio"] == pytest.approx(r["reference"]["seconds"] / r["fast"]["seconds"])
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_quiet_and_options(tmp_path, capsys):
    case = _write(tmp_path, box_case(30.0, 6.0, ratio=0.85, bulk_to_shear=200))
    report = tmp_path / "r.json"
    assert main(["validate", str(case), "-q", "-o", str(report), "--mesh-size", "0.5", "--area-ratio", "0.9"]) == 0
    assert capsys.readouterr().err == ""
    r = json.loads(report.read_text())
    assert r["reference"]["solver"]["bulk_to_shear"] == 200.0
    assert r["area"]["target"] == pytest.approx(0.9 * 180.0)


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--plot", "fig.bmp"], "unknown figure format"),
        (["--bulk-to-shear", "10"], "bulk_to_shear"),
        (["--mesh-size", "-1"], "mesh_size"),
        (["-o", "no/such/folder/r.json"], "does not exist"),
    ],
)
def test_bad_options_exit_2_without_output(tmp_path, capsys, monkeypatch, extra, message):
    monkeypatch.chdir(tmp_path)
    case = _write(tmp_path, box_case(10.0, 4.0))
    assert main(["validate", str(case), "-q", *extra]) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.json"]


def test_bad_case_exits_2(tmp_path, capsys):
    assert main(["validate", str(tmp_path / "missing.json"), "-q"]) == 2
    assert "cannot read" in capsys.readouterr().err
    bad = _write(tmp_path, "{not json", "bad.json")
    assert main(["validate", str(bad), "-q"]) == 2


def test_no_convergence_exits_2_and_writes_nothing(tmp_path, capsys):
    case = _write(tmp_path, box_case(20.0, 5.0, target={"polyline": [[0, 0], [10, 0], [0, 0.01]]}))
    report = tmp_path / "r.json"
    # The paper model itself may refuse this target; either way: one line, status 2, no report.
    assert main(["validate", str(case), "-q", "--mesh-size", "0.5", "-o", str(report)]) == 2
    assert "error:" in capsys.readouterr().err
    assert not report.exists()


def test_missing_extra_exits_2(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "skfem", None)
    case = _write(tmp_path, box_case(10.0, 4.0))
    assert main(["validate", str(case), "-q"]) == 2
    assert "sectiondeform[fem]" in capsys.readouterr().err
