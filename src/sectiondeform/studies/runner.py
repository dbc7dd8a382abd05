"""Run the rows of one section on a worker: the section prepared once, re-deformed per row.

:func:`run_chunk` is the task every engine runs. A worker keeps the last few
prepared sections (:data:`CACHE_SIZE`), so the chunks of one section that
land on the same worker prepare it once.
"""

from __future__ import annotations

import json
import os
import socket
import time
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..case import load_case
from ..compare import hausdorff_distance
from . import _adapter
from .study import Row, read_target
from .targets import TRANSFORMS, transformed_target

__all__ = ["CACHE_SIZE", "Chunk", "run_chunk", "run_row"]

CACHE_SIZE = 8
_SECTIONS: OrderedDict = OrderedDict()  # section key -> Deformer, or the exception that preparing it raised
_FILES: dict = {}  # path -> parsed target curve or reference contour
_WORKER = f"{socket.gethostname()}:{os.getpid()}"


@dataclass(frozen=True)
class Chunk:
    """Rows of one section, with where to save per-row files.

    Attributes
    ----------
    rows : tuple of Row
        All with the same ``section_key``.
    save : str
        ``"none"``, ``"results"`` (a result JSON per row) or ``"figures"`` (also a PNG).
    outdir : str or None
        Folder of the per-row files.
    """

    rows: tuple[Row, ...]
    save: str = "none"
    outdir: str | None = None


def _section(row: Row):
    key = row.section_key
    if key in _SECTIONS:
        _SECTIONS.move_to_end(key)
    else:
        try:
            _SECTIONS[key] = _adapter.prepare(load_case(row.case_path), row.model, row.element_size)
        except Exception as exc:  # noqa: BLE001 - a section that cannot be prepared fails each of its rows, not the study
            _SECTIONS[key] = exc
        while len(_SECTIONS) > CACHE_SIZE:
            _SECTIONS.popitem(last=False)
    return _SECTIONS[key]


def _file(path: str, kind: str):
    key = (path, kind)
    if key not in _FILES:
        if kind == "target":
            _FILES[key] = read_target(path)
        else:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
            contour = np.asarray(data["contour"], dtype=np.float64)
            _FILES[key] = np.concatenate((contour, contour[:1]))
    return _FILES[key]


def _message(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


def run_row(row: Row, deformer, save: str = "none", outdir: str | None = None) -> dict:
    """Deform one row on its prepared section; a record for the table, never an exception.

    Returns
    -------
    dict
        The row's inputs, ``ok``, ``error_type`` and ``error`` (one line),
        areas (units²), ``relative_error`` of the law, ``jacobian_min``,
        ``quality`` and ``info`` (JSON text), ``hausdorff`` (units),
        ``prepare_s``, ``place_s``, ``row_s`` (seconds) and ``worker``.
    """
    t0 = time.perf_counter()
    rec = {"row_id": row.row_id, **row.inputs(), "ok": False, "error_type": None, "error": None, "worker": _WORKER}
    try:
        if isinstance(deformer, BaseException):
            raise deformer
        rec["prepare_s"] = deformer.prepare_seconds
        base = None if row.target_path is None else _file(row.target_path, "target")
        amounts = {k: getattr(row, k) for k in TRANSFORMS}
        if any(v is not None for v in amounts.values()):
            base = transformed_target(base if base is not None else deformer.case.target, **amounts)
        result = _adapter.deform(deformer, base, row.area_ratio)
        q = result.quality.to_json()
        rec.update(
            ok=True,
            area_initial=result.area_initial, area_target=result.area_target, area_final=result.area_final,
            relative_error=result.relative_error,
            jacobian_min=q.get("final_jacobian_min", q.get("final_area_stretch_min")),
            quality=json.dumps(q, default=str), info=json.dumps(result.info.to_json(), default=str),
            warnings="; ".join(result.warnings) or None,
            place_s=result.timings.get("place_s"),
        )
        if row.reference_path is not None:
            contour = np.concatenate((result.contour, result.contour[:1]))
            rec["hausdorff"] = hausdorff_distance(contour, _file(row.reference_path, "reference"))
        if save != "none" and outdir is not None:
            _save(result, row, save, Path(outdir))
    except Exception as exc:  # noqa: BLE001 - a failed row is recorded, never stops the study
        rec.update(ok=False, error_type=type(exc).__name__, error=_message(exc))
    rec["row_s"] = time.perf_counter() - t0
    return rec


def _save(result, row: Row, save: str, outdir: Path) -> None:
    from ..io.json import write_result

    write_result(outdir / f"{row.row_id}.json", result, meshes=False)
    if save == "figures":
        from ..plot import save_figure

        save_figure(result, outdir / f"{row.row_id}.png")


def run_chunk(chunk: Chunk) -> list[dict]:
    """Run every row of a chunk (one section) on this worker; one record per row, in order."""
    return [run_row(row, _section(row), chunk.save, chunk.outdir) for row in chunk.rows]
