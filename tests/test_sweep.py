"""Parametric studies: same table on every engine, resume, failed rows, bad study files."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pa = pytest.importorskip("pyarrow")
import pyarrow.parquet as pq

import sectiondeform as sd
from sectiondeform.cli import main
from sectiondeform.compare import hausdorff_distance
from sectiondeform.curves import Polyline
from sectiondeform.studies import StudyError, load_study
from sectiondeform.studies.targets import transformed_target

DATA = Path(__file__).parent / "data" / "sweep"
VOLATILE = {"prepare_s", "place_s", "row_s", "worker"}
PAPER_RADIUS = 115.03571428571429


def _study(tmp_path, vary, name="study.json", extra=None):
    """A study file next to copies of the shared cases, so relative names resolve."""
    for f in DATA.glob("*.json"):
        if f.name != "study.json" and not (tmp_path / f.name).exists():
            shutil.copy(f, tmp_path / f.name)
    data = {"format": "section-study/1", "name": "t", "cases": [{"case": "paper-example.json", "vary": vary}], **(extra or {})}
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return path


BIG = {  # 2 x 3 x 2 x 2 x 2 = 48 rows, two sections (each row a deform run: a target prepares its own sampling)
    "area_ratio": {"start": 0.7, "stop": 1.0, "num": 2},
    "bend_radius": [30, PAPER_RADIUS, -150],
    "crown": {"start": 0, "stop": 4, "num": 2},
    "element_size": [None, 4.0],
    "stretch": [1.0, 1.05],
}


def _rows(table):
    """Table as a list of dicts in row order, without the timing and worker columns."""
    return [{k: v for k, v in r.items() if k not in VOLATILE} for r in table.sort_by("row").to_pylist()]


def _same(a, b):
    assert len(a) == len(b)
    for ra, rb in zip(a, b):
        assert ra.keys() == rb.keys()
        for k in ra:
            if isinstance(ra[k], float) and isinstance(rb[k], float):
                assert math.isclose(ra[k], rb[k], rel_tol=1e-9, abs_tol=1e-12), (k, ra, rb)
            else:
                assert ra[k] == rb[k], (k, ra, rb)


def test_same_table_on_every_engine(tmp_path):
    study = _study(tmp_path, BIG)
    one = sd.sweep(study, tmp_path / "one", workers=1)
    assert one.num_rows == 48
    ok = one.column("ok").to_pylist()
    assert 0 < sum(ok) < 48  # the tightest bends cannot carry the section: recorded, not raised
    two = sd.sweep(study, tmp_path / "two", workers=2)
    _same(_rows(one), _rows(two))
    pytest.importorskip("distributed")
    dask = sd.sweep(study, tmp_path / "dask", workers=2, scheduler="local")
    _same(_rows(one), _rows(dask))
    assert len(set(dask.column("worker").to_pylist())) >= 1


def test_rows_meet_the_law_and_keep_inputs(tmp_path):
    table = sd.sweep(_study(tmp_path, {"area_ratio": [0.75, 0.9], "crown": [0.0, 3.0]}), workers=0)
    for r in table.to_pylist():
        assert r["ok"], r["error"]
        assert r["area_final"] == pytest.approx(r["area_ratio"] * r["area_initial"], rel=1e-9)
        assert abs(r["relative_error"]) < 1e-9 and r["final_jacobian_min"] > 0 and r["final_area_stretch_min"] is None
    assert table.column("row").to_pylist() == [0, 1, 2, 3]
    assert [(r["area_ratio"], r["crown"]) for r in table.to_pylist()] == [(0.75, 0.0), (0.75, 3.0), (0.9, 0.0), (0.9, 3.0)]


def test_interrupted_study_resumes(tmp_path):
    out = tmp_path / "out"
    part = _study(tmp_path, {"area_ratio": [0.8, 0.9], "crown": [0.0, 2.0]}, "part.json")
    whole = _study(tmp_path, {"area_ratio": [0.7, 0.8, 0.9], "crown": [0.0, 2.0]}, "whole.json")
    first = pq.read_table(sd.sweep(part, out, workers=0) and out / "rows.parquet").to_pylist()
    # a run killed while writing leaves an unreadable part: it is dropped and its rows redone
    (out / "parts").mkdir()
    (out / "parts" / "part-0-0.parquet").write_bytes(b"PAR1 cut short")
    from sectiondeform.studies.api import _as_study, run_study

    info = run_study(_as_study(whole, None), out, workers=0)
    assert (info["skipped"], info["run"]) == (4, 2)
    table = pq.read_table(out / "rows.parquet").to_pylist()
    assert len(table) == 6 and len({r["row_id"] for r in table}) == 6
    again = {r["row_id"]: r["place_s"] for r in table}
    assert all(again[r["row_id"]] == r["place_s"] for r in first)  # done rows kept, not redone
    assert not (out / "parts").exists()
    assert run_study(_as_study(whole, None), out, workers=0)["run"] == 0


def test_failed_rows_are_recorded_and_the_others_done(tmp_path):
    (tmp_path / "targets").mkdir()
    (tmp_path / "targets" / "a-line.json").write_text(json.dumps({"polyline": [[0, 0], [110, 0]]}))
    tight = transformed_target(sd.load_case(DATA / "paper-example.json").lower, bend_radius=20.0)
    (tmp_path / "targets" / "b-tight.json").write_text(json.dumps(tight.to_json()))
    study = _study(tmp_path, {"targets": "targets", "area_ratio": [0.8, 0.85]})
    rows = sd.sweep(study, tmp_path / "out", workers=2, save="results", csv=True).to_pylist()
    assert [r["target_file"] for r in rows] == ["targets/a-line.json"] * 2 + ["targets/b-tight.json"] * 2
    assert [r["ok"] for r in rows] == [True, True, False, False]
    for r in rows[2:]:
        assert r["error"] and "\n" not in r["error"] and r["error_type"].endswith("Error")
        assert r["area_final"] is None
    saved = sorted(p.stem for p in (tmp_path / "out" / "results").glob("*.json"))
    assert saved == sorted(r["row_id"] for r in rows[:2])
    assert (tmp_path / "out" / "rows.csv").read_text().count("\n") == 5


def test_reference_gives_hausdorff_distance(tmp_path):
    ref = tmp_path / "ref.json"
    main(["deform", str(DATA / "paper-example.json"), "-o", str(ref), "--no-meshes"])
    table = sd.sweep(_study(tmp_path, {"area_ratio": [0.8, 0.7]}), workers=0, reference=ref).to_pylist()
    assert table[0]["hausdorff"] < 1e-9  # the case itself
    assert table[1]["hausdorff"] > 0.5


def test_csv_rows(tmp_path):
    _study(tmp_path, {})
    path = tmp_path / "rows.csv"
    path.write_text("case,area_ratio,model,bend,stretch\npaper-example.json,0.8,,,\npaper-example.json,0.9,paper,200,1.1\n")
    rows = load_study(path).rows
    assert [(r.area_ratio, r.model, r.bend_radius, r.stretch) for r in rows] == [(0.8, "paper", None, None), (0.9, "paper", 200.0, 1.1)]
    assert all(sd.sweep(path, workers=0).column("ok").to_pylist())


@pytest.mark.parametrize(
    "vary, extra, field",
    [
        ({"area_ratios": [0.8]}, None, "cases[0].vary.area_ratios"),
        ({"area_ratio": {"start": 0.5, "stop": 1, "n": 3}}, None, "cases[0].vary.area_ratio.n"),
        ({"area_ratio": [0.8, -1]}, None, "cases[0].vary.area_ratio[1]"),
        ({"model": ["fast"]}, None, "cases[0].vary.model[0]"),
        ({"area_ratio": [0.8, 0.8]}, None, "cases[0]"),
        ({}, {"format": "section-study/9"}, "format"),
        ({}, {"cases": [{"case": "missing.json"}]}, "cases[0].case"),
        # Sizes bounded before the rows are built (this product of 3e11 rows ran without end).
        ({"area_ratio": {"start": 0.5, "stop": 1, "num": 10**12}}, None, "cases[0].vary.area_ratio.num"),
        ({"area_ratio": {"start": 0.5, "stop": 1, "num": 10000}, "crown": {"start": 0, "stop": 1, "num": 3000},
          "translate_x": {"start": 0, "stop": 1, "num": 10000}}, None, "cases[0]"),
    ],
)
def test_bad_study_one_line_exit_2(tmp_path, capsys, vary, extra, field):
    study = _study(tmp_path, vary, extra=extra)
    assert main(["sweep", str(study), "-o", str(tmp_path / "out"), "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and f"error: {field}:" in err
    assert not (tmp_path / "out").exists()
    with pytest.raises(StudyError):
        load_study(study)


@pytest.mark.parametrize("data, message", [
    (b"case\xff\xfe,area_ratio\nx.json,0.8\n", "not UTF-8 text (byte 0xff at position 4)"),
    (b"case,area_ratio\n" + b"x" * 200_000 + b",0.8\n", "not a readable CSV file (field larger than"),
], ids=["not-utf8", "huge-field"])
def test_an_unreadable_csv_is_one_line(tmp_path, capsys, data, message):
    path = tmp_path / "rows.csv"
    path.write_bytes(data)
    assert main(["sweep", str(path), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and f"error: {path}: {message}" in err
    assert not (tmp_path / "out").exists()


def test_the_rows_of_all_the_cases_together_are_bounded(tmp_path):
    (tmp_path / "p.json").write_text((DATA / "paper-example.json").read_text())
    half = {"area_ratio": {"start": 0.5, "stop": 1.0, "num": 250}, "crown": {"start": 0.0, "stop": 1.0, "num": 240}}
    study = {"format": "section-study/1", "cases": [{"case": "p.json", "vary": half}] * 2}
    (tmp_path / "s.json").write_text(json.dumps(study))
    with pytest.raises(StudyError, match=r"^cases\[1\]: 120000 rows needed, more than the bound 100000"):
        load_study(tmp_path / "s.json")


def test_bad_csv_column(tmp_path, capsys):
    path = tmp_path / "rows.csv"
    path.write_text("case,ratio\nx.json,0.8\n")
    assert main(["sweep", str(path), "-o", str(tmp_path / "out")]) == 2
    assert "column 'ratio'" in capsys.readouterr().err


def test_bend_of_the_straight_support_is_the_paper_target():
    case = sd.load_case(DATA / "paper-example.json")
    bent = transformed_target(case.lower, bend_radius=PAPER_RADIUS)
    d = hausdorff_distance(bent.at_fractions(np.linspace(0, 1, 2001)), case.target.at_fractions(np.linspace(0, 1, 2001)))
    assert d < 1e-3
    assert bent.length == pytest.approx(case.lower.length, rel=1e-5)
    # bending to a radius does not depend on the target's own curvature
    again = transformed_target(case.target, bend_radius=PAPER_RADIUS)
    assert hausdorff_distance(again.at_fractions(np.linspace(0, 1, 501)), bent.at_fractions(np.linspace(0, 1, 501))) < 1e-3


def test_crown_stretch_rotate_translate():
    line = Polyline(np.array([[0.0, 0.0], [100.0, 0.0]]))
    h = 8.0
    crowned = transformed_target(line, crown=h).at_fractions(np.linspace(0, 1, 101))
    radius = (50.0**2 + h * h) / (2 * h)
    centre = np.array([50.0, h - radius])
    assert np.allclose(np.hypot(*(crowned - centre).T), radius, atol=1e-9)
    moved = transformed_target(line, stretch=2.0, rotate_deg=90.0, translate_x=1.0, translate_y=-2.0)
    assert np.allclose(moved.at_fractions(np.array([0.0, 1.0])), [[51.0, -102.0], [51.0, 98.0]])


def test_study_of_every_axis_expands_to_the_product(tmp_path):
    study = load_study(_study(tmp_path, {"area_ratio": {"start": 0.6, "stop": 0.9, "num": 4}, "scale": [1, 1.1],
                                         "rotate_deg": [0, 5, 10], "model": ["paper"]}))
    assert len(study.rows) == 24 and len({r.row_id for r in study.rows}) == 24
    assert sorted({r.area_ratio for r in study.rows}) == pytest.approx([0.6, 0.7, 0.8, 0.9])


def test_importing_sectiondeform_does_not_import_pyarrow():
    code = "import sys, sectiondeform; assert 'pyarrow' not in sys.modules; sectiondeform.sweep; assert 'pyarrow' in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


V2 = Path(__file__).parent / "data" / "cases" / "v2"


def test_a_sweep_of_version_2_cases_of_one_body_and_several(tmp_path):
    for name in ("two-layer-strip.json", "cover-alone-on-arc.json"):
        shutil.copy(V2 / name, tmp_path / name)
    study = {"format": "section-study/1", "name": "v2",
             "cases": [{"case": "two-layer-strip.json", "vary": {"crown": [0.0, 2.0]}},
                       {"case": "cover-alone-on-arc.json", "vary": {"area_ratio": [0.8, 0.9]}}]}
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    rows = sd.sweep(path, workers=0).to_pylist()
    assert [r["ok"] for r in rows] == [True] * 4, [r["error"] for r in rows]
    strip = sd.load_case(V2 / "two-layer-strip.json")
    target = sum(b.law.ratio * sd.deform(strip).body(b.name).area_initial for b in strip.bodies)
    for r in rows[:2]:  # each body under its own law: the areas summed
        assert r["area_final"] == pytest.approx(target, rel=1e-9) and set(json.loads(r["quality"])) == {"backing", "cover"}
    for r in rows[2:]:
        assert r["area_final"] == pytest.approx(r["area_ratio"] * r["area_initial"], rel=1e-9)


def test_an_area_ratio_axis_on_a_case_of_several_bodies_is_refused(tmp_path):
    shutil.copy(V2 / "two-layer-strip.json", tmp_path / "strip.json")
    path = tmp_path / "study.json"
    path.write_text(json.dumps({"format": "section-study/1", "cases": [{"case": "strip.json", "vary": {"area_ratio": [0.9]}}]}))
    with pytest.raises(StudyError) as exc:
        load_study(path)
    assert str(exc.value).startswith("cases[0].vary.area_ratio: sets the law of a one-body case; this case has 2 bodies")


def _row_problem(problem, row):
    """The case of one table row: its target transformed as the row says, its law the row's."""
    amounts = {k: row[k] for k in ("bend_radius", "crown", "stretch", "scale", "rotate_deg", "translate_x", "translate_y")}
    if any(v is not None for v in amounts.values()):
        problem = problem.replace(target=transformed_target(problem.target, **amounts))
    if row["area_ratio"] is not None:
        problem = problem.replace(law=sd.AreaRatio(row["area_ratio"]))
    return problem


@pytest.mark.parametrize("case, model, vary", [
    ("paper-example.json", "paper", {"area_ratio": [0.8, 0.95], "bend_radius": [None, 60, -150, 400], "crown": [0.0, 3.0]}),
    ("grooved-tread.json", "hyperelastic", {"bend_radius": [None, -120.0], "stretch": [1.0, 1.1]}),
])
def test_each_row_is_what_deform_gives_for_it(tmp_path, case, model, vary):
    """A row is ``deform`` of the row's case: same contour to 1e-9 of the size, same figures, same warnings."""
    path = _study(tmp_path, vary, extra={"cases": [{"case": case, "vary": {**vary, "model": [model]}}]})
    table = sd.sweep(path, tmp_path / "out", workers=0, save="results").to_pylist()
    problem = sd.load_case(tmp_path / case)
    size = float(np.ptp(np.asarray(sd.deform(problem, model).contour), axis=0).max())
    warned = 0
    for row in table:
        try:
            expected = sd.deform(_row_problem(problem, row), model)
        except sd.SectionDeformError as exc:
            assert not row["ok"] and row["error_type"] == type(exc).__name__ and row["error"] == str(exc), row
            continue
        assert row["ok"], row["error"]
        saved = json.loads((tmp_path / "out" / "results" / f"{row['row_id']}.json").read_text())
        contour = np.asarray(saved["contour"])
        assert contour.shape == np.asarray(expected.contour).shape
        assert np.abs(contour - expected.contour).max() <= 1e-9 * size
        assert row["warnings"] == list(expected.warnings)
        warned += bool(expected.warnings)
        quality = expected.bodies[0].quality.to_json()
        for column in ("final_jacobian_min", "final_area_stretch_min"):
            assert row[column] == (pytest.approx(quality[column], rel=1e-9) if column in quality else None)
    assert sum(r["ok"] for r in table) >= len(table) // 2


def test_each_column_has_one_unit_and_warnings_are_a_list(tmp_path):
    from sectiondeform.studies.table import SCHEMA

    study = _study(tmp_path, {}, extra={"cases": [{"case": "grooved-tread.json", "vary": {"area_ratio": [0.8, 1.0]}}]})
    table = pq.read_table(sd.sweep(study, tmp_path / "out", workers=0, csv=True) and tmp_path / "out" / "rows.parquet")
    assert "jacobian_min" not in table.column_names
    units = {f.name: (f.metadata or {}).get(b"unit") for f in SCHEMA}
    assert units["final_jacobian_min"] == "units²".encode() and units["final_area_stretch_min"] == b"1"
    assert table.schema.field("warnings").type == pa.list_(pa.string())
    rows = table.to_pylist()
    assert rows[0]["warnings"] and rows[1]["warnings"] == []  # the heights change by -20 %: warned
    assert all(isinstance(w, str) and "\n" not in w for r in rows for w in r["warnings"] or [])
    import csv

    with open(tmp_path / "out" / "rows.csv", newline="", encoding="utf-8") as f:
        cells = [json.loads(r["warnings"]) if r["warnings"] else None for r in csv.DictReader(f)]
    assert cells == [r["warnings"] for r in rows]


def test_sweep_quiet_prints_nothing_on_success(tmp_path):
    path = _study(tmp_path, {"area_ratio": [0.8, 0.9]})
    run = subprocess.run([sys.executable, "-m", "sectiondeform", "sweep", str(path), "-o", str(tmp_path / "out"),
                          "--workers", "0", "--quiet"], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0 and run.stdout == "" and run.stderr == ""
    assert (tmp_path / "out" / "rows.parquet").is_file()
