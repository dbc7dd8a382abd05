"""``benchmarks/validation.py`` with version-2 cases: its own blocks only, refusals as one-line rows."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from conftest import CASES_DIR  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
STRIP = CASES_DIR / "v2" / "two-layer-strip.json"


@pytest.fixture(scope="module")
def bench():
    spec = importlib.util.spec_from_file_location("bench_validation", ROOT / "benchmarks" / "validation.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def cells(row: str) -> list[str]:
    return [c.strip() for c in row.strip().strip("|").split("|")]


def test_an_assembly_the_reference_refuses_is_a_row_with_the_one_line_refusal(bench):
    table = bench.v2_table([bench.sd.load_case(STRIP)], ["paper", "hyperelastic"], None).splitlines()
    width = len(cells(table[0]))
    assert len(table) == 2 + 2
    assert all(len(cells(row)) == width for row in table)
    for row, model in zip(table[2:], ("paper", "hyperelastic")):
        c = cells(row)
        assert c[:4] == ["two-layer-strip", "backing, cover", model, "plane"]
        assert c[5].startswith("refused: bodies: validate compares one body; this assembly has 2")


def test_only_the_blocks_of_the_cases_given_are_rewritten(bench, tmp_path, capsys):
    doc = tmp_path / "doc.md"
    untouched = "<!-- validation:table -->\nv1 table\n<!-- /validation:table -->\n"
    doc.write_text(untouched + "<!-- validation:assemblies -->\nold\n<!-- /validation:assemblies -->\n")
    assert bench.main([str(STRIP), "--models", "paper", "--write", str(doc)]) == 0
    text = doc.read_text()
    assert text.startswith(untouched)  # no version-1 case given: its tables are left as they are
    assert "old" not in text and "refused: bodies:" in text
    capsys.readouterr()
