"""File formats, one module each, chosen by file extension.

:data:`FORMATS` maps an extension to the module implementing it; a module
gives what its format can do, under the same names: ``read_case(path,
**options) -> Problem``, ``write_case(path, problem)``, ``write_result(path,
result, **options)``, ``read_drawing(path, chordal_error) -> Drawing``.
Format modules are leaves: none imports another; what they share is in
:mod:`.layers` (the layers of bodies in drawings), :mod:`.files` (atomic
writing), :mod:`.drawing` (a drawing's pieces to a problem) and
:mod:`.case` (the case object).

=========  ==========================================  ==========================================
extension  case in / out                               result out
=========  ==========================================  ==========================================
``.json``  section-case/1 and /2 (may name a drawing)  section-result/1 and /2
``.dxf``   layers (:mod:`.layers`): LOWER, UPPER,      DEFORMED, INITIAL, TARGET, MESH_INITIAL,
           TARGET (or a contour); or SUPPORT,          MESH_FINAL; or per body DEFORMED-<name>-...,
           TARGET, BODY-<name>-LOWER, -UPPER           INITIAL-<name>-..., MESH-FINAL-<name>...
``.svg``   the same names as ids or classes            groups with the same names
``.vtu``,  --                                          every body's mesh, one cell block each
``.msh``,                                              (see :mod:`.meshes`)
``.inp``,
``.vtk``,
``.xdmf``
=========  ==========================================  ==========================================
"""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path

from ..errors import CaseError

__all__ = [
    "read_case",
    "read_drawing",
    "write_case",
    "write_result",
    "FORMATS",
    "CASE_READERS",
    "CASE_WRITERS",
    "RESULT_WRITERS",
    "DRAWING_READERS",
    "check_output_path",
    "check_figure_path",
    "MESH_FORMATS",
    "FIGURE_FORMATS",
]

# extension -> format module; modules are imported on first use.
FORMATS = {".json": ".json", ".dxf": ".dxf", ".svg": ".svg", ".vtu": ".meshes", ".vtk": ".meshes", ".msh": ".meshes",
           ".xdmf": ".meshes", ".inp": ".meshes"}
CASE_READERS = (".json", ".dxf", ".svg")
CASE_WRITERS = (".json", ".dxf", ".svg")
DRAWING_READERS = (".dxf", ".svg")
RESULT_WRITERS = tuple(FORMATS)


def _resolve(table, path: Path, what: str, func: str):
    ext = path.suffix.lower()
    if ext not in table:
        raise CaseError(str(path), f"unknown {what} format {ext or '(none)'!r}; use one of {', '.join(sorted(table))}")
    return getattr(importlib.import_module(FORMATS[ext], __name__), func)


def read_case(path, **options):
    """Read a case (a :class:`~sectiondeform.problem.Problem`) from any supported input format, chosen by extension."""
    path = Path(path)
    return _resolve(CASE_READERS, path, "case", "read_case")(path, **options)


def read_drawing(path, chordal_error: float | None = None):
    """The pieces of a drawing file (.dxf, .svg), chosen by extension."""
    path = Path(path)
    return _resolve(DRAWING_READERS, path, "drawing", "read_drawing")(path, chordal_error)


def write_case(path, case) -> None:
    """Write a case in the format its extension names (.json, .dxf, .svg), atomically, in the problem's dialect."""
    path = Path(path)
    _resolve(CASE_WRITERS, path, "case output", "write_case")(path, case)


def write_result(path, result, **options) -> None:
    """Write a result in the format its extension names, atomically.

    Parameters
    ----------
    path : str or Path
    result : Result
    **options
        Keywords of that format's writer (``meshes``, ``fields`` for JSON;
        ``spline``, ``chordal_error``, ``case`` for DXF; ``case`` for SVG;
        ``fields`` for the mesh formats).

    Raises
    ------
    CaseError
        For an unknown extension, or an option the format's writer does not take.
    """
    path = Path(path)
    writer = _resolve(RESULT_WRITERS, path, "output", "write_result")
    known = list(inspect.signature(writer).parameters)[2:]  # after (path, result)
    for key in options:
        if key not in known:
            takes = f"it takes {', '.join(known)}" if known else "it takes none"
            raise CaseError(key, f"not an option of the {path.suffix.lower()} result writer; {takes}")
    writer(path, result, **options)


MESH_FORMATS = (".vtu", ".vtk", ".msh", ".xdmf", ".inp")
FIGURE_FORMATS = (".png", ".svg", ".pdf")


def check_output_path(path, option: str, formats, what: str = "output") -> Path:
    """Check an output path's extension and folder before any work is done.

    Parameters
    ----------
    path : str or Path
    option : str
        What named the path (a field, or the command line's option), for the message.
    formats : sequence of str
        Accepted extensions, with the dot.
    what : str
        What the file is (``"output"``, ``"mesh"``, ``"figure"``), for the message.

    Raises
    ------
    CaseError
        If the extension is not among ``formats`` or the folder does not exist.
    """
    path = Path(path)
    if path.is_dir():
        ext = ".json" if ".json" in formats else sorted(formats)[0]
        raise CaseError(option, f"{str(path)!r} is a folder; give a file in it, such as {str(path / ('out' + ext))!r}")
    if path.suffix.lower() not in formats:
        raise CaseError(option, f"unknown {what} format {path.suffix or '(none)'!r}; use one of {', '.join(sorted(formats))}")
    if not path.parent.is_dir():
        raise CaseError(option, f"the folder {str(path.parent)!r} does not exist")
    return path


def check_figure_path(path, field: str = "figure") -> Path:
    """:func:`check_output_path` for a figure (.png, .svg, .pdf); ``field`` names it in messages."""
    return check_output_path(path, field, FIGURE_FORMATS, "figure")
