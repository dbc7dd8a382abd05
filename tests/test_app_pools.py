"""Where the page's work runs: full hyperelastic solves in solver processes, replaced when grown or dead.

The pools themselves (:mod:`sectiondeform.app.pools`) with library jobs, and a
real server (uvicorn in a thread, as in test_app_load) whose only worker
thread is held by a slow preview while another page's full solve is still
answered, from its process.
"""

from __future__ import annotations

import asyncio
import json
import os
import time

import pytest

pytest.importorskip("starlette")

import sectiondeform as sd  # noqa: E402
from sectiondeform.app import pools, server  # noqa: E402


@pytest.fixture(scope="module")
def case_json():
    return sd.case_to_dict(sd.load_case(sd.example_case_path()))


def preview(case_json, seq=1, model="paper", final=False, ratio=0.8) -> dict:
    return {"seq": seq, "final": final, "case": case_json, "model": model, "ratio": ratio}


def header(frame: bytes) -> dict:
    n = int.from_bytes(frame[:4], "little")
    return json.loads(frame[4:4 + n])


async def _jobs(solvers: pools.Solvers, *jobs):
    """Run ``jobs`` one after the other in the first process of ``solvers``."""
    solver, out = solvers.solvers[0], []
    for fn, *args in jobs:
        await solver.acquire()
        out.append(await solver.run(fn, *args, died="died"))
    return out


def test_a_full_solve_in_a_solver_process_is_the_same_answer_as_in_the_server(case_json):
    msg = preview(case_json, model="hyperelastic", final=True)
    solvers = pools.Solvers(1, nice=0, preload=("sectiondeform.app.server",))
    try:
        [(ok, frame)] = asyncio.run(_jobs(solvers, (server._solve, "page", msg)))
    finally:
        solvers.close()
    assert ok, frame
    local = header(server._compute(sd.app.engine.DeformerCache(), msg))
    remote = header(frame)
    for key in ("area_initial", "area_final", "warnings"):
        assert remote[key] == local[key]


def test_a_solver_process_grown_past_its_memory_is_replaced(case_json):
    solvers = pools.Solvers(1, memory_mb=0.0, nice=0)
    try:
        asyncio.run(_jobs(solvers, (server._solve, "page", preview(case_json, final=True))))
        assert solvers.replaced == 1
    finally:
        solvers.close()


def test_pages_are_pinned_to_the_solver_processes_in_turn():
    solvers = pools.Solvers(2, nice=0)
    try:
        first, second, third = solvers.assign(), solvers.assign(), solvers.assign()
    finally:
        solvers.close()
    assert first is third is solvers.solvers[0] and second is solvers.solvers[1]


def test_a_solver_process_is_replaced_after_its_count_of_solves(case_json):
    solvers = pools.Solvers(1, tasks=2, nice=0)
    try:
        job = (server._solve, "page", preview(case_json, final=True))
        asyncio.run(_jobs(solvers, job))
        assert solvers.replaced == 0
        asyncio.run(_jobs(solvers, job))
        assert solvers.replaced == 1
    finally:
        solvers.close()


def test_a_dead_solver_process_is_answered_in_one_line_and_replaced(case_json):
    solvers = pools.Solvers(1, nice=0)
    try:
        died, (ok, frame) = asyncio.run(_jobs(solvers, (os._exit, 3),
                                              (server._solve, "page", preview(case_json, final=True))))
    finally:
        solvers.close()
    assert died == "died"
    assert ok and header(frame)["type"] == "result"
    assert solvers.replaced >= 1


def test_solver_processes_run_below_the_servers_priority():
    solvers = pools.Solvers(1, nice=3)
    try:
        niceness = asyncio.run(_jobs(solvers, (_niceness_job,)))[0]
    finally:
        solvers.close()
    assert niceness == os.nice(0) + 3


def _niceness_job():
    return os.nice(0), pools.resident_mb()


def test_resident_memory_is_read():
    assert 1.0 < pools.resident_mb() < 1e6


def test_the_hyperelastic_models_work_goes_to_the_processes():
    assert server._in_solver("hyperelastic") and server._in_solver("hyperelastic", what="figure")
    assert not server._in_solver("paper")
    assert not server._in_solver("hyperelastic", what="case")


uvicorn = pytest.importorskip("uvicorn")
pytest.importorskip("websockets.sync.client")
from test_app_load import answer_to, connect, running  # noqa: E402

HELD = 8.0
"""Seconds the only worker thread is held (a full solve in its process takes well under that)."""


def test_a_full_solve_is_answered_while_the_only_worker_thread_is_held(case_json, monkeypatch):
    """Previews hold the threads, full solves a process: neither waits for the other."""
    real = server.engine.answer

    def slow(cache, case, model, ratio, final, **kw):  # only in this process: the solver's own is not slowed
        if model == "paper":
            time.sleep(HELD)
        return real(cache, case, model, ratio, final, **kw)

    monkeypatch.setattr(server.engine, "answer", slow)
    with running(case_json, workers=1, solvers=1) as port, connect(port) as busy, connect(port) as solving:
        busy.send(json.dumps(preview(case_json)))
        time.sleep(0.3)  # the only thread sleeps in the paper preview
        solving.send(json.dumps(preview(case_json, model="hyperelastic", final=True)))
        got = answer_to(solving, 1, timeout=60)
        with pytest.raises(TimeoutError):  # the solve was answered while the thread was still held
            busy.recv(timeout=0)
        assert answer_to(busy, 1)["type"] == "result"
    assert got["type"] == "result", got


def _descendants(pid: int) -> set[int]:
    """The processes started by ``pid`` and theirs (from /proc)."""
    from pathlib import Path

    out, todo = set(), [pid]
    while todo:
        for task in Path(f"/proc/{todo.pop()}/task").glob("*"):
            try:
                children = {int(c) for c in (task / "children").read_text().split()}
            except OSError:
                continue
            todo += sorted(children - out)
            out |= children
    return out


@pytest.mark.parametrize("how", ["SIGTERM", "SIGKILL"])
def test_the_solver_processes_end_with_the_server_however_it_ends(how):
    """Stopped (SIGTERM: its shutdown runs) or killed (SIGKILL: no shutdown), the server leaves no process behind."""
    import signal
    import subprocess
    import sys
    from pathlib import Path

    if not Path("/proc/self/task").exists():
        pytest.skip("needs /proc to find the server's processes")
    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", "--port", "0", "--no-browser",
                             "--token", "a-token-for-this-test-0123456789"], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    try:
        assert "token=" in proc.stdout.readline()
        end = time.monotonic() + 30
        while len(helpers := _descendants(proc.pid)) < 2 and time.monotonic() < end:  # a forkserver and its solver
            time.sleep(0.1)
        assert len(helpers) >= 2, helpers
        proc.send_signal(getattr(signal, how))
        proc.wait(timeout=30)
        end = time.monotonic() + 15
        while (left := {p for p in helpers if Path(f"/proc/{p}").exists()}) and time.monotonic() < end:
            time.sleep(0.1)
        assert not left, f"left behind after {how}: {sorted(left)}"
    finally:
        if proc.poll() is None:
            proc.kill()
