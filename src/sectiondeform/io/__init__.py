"""File formats, one module each, chosen by file extension.

:data:`CASE_READERS` maps an extension to a function ``(path, **options) -> Case``;
:data:`CASE_WRITERS` maps one to ``(path, case) -> None``;
:data:`RESULT_WRITERS` maps one to ``(path, result, **options) -> None``. Optional
formats register themselves here with the module that implements them.

=========  ======================  ==========================================
extension  case in / out           result out
=========  ======================  ==========================================
``.json``  section-case/1 (may     section-result/1
           name a drawing)
``.dxf``   layers LOWER, UPPER,    layers DEFORMED, INITIAL, TARGET,
           TARGET (or a contour)   MESH_INITIAL, MESH_FINAL
``.svg``   ids/classes lower,      groups deformed, initial, target,
           upper, target           mesh-initial, mesh-final
``.vtu``,  --                      the final mesh, initial coordinates as
``.msh``,                          point data (see :mod:`.meshes`)
``.inp``,
``.vtk``,
``.xdmf``
=========  ======================  ==========================================
"""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path

from ..errors import CaseError

__all__ = [
    "read_case",
    "write_case",
    "write_result",
    "CASE_READERS",
    "CASE_WRITERS",
    "RESULT_WRITERS",
    "check_output_path",
    "check_figure_path",
    "MESH_FORMATS",
    "FIGURE_FORMATS",
]

# extension -> (module, function); modules are imported on first use.
CASE_READERS = {
    ".json": (".drawing", "read_json_case"),
    ".dxf": (".dxf", "read_case"),
    ".svg": (".svg", "read_case"),
}
CASE_WRITERS = {
    ".json": (".json", "write_case"),
    ".dxf": (".dxf", "write_case"),
    ".svg": (".svg", "write_case"),
}
RESULT_WRITERS = {
    ".json": (".json", "write_result"),
    ".dxf": (".dxf", "write_result"),
    ".svg": (".svg", "write_result"),
    ".vtu": (".meshes", "write_result"),
    ".vtk": (".meshes", "write_result"),
    ".msh": (".meshes", "write_result"),
    ".xdmf": (".meshes", "write_result"),
    ".inp": (".meshes", "write_result"),
}


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


def write_case(path, case) -> None:
    """Write a case in the format its extension names (.json, .dxf, .svg), atomically."""
    path = Path(path)
    _resolve(CASE_WRITERS, path, "case output")(path, case)


def write_result(path, result, **options) -> None:
    """Write a result in the format its extension names, atomically.

    Parameters
    ----------
    path : str or Path
    result : Result
    **options
        Keywords of that format's writer (``meshes`` for JSON; ``spline``,
        ``chordal_error`` for DXF; none for SVG and the mesh formats).

    Raises
    ------
    CaseError
        For an unknown extension, or an option the format's writer does not take.
    """
    path = Path(path)
    writer = _resolve(RESULT_WRITERS, path, "output")
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
    if path.suffix.lower() not in formats:
        raise CaseError(option, f"unknown {what} format {path.suffix or '(none)'!r}; use one of {', '.join(sorted(formats))}")
    if not path.parent.is_dir():
        raise CaseError(option, f"the folder {str(path.parent)!r} does not exist")
    return path


def check_figure_path(path, field: str = "figure") -> Path:
    """:func:`check_output_path` for a figure (.png, .svg, .pdf); ``field`` names it in messages."""
    return check_output_path(path, field, FIGURE_FORMATS, "figure")
