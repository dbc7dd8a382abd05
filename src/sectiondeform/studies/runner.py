"""Run the rows of one section on a worker: each row is what ``deform`` gives for it.

:func:`run_chunk` is the task every engine runs. A row is the case with its
target and law replaced; its result is :func:`~sectiondeform.deform.deform`
of that problem, to the bit. Preparing is what costs, so a worker keeps the
last few prepared sections (:data:`CACHE_SIZE`) keyed by their sampling: a
row whose sections come out sampled as a kept one's (the lower curves
resolve the row's target at the same points: a change of law, or a target
the case's sampling already resolves) reuses it; any other prepares again.
"""

from __future__ import annotations

import copy
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
from ..stack import Stack
from .study import Row, read_target
from .targets import TRANSFORMS, transformed_target

__all__ = ["CACHE_SIZE", "Chunk", "run_chunk", "run_row"]

CACHE_SIZE = 8
_SECTIONS: OrderedDict = OrderedDict()  # (section key, sampling) -> Deformer, or the exception preparing it raised
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


def _kept(key, build):
    """The prepared section kept under ``key``, else ``build()`` (or the exception it raised), kept."""
    if key in _SECTIONS:
        _SECTIONS.move_to_end(key)
    else:
        try:
            _SECTIONS[key] = build()
        except Exception as exc:  # noqa: BLE001 - a section that cannot be prepared fails each of its rows, not the study
            _SECTIONS[key] = exc
        while len(_SECTIONS) > CACHE_SIZE:
            _SECTIONS.popitem(last=False)
    return _SECTIONS[key]


def _with_friction(problem, row: Row):
    """The problem with every rigid part's friction set, as the row asks."""
    if row.friction is None:
        return problem
    return problem.replace(rigid=tuple(dataclasses.replace(part, friction=row.friction) for part in problem.rigid))


def _travels(row: Row, problem) -> list | None:
    """Every rigid part's travel scaled from the same start, as the row asks (None: the case's)."""
    if row.travel_scale is None:
        return None
    return [tuple(row.travel_scale * np.asarray(part.travel, dtype=np.float64)) for part in problem.rigid]


def _contact(result) -> str | None:
    """Per rigid part (and the support) its force, contact length and peak pressure, as JSON text; None without parts."""
    if not result.rigid:
        return None
    out = {p.name: {"force_x": p.force[0], "force_y": p.force[1], "contact_length": p.length,
                    "pressure_max": p.pressure_max} for p in result.rigid}
    out["support"] = {"force_x": result.support_force[0], "force_y": result.support_force[1]}
    return json.dumps(out)


def _section(row: Row):
    """The case's own section prepared for ``row``'s model and element size (a Deformer, or the exception)."""
    return _kept((row.section_key, None), lambda: Deformer(_with_friction(load_case(row.case_path), row), model=row.model,
                                                           element_size=row.element_size))


def _sampling(stack: Stack) -> bytes:
    """What a prepared section depends on the target by: the support fractions and each section's lower nodes."""
    return b"".join(np.ascontiguousarray(a, dtype=np.float64).tobytes()
                    for a in (stack.fractions, *(s.lower for s in stack.sections)))


def row_deformer(row: Row, deformer: Deformer, target, law) -> Deformer:
    """A deformer of ``row``'s own problem (the case with ``target`` and ``law``), prepared only when needed.

    ``deformer.deform(travel=...)`` of the returned one (the row's
    travels) is what ``deform(problem, row.model, row.element_size)`` gives
    for the row's problem: the row's sections are built (cheap) and, when they come out
    sampled as a kept prepared section's, that one is reused with the row's
    problem; otherwise the row's problem is prepared (and kept).
    """
    problem = deformer.problem
    if law is not None:
        deformer.laws(law)  # one law for a one-body problem: the same refusal as Deformer.deform
        problem = problem.replace(law=law)
    if target is not None:
        problem = problem.replace(target=target)
    if problem == deformer.problem:
        return deformer
    sampling = _sampling(Stack(problem, row.element_size))
    if sampling == _sampling(deformer.stack):
        kept = deformer
    else:
        kept = _kept((row.section_key, sampling),
                     lambda: Deformer(problem, model=row.model, element_size=row.element_size))
    if isinstance(kept, BaseException):
        raise kept
    if kept.problem == problem:
        return kept
    same = copy.copy(kept)
    same.problem = problem
    return same


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
    """The table's figures of a result: areas summed over the bodies, the worst error, Jacobian and area stretch, quality and info.

    ``quality`` and ``info`` are JSON text: the one body's object for a
    ``section-result/1`` result, else an object by body name.
    """
    bodies = result.bodies
    qualities = [b.quality.to_json() if b.quality is not None else {} for b in bodies]
    infos = [b.info.to_json() for b in bodies]

    def smallest(key):
        values = [q[key] for q in qualities if q.get(key) is not None]
        return min(values, default=None)
    targets = [b.area_target for b in bodies]

    def by_body(values):
        return values[0] if result.dialect == RESULT_V1 else {b.name: v for b, v in zip(bodies, values)}

    return dict(
        area_initial=sum(b.area_initial for b in bodies),
        area_target=None if None in targets else sum(targets),
        area_final=sum(b.area_final for b in bodies),
        relative_error=result.relative_error,
        final_jacobian_min=smallest("final_jacobian_min"),
        final_area_stretch_min=smallest("final_area_stretch_min"),
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
        law (the worst body's), ``final_jacobian_min`` (units², the paper
        model's) or ``final_area_stretch_min`` (a ratio, the hyperelastic
        model's), the smallest over the bodies, ``quality`` and ``info``
        (JSON text), ``warnings`` (a list of lines), ``rigid`` (JSON text: per rigid
        part ``force_x``, ``force_y``, ``contact_length``, ``pressure_max``,
        and the support's force), ``hausdorff`` (units),
        ``prepare_s``, ``place_s``, ``row_s`` (seconds) and ``worker``.
    """
    t0 = time.perf_counter()
    rec = {"row_id": row.row_id, **row.inputs(), "ok": False, "error_type": None, "error": None, "worker": _WORKER}
    try:
        if isinstance(deformer, BaseException):
            raise deformer
        base = None if row.target_path is None else _file(row.target_path, "target")
        amounts = {k: getattr(row, k) for k in TRANSFORMS}
        if any(v is not None for v in amounts.values()):
            base = transformed_target(base if base is not None else deformer.problem.target, **amounts)
        deformer = row_deformer(row, deformer, base, None if row.area_ratio is None else AreaRatio(row.area_ratio))
        rec["prepare_s"] = deformer.prepare_seconds
        result = deformer.deform(travel=_travels(row, deformer.problem))
        rec.update(ok=True, **_figures(result), rigid=_contact(result), warnings=list(result.warnings),
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
    """Run every row of a chunk (one section) on this worker; one record per row, in order.

    The rows run grouped by target (rows that differ only in their law one
    after the other), so a target that needs its own preparation is
    prepared once for all of them.
    """
    def target_of(i):
        row = chunk.rows[i]
        return repr((row.target_path, *(getattr(row, k) for k in TRANSFORMS)))

    order = sorted(range(len(chunk.rows)), key=target_of)
    records = [None] * len(chunk.rows)
    for i in order:
        records[i] = run_row(chunk.rows[i], _section(chunk.rows[i]), chunk.save, chunk.outdir)
    return records
