"""The promise on generated inputs: a result that passes the independent checks, or one clean refusal.

The cases come from :mod:`fuzz_cases`: one-body sections of many sizes and
shapes, targets that stretch, bend, turn over or collapse, laws and options
of both models, a quarter of them damaged; assemblies of 1-4 bodies
(stacked, side by side, thin layers, stiffness contrasts to 1000, every
rubber model, rigid parts) plane or of revolution close to the axis; and
runs of the commands ``fit``, ``sweep``, ``export-fe`` and ``convert`` (of
damaged DXF and SVG files too). Each example is classified by
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
from fuzz_cases import (
    TIME_LIMIT_S,
    assemblies,
    cases,
    command_runs,
    outcome_api,
    outcome_cli,
    outcome_command_run,
)
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


@pytest.mark.parametrize("model, examples", [("paper", 4), ("hyperelastic", 1)])
def test_assemblies_and_bodies_of_revolution_give_checked_results_or_one_line(model, examples):
    outcomes = Outcomes()

    @settings(max_examples=examples * SCALE, deadline=None, suppress_health_check=SLOW, derandomize=FIXED_SEED)
    @given(case=assemblies(models=(model,)))
    def run(case):
        outcome = outcome_api(case, TIME_LIMIT_S)
        assert not outcome.failed, f"{outcome.kind}: {outcome.detail}\ninput: {case}"
        if outcome.kind == "ok":
            outcomes.checked()
        else:
            outcomes.refused(outcome.kind)

    run()
    outcomes.assert_mostly_checked(at_least=examples * SCALE // 10, max_refused_fraction=0.95)


@settings(max_examples=2 * SCALE, deadline=None, suppress_health_check=SLOW, derandomize=FIXED_SEED)
@given(run=command_runs())
def test_the_commands_exit_0_or_2_with_one_line_decks_calculix_reads_and_quiet_sweeps(run):
    with tempfile.TemporaryDirectory() as folder:
        outcome = outcome_command_run(run, Path(folder), TIME_LIMIT_S)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}\ninput: {run}"
