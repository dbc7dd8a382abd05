"""Case and result JSON files (``section-case/1`` and ``/2``, ``section-result/1`` and ``/2``).

The case object itself is :mod:`sectiondeform.io.case`; a case JSON naming
a drawing is read by :func:`sectiondeform.io.drawing.read_json_case`.
"""

from __future__ import annotations

from pathlib import Path

from ..problem import Problem
from .case import case_to_dict
from .drawing import read_json_case
from .files import atomic_write, dumps

__all__ = ["read_case", "write_case", "write_result", "atomic_write", "dumps"]


def _dump(obj, path: Path) -> None:
    path.write_text(dumps(obj) + "\n", encoding="utf-8")


def read_case(path, *, report=None, **options) -> Problem:
    """Read a case JSON file, either version; one naming a drawing takes its curves from it.

    See :func:`sectiondeform.io.drawing.read_json_case`, and
    :func:`sectiondeform.io.case.load_case` for a plain case object.
    """
    return read_json_case(path, report=report, **options)


def write_case(path, case: Problem) -> None:
    """Write a case JSON file atomically, in the problem's dialect."""
    data = case_to_dict(case)
    atomic_write(path, lambda tmp: _dump(data, tmp))


def write_result(path, result, meshes: bool = True, fields: bool = False) -> None:
    """Write a result JSON file atomically, meshes included by default, geometric fields if asked."""
    atomic_write(path, lambda tmp: _dump(result.to_json(meshes=meshes, fields=fields), tmp))
