"""File formats, one module each, chosen by file extension.

:data:`CASE_READERS` maps an extension to a function ``(path, **options) -> Case``;
:data:`RESULT_WRITERS` maps one to ``(path, result) -> None``. Optional
formats register themselves here with the module that implements them.
"""

from __future__ import annotations

import importlib
from pathlib import Path

from ..errors import CaseError

__all__ = ["read_case", "write_result", "CASE_READERS", "RESULT_WRITERS"]

# extension -> (module, function); modules are imported on first use.
CASE_READERS = {".json": (".json", "read_case")}
RESULT_WRITERS = {".json": (".json", "write_result")}


def _resolve(table: dict, path: Path, what: str):
    ext = path.suffix.lower()
    if ext not in table:
        raise CaseError(str(path), f"unknown {what} format {ext or '(none)'!r}; use one of {', '.join(sorted(table))}")
    module, func = table[ext]
    return getattr(importlib.import_module(module, __name__), func)


def read_case(path, **options):
    """Read a case from any supported input format, chosen by extension."""
    path = Path(path)
    return _resolve(CASE_READERS, path, "case")(path, **options)


def write_result(path, result, **options) -> None:
    """Write a result in the format its extension names, atomically."""
    path = Path(path)
    _resolve(RESULT_WRITERS, path, "output")(path, result, **options)
