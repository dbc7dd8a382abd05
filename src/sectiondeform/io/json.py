"""Case and result JSON files (``section-case/1``, ``section-result/1``)."""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

from ..problem import Problem
from .case import case_to_dict, load_case

__all__ = ["read_case", "write_case", "write_result", "atomic_write", "dumps"]


def atomic_write(path, write) -> None:
    """Call ``write(tmp_path)`` then rename the temporary file to ``path``.

    Nothing is left at ``path`` if ``write`` raises: no half-written output.
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent or ".")
    os.close(fd)
    try:
        write(Path(tmp))
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the file the usual mode
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def dumps(obj: dict) -> str:
    """JSON text of a case or result: one top-level key a line, values compact.

    Python's indenting encoder is pure Python and takes about 0.1 s on a
    result with meshes; the compact C encoder per key keeps the file
    readable by key at a tenth of the cost.

    Examples
    --------
    >>> print(dumps({"a": [1, 2], "b": {"c": 3}}))
    {
     "a": [1, 2],
     "b": {"c": 3}
    }
    """
    items = [f" {json.dumps(k)}: {json.dumps(v)}" for k, v in obj.items()]
    return "{\n" + ",\n".join(items) + "\n}"


def _dump(obj, path: Path) -> None:
    path.write_text(dumps(obj) + "\n", encoding="utf-8")


def read_case(path) -> Problem:
    """Read a case JSON file (see :func:`sectiondeform.io.case.load_case`)."""
    return load_case(path)


def write_case(path, case: Problem) -> None:
    """Write a case JSON file atomically, in the problem's dialect."""
    data = case_to_dict(case)
    atomic_write(path, lambda tmp: _dump(data, tmp))


def write_result(path, result, meshes: bool = True, fields: bool = False) -> None:
    """Write a result JSON file atomically, meshes included by default, geometric fields if asked."""
    atomic_write(path, lambda tmp: _dump(result.to_json(meshes=meshes, fields=fields), tmp))
