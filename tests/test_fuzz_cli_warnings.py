"""The command line's deform puts each of a result's warnings on stderr, one line ``warning: ...``.

Issue 10: a result far outside what the model can mean carries a warning
on stderr and in the result's ``warnings``. The grooved tread under the
paper model changes its heights by more than the documented limit (the
height-change warning); the paper example does not.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from sectiondeform.commands._common import OPTION_FLAGS
from sectiondeform.errors import spelled

CASES = Path(__file__).parent / "data" / "cases"


def run_deform(case: Path, out: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "sectiondeform", "deform", str(case), "-o", str(out), "--no-meshes", *extra],
        capture_output=True, text=True, timeout=300,
    )


@pytest.mark.parametrize("name, model", [("grooved-tread", "paper"), ("paper-example", "paper"),
                                         ("tread-on-drum", None)])
def test_each_warning_is_one_stderr_line_and_in_the_result(tmp_path, name, model):
    path = CASES / f"{name}.json" if (CASES / f"{name}.json").exists() else CASES / "v2" / f"{name}.json"
    out = tmp_path / "result.json"
    run = run_deform(path, out, *(["--model", model] if model else []))
    assert run.returncode == 0, run.stderr
    warnings = json.loads(out.read_text())["warnings"]
    lines = [line for line in run.stderr.splitlines() if line.strip()]
    # each the result's warning, with the options it names spelled as the command line's flags
    assert lines == [f"warning: {spelled(' '.join(w.split()), OPTION_FLAGS)}" for w in warnings]
    assert "warning:" not in run.stdout
    if name == "grooved-tread":  # the height-change warning, with its number
        assert len(lines) == 1 and "heights change" in lines[0] and "%" in lines[0]
        assert "(--model hyperelastic)" in lines[0] and "option model" in warnings[0]
    if name == "paper-example":
        assert lines == []
