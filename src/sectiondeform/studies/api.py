"""``sweep``: run a study and give back its table."""

from __future__ import annotations

import os
import shutil
import tempfile
from dataclasses import replace
from pathlib import Path

from ..errors import CaseError, require
from . import engines
from .progress import Progress
from .study import Study, StudyError, load_study, study_from_dict
from .table import TableStore

__all__ = ["SAVE", "run_study", "sweep"]

SAVE = ("none", "results", "figures")


def _as_study(study, reference) -> Study:
    if isinstance(study, Study):
        out = study
    elif isinstance(study, dict):
        out = study_from_dict(study, ".")
    else:
        out = load_study(study)
    if reference is not None:
        path = Path(reference)
        if not path.is_file():
            raise StudyError("reference", f"no such result file {str(reference)!r}")
        from .study import _finish

        rows = [replace(r, reference=str(reference), reference_path=str(path.resolve()), row_id="") for r in out.rows]
        out = _finish(out.name, rows, [f"row {i}" for i in range(len(rows))])
    return out


def run_study(study: Study, outdir, *, workers: int | None = None, scheduler: str | None = None,
              save: str = "none", csv: bool = False, quiet: bool = True) -> dict:
    """Run the rows of ``study`` not yet in ``outdir``'s table; the table is ``outdir/rows.parquet``.

    Returns
    -------
    dict
        ``rows`` (in the study), ``skipped`` (already done), ``run``, ``failed``, ``table`` (Path), ``csv`` (Path or None).
    """
    if save not in SAVE:
        raise CaseError("save", f"expected one of {', '.join(SAVE)}, got {save!r}")
    if workers is not None and workers < 0:
        raise CaseError("workers", f"must be >= 0 (0: in this process), got {workers}")
    if scheduler is not None and scheduler != "local" and not scheduler.startswith("tcp://"):
        raise CaseError("scheduler", f"expected 'local' or tcp://HOST:PORT, got {scheduler!r}")
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    store = TableStore(outdir)
    done = store.done_ids()
    todo = [r for r in study.rows if r.row_id not in done]
    files = None
    if save != "none":
        files = outdir / "results"
        files.mkdir(exist_ok=True)
        files = str(files)
    index = {r.row_id: i for i, r in enumerate(study.rows)}
    n_workers = workers or os.cpu_count() or 1
    tasks = engines.chunks(todo, n_workers, save, files)
    if scheduler is not None:
        results = engines.run_dask(tasks, scheduler, n_workers)
    elif workers == 0:
        results = engines.run_inline(tasks)
    else:
        results = engines.run_local(tasks, n_workers)
    progress = Progress(len(todo), quiet=quiet)
    try:
        for records in results:
            for rec in records:
                rec["row"] = index[rec["row_id"]]
            store.add(records)
            progress.update(records)
    finally:
        store.close()
        progress.close()
    table = store.merge()
    return {"rows": len(study.rows), "skipped": len(study.rows) - len(todo), "run": progress.done,
            "failed": progress.failed, "table": table, "csv": store.write_csv() if csv else None}


def sweep(study, outdir=None, *, workers: int | None = None, scheduler: str | None = None,
          save: str = "none", csv: bool = False, reference=None, quiet: bool = True, pandas: bool = False):
    """Run a parametric study and return its table, one row per run, in the study's order.

    Parameters
    ----------
    study : str, Path, dict or Study
        A ``section-study/1`` JSON file or a CSV of rows, a parsed study
        (file names relative to the working folder), or a loaded :class:`Study`.
    outdir : str or Path, optional
        Folder of the table (``rows.parquet``); rows already in it are not
        redone. By default a temporary folder, removed afterwards.
    workers : int, optional
        Worker processes (default: every core; 0: in this process).
    scheduler : str, optional
        ``"local"`` (a Dask LocalCluster of ``workers`` processes) or
        ``"tcp://HOST:PORT"`` (a running Dask scheduler).
    save : {"none", "results", "figures"}
        Per-row files in ``outdir/results/`` named by row id.
    csv : bool
        Also write ``outdir/rows.csv``.
    reference : str or Path, optional
        A result file (one body or as many as the cases): the table gets the Hausdorff distance
        (units) of every row's contour to its contour.
    quiet : bool
        No progress bar on stderr.
    pandas : bool
        Return a pandas DataFrame instead of a pyarrow Table.

    Returns
    -------
    pyarrow.Table or pandas.DataFrame
        The study's rows (columns: see the ``section-study/1`` table in the file formats).

    Raises
    ------
    StudyError
        If the study names a bad field.
    """
    pa = require("pyarrow", "sweep", "a sweep")
    import pyarrow.compute as pc
    import pyarrow.parquet as pq

    loaded = _as_study(study, reference)
    tmp = None
    if outdir is None:
        tmp = outdir = tempfile.mkdtemp(prefix="sweep-")
    try:
        info = run_study(loaded, outdir, workers=workers, scheduler=scheduler, save=save, csv=csv, quiet=quiet)
        table = pq.read_table(info["table"])
    finally:
        if tmp is not None:
            shutil.rmtree(tmp, ignore_errors=True)
    ids = pa.array([r.row_id for r in loaded.rows], pa.string())
    order = pc.index_in(table["row_id"], value_set=ids)
    table = table.set_column(table.schema.get_field_index("row"), "row", pc.cast(order, pa.int64()))
    table = table.filter(pc.is_valid(order)).sort_by("row")
    return table.to_pandas() if pandas else table
