"""Inputs the command-line fuzz runs found (``benchmarks/fuzz.py``, ``command_runs``), kept as regression tests.

``v3-export-fe-no-support-nodes.json``: a section a thousandth of a unit
across on a small arc; the deck's mesher found no node on the support, the
rigid fit of zero points gave NaN and ``export-fe`` died with a traceback
(``ValueError: a deck holds finite reals only``). A deck with fewer than two
support nodes has no loading: it is now one line naming the count.
"""

from __future__ import annotations

import sys
from pathlib import Path

from fuzz_cases import outcome_command_run

DATA = Path(__file__).parent / "data" / "fuzz-found"


def test_export_fe_of_a_section_whose_support_the_mesher_loses_is_one_line(tmp_path):
    case = (DATA / "v3-export-fe-no-support-nodes.json").read_text(encoding="utf-8")
    run = {"command": "export-fe", "files": {"case.json": case}, "damage": None,
           "steps": [{"args": ["export-fe", "case.json", "-o", "deck.inp"], "outputs": ["deck.inp"]}]}
    outcome = outcome_command_run(run, tmp_path)
    assert not outcome.failed, f"{outcome.kind}: {outcome.detail}"
    assert outcome.kind == "refused:exit-2" and "nodes on the support" in outcome.detail, sys.version


def test_a_contact_loading_is_bounded_in_work_before_each_solve(monkeypatch):
    """Found by the assemblies' fuzz: a rigid plate pressing a thin stack ran load step after load step (each
    Newton solve within its own bound) for minutes. The loading as a whole is now bounded, checked before
    each solve, and refused with the number, never halved further.
    """
    import sectiondeform as sd
    from sectiondeform.models import hyperelastic_contact

    case = sd.load_case(Path(__file__).parent / "data" / "cases" / "v2" / "bumper-under-plate.json")
    assert sd.deform(case).rigid  # within the bound
    monkeypatch.setattr(hyperelastic_contact, "work_budget", lambda unknowns: 1)
    try:
        sd.deform(case)
    except sd.ConvergenceError as exc:
        message = str(exc)
    assert "factorisations" in message and "beyond its bound of 1 at this size" in message
    assert "halved" not in message and "\n" not in message
