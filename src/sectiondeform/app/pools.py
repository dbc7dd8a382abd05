"""Where the page's computations run: worker threads for previews, solver processes for full solves.

A preview of a prepared section takes a millisecond or two and needs the
section prepared in the server (:class:`Workers`, threads). A full
hyperelastic solve takes up to seconds of Python and numerical code; on a
thread it would hold the interpreter lock a good part of that time, so
every other page's previews would wait behind it, and the solver's working
memory would stay with the server. It runs in a process of its own instead
(:class:`Solvers`): the server's interpreter stays free for the previews,
the process runs at a lower priority than the server (a preview being
dragged goes before a solve on release), and it is replaced once it has
grown past :data:`SOLVER_MEMORY_MB` or served :data:`SOLVER_TASKS` solves,
so the memory of a long session stays bounded.

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
import weakref
from concurrent.futures.process import BrokenProcessPool

__all__ = ["SOLVER_MEMORY_MB", "SOLVER_NICE", "SOLVER_TASKS", "Solvers", "Workers", "resident_mb"]

SOLVER_MEMORY_MB = 1024
"""A solver process whose resident memory has grown past this (MB) is replaced after its solve."""
SOLVER_TASKS = 200
"""A solver process is replaced after this many solves, whatever its memory."""
SOLVER_NICE = 5
"""How much lower a solver process's scheduling priority is than the server's (POSIX ``nice`` increment)."""


def resident_mb() -> float:
    """This process's resident memory (MB; from ``/proc``, or the peak from ``resource`` elsewhere; NaN if neither)."""
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


def _start_solver(nice: int) -> None:
    """Run first in each solver process: a lower priority than the server's."""
    if nice and hasattr(os, "nice"):
        try:
            os.nice(nice)
        except OSError:
            pass


def _ready() -> float:
    """A job that only starts the process (the first real solve then does not wait for it); its memory."""
    return resident_mb()


def _context():
    """``forkserver`` where there is one (never ``fork`` from a server with threads), else ``spawn``."""
    return multiprocessing.get_context("forkserver" if "forkserver" in multiprocessing.get_all_start_methods()
                                       else "spawn")


class Solvers:
    """A bounded pool of solver processes shared by all connections (full solves).

    A job is a picklable module-level function that returns ``(value,
    resident_mb)``: its answer and the process's resident memory after it.
    A process past ``memory_mb`` or ``tasks`` solves is replaced once it is
    idle; a process that dies (killed, out of memory) is replaced too and its
    job answered with one line.

    Parameters
    ----------
    size : int
        Processes, and so the most solves running at once.
    memory_mb : float
        Resident memory (MB) past which a process is replaced.
    tasks : int
        Solves after which a process is replaced.
    nice : int
        Priority decrement of the processes (0: the server's own).
    preload : sequence of str
        Modules the processes import once, before the first job (a forkserver
        forks them ready).
    """

    def __init__(self, size: int, memory_mb: float = SOLVER_MEMORY_MB, tasks: int = SOLVER_TASKS,
                 nice: int = SOLVER_NICE, preload: tuple[str, ...] = ()):
        if size < 1:
            raise ValueError("Solvers needs at least one process")
        self.size, self.memory_mb, self.tasks, self.nice = size, memory_mb, tasks, nice
        self._context = _context()
        if preload and self._context.get_start_method() == "forkserver":
            self._context.set_forkserver_preload(list(preload))
        self._slots = _Slots(size)
        self._running = 0
        self._served = 0
        self._grown = False
        self.replaced = 0
        """How many times the processes were replaced (grown, served their count, or died)."""
        self.pool = self._new_pool()

    def _new_pool(self) -> concurrent.futures.ProcessPoolExecutor:
        pool = concurrent.futures.ProcessPoolExecutor(max_workers=self.size, mp_context=self._context,
                                                      initializer=_start_solver, initargs=(self.nice,))
        for _ in range(self.size):
            pool.submit(_ready)  # start the processes now, not on the first solve
        return pool

    def _replace(self) -> None:
        old, self.pool = self.pool, self._new_pool()
        self._served, self._grown = 0, False
        self.replaced += 1
        old.shutdown(wait=False, cancel_futures=True)

    async def acquire(self) -> None:
        """Wait for a free process (cancellable)."""
        await self._slots.get().acquire()

    def release(self) -> None:
        """Give back a slot taken by :meth:`acquire` and not used."""
        self._slots.get().release()

    async def run(self, fn, *args, died: str = "server: the solver stopped before answering; try again"):
        """Run ``fn(*args)`` in a process, after :meth:`acquire`: its value, or ``died`` if the process died.

        ``fn`` returns ``(value, resident_mb)``. The slot is given back when
        the process is done, even if the one awaiting the answer has gone.
        """
        loop, slots = asyncio.get_running_loop(), self._slots.get()
        try:
            try:
                future = self.pool.submit(fn, *args)
            except BrokenProcessPool:  # died idle: a new pool, once
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
        """A job has ended (on the event loop): its slot back, and the processes replaced if due and idle."""
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
        self.pool.shutdown(wait=False, cancel_futures=True)
