"""``benchmarks/validation.py`` with version-2 cases: its own blocks only, a row per body of a problem."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from conftest import CASES_DIR, load_benchmark  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
STRIP = CASES_DIR / "v2" / "two-layer-strip.json"


@pytest.fixture(scope="module")
def bench():
    return load_benchmark("validation")


def cells(row: str) -> list[str]:
    return [c.strip() for c in row.strip().strip("|").split("|")]


def test_a_problem_is_one_row_per_body_and_model(bench):
    table = bench.bodies_table([bench.sd.load_case(STRIP)], ["paper", "hyperelastic"], None, 0.8).splitlines()
    width = len(cells(table[0]))
    assert len(table) == 2 + 2 * 2
    assert all(len(cells(row)) == width for row in table)
    for row, (model, body) in zip(table[2:], [(m, b) for m in ("paper", "hyperelastic") for b in ("backing", "cover")]):
        c = cells(row)
        assert c[:3] == ["two-layer-strip", "plane", body] and c[5] == model
        assert c[4] == {"backing": "area_ratio 0.95", "cover": "area_ratio 0.9"}[body]
        assert c[3] == {"backing": "neo-hookean, μ 3 MPa", "cover": "neo-hookean, μ 1 MPa"}[body]
        assert c[11].startswith("area ") and c[12].endswith(")")


def test_a_reference_that_fails_is_a_row_saying_so(bench, monkeypatch):
    from sectiondeform.errors import ConvergenceError

    def fail(*args, **kwargs):
        raise ConvergenceError("reference: Newton did not converge beyond load 40.0%")

    monkeypatch.setattr(bench, "solve_reference", fail)
    table = bench.bodies_table([bench.sd.load_case(STRIP)], ["paper"], None, 0.8).splitlines()
    assert len(table) == 3 and len(cells(table[2])) == len(cells(table[0]))
    assert cells(table[2])[6] == "reference failed: reference: Newton did not converge beyond load 40.0%"


def test_only_the_blocks_of_the_cases_given_are_rewritten(bench, tmp_path, capsys):
    doc = tmp_path / "doc.md"
    untouched = "<!-- validation:table -->\nv1 table\n<!-- /validation:table -->\n"
    doc.write_text(untouched + "<!-- validation:assemblies -->\nold\n<!-- /validation:assemblies -->\n")
    assert bench.main([str(STRIP), "--models", "paper", "--assembly-mesh-size", "0.8", "--write", str(doc)]) == 0
    text = doc.read_text()
    assert text.startswith(untouched)  # no version-1 case given: its tables are left as they are
    assert "old" not in text and "| two-layer-strip | plane | backing |" in text
    capsys.readouterr()
