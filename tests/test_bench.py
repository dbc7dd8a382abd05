"""The benchmark's quick mode, run in-process: the report's structure, finite positive figures.

No time limits: the benchmark reports figures, it does not assert them.
"""

import json
import math

from sectiondeform.cli import main

from conftest import ROOT

CASES = ROOT / "benchmarks" / "cases"  # copies of the shared cases, in the repository


def _positive(value):
    return isinstance(value, (int, float)) and math.isfinite(value) and value > 0


def test_quick_benchmark_writes_json_and_markdown(tmp_path):
    out_json, out_md = tmp_path / "b.json", tmp_path / "b.md"
    assert main(["bench", "--quick", "--cases", str(CASES), "--json", str(out_json), "--markdown", str(out_md)]) == 0
    r = json.loads(out_json.read_text())
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
    for t in r["targets"]:
        assert math.isfinite(t["value"]) and isinstance(t["met"], bool)
    md = out_md.read_text()
    assert md.startswith("# Benchmarks") and "| figure | measured | target |" in md
