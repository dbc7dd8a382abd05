"""Every input the fuzzing found (tests/data/fuzz-found): a checked result or one clean error, in time."""

from __future__ import annotations

import signal
from pathlib import Path

import pytest

import sectiondeform as sd
from sectiondeform.verify import check_result

DATA = Path(__file__).parent / "data" / "fuzz-found"
FILES = sorted(DATA.glob("*.json"))
LIMIT_S = 20


class _TimeLimit(Exception):
    pass


def _alarm(signum, frame):
    raise _TimeLimit(f"no answer within {LIMIT_S} s")


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_checked_result_or_one_line_error_in_time(path):
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(LIMIT_S)
    try:
        case = sd.load_case(path)
        result = sd.deform(case)
    except sd.SectionDeformError as exc:
        message = str(exc)
        assert message and "\n" not in message
        return
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    assert check_result(result, case) == []
