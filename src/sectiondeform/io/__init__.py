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
``.vtk``
=========  ======================  ==========================================
"""

from __future__ import annotations

import importlib
from pathlib import Path

from ..errors import CaseError, require
from .drawing import add_input_args, input_options

__all__ = [
    "read_case",
    "write_case",
    "write_result",
    "CASE_READERS",
    "CASE_WRITERS",
    "RESULT_WRITERS",
    "add_input_args",
    "input_options",
    "add_output_args",
    "check_outputs",
    "check_output_path",
    "check_figure_path",
    "output_options",
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
    """Write a result in the format its extension names, atomically."""
    path = Path(path)
    _resolve(RESULT_WRITERS, path, "output")(path, result, **options)


MESH_FORMATS = (".vtu", ".vtk", ".msh", ".inp")
FIGURE_FORMATS = (".png", ".svg", ".pdf")


def check_output_path(path, option: str, formats, what: str = "output") -> Path:
    """Check an output path's extension and folder before any work is done.

    Parameters
    ----------
    path : str or Path
    option : str
        The command-line option or field that named it, for the message.
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


def check_figure_path(path) -> Path:
    """:func:`check_output_path` for a ``--plot`` figure (.png, .svg, .pdf)."""
    return check_output_path(path, "--plot", FIGURE_FORMATS, "figure")


def check_outputs(args) -> None:
    """Check every output path's format before any work is done.

    Raises
    ------
    CaseError
        Naming the option and the formats it accepts, so that a bad name
        never leaves the other outputs half written.
    """
    if getattr(args, "output", None) is not None:
        check_output_path(args.output, "--output", RESULT_WRITERS)
    for option in ("mesh_out", "initial_mesh_out"):
        for p in getattr(args, option, None) or []:
            check_output_path(p, f"--{option.replace('_', '-')}", MESH_FORMATS, "mesh")
    plot = getattr(args, "plot", None)
    if plot is not None:
        check_figure_path(plot)
    # The optional packages the outputs need, before anything is written.
    needs = {".dxf": ("ezdxf", "cad"), **{ext: ("meshio", "cad") for ext in MESH_FORMATS}}
    paths = [getattr(args, "output", None), *(getattr(args, "mesh_out", None) or []),
             *(getattr(args, "initial_mesh_out", None) or [])]
    for p in paths:
        if p is not None and p.suffix.lower() in needs:
            module, extra = needs[p.suffix.lower()]
            require(module, extra, f"writing {p.suffix} files")
    if plot is not None:
        require("matplotlib", "plot", "drawing a figure")


def add_output_args(parser) -> None:
    """Add the output options of ``deform``: ``--mesh-out``, ``--initial-mesh-out``, ``--dxf-spline``."""
    g = parser.add_argument_group("output")
    g.add_argument("--mesh-out", type=Path, action="append", default=[], metavar="FILE",
                   help="also write the final mesh (.vtu, .vtk, .msh, .inp); repeatable")
    g.add_argument("--initial-mesh-out", type=Path, action="append", default=[], metavar="FILE",
                   help="also write the initial mesh (.vtu, .vtk, .msh, .inp); repeatable")
    g.add_argument("--dxf-spline", action="store_true",
                   help="DXF output: the deformed section as SPLINEs fitted within the chordal error")


def output_options(args, path: Path) -> dict:
    """Writer options for ``path`` from parsed arguments (see :func:`add_output_args`)."""
    ext = Path(path).suffix.lower()
    if ext == ".dxf" and getattr(args, "dxf_spline", False):
        return {"spline": True, "chordal_error": getattr(args, "chordal_error", None)}
    return {}


def write_meshes(args, result) -> list[Path]:
    """Write the meshes asked for by ``--mesh-out`` and ``--initial-mesh-out``; the paths written."""
    from .meshes import write_mesh

    written = []
    for which, paths in (("final", getattr(args, "mesh_out", [])), ("initial", getattr(args, "initial_mesh_out", []))):
        for p in paths:
            write_mesh(p, result, which)
            written.append(p)
    return written
