"""Where the chunks run: in this process, local worker processes, or a Dask cluster.

Every engine runs :func:`~sectiondeform.studies.runner.run_chunk` on the same
chunks and yields each chunk's records as it finishes; the table does not
depend on the engine. Local processes use
:class:`concurrent.futures.ProcessPoolExecutor`; Dask uses
``distributed.Client`` (``pip install 'sectiondeform[dask]'``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator

from ..errors import require
from .runner import Chunk, run_chunk
from .study import Row

__all__ = ["chunks", "run_dask", "run_inline", "run_local"]

MAX_CHUNK = 256


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
    """Run the chunks on ``workers`` local processes (default: every core), as they finish."""
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(max_workers=workers or os.cpu_count()) as pool:
        futures = [pool.submit(run_chunk, t) for t in tasks]
        try:
            for future in as_completed(futures):
                yield future.result()
        finally:
            for future in futures:
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
        futures = client.map(run_chunk, tasks, pure=False)
        try:
            for future in distributed.as_completed(futures):
                yield future.result()
                future.release()
        finally:
            client.cancel(futures)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
