"""The study's table on disk: Parquet parts written as rows finish, merged into one file.

While a study runs, finished rows go to ``OUTDIR/parts/part-*.parquet``
(one row group per batch, a new part every :data:`PART_SECONDS`, so a
killed run loses at most the open part). When the run ends the parts and
the previous ``rows.parquet`` are streamed, row group by row group, into a
new ``rows.parquet`` (memory flat), each ``row_id`` once.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq

from .study import NUMBER_AXES

__all__ = ["SCHEMA", "TableStore"]

PART_SECONDS = 30.0
BATCH_ROWS = 512
BATCH_SECONDS = 2.0

_F, _S = pa.float64(), pa.string()


def _unit(name: str, unit: str) -> pa.Field:
    """A float column with its unit in the field's metadata (``unit``: ``units``, ``units²``, ``1``, ``s``)."""
    return pa.field(name, _F, metadata={"unit": unit})


SCHEMA = pa.schema(
    [("row", pa.int64()), ("row_id", _S), ("case", _S), ("model", _S)]
    + [(k, _F) for k in NUMBER_AXES]
    + [("target_file", _S), ("reference", _S), ("ok", pa.bool_()), ("error_type", _S), ("error", _S),
       _unit("area_initial", "units²"), _unit("area_target", "units²"), _unit("area_final", "units²"),
       _unit("relative_error", "1"), _unit("final_jacobian_min", "units²"), _unit("final_area_stretch_min", "1"),
       _unit("hausdorff", "units"), ("quality", _S), ("info", _S), ("rigid", _S), ("warnings", pa.list_(_S)),
       _unit("prepare_s", "s"), _unit("place_s", "s"), _unit("row_s", "s"), ("worker", _S)]
)
"""The table's columns: one unit per column (in the field's metadata), ``warnings`` a list of lines."""


class TableStore:
    """The table of a study in ``outdir``: which rows are done, appending, merging.

    Parameters
    ----------
    outdir : Path
    """

    def __init__(self, outdir):
        self.outdir = Path(outdir)
        self.parts = self.outdir / "parts"
        self.path = self.outdir / "rows.parquet"
        self._writer = None
        self._buffer: list[dict] = []
        self._opened = self._flushed = 0.0
        self._count = 0

    def _files(self) -> list[Path]:
        return ([self.path] if self.path.exists() else []) + sorted(self.parts.glob("part-*.parquet"))

    def done_ids(self) -> set[str]:
        """Row ids already in the table (parts a killed run left unreadable are removed)."""
        done = set()
        for f in self._files():
            try:
                done.update(pq.read_table(f, columns=["row_id"]).column(0).to_pylist())
            except (pa.ArrowInvalid, OSError):
                f.unlink()
        return done

    def add(self, records: list[dict]) -> None:
        """Queue finished rows; written as a row group every BATCH_ROWS rows or BATCH_SECONDS."""
        self._buffer += records
        now = time.monotonic()
        if len(self._buffer) >= BATCH_ROWS or now - self._flushed > BATCH_SECONDS:
            self.flush()

    def flush(self) -> None:
        """Write the queued rows as one row group of the open part."""
        now = time.monotonic()
        if self._buffer:
            if self._writer is not None and now - self._opened > PART_SECONDS:
                self._close()
            if self._writer is None:
                self.parts.mkdir(parents=True, exist_ok=True)
                name = f"part-{time.time_ns():020d}-{os.getpid()}.parquet"
                self._writer = pq.ParquetWriter(self.parts / name, SCHEMA)
                self._opened = now
            self._writer.write_table(pa.Table.from_pylist(self._buffer, schema=SCHEMA))
            self._count += len(self._buffer)
            self._buffer = []
        self._flushed = now

    def _close(self) -> None:
        if self._writer is not None:
            self._writer.close()
            self._writer = None

    def close(self) -> None:
        """Write what is queued and close the open part."""
        self.flush()
        self._close()

    def merge(self) -> Path:
        """Stream every part and the previous table into one ``rows.parquet``, each row id once."""
        files = self._files()
        tmp = self.outdir / ".rows.parquet.tmp"
        seen: set[str] = set()
        with pq.ParquetWriter(tmp, SCHEMA) as writer:
            for f in files:
                pf = pq.ParquetFile(f)
                for i in range(pf.num_row_groups):
                    group = pf.read_row_group(i).cast(SCHEMA)
                    ids = group.column("row_id").to_pylist()
                    keep = [j for j, rid in enumerate(ids) if rid not in seen]
                    seen.update(ids)
                    if keep:
                        writer.write_table(group.take(keep) if len(keep) < len(ids) else group)
        os.replace(tmp, self.path)
        for f in files:
            if f != self.path:
                f.unlink()
        if self.parts.exists() and not any(self.parts.iterdir()):
            self.parts.rmdir()
        return self.path

    def write_csv(self) -> Path:
        """``rows.csv`` next to ``rows.parquet``, streamed row group by row group (``warnings`` as a JSON list)."""
        import json

        import pyarrow.csv as pacsv

        out = self.outdir / "rows.csv"
        pf = pq.ParquetFile(self.path)
        i = SCHEMA.get_field_index("warnings")
        schema = SCHEMA.set(i, pa.field("warnings", _S))  # a CSV cell holds the list as JSON text
        with pacsv.CSVWriter(out, schema) as writer:
            for g in range(pf.num_row_groups):
                group = pf.read_row_group(g)
                text = [None if w is None else json.dumps(w) for w in group.column(i).to_pylist()]
                writer.write_table(group.set_column(i, schema.field(i), pa.array(text, _S)))
        return out
