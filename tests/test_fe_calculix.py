"""CalculiX runs (need ccx: skipped without it, failing when SECTIONDEFORM_REQUIRE_CCX=1 as in CI)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.cli import main
from sectiondeform.compare import compare_curves
from sectiondeform.laws import AreaRatio

DATA = Path(__file__).parent / "data" / "fe"


def test_paper_example_at_area_ratio_one(ccx, tmp_path):
    from sectiondeform.external.solve import solve_calculix

    case = sd.load_case(DATA / "paper-example.json").replace(law=AreaRatio(1.0))
    sol = solve_calculix(case, mesh_size=0.3)
    T = sol.area_initial / case.lower.length
    # Nearly incompressible: the area is kept to the compressibility of kappa = 1000 mu.
    assert abs(sol.area_final / sol.area_initial - 1.0) < 2e-3
    assert sol.dialect == "section-result/1" and sol.model == "calculix"
    # The support went onto the target; the upper curve ends where the target ends.
    on_target = case.target.at_fractions(sd.build_section(case).fractions)
    assert np.allclose(sol.lower, on_target, atol=1e-4 * T)
    assert np.allclose(sol.upper[0], case.target.at_fractions(np.array([1.0]))[0], atol=1e-4 * T)
    assert np.allclose(sol.upper[-1], case.target.at_fractions(np.array([0.0]))[0], atol=1e-4 * T)
    # Against the project's hyperelastic model (same physics, its own coarse mesh): close.
    fast = sd.Deformer(case, model="hyperelastic").deform()
    assert compare_curves(fast.upper, sol.upper, scale=T).hausdorff_relative < 0.02


def test_thick_block_against_the_project_reference(ccx):
    from sectiondeform.external.solve import solve_calculix
    from sectiondeform.reference import solve_reference

    case = sd.load_case(DATA / "thick-block-s-curve.json")
    sol = solve_calculix(case, mesh_size=0.2)
    ref = solve_reference(case, mesh_size=0.2)
    T = ref.bodies[0].area_initial / case.lower.length
    assert compare_curves(sol.upper, ref.bodies[0].upper, scale=T).hausdorff_relative < 0.005


def test_solve_fe_cli_writes_a_section_result(ccx, tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["solve-fe", str(DATA / "square.json"), "--mesh-size", "0.5", "-o", str(out), "-q"]) == 0
    data = json.loads(out.read_text())
    case = sd.load_case(DATA / "square.json")
    assert data["format"] == "section-result/1" and data["model"] == "calculix"
    assert len(data["upper"]) == len(sd.build_section(case).upper)
    assert abs(data["area"]["relative_error"]) < 2e-3


def test_validate_against_calculix_writes_the_report_and_the_figure(ccx, tmp_path, capsys):
    report, fig = tmp_path / "v.json", tmp_path / "v.png"
    # The square bent by its target changes its layers' aspect 6.6-fold, which the paper model refuses:
    # the case's fast model is the hyperelastic one.
    square = tmp_path / "square.json"
    square.write_text(json.dumps({**json.loads((DATA / "square.json").read_text()), "options": {"model": "hyperelastic"}}))
    args = ["validate", str(square), "--reference", "calculix", "--mesh-size", "0.5", "-q"]
    assert main([*args, "-o", str(report), "--plot", str(fig)]) == 0
    out = capsys.readouterr().out
    assert "Hausdorff" in out and "of the height" in out and "wrote" in out
    r = json.loads(report.read_text())
    case = sd.load_case(square)
    section = sd.build_section(case)
    height = float(np.max(section.upper[:, 1]) - np.min(section.lower[:, 1]))
    assert r["height"] == pytest.approx(height)
    assert r["hausdorff_over_height"] == pytest.approx(r["shape"]["hausdorff"] / height)
    assert r["reference"]["model"].startswith("CalculiX")
    assert r["reference"]["solver"]["solver"] == "calculix"
    assert len(r["fast"]["upper"]) == len(r["reference"]["upper"])
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_missing_and_failing_ccx_are_one_line_errors(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("SECTIONDEFORM_CCX", str(tmp_path / "no-ccx"))
    assert main(["solve-fe", str(DATA / "square.json"), "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "apt-get install calculix-ccx" in err[0]
    fake = tmp_path / "ccx"
    fake.write_text("#!/bin/sh\necho ' *ERROR reading *FOO: card image cannot be interpreted'\nexit 201\n")
    fake.chmod(0o755)
    monkeypatch.setenv("SECTIONDEFORM_CCX", str(fake))
    assert main(["solve-fe", str(DATA / "square.json"), "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "*ERROR reading *FOO" in err[0]
