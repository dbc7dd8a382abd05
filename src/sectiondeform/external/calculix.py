"""Running CalculiX (``ccx``) on a deck, in a folder of its own.

:func:`find_ccx` looks the solver up (``SECTIONDEFORM_CCX`` or ``ccx`` on
the ``PATH``); :func:`run_ccx` writes a deck into a temporary folder, runs
``ccx`` there with its increments shown as progress, and reads its ``.frd``
back. A missing solver and a failed run each give one line.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
import threading
import time
from pathlib import Path

from ..errors import SectionDeformError
from .frd import FrdResults, read_frd

__all__ = ["INSTALL_HINT", "SolverFailedError", "SolverNotFoundError", "find_ccx", "run_ccx"]

INSTALL_HINT = ("CalculiX's solver 'ccx' was not found: install it (Debian/Ubuntu: apt-get install calculix-ccx; "
                "conda: conda install -c conda-forge calculix) or set SECTIONDEFORM_CCX to its path")


class SolverNotFoundError(SectionDeformError):
    """The external solver is not installed."""


class SolverFailedError(SectionDeformError):
    """The external solver ran and failed; the message quotes its last error line."""


def find_ccx() -> str:
    """Path of the ``ccx`` executable.

    Raises
    ------
    SolverNotFoundError
        With the way to install it.
    """
    exe = os.environ.get("SECTIONDEFORM_CCX") or shutil.which("ccx")
    if not exe or not shutil.which(exe):
        raise SolverNotFoundError(INSTALL_HINT)
    return exe


def _last_error(lines: list[str]) -> str:
    for line in reversed(lines):
        if "*ERROR" in line.upper() or "ERROR" in line.split(":")[0].upper():
            return line.strip()
    tail = [line.strip() for line in lines if line.strip()]
    return tail[-1] if tail else "no output"


def run_ccx(deck: str, job: str = "deck", progress=None, keep: Path | None = None,
            timeout: float | None = None) -> tuple[FrdResults, dict]:
    """Run ``ccx`` on a deck and read its results.

    Parameters
    ----------
    deck : str
        The ``.inp`` text.
    job : str
        Job name (file stem).
    progress : callable, optional
        Called with one line per converged increment.
    keep : Path, optional
        A folder to copy the job's files into (``.inp``, ``.frd``, ``.sta``, ``.dat``).
    timeout : float, optional
        Seconds after which ``ccx`` is stopped (a failed run).

    Returns
    -------
    results : FrdResults
    info : dict
        ``seconds`` (wall time of ccx), ``increments``, ``iterations``,
        ``cutbacks`` (from the ``.sta`` file), ``dat`` (the ``.dat`` text: printed forces).

    Raises
    ------
    SolverNotFoundError
        Without ``ccx``.
    SolverFailedError
        If ``ccx`` stops with an error or writes no results.
    """
    exe = find_ccx()
    with tempfile.TemporaryDirectory(prefix="sectiondeform-ccx-") as tmp:
        folder = Path(tmp)
        (folder / f"{job}.inp").write_text(deck, encoding="ascii")
        env = {**os.environ, "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "1")}
        t0 = time.perf_counter()
        proc = subprocess.Popen([exe, "-i", job], cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, errors="replace", env=env)
        timer = threading.Timer(timeout, proc.kill) if timeout else None
        if timer is not None:
            timer.start()
        lines = []
        for line in proc.stdout:
            lines.append(line.rstrip("\n"))
            if progress is not None and line.strip().startswith("increment") and "attempt" in line:
                progress(f"calculix: {line.strip()}")
        code = proc.wait()
        seconds = time.perf_counter() - t0
        if timer is not None:
            timer.cancel()
            if timeout and seconds >= timeout:
                raise SolverFailedError(f"ccx did not finish in {timeout:g} s (stopped); last line: {_last_error(lines)}")
        frd = folder / f"{job}.frd"
        if keep is not None:
            for ext in (".inp", ".frd", ".sta", ".dat"):
                if (folder / f"{job}{ext}").exists():
                    shutil.copy(folder / f"{job}{ext}", Path(keep) / f"{job}{ext}")
        failed = code != 0 or any("*ERROR" in line for line in lines)
        if failed or not frd.exists() or "Job finished" not in "\n".join(lines):
            raise SolverFailedError(f"ccx failed (exit {code}): {_last_error(lines)}")
        results = read_frd(frd)
        dat = folder / f"{job}.dat"
        info = {"seconds": seconds, **_status(folder / f"{job}.sta"),
                "dat": dat.read_text(encoding="ascii", errors="replace") if dat.exists() else ""}
    return results, info


def _status(sta: Path) -> dict:
    """Increments, Newton iterations and cut-backs from a ``.sta`` file."""
    increments = iterations = cutbacks = 0
    if sta.exists():
        for line in sta.read_text(errors="replace").splitlines()[2:]:
            parts = line.split()
            if len(parts) < 4:
                continue
            if parts[2].endswith("U"):
                cutbacks += 1
            else:
                increments += 1
            try:
                iterations += int(parts[3])
            except ValueError:
                pass
    return {"increments": increments, "iterations": iterations, "cutbacks": cutbacks}
