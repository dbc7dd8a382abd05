"""The promise on generated inputs: a result that passes the independent checks, or one clean refusal.

The cases come from :mod:`fuzz_cases` (sections of many sizes and shapes,
targets that stretch, bend, turn over or collapse, laws and options of both
models, a quarter of them damaged). Each example is classified by
:func:`fuzz_cases.outcome_api` (library) or :func:`fuzz_cases.outcome_cli`
(a new ``sectiondeform deform`` process, killed at the time limit); any
``failure:`` outcome fails the test with the input. A larger run of the
same generator is ``benchmarks/fuzz.py`` (docs/reliability.md).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import pytest
from fuzz_cases import TIME_LIMIT_S, cases, outcome_api, outcome_cli
from hypothesis import HealthCheck, given, settings

from conftest import Outcomes

SLOW = [HealthCheck.too_slow, HealthCheck.data_too_large]

# The CI budget: SECTIONDEFORM_FUZZ_SCALE multiplies every example count (`.ci/run` sets 30: about two
# thousand examples across both models and the command line), with a fixed seed so that CI runs exactly
# the examples a developer can run with the same setting.
SCALE = max(1, int(os.environ.get("SECTIONDEFORM_FUZZ_SCALE", "1")))
FIXED_SEED = SCALE > 1


@pytest.mark.parametrize("model, examples", [("paper", 40), ("hyperelastic", 20)])
def test_library_gives_a_checked_result_or_one_line_refusal(model, examples):
    outcomes = Outcomes()

    @settings(max_examples=examples * SCALE, deadline=None, suppress_health_check=SLOW, derandomize=FIXED_SEED)
    @given(case=cases(models=(model,)))
    def run(case):
        outcome = outcome_api(case, TIME_LIMIT_S)
        assert not outcome.failed, f"{outcome.kind}: {outcome.detail}\ninput: {case}"
        if outcome.kind == "ok":
            outcomes.checked()
        else:
            outcomes.refused(outcome.kind)

    run()
    # The generator must reach the models, not only their refusals.
    outcomes.assert_mostly_checked(at_least=examples * SCALE // 10, max_refused_fraction=0.9)


@settings(max_examples=4 * SCALE, deadline=None, suppress_health_check=SLOW, derandomize=FIXED_SEED)
@given(case=cases(models=("paper", "hyperelastic")))
def test_command_line_exits_0_with_a_checked_result_or_2_with_one_line_and_no_file(case):
    with tempfile.TemporaryDirectory() as folder:
        outcome = outcome_cli(case, Path(folder), TIME_LIMIT_S)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}\ninput: {case}"
