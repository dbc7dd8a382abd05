"""The project benchmark's quick mode, run in-process: the report's structure, finite positive figures.

No time limits: the benchmark reports figures, it does not assert them.
"""

import importlib.util
import json
import math

import pytest

from conftest import ROOT, load_benchmark

CASES = ROOT / "tests" / "data" / "cases"


def _load_runner():
    return load_benchmark("run")


def _positive(value):
    return isinstance(value, (int, float)) and math.isfinite(value) and value > 0


@pytest.fixture(scope="module")
def runner():
    return _load_runner()


def test_quick_benchmark_writes_json_and_markdown(tmp_path, runner, capsys):
    docs = ROOT / "docs"
    before = {p: p.stat().st_mtime_ns for p in docs.glob("benchmarks.*")}
    assert runner.main(["--quick", "--cases", str(CASES), "-o", str(tmp_path)]) == 0
    assert str(tmp_path / "benchmarks.json") in capsys.readouterr().out  # says where it wrote
    assert {p: p.stat().st_mtime_ns for p in docs.glob("benchmarks.*")} == before  # the tracked report untouched
    r = json.loads((tmp_path / "benchmarks.json").read_text())
    assert r["quick"] is True
    assert {"python", "numpy", "scipy", "shapely", "platform"} <= set(r["machine"])
    assert {p["case"] for p in r["pipeline"]} == {p.stem for p in CASES.glob("*.json")}
    for p in r["pipeline"]:
        assert all(_positive(p[k]) for k in ("full_s", "section_s", "prepare_s", "deform_s"))
        assert p["relative_area_error"] <= 1e-9
    assert all(_positive(p["redeform_s"]) for p in r["redeform"])
    rows = r["locate_scaling"]["rows"]
    assert [row["n"] for row in rows] == sorted(row["n"] for row in rows)
    assert all(_positive(row[k]) for row in rows for k in ("time_s", "per_point_s", "peak_mb"))
    assert math.isfinite(r["locate_scaling"]["exponent"])
    assert all(_positive(row["full_s"]) and row["elements"] > 0 for row in r["refinement"]["rows"])
    assert _positive(r["rbf"]["rbf_s"]) and r["rbf"]["rbf_area_error"] >= 0
    assert "available" in r["fe"]
    assert _positive(r["cli"]["cli_s"])
    if r["io"]["available"]:
        assert _positive(r["io"]["chain_s"]) and _positive(r["io"]["seal_read_s"])
    for model in ("paper", "hyperelastic"):  # the one implementation on one body and on two bonded ones
        rows = [row for row in r["bodies"] if row["model"] == model]
        assert sorted(row["bodies"] for row in rows) == [1, 2]
        for row in rows:
            assert all(_positive(row[k]) for k in ("prepare_s", "deform_s", "warm_s", "preview_s"))
            assert math.isfinite(row["preview_error"]) and row["preview_error"] >= 0
    for t in r["targets"]:
        assert math.isfinite(t["value"]) and isinstance(t["met"], bool)
    md = (tmp_path / "benchmarks.md").read_text()
    assert md.startswith("# Benchmarks") and "| figure | measured | target |" in md
    assert "## 7. One body and several" in md and "per body /" in md
    shared = {p.stem for p in CASES.glob("*.json")} | {p.stem for p in (CASES / "v2").glob("*.json")}
    assert {row["case"] for row in r["hyperelastic"]} == shared  # every shared case, one body and several
    for row in r["hyperelastic"]:
        assert all(_positive(row[k]) for k in ("full_s", "again_s", "preview_s")) and row["unknowns"] > 0
        assert row["factorisations_again"] >= 0 and 0 <= row["preview_error"] < 0.05
    assert "## 8. The hyperelastic model on every shared case" in md


def test_quick_run_without_output_goes_to_a_temporary_folder(runner, tmp_path):
    folder = runner.output_folder(None, quick=True)
    assert folder.is_dir() and not folder.is_relative_to(ROOT)
    folder.rmdir()
    assert runner.output_folder(tmp_path, quick=True) == tmp_path
    assert runner.output_folder(None, quick=False) == ROOT / "docs"


def test_the_package_holds_no_benchmark():
    assert importlib.util.find_spec("sectiondeform.bench") is None
