"""Every input the fuzzing found (tests/data/fuzz-found): a checked result or one clean error, in time."""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_cases import TIME_LIMIT_S, outcome_api

DATA = Path(__file__).parent / "data" / "fuzz-found"
# Version-1 cases: ``deform`` takes them. The version-2 cases of v2/ run through the command line
# (tests/test_fuzz_found_cli.py), which deforms assemblies, and their own tests.
FILES = sorted(DATA.glob("*.json"))


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_checked_result_or_one_line_error_in_time(path):
    outcome = outcome_api(path, TIME_LIMIT_S)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}"
