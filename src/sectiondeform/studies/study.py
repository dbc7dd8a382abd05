"""A parametric study (``section-study/1``, or a CSV of rows) and its expansion into rows.

A study names cases and, for each, the values of its variation axes; the
product of the axes gives the rows. Each row carries a stable ``row_id``, a
hash of everything that decides its outcome (the case file's content, the
row's inputs, the reference's content), so a study run again skips the
rows already in its table.
"""

from __future__ import annotations

import csv
import hashlib
import itertools
import json
import math
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from ..curves import curve_from_json
from ..errors import CaseError, SectionDeformError
from ..io.case import load_case
from ..limits import MAX_STUDY_ROWS, bounded
from ..models import MODEL_NAMES
from .targets import TRANSFORMS

__all__ = ["AXES", "STUDY_FORMAT", "Row", "Study", "StudyError", "load_study", "study_from_dict"]

STUDY_FORMAT = "section-study/1"
RIGID_AXES = ("travel_scale", "friction")
NUMBER_AXES = ("area_ratio", "element_size", *TRANSFORMS, *RIGID_AXES)
AXES = ("model", "targets", *NUMBER_AXES)
POSITIVE = ("area_ratio", "element_size", "stretch", "scale", "travel_scale")
CSV_COLUMNS = ("case", "model", "target_file", "reference", *NUMBER_AXES)
CSV_ALIASES = {"bend": "bend_radius", "rotate": "rotate_deg", "target": "target_file"}


class StudyError(CaseError):
    """A study file is malformed; the message names the field (or CSV line and column)."""


@dataclass(frozen=True)
class Row:
    """One run of a study: a problem (case, model, element size; one body or several), a target and a law.

    Attributes
    ----------
    case : str
        The case file as the study names it (relative to the study file).
    case_path : str
        The case file's absolute path.
    model : str
    element_size : float or None
        Units; None for the case's own.
    area_ratio : float or None
        The law of a one-body case; None keeps the case's laws.
    bend_radius, crown, stretch, scale, rotate_deg, translate_x, translate_y : float or None
        Target transformations (see :mod:`sectiondeform.studies.targets`); None: not applied.
    travel_scale : float or None
        Every rigid part's travel times this, from the same start (its end
        moves: a squeeze, an interference); None: the case's.
    friction : float or None
        Every rigid part's Coulomb coefficient; None: the case's.
    target_file : str or None
        A target curve file (as the study names it) replacing the case's target.
    reference : str or None
        A result file (``section-result/1`` or ``/2``, as many bodies as the
        case) to measure the Hausdorff distance to, body by body.
    row_id : str
        Stable hash of the inputs and of the files' contents.
    """

    case: str
    case_path: str
    model: str
    element_size: float | None = None
    area_ratio: float | None = None
    bend_radius: float | None = None
    crown: float | None = None
    stretch: float | None = None
    scale: float | None = None
    rotate_deg: float | None = None
    translate_x: float | None = None
    translate_y: float | None = None
    travel_scale: float | None = None
    friction: float | None = None
    target_file: str | None = None
    target_path: str | None = None
    reference: str | None = None
    reference_path: str | None = None
    row_id: str = ""

    @property
    def section_key(self) -> tuple:
        """Rows with the same key share one prepared section: (case file, model, element size, rigid parts' friction).

        The travel is not in it: a row's travel is an argument of its
        deformation (:meth:`~sectiondeform.deform.Deformer.deform`'s ``travel``).
        """
        return (self.case_path, self.model, self.element_size, self.friction)

    def inputs(self) -> dict:
        """The row's inputs as the table records them."""
        d = asdict(self)
        for key in ("case_path", "target_path", "reference_path", "row_id"):
            d.pop(key)
        return d


@dataclass(frozen=True)
class Study:
    """A study expanded: its name and its rows, in order."""

    name: str
    rows: tuple[Row, ...]


def _digest(path: Path, cache: dict) -> str:
    if path not in cache:
        try:
            cache[path] = hashlib.sha256(path.read_bytes()).hexdigest()
        except OSError as exc:
            raise StudyError(str(path), f"cannot read the file ({exc.strerror})") from None
    return cache[path]


def _row_id(row: Row, digests: dict) -> str:
    key = row.inputs()
    key["case"] = _digest(Path(row.case_path), digests)
    for name in ("target", "reference"):
        path = getattr(row, f"{name}_path")
        key[f"{name}_file" if name == "target" else name] = None if path is None else _digest(Path(path), digests)
    text = json.dumps(key, sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def _number(value, field: str, name: str | None = None) -> float | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise StudyError(field, f"expected a finite number or null, got {value!r}")
    name = name or field.rsplit(".", 1)[-1].split("[")[0]
    if name in POSITIVE and not value > 0:
        raise StudyError(field, f"must be > 0, got {value!r}")
    if name == "friction" and value < 0:
        raise StudyError(field, f"a Coulomb coefficient is >= 0, got {value!r}")
    if name == "bend_radius" and value == 0:
        raise StudyError(field, "must be non-zero (null for an unbent target)")
    return float(value)


def _values(spec, field: str) -> list:
    """The values of one axis: a list, a single value, or a range ``{"start", "stop", "num"}``."""
    if isinstance(spec, dict):
        unknown = set(spec) - {"start", "stop", "num"}
        if unknown or set(spec) != {"start", "stop", "num"}:
            bad = sorted(unknown) or sorted({"start", "stop", "num"} - set(spec))
            raise StudyError(f"{field}.{bad[0]}", "a range is {\"start\": a, \"stop\": b, \"num\": n} (n values, both ends included)")
        start = _number(spec["start"], f"{field}.start")
        stop = _number(spec["stop"], f"{field}.stop")
        num = spec["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise StudyError(f"{field}.num", f"expected an integer >= 1, got {num!r}")
        _bounded_rows(num, f"{field}.num")
        if start is None or stop is None:
            raise StudyError(field, "a range needs numbers for start and stop")
        return [start + (stop - start) * i / (num - 1) if num > 1 else start for i in range(num)]
    values = spec if isinstance(spec, list) else [spec]
    if not values:
        raise StudyError(field, "an empty list gives no rows; leave the axis out instead")
    return values


def _axis(name: str, spec, field: str, base: Path) -> list:
    if name == "model":
        values = _values(spec, field)
        for i, v in enumerate(values):
            if v is not None and v not in MODEL_NAMES:
                raise StudyError(f"{field}[{i}]", f"unknown model {v!r}; use one of {', '.join(MODEL_NAMES)}")
        return values
    if name == "targets":
        return _target_files(spec, field, base)
    values = _values(spec, field)
    return [_number(v, f"{field}[{i}]") for i, v in enumerate(values)]


def _target_files(spec, field: str, base: Path) -> list:
    """``"folder/"`` (every .json file in it, sorted) or a list of files, relative to the study."""
    names = spec if isinstance(spec, list) else [spec]
    out = []
    for i, name in enumerate(names):
        if not isinstance(name, str):
            raise StudyError(f"{field}[{i}]", f"expected a file or folder name, got {name!r}")
        path = base / name
        files = sorted(path.glob("*.json")) if path.is_dir() else [path]
        if not files:
            raise StudyError(f"{field}[{i}]", f"the folder {name!r} holds no .json target file")
        for f in files:
            if not f.is_file():
                raise StudyError(f"{field}[{i}]", f"no such file {str(f)!r}")
            _check_target_file(f, f"{field}[{i}]")
            out.append(f.relative_to(base).as_posix() if f.is_relative_to(base) else str(f))
    return out


def read_target(path) -> Curve:  # noqa: F821 - documentation type
    """A target curve file: a CURVE object, or any object with a ``"target"`` CURVE (a case)."""
    data = json.loads(Path(path).read_text(encoding="utf-8"))
    if isinstance(data, dict) and "target" in data:
        data = data["target"]
    return curve_from_json(data, "target")


def _check_target_file(path: Path, field: str) -> None:
    try:
        read_target(path)
    except (OSError, ValueError, SectionDeformError) as exc:
        raise StudyError(field, f"{path.name}: not a target curve ({str(exc).splitlines()[0]})") from None


def _bounded_rows(count: int, field: str) -> int:
    """``count`` rows, or a :class:`StudyError` naming ``field``, the count and :data:`~sectiondeform.limits.MAX_STUDY_ROWS`."""
    return bounded(count, MAX_STUDY_ROWS, "rows", "vary fewer axes or use fewer values (a range's num); split the "
                   "study into several", lambda message: StudyError("", message), field)


def _case_rows(entry, field: str, defaults: dict, base: Path, reference: str | None, cases: dict,
               already: int = 0) -> list[Row]:
    """The rows of one case entry: the product of its axes; ``already`` rows of the study come before them."""
    if isinstance(entry, str):
        entry = {"case": entry}
    if not isinstance(entry, dict):
        raise StudyError(field, f"expected a case file name or an object, got {entry!r}")
    unknown = set(entry) - {"case", "vary", "reference"}
    if unknown:
        raise StudyError(f"{field}.{min(unknown)}", "unknown key; a case entry has case, vary and reference")
    name = entry.get("case")
    if not isinstance(name, str):
        raise StudyError(f"{field}.case", f"expected the case file's name, got {name!r}")
    case_path = (base / name).resolve()
    if case_path not in cases:
        try:
            cases[case_path] = load_case(case_path)
        except SectionDeformError as exc:
            raise StudyError(f"{field}.case", f"{name}: {exc}") from None
    case = cases[case_path]
    vary = entry.get("vary", {})
    if not isinstance(vary, dict):
        raise StudyError(f"{field}.vary", f"expected an object of axes, got {vary!r}")
    axes = {**defaults}
    for key, spec in vary.items():
        if key not in AXES:
            raise StudyError(f"{field}.vary.{key}", f"unknown axis; use one of {', '.join(AXES)}")
        axes[key] = _axis(key, spec, f"{field}.vary.{key}", base)
    ref = entry.get("reference", reference)
    if ref is not None and not isinstance(ref, str):
        raise StudyError(f"{field}.reference", f"expected a result file name, got {ref!r}")
    _check_law_axis(case, axes, "vary.area_ratio" if "area_ratio" in defaults and "area_ratio" not in vary
                    else f"{field}.vary.area_ratio")
    for key in RIGID_AXES:  # a case without rigid parts has no travel or friction to vary
        if not case.rigid and any(v is not None for v in axes.get(key, ())):
            raise StudyError(f"vary.{key}" if key in defaults and key not in vary else f"{field}.vary.{key}",
                             f"case {name!r} has no rigid parts; vary {key} only over cases with rigid parts")
    names = list(axes)
    _bounded_rows(math.prod(len(axes[k]) for k in names) + already, field)
    rows = []
    for combo in itertools.product(*(axes[k] for k in names)):
        values = dict(zip(names, combo))
        values["model"] = values.get("model") or case.model
        target = values.pop("targets", None)
        rows.append(Row(
            case=name, case_path=str(case_path), target_file=target,
            target_path=None if target is None else str((base / target).resolve()),
            reference=ref, reference_path=None if ref is None else str((base / ref).resolve()),
            **values,
        ))
    return rows


def _check_law_axis(problem, axes: dict, field: str) -> None:
    """Refuse an ``area_ratio`` axis on a case of several bodies: each has its own law."""
    if len(problem.bodies) > 1 and any(v is not None for v in axes.get("area_ratio", ())):
        raise StudyError(field, f"sets the law of a one-body case; this case has {len(problem.bodies)} bodies, "
                                "each with its own law (vary the target, model or element size)")


def _finish(name: str, rows: list[Row], wheres: list[str]) -> Study:
    digests: dict = {}
    seen: dict[str, int] = {}
    out = []
    for i, row in enumerate(rows):
        for attr in ("reference_path",):
            path = getattr(row, attr)
            if path is not None and not Path(path).is_file():
                raise StudyError(f"{wheres[i]}.reference", f"no such result file {row.reference!r}")
        rid = _row_id(row, digests)
        if rid in seen:
            raise StudyError(wheres[i], f"the same row as {wheres[seen[rid]]} ({row.inputs()}); remove the repeat")
        seen[rid] = i
        out.append(replace(row, row_id=rid))
    return Study(name=name, rows=tuple(out))


def study_from_dict(data, base=".") -> Study:
    """Check a parsed ``section-study/1`` object and expand it into rows.

    Parameters
    ----------
    data : dict
    base : str or Path
        Folder that the study's file names are relative to.

    Returns
    -------
    Study

    Raises
    ------
    StudyError
        Naming the first field at fault.
    """
    base = Path(base)
    if not isinstance(data, dict):
        raise StudyError("study", f"expected a JSON object, got {type(data).__name__}")
    unknown = set(data) - {"format", "name", "note", "cases", "vary", "reference"}
    if unknown:
        raise StudyError(min(unknown), "unknown key; a study has format, name, note, cases, vary and reference")
    if data.get("format") != STUDY_FORMAT:
        raise StudyError("format", f"expected {STUDY_FORMAT!r}, got {data.get('format')!r}")
    name = data.get("name", "study")
    if not isinstance(name, str):
        raise StudyError("name", f"expected a string, got {name!r}")
    cases = data.get("cases")
    if not isinstance(cases, list) or not cases:
        raise StudyError("cases", "expected a non-empty list of case files or {\"case\", \"vary\"} objects")
    vary = data.get("vary", {})
    if not isinstance(vary, dict):
        raise StudyError("vary", f"expected an object of axes, got {vary!r}")
    defaults = {}
    for key, spec in vary.items():
        if key not in AXES:
            raise StudyError(f"vary.{key}", f"unknown axis; use one of {', '.join(AXES)}")
        defaults[key] = _axis(key, spec, f"vary.{key}", base)
    reference = data.get("reference")
    if reference is not None and not isinstance(reference, str):
        raise StudyError("reference", f"expected a result file name, got {reference!r}")
    rows, wheres, loaded = [], [], {}
    for i, entry in enumerate(cases):
        more = _case_rows(entry, f"cases[{i}]", defaults, base, reference, loaded, len(rows))
        rows += more
        wheres += [f"cases[{i}]"] * len(more)
    return _finish(name, rows, wheres)


def _csv_value(column: str, text: str, where: str):
    text = text.strip()
    if text == "":
        return None
    if column in ("case", "model", "target_file", "reference"):
        if column == "model" and text not in MODEL_NAMES:
            raise StudyError(where, f"unknown model {text!r}; use one of {', '.join(MODEL_NAMES)}")
        return text
    try:
        value = float(text)
    except ValueError:
        raise StudyError(where, f"expected a number, got {text!r}") from None
    return _number(value, where, column)


def _study_from_csv(path: Path) -> Study:
    base = path.parent
    with path.open(newline="", encoding="utf-8") as fh:
        reader = csv.reader(fh)
        header = next(reader, None)
        if not header:
            raise StudyError(f"{path.name}", "empty CSV; the first line names the columns (case, area_ratio, ...)")
        columns = [CSV_ALIASES.get(h.strip(), h.strip()) for h in header]
        for c in columns:
            if c not in CSV_COLUMNS:
                raise StudyError(f"column {c!r}", f"unknown column; use {', '.join(CSV_COLUMNS)}")
        if "case" not in columns:
            raise StudyError("column 'case'", "missing; every row names its case file")
        rows, wheres, loaded = [], [], {}
        for line, record in enumerate(reader, start=2):
            if not any(cell.strip() for cell in record):
                continue
            if len(record) != len(columns):
                raise StudyError(f"line {line}", f"expected {len(columns)} cells, got {len(record)}")
            values = {c: _csv_value(c, cell, f"line {line}, {c}") for c, cell in zip(columns, record)}
            if values["case"] is None:
                raise StudyError(f"line {line}, case", "empty; every row names its case file")
            vary = {k: v for k, v in values.items() if k not in ("case", "reference", "target_file") and v is not None}
            if values.get("target_file") is not None:
                vary["targets"] = values["target_file"]
            entry = {"case": values["case"], "vary": vary}
            if values.get("reference") is not None:
                entry["reference"] = values["reference"]
            rows += _case_rows(entry, f"line {line}", {}, base, None, loaded, len(rows))
            wheres.append(f"line {line}")
    return _finish(path.stem, rows, wheres)


def _not_utf8(exc: UnicodeDecodeError) -> str:
    """The message for a study file that is not UTF-8 text."""
    return (f"not UTF-8 text (byte 0x{exc.object[exc.start]:02x} at position {exc.start}); "
            "save the file as UTF-8 (CSV UTF-8 in a spreadsheet)")


def load_study(path) -> Study:
    """Read a study: a ``section-study/1`` JSON file, or a CSV of rows (``.csv``).

    Raises
    ------
    StudyError
        If the file cannot be read or names a bad field (the message names it).
    """
    path = Path(path)
    if path.suffix.lower() == ".csv":
        try:
            return _study_from_csv(path)
        except OSError as exc:
            raise StudyError(str(path), f"cannot read the study file ({exc.strerror})") from None
        except UnicodeDecodeError as exc:
            raise StudyError(str(path), _not_utf8(exc)) from None
        except csv.Error as exc:
            raise StudyError(str(path), f"not a readable CSV file ({exc}); save it again as CSV") from None
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise StudyError(str(path), f"cannot read the study file ({exc.strerror})") from None
    except UnicodeDecodeError as exc:
        raise StudyError(str(path), _not_utf8(exc)) from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise StudyError(str(path), f"not valid JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}") from None
    except RecursionError:
        raise StudyError(str(path), "the JSON nests too deeply; a study is a few levels deep") from None
    return study_from_dict(data, path.parent)
