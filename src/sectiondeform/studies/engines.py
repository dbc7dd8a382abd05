"""Where the chunks run: in this process, local worker processes, or a Dask cluster.

Every engine runs :func:`~sectiondeform.studies.runner.run_chunk` on the same
chunks and yields each chunk's records as it finishes; the table does not
depend on the engine. Local processes use
:class:`concurrent.futures.ProcessPoolExecutor`; Dask uses
``distributed.Client`` (``pip install 'sectiondeform[dask]'``).
"""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Iterator

from ..errors import require
from .runner import Chunk, run_chunk
from .study import Row

__all__ = ["chunks", "run_dask", "run_inline", "run_local"]

MAX_CHUNK = 256
WINDOW = 4  # chunks in flight per worker


def chunks(rows: list[Row], workers: int, save: str = "none", outdir: str | None = None) -> list[Chunk]:
    """Rows grouped by section (case, model, element size) and cut into chunks.

    A chunk holds rows of one section only, so a worker re-uses one prepared
    section for all of it; about four chunks per worker keep the workers busy
    to the end, and no chunk has more than ``MAX_CHUNK`` rows so the table grows
    steadily.
    """
    groups: dict[tuple, list[Row]] = {}
    for row in rows:
        groups.setdefault(row.section_key, []).append(row)
    size = max(1, min(MAX_CHUNK, math.ceil(len(rows) / (4 * max(1, workers)))))
    return [Chunk(tuple(g[i:i + size]), save, outdir) for g in groups.values() for i in range(0, len(g), size)]


def run_inline(tasks: list[Chunk]) -> Iterator[list[dict]]:
    """Run the chunks one after the other in this process."""
    for task in tasks:
        yield run_chunk(task)


def run_local(tasks: list[Chunk], workers: int | None = None) -> Iterator[list[dict]]:
    """Run the chunks on ``workers`` local processes (default: every core), as they finish.

    At most ``WINDOW`` chunks per worker are in flight, so memory stays flat
    however long the study.
    """
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    n = workers or os.cpu_count() or 1
    pending = iter(tasks)
    with ProcessPoolExecutor(max_workers=n) as pool:
        running = {pool.submit(run_chunk, t) for t in itertools.islice(pending, WINDOW * n)}
        try:
            while running:
                done, running = wait(running, return_when=FIRST_COMPLETED)
                running |= {pool.submit(run_chunk, t) for t in itertools.islice(pending, len(done))}
                for future in done:
                    yield future.result()
        finally:
            for future in running:
                future.cancel()


def run_dask(tasks: list[Chunk], scheduler: str, workers: int | None = None) -> Iterator[list[dict]]:
    """Run the chunks on Dask: ``scheduler`` ``"local"`` (a LocalCluster of ``workers`` processes) or ``"tcp://HOST:PORT"``."""
    distributed = require("distributed", "dask", "a sweep on Dask")
    cluster = None
    if scheduler == "local":
        cluster = distributed.LocalCluster(n_workers=workers or os.cpu_count(), threads_per_worker=1,
                                           processes=True, dashboard_address=None)
        client = distributed.Client(cluster)
    else:
        client = distributed.Client(scheduler)
    try:
        n = workers or len(client.scheduler_info().get("workers", {})) or os.cpu_count() or 1
        pending = iter(tasks)
        first = [client.submit(run_chunk, t, pure=False) for t in itertools.islice(pending, WINDOW * n)]
        flow = distributed.as_completed(first)
        try:
            for future in flow:
                for t in itertools.islice(pending, 1):
                    flow.add(client.submit(run_chunk, t, pure=False))
                yield future.result()
                future.release()
        finally:
            client.cancel(list(flow.futures))
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
