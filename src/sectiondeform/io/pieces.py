"""Pieces of a drawing: one curve each, as the CAD or SVG file gives them.

A :class:`Piece` is a :class:`~sectiondeform.curves.Curve` (a polyline, a
circular arc or a clamped non-rational B-spline) together with the names
it carries (DXF layer, SVG id and classes) and where it came from, for
error messages; a :class:`Drawing` is the pieces of one file with its
units and the case data it stores. The curve behaviour itself (reverse,
transform, ends) is the curves' own; the functions here only join curves.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..checks import COORDINATE_LIMIT
from ..curves import Arc, BSpline, Chain, Curve, Polyline
from ..errors import CaseError

__all__ = ["Piece", "Drawing", "checked_coordinates", "merge_runs", "pin_ends"]


@dataclass(frozen=True, eq=False)
class Piece:
    """One curve of a drawing.

    Attributes
    ----------
    curve : Curve or None
        Polyline, Arc or BSpline (never a Chain), in drawing units; None
        for an entity that is not a supported curve (an error if its
        layer is used).
    tags : frozenset of str
        Upper-cased names the piece carries: its DXF layer, or its SVG id,
        classes and those of its parent groups.
    source : str
        Where it came from, e.g. ``"LINE #5 (handle 2F)"``, for messages.
    """

    curve: Curve | None
    tags: frozenset
    source: str


@dataclass(frozen=True, eq=False)
class Drawing:
    """The pieces of a drawing file with its units and stored case data.

    Attributes
    ----------
    pieces : tuple of Piece
    units : str
        Length unit of the coordinates, e.g. ``"mm"``.
    mm_per_unit : float
    meta : dict
        Case data stored in the file by a writer of this package (``law``,
        ``name``, ``options``, ``lower_start``, ``target_start``), else {}.
    path : Path
    ignored : tuple of str
        Entities skipped (annotation).
    unitless : bool
        True when the file declares no units and ``units`` is the default.
    labels : dict
        Upper-cased tag -> its spelling in the file (first seen), so that a
        name read from a layer, id or class keeps its case.
    """

    pieces: tuple
    units: str
    mm_per_unit: float
    meta: dict
    path: Path
    ignored: tuple = ()
    unitless: bool = False
    labels: dict = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "pieces", tuple(self.pieces))
        object.__setattr__(self, "ignored", tuple(self.ignored))
        object.__setattr__(self, "path", Path(self.path))


def _defining_numbers(curve: Curve) -> np.ndarray:
    """The numbers that fix a curve, as rows of two: vertices, control points, or an arc's centre and radius."""
    if isinstance(curve, Polyline):
        return curve.vertices
    if isinstance(curve, BSpline):
        return curve.control_points
    if isinstance(curve, Arc):
        return np.array([curve.center, [curve.radius, curve.end_deg - curve.start_deg]])
    return np.vstack([_defining_numbers(p) for p in curve.parts()])


def checked_coordinates(curve: Curve, where: str) -> Curve:
    """``curve`` unchanged if every number fixing it is finite and within the coordinate bound.

    Parameters
    ----------
    curve : Curve
        A piece read from a drawing, in case units.
    where : str
        The entity or element it came from, for the message.

    Raises
    ------
    CaseError
        Naming ``where`` and the first bad point: a NaN, an infinity, or a
        coordinate beyond ±1e9 (a number the file spells that way, or one
        that a transform or a unit scale made overflow).

    Examples
    --------
    >>> checked_coordinates(Polyline([[0, 0], [float("nan"), 1]]), "LINE #3")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: LINE #3: coordinates must be finite numbers within +-1e+09 units, got [nan, 1.0]; correct the drawing
    """
    numbers = _defining_numbers(curve)
    bad = ~(np.isfinite(numbers) & (np.abs(numbers) <= COORDINATE_LIMIT)).all(axis=1)
    if bad.any():
        row = numbers[int(np.argmax(bad))]
        raise CaseError(where, f"coordinates must be finite numbers within +-{COORDINATE_LIMIT:g} units, "
                               f"got {row.tolist()}; correct the drawing")
    return curve


def merge_runs(curves: list[Curve]) -> list[Curve]:
    """Join runs of consecutive curves that make one curve of their kind (polylines).

    The curves must already run end to start; the shared vertex is kept once.

    Examples
    --------
    >>> out = merge_runs([Polyline([[0, 0], [1, 0]]), Polyline([[1, 0], [2, 0]])])
    >>> len(out), out[0].vertices.tolist()
    (1, [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    """
    out: list[Curve] = []
    for c in curves:
        merged = out[-1].joined(c) if out else None
        if merged is None:
            out.append(c)
        else:
            out[-1] = merged
    return out


def pin_ends(curve: Curve, start, end, scale: float = 1.0) -> Curve:
    """The curve with its ends moved exactly onto ``start`` and ``end``, ``(2,)`` each.

    Polyline vertices and spline end control points are moved; an arc that
    cannot move gets a straight bridge when the gap is larger than 1e-9 of
    ``scale``. Meant for gaps within a join or snap tolerance.
    """
    start, end = np.asarray(start, dtype=np.float64), np.asarray(end, dtype=np.float64)
    pieces = list(curve.parts())

    def move(c: Curve, at_end: bool, p: np.ndarray) -> list[Curve]:
        q = c.ends[1 if at_end else 0]
        if np.array_equal(p, q):
            return [c]
        moved = c.with_end_moved(at_end, p)
        if moved is not None:
            return [moved]
        if np.hypot(*(p - q)) <= 1e-9 * scale:
            return [c]
        bridge = Polyline(np.vstack((q, p)) if at_end else np.vstack((p, q)))
        return [c, bridge] if at_end else [bridge, c]

    first = move(pieces[0], False, start)
    pieces = first + pieces[1:]
    last = move(pieces[-1], True, end)
    pieces = pieces[:-1] + last
    return pieces[0] if len(pieces) == 1 else Chain(tuple(pieces))
