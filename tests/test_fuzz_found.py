"""Every input the fuzzing found (tests/data/fuzz-found): a checked result or one clean error, in time."""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_bundles import is_bundle
from fuzz_cases import TIME_LIMIT_S, outcome_api

DATA = Path(__file__).parent / "data" / "fuzz-found"
# Plain cases only: the command-line runs of v2 (bundles) are tests/test_fuzz_found_cli.py's.
FILES = sorted(DATA.glob("*.json")) + sorted(p for p in (DATA / "v2").glob("*.json") if not is_bundle(p))


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_checked_result_or_one_line_error_in_time(path):
    outcome = outcome_api(path, TIME_LIMIT_S)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}"
