"""Run the rows of one section on a worker: the section prepared once, re-deformed per row.

:func:`run_chunk` is the task every engine runs. A worker keeps the last few
prepared sections (:data:`CACHE_SIZE`), so the chunks of one section that
land on the same worker prepare it once.
"""

from __future__ import annotations

import dataclasses
import json
import os
import socket
import time
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..compare import hausdorff_distance
from ..deform import Deformer
from ..errors import CaseError
from ..io.case import load_case
from ..laws import AreaRatio
from ..result import RESULT_V1
from .study import Row, read_target
from .targets import TRANSFORMS, transformed_target

__all__ = ["CACHE_SIZE", "Chunk", "run_chunk", "run_row"]

CACHE_SIZE = 8
_SECTIONS: OrderedDict = OrderedDict()  # section key -> Deformer, or the exception that preparing it raised
_FILES: dict = {}  # path -> parsed target curve, or the reference's closed contours (one per body)
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
            _SECTIONS[key] = Deformer(_with_rigid(load_case(row.case_path), row), model=row.model,
                                      element_size=row.element_size)
        except Exception as exc:  # noqa: BLE001 - a section that cannot be prepared fails each of its rows, not the study
            _SECTIONS[key] = exc
        while len(_SECTIONS) > CACHE_SIZE:
            _SECTIONS.popitem(last=False)
    return _SECTIONS[key]


def _with_rigid(problem, row: Row):
    """The problem with every rigid part's travel scaled from the same start and its friction set, as the row asks."""
    if row.travel_scale is None and row.friction is None:
        return problem
    parts = []
    for part in problem.rigid:
        contour, travel = part.contour, part.travel
        if row.travel_scale is not None:
            shift = (row.travel_scale - 1.0) * np.asarray(part.travel)
            contour, travel = contour.transformed(np.eye(2), shift), tuple(row.travel_scale * np.asarray(part.travel))
        parts.append(dataclasses.replace(part, contour=contour, travel=travel,
                                         friction=part.friction if row.friction is None else row.friction))
    return problem.replace(rigid=tuple(parts))


def _contact(result) -> str | None:
    """Per rigid part (and the support) its force, contact length and peak pressure, as JSON text; None without parts."""
    if not result.rigid:
        return None
    out = {p.name: {"force_x": p.force[0], "force_y": p.force[1], "contact_length": p.length,
                    "pressure_max": p.pressure_max} for p in result.rigid}
    out["support"] = {"force_x": result.support_force[0], "force_y": result.support_force[1]}
    return json.dumps(out)


def _file(path: str, kind: str):
    key = (path, kind)
    if key not in _FILES:
        if kind == "target":
            _FILES[key] = read_target(path)
        else:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
            contours = [data["contour"]] if "contour" in data else [b["contour"] for b in data["bodies"]]
            _FILES[key] = [_closed(np.asarray(c, dtype=np.float64)) for c in contours]
    return _FILES[key]


def _closed(contour: np.ndarray) -> np.ndarray:
    return np.concatenate((contour, contour[:1]))


def _hausdorff(result, reference: list) -> float:
    """The largest Hausdorff distance of a body's contour to the reference's, body by body (units)."""
    if len(reference) != len(result.bodies):
        raise CaseError("reference", f"holds {len(reference)} bodies, the result {len(result.bodies)}")
    return max(hausdorff_distance(_closed(b.contour), ref) for b, ref in zip(result.bodies, reference))


def _figures(result) -> dict:
    """The table's figures of a result: areas summed over the bodies, the worst error and Jacobian, quality and info.

    ``quality`` and ``info`` are JSON text: the one body's object for a
    ``section-result/1`` result, else an object by body name.
    """
    bodies = result.bodies
    qualities = [b.quality.to_json() if b.quality is not None else {} for b in bodies]
    infos = [b.info.to_json() for b in bodies]
    jacobians = [q.get("final_jacobian_min", q.get("final_area_stretch_min")) for q in qualities]
    jacobians = [j for j in jacobians if j is not None]
    targets = [b.area_target for b in bodies]

    def by_body(values):
        return values[0] if result.dialect == RESULT_V1 else {b.name: v for b, v in zip(bodies, values)}

    return dict(
        area_initial=sum(b.area_initial for b in bodies),
        area_target=None if None in targets else sum(targets),
        area_final=sum(b.area_final for b in bodies),
        relative_error=result.relative_error,
        jacobian_min=min(jacobians, default=None),
        quality=json.dumps(by_body(qualities), default=str), info=json.dumps(by_body(infos), default=str),
    )


def _message(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


def run_row(row: Row, deformer, save: str = "none", outdir: str | None = None) -> dict:
    """Deform one row on its prepared section; a record for the table, never an exception.

    Returns
    -------
    dict
        The row's inputs, ``ok``, ``error_type`` and ``error`` (one line),
        areas (units², summed over the bodies), ``relative_error`` of the
        law (the worst body's), ``jacobian_min`` (the smallest),
        ``quality`` and ``info`` (JSON text), ``rigid`` (JSON text: per rigid
        part ``force_x``, ``force_y``, ``contact_length``, ``pressure_max``,
        and the support's force), ``hausdorff`` (units),
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
            base = transformed_target(base if base is not None else deformer.problem.target, **amounts)
        result = deformer.deform(base, None if row.area_ratio is None else AreaRatio(row.area_ratio))
        rec.update(ok=True, **_figures(result), rigid=_contact(result), warnings="; ".join(result.warnings) or None,
                   place_s=result.timings.get("place_s"))
        if row.reference_path is not None:
            rec["hausdorff"] = _hausdorff(result, _file(row.reference_path, "reference"))
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
