"""Command-line runs kept as ``sdfuzz-bundle/1`` files (``tests/data/fuzz-found/v2``), and their classification.

A bundle is a JSON object: ``files`` to write into an empty folder first
(``text``: this text; ``b64``: these bytes; ``copy``: a file kept in
``tests/data``, named as ``shared/<path>`` for ``tests/data/<path>``), then
``steps``, each ``{"cmd": ..., "args": [...], "outputs": [...]}`` run as
``sectiondeform CMD ARGS...`` in that folder, in a new process that the
kernel stops at the CPU-time limit.

The promise on each step: exit 0, or exit 2 with exactly one line on
stderr and none of the step's ``outputs`` written; no traceback and no
Python warning on stderr, and nothing non-finite (``nan``, ``inf``) printed
on stdout. A refusal ends the bundle (later steps read what it did not
write).
"""

from __future__ import annotations

import base64
import json
import os
import re
import signal
import subprocess
import sys
from pathlib import Path

from fuzz_cases import TIME_LIMIT_S, WALL_FACTOR, Outcome, _children_cpu, _limit_cpu

import sectiondeform

__all__ = ["is_bundle", "outcome_bundle"]

DATA = Path(__file__).parent / "data"
_NON_FINITE = re.compile(r"(?<![A-Za-z_])(nan|[+-]?inf)(?![A-Za-z_])", re.IGNORECASE)


def is_bundle(path: Path) -> bool:
    """True for a ``sdfuzz-bundle/1`` file (a command-line run), False for a plain case."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError):
        return False
    return isinstance(data, dict) and data.get("format") == "sdfuzz-bundle/1"


def _write_files(files: dict, folder: Path) -> None:
    for name, spec in files.items():
        target = folder / name
        if "text" in spec:
            target.write_text(spec["text"], encoding="utf-8")
        elif "b64" in spec:
            target.write_bytes(base64.b64decode(spec["b64"]))
        else:
            source = DATA / Path(spec["copy"]).relative_to("shared")
            if not source.is_file():
                raise FileNotFoundError(f"bundle fixture {source} is missing")
            target.write_bytes(source.read_bytes())


def _present(folder: Path, name: str) -> bool:
    path = folder / name
    return path.is_file() or (path.is_dir() and any(path.iterdir()))


def _run_step(step: dict, folder: Path, limit_s: float) -> Outcome:
    for name in step.get("outputs", ()):
        if (folder / name).is_file():
            (folder / name).unlink()
    # The steps run in the bundle's folder: import this sectiondeform whatever the relative PYTHONPATH says.
    paths = [str(Path(sectiondeform.__file__).resolve().parents[1]), *os.environ.get("PYTHONPATH", "").split(os.pathsep)]
    env = {**os.environ, "PYTHONWARNINGS": "default",
           "PYTHONPATH": os.pathsep.join(str(Path(p).resolve()) for p in paths if p)}
    t0 = _children_cpu()
    try:
        run = subprocess.run([sys.executable, "-m", "sectiondeform", step["cmd"], *step.get("args", ())],
                             cwd=folder, capture_output=True, text=True, timeout=WALL_FACTOR * limit_s, env=env,
                             preexec_fn=_limit_cpu(limit_s))
    except subprocess.TimeoutExpired:
        return Outcome("failure:slow", f"killed after {WALL_FACTOR * limit_s:g} s wall time", _children_cpu() - t0)
    seconds = _children_cpu() - t0
    if run.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        return Outcome("failure:slow", f"stopped after {limit_s:g} s of CPU time", seconds)
    err = run.stderr
    if "Traceback" in err or "Warning:" in err:
        return Outcome("failure:stderr", err[-600:], seconds)
    if run.returncode == 2:
        lines = [line for line in err.splitlines() if line.strip()]
        if len(lines) != 1:
            return Outcome("failure:message", err[-600:], seconds)
        left = [name for name in step.get("outputs", ()) if _present(folder, name)]
        if left:
            return Outcome("failure:output-left", f"{left}: {lines[0]}", seconds)
        return Outcome("refused:exit-2", lines[0], seconds)
    if run.returncode != 0:
        return Outcome(f"failure:exit-{run.returncode}", err[-600:], seconds)
    if _NON_FINITE.search(run.stdout):
        return Outcome("failure:non-finite", run.stdout[-600:], seconds)
    return Outcome("ok", (run.stdout + run.stderr)[-600:], seconds)  # what it printed


def outcome_bundle(path: Path, folder: Path, limit_s: float = TIME_LIMIT_S) -> Outcome:
    """Run the bundle ``path`` in the empty ``folder``; the outcome of its last step run.

    Parameters
    ----------
    path : Path
        A ``sdfuzz-bundle/1`` file.
    folder : Path
        An empty folder to run it in.
    limit_s : float
        CPU seconds each step may take.

    Returns
    -------
    Outcome
        ``ok`` when every step exits 0, ``refused:exit-2`` at the first
        clean refusal, else the first ``failure:…``.
    """
    bundle = json.loads(path.read_text(encoding="utf-8"))
    folder.mkdir(parents=True, exist_ok=True)
    _write_files(bundle["files"], folder)
    outcome = Outcome("ok")
    for step in bundle["steps"]:
        outcome = _run_step(step, folder, limit_s)
        if outcome.kind != "ok":
            return outcome
    return outcome
