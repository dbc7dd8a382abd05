"""Every input the fuzzing found, through the command line: exit 0 with a checked result, or 2 with one line.

Each file runs in a new ``sectiondeform deform FILE -o OUT`` process that
the kernel stops at the CPU-time limit (a hang in compiled code cannot be
interrupted from inside the process; the limit is on work, so the load of
the machine does not matter). Exit 2 must leave no output file.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_bundles import is_bundle, outcome_bundle
from fuzz_cases import TIME_LIMIT_S, outcome_cli_file

DATA = Path(__file__).parent / "data" / "fuzz-found"
V2 = sorted((DATA / "v2").glob("*.json"))
FILES = sorted(DATA.glob("*.json")) + [p for p in V2 if not is_bundle(p)]
BUNDLES = [p for p in V2 if is_bundle(p)]
# The inputs found with odd arguments: a usage error must be one line too.
EXTRA = {"cli-dirty-error-n-stderr-lines-argparse": ("--area-ratio",)}


def test_the_fuzz_found_inputs_are_present():
    assert len(FILES) >= 69  # a missing fixture is a failure, not a skip


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_exit_0_with_a_checked_result_or_2_with_one_line_and_no_file(path, tmp_path):
    outcome = outcome_cli_file(path, tmp_path / "out.json", TIME_LIMIT_S, EXTRA.get(path.stem, ()))
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}"


def test_the_v2_command_line_runs_are_present():
    assert len(BUNDLES) >= 11


@pytest.mark.parametrize("path", BUNDLES, ids=[p.stem for p in BUNDLES])
def test_each_command_exits_0_or_2_with_one_line_and_nothing_written(path, tmp_path):
    outcome = outcome_bundle(path, tmp_path / "run", TIME_LIMIT_S)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}"


def test_a_usage_error_is_one_line_naming_help(tmp_path):
    path = DATA / "cli-dirty-error-n-stderr-lines-argparse.json"
    outcome = outcome_cli_file(path, tmp_path / "out.json", TIME_LIMIT_S, ("--area-ratio",))
    assert outcome.kind == "refused:exit-2"
    assert "--area-ratio" in outcome.detail and "--help" in outcome.detail
