"""Every input the fuzzing found (tests/data/fuzz-found): a checked result or one clean error, in time."""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_bundles import is_bundle
from fuzz_cases import TIME_LIMIT_S, outcome_api

DATA = Path(__file__).parent / "data" / "fuzz-found"
# Every case: those of the first round, and the plain cases of v2/ (section-case/2, checked body by
# body). The v2/ bundles are command-line runs (tests/test_fuzz_found_cli.py).
V2 = [p for p in sorted((DATA / "v2").glob("*.json")) if not is_bundle(p)]
FILES = sorted(DATA.glob("*.json")) + V2


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_checked_result_or_one_line_error_in_time(path):
    outcome = outcome_api(path, TIME_LIMIT_S)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}"


def test_the_v2_cases_are_checked_body_by_body():
    """The per-body check passes a real result of three bodies of revolution, and names a body that breaks its law."""
    import dataclasses

    from fuzz_cases import check_bodies

    import sectiondeform as sd

    assert len(V2) >= 5
    result = sd.deform(sd.load_case(DATA / "v2" / "api-HANG-curves-py-ends-400.json"))
    assert len(result.bodies) == 3 and check_bodies(result) == []
    base, cover, tread = result.bodies
    grown = dataclasses.replace(cover, contour=cover.contour * 1.001)
    fails = check_bodies(dataclasses.replace(result, bodies=(base, grown, tread)))
    assert fails and all(f.startswith(f"{cover.name}: ") for f in fails)
    assert any("volume_law" in f for f in fails)
