"""Where the page's computations run: worker threads for previews, solver processes for full solves.

A paper-model answer takes a millisecond or two: it runs on a thread of
the server (:class:`Workers`). A full hyperelastic solve takes up to
seconds of Python and numerical code; on a thread it would hold the
interpreter lock a good part of that time, so every other page's previews
would wait behind it, and the solver's working memory would stay with the
server. The hyperelastic model's work runs in a process of its own instead
(:class:`Solvers`; a page's previews too, since each starts from the page's
last full solve and its factorisation, which stay in that process): the
server's interpreter stays free, the process runs at a lower priority than
the server (a paper-model preview being dragged goes first), and it is
replaced once it has grown past :data:`SOLVER_MEMORY_MB` or run
:data:`SOLVER_TASKS` jobs, so the memory of a long session stays bounded.

Both pools hand out slots on the event loop: a job first waits for a slot
(cancellable, so a newer request can replace it or a closed connection drop
it), then runs; the slot comes back when the work ends, even if the one
waiting for the answer has gone. Nothing ever waits in an executor's queue.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import multiprocessing
import os
import threading
import time
import weakref
from concurrent.futures.process import BrokenProcessPool

__all__ = ["SOLVER_MEMORY_MB", "SOLVER_NICE", "SOLVER_TASKS", "Solver", "Solvers", "Workers", "resident_mb"]

SOLVER_MEMORY_MB = 1024
"""A solver process whose resident memory has grown past this (MB) is replaced after its solve."""
SOLVER_TASKS = 1000
"""A solver process is replaced after this many jobs (solves and previews), whatever its memory."""
SOLVER_NICE = 5
"""How much lower a solver process's scheduling priority is than the server's (POSIX ``nice`` increment)."""


def resident_mb() -> float:
    """The resident memory of the calling process (MB; from ``/proc``, or the peak from ``resource`` elsewhere; NaN if neither)."""
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20
    except (OSError, ValueError, IndexError, AttributeError):
        pass
    try:
        import resource
    except ImportError:
        return float("nan")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux, bytes on macOS
    return peak / 2**20 if peak > 2**32 else peak / 2**10


class _Slots:
    """One asyncio semaphore of ``size`` per event loop (a pool may outlive a loop, as in tests)."""

    def __init__(self, size: int):
        self.size = size
        self._by_loop: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()

    def get(self) -> asyncio.Semaphore:
        loop = asyncio.get_running_loop()
        if loop not in self._by_loop:
            self._by_loop[loop] = asyncio.Semaphore(self.size)
        return self._by_loop[loop]


class Workers:
    """A bounded pool of worker threads shared by all connections (previews, file reading, saving).

    Parameters
    ----------
    size : int
        Threads, and so the most jobs running at once.
    """

    def __init__(self, size: int):
        self.size = size
        self.pool = concurrent.futures.ThreadPoolExecutor(max_workers=size, thread_name_prefix="sectiondeform")
        self._slots = _Slots(size)

    async def acquire(self) -> None:
        """Wait for a free worker (cancellable: a job never started holds nothing)."""
        await self._slots.get().acquire()

    def release(self) -> None:
        """Give back a slot taken by :meth:`acquire` and not used."""
        self._slots.get().release()

    async def run(self, fn, *args):
        """Run ``fn(*args)`` on a worker, after :meth:`acquire`; the slot is given back when it ends."""
        loop, slots = asyncio.get_running_loop(), self._slots.get()
        try:
            future = self.pool.submit(fn, *args)
        except BaseException:
            slots.release()
            raise
        future.add_done_callback(lambda _: loop.call_soon_threadsafe(slots.release))
        return await asyncio.wrap_future(future)

    async def call(self, fn, *args):
        """Wait for a worker and run ``fn(*args)`` on it."""
        await self.acquire()
        return await self.run(fn, *args)

    def close(self) -> None:
        self.pool.shutdown(wait=False, cancel_futures=True)


def _start_solver(nice: int, server: int) -> None:
    """Run first in each solver process: a lower priority than the server's, and an end with the server.

    A process of a pool never learns that the process that started it has
    gone (its queue's pipe stays open in itself): if the server is killed
    without its shutdown, a thread here ends the solver within a second of
    it (its forkserver then ends too, having no one left).
    """
    if nice and hasattr(os, "nice"):
        try:
            os.nice(nice)
        except OSError:
            pass
    if os.name == "posix":  # (on Windows os.kill(pid, 0) would end the server, not ask about it)
        threading.Thread(target=_watch, args=(server,), name="sectiondeform-server-watch", daemon=True).start()


def _watch(server: int, every: float = 1.0) -> None:
    """End this process once process ``server`` has gone (POSIX: signal 0 asks whether it exists)."""
    while True:
        time.sleep(every)
        try:
            os.kill(server, 0)
        except ProcessLookupError:
            os._exit(0)
        except OSError:  # alive, someone else's (no permission to signal it)
            pass


def _ready() -> float:
    """A job that only starts the process (the first real solve then does not wait for it); its memory."""
    return resident_mb()


def _context():
    """``forkserver`` where there is one (never ``fork`` from a server with threads), else ``spawn``."""
    return multiprocessing.get_context("forkserver" if "forkserver" in multiprocessing.get_all_start_methods()
                                       else "spawn")


class Solver:
    """One solver process: its jobs run one at a time, and it is replaced when grown, worn or dead.

    A job is a picklable module-level function that returns ``(value,
    resident_mb)``: its answer and the process's resident memory after it.
    Once idle, a process past ``memory_mb`` or ``tasks`` jobs is replaced by
    a fresh one (what it kept, prepared sections and warm starts, goes with
    it); a process that dies (killed, out of memory) is replaced too and its
    job answered ``died``.

    Parameters
    ----------
    memory_mb : float
        Resident memory (MB) past which the process is replaced.
    tasks : int
        Jobs after which the process is replaced.
    nice : int
        Priority decrement of the process (0: the server's own).
    context : multiprocessing context
    """

    def __init__(self, memory_mb: float, tasks: int, nice: int, context):
        self.memory_mb, self.tasks, self.nice, self._context = memory_mb, tasks, nice, context
        self._slots = _Slots(1)
        self._running = self._served = 0
        self._grown = False
        self.replaced = 0
        """How many times the process was replaced (grown, worn, or dead)."""
        self.pool = self._new_pool()

    def _new_pool(self) -> concurrent.futures.ProcessPoolExecutor:
        pool = concurrent.futures.ProcessPoolExecutor(max_workers=1, mp_context=self._context,
                                                      initializer=_start_solver, initargs=(self.nice, os.getpid()))
        pool.submit(_ready)  # start the process now, not on the first solve
        return pool

    def _replace(self) -> None:
        old, self.pool = self.pool, self._new_pool()
        self._served, self._grown = 0, False
        self.replaced += 1
        old.shutdown(wait=False, cancel_futures=True)

    async def acquire(self) -> None:
        """Wait until the process is free (cancellable)."""
        await self._slots.get().acquire()

    def release(self) -> None:
        """Give back the slot taken by :meth:`acquire` and not used."""
        self._slots.get().release()

    async def run(self, fn, *args, died=None):
        """Run ``fn(*args)`` in the process, after :meth:`acquire`: its value, or ``died`` if the process died.

        The slot is given back when the process is done, even if the one
        awaiting the answer has gone.
        """
        loop, slots = asyncio.get_running_loop(), self._slots.get()
        try:
            try:
                future = self.pool.submit(fn, *args)
            except BrokenProcessPool:  # died idle: a new process, once
                self._replace()
                future = self.pool.submit(fn, *args)
        except BaseException:
            slots.release()
            raise
        self._running += 1
        future.add_done_callback(lambda f: loop.call_soon_threadsafe(self._done, f, slots))
        try:
            value, _ = await asyncio.wrap_future(future)
        except BrokenProcessPool:
            return died
        return value

    def _done(self, future: concurrent.futures.Future, slots: asyncio.Semaphore) -> None:
        """A job has ended (on the event loop): the slot back, and the process replaced if due."""
        self._running -= 1
        slots.release()
        if future.cancelled():
            pass
        elif isinstance(future.exception(), BrokenProcessPool):
            self._grown = True
        elif future.exception() is None:
            self._served += 1
            self._grown |= bool(future.result()[1] > self.memory_mb)
        if self._running == 0 and (self._grown or self._served >= self.tasks):
            self._replace()

    def close(self) -> None:
        """Stop the process: waiting jobs are dropped, a running one ends first (the server's shutdown)."""
        self.pool.shutdown(wait=True, cancel_futures=True)


class Solvers:
    """The solver processes shared by all connections, each connection pinned to one.

    A page's hyperelastic work all runs in one process (:meth:`assign`):
    its full solves, and its previews, which start from its last full
    solve and that solve's factorisation, kept where it was computed.

    Parameters
    ----------
    size : int
        Processes, and so the most solves running at once.
    memory_mb, tasks, nice
        As :class:`Solver`.
    preload : sequence of str
        Modules the processes import once, before the first job (a forkserver
        forks them ready).
    """

    def __init__(self, size: int, memory_mb: float = SOLVER_MEMORY_MB, tasks: int = SOLVER_TASKS,
                 nice: int = SOLVER_NICE, preload: tuple[str, ...] = ()):
        if size < 1:
            raise ValueError("Solvers needs at least one process")
        context = _context()
        if preload and context.get_start_method() == "forkserver":
            context.set_forkserver_preload(list(preload))
        self.solvers = [Solver(memory_mb, tasks, nice, context) for _ in range(size)]
        self._next = 0

    def assign(self) -> Solver:
        """The solver of a new connection (in turn)."""
        solver = self.solvers[self._next % len(self.solvers)]
        self._next += 1
        return solver

    @property
    def replaced(self) -> int:
        """How many times a process was replaced."""
        return sum(s.replaced for s in self.solvers)

    def close(self) -> None:
        for solver in self.solvers:
            solver.close()
