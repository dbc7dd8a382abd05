"""Writing output files atomically, and the JSON text of cases and results.

Every writer of :mod:`sectiondeform.io` writes through :func:`atomic_write`:
a failed write leaves nothing at the output path.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

__all__ = ["atomic_write", "dumps"]


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
