"""A reader of CalculiX ASCII result files (``.frd``): nodes and nodal result blocks.

The format (CalculiX's CGX manual, "Result Format"): a node block ``2C``
with one ``-1`` record per node (node number I10, coordinates 3 × E12.5),
then result blocks ``100C``, each named by a ``-4`` record (``DISP``,
``STRESS``...), with one ``-1`` record per node (node number I10, values
E12.5 each), every block closed by ``-3``. Only the ASCII short format that
``ccx`` writes by default is read; that is all this project needs (nodal
displacements), so a small reader is kept here rather than a dependency.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import SectionDeformError

__all__ = ["FrdError", "FrdResults", "read_frd"]


class FrdError(SectionDeformError):
    """A ``.frd`` file cannot be read; the message names the line."""


@dataclass(frozen=True, eq=False)
class FrdResults:
    """What a ``.frd`` file holds.

    Attributes
    ----------
    nodes : (N,) int64 ndarray
        Node numbers, in file order.
    coordinates : (N, 3) float64 ndarray
        Initial node coordinates.
    blocks : dict
        Result name (``"DISP"``, ``"STRESS"``...) to a list, one per output
        time in file order, of ``(time, node numbers (k,), values (k, c))``.
    """

    nodes: np.ndarray
    coordinates: np.ndarray
    blocks: dict = field(default_factory=dict)

    def last(self, name: str) -> tuple[float, np.ndarray, np.ndarray]:
        """The last block of a result: ``(time, node numbers, values)``.

        Raises
        ------
        FrdError
            If the file has no such block.
        """
        if not self.blocks.get(name):
            raise FrdError(f"the .frd file has no {name} results (has {', '.join(self.blocks) or 'none'})")
        return self.blocks[name][-1]


def _values(line: str, count: int | None, lineno: int) -> tuple[int, list[float]]:
    if count is None:  # as many E12.5 fields as the record holds
        count = (len(line.rstrip()) - 13) // 12
    try:
        return int(line[3:13]), [float(line[13 + 12 * k: 25 + 12 * k]) for k in range(count)]
    except ValueError:
        raise FrdError(f"line {lineno}: not a node record of {count} values: {line.strip()[:60]!r}") from None


def read_frd(path) -> FrdResults:
    """Read the nodes and the nodal result blocks of an ASCII ``.frd`` file.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    FrdResults

    Raises
    ------
    FrdError
        If a record cannot be read, or the file has no node block.
    """
    lines = Path(path).read_text(encoding="ascii", errors="replace").splitlines()
    nodes, coords, blocks = [], [], {}
    i, n = 0, len(lines)
    while i < n:
        head = lines[i].strip()
        if head.startswith("2C"):
            i += 1
            while i < n and lines[i].startswith(" -1"):
                k, xyz = _values(lines[i], 3, i + 1)
                nodes.append(k)
                coords.append(xyz)
                i += 1
            continue
        if head.startswith("100C"):
            try:
                time = float(lines[i][12:24])
            except ValueError:
                raise FrdError(f"line {i + 1}: no time in the result header") from None
            i += 1
            if i >= n or not lines[i].startswith(" -4"):
                raise FrdError(f"line {i + 1}: a result block without its -4 name record")
            parts = lines[i].split()
            name = parts[1]
            i += 1
            components = 0
            while i < n and lines[i].startswith(" -5"):
                components += lines[i].split()[1] != "ALL"  # ALL is derived, not written
                i += 1
            count = components
            ids, vals = [], []
            while i < n and lines[i].startswith(" -1"):
                k, v = _values(lines[i], count, i + 1)
                ids.append(k)
                vals.append(v)
                i += 1
            blocks.setdefault(name, []).append((time, np.asarray(ids, dtype=np.int64),
                                                np.asarray(vals, dtype=np.float64).reshape(len(ids), count)))
            continue
        i += 1
    if not nodes:
        raise FrdError(f"{path}: no node block (2C) found; is it an ASCII .frd file?")
    return FrdResults(np.asarray(nodes, dtype=np.int64), np.asarray(coords, dtype=np.float64), blocks)
