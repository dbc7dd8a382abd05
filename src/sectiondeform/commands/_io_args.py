"""Command-line options for reading drawings and writing outputs, over :mod:`sectiondeform.io`."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..errors import require
from ..io import (
    FIGURE_FORMATS,
    MESH_FORMATS,
    RESULT_WRITERS,
    check_output_path,
    read_case,
)
from ..io.drawing import ROLES, SIDES
from ._common import area_ratio_law

__all__ = ["add_input_args", "input_options", "read_input_case", "add_output_args", "check_outputs",
           "output_options", "write_meshes", "coordinate_tokens"]

# Drawing option -> the command-line flag that gives it, for messages.
FLAGS = {
    "layers": "--layers", "split": "--split", "split_tol": "--split-tol", "lower_side": "--lower-side",
    "target_arc": "--target-arc", "bbox": "--bbox", "snap": "--snap", "close_gap": "--close-gap",
    "join_tol": "--join-tol", "simplify": "--simplify", "chordal_error": "--chordal-error", "units": "--units",
}


def _point(text: str):
    try:
        x, y = (float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected X,Y, got {text!r}") from None
    return (x, y)


def _box(text: str):
    try:
        v = tuple(float(t) for t in text.split(","))
    except ValueError:
        v = ()
    if len(v) != 4 or v[0] >= v[2] or v[1] >= v[3]:
        raise argparse.ArgumentTypeError(f"expected XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX, got {text!r}")
    return v


def _roles(text: str):
    out = {}
    for item in text.split(","):
        role, sep, name = item.partition("=")
        if not sep or role.strip() not in ROLES or not name.strip():
            raise argparse.ArgumentTypeError(f"expected ROLE=NAME[,ROLE=NAME...] with ROLE in {', '.join(ROLES)}, got {item!r}")
        out[role.strip()] = name.strip()
    return out


def coordinate_tokens(argv: list[str]) -> list[str]:
    """``argv`` with the values of ``--split`` that start with a minus sign protected from argparse.

    argparse (before Python 3.13) takes ``-19.6,0`` for an option: it knows
    plain negative numbers only, and ``--split=VALUE`` cannot give two
    values. Each such token gets a leading space, which argparse reads as a
    value and :func:`float` ignores.
    """
    out, pending = [], 0
    for tok in argv:
        if pending and tok[:1] == "-" and len(tok) > 1 and (tok[1].isdigit() or tok[1] == "."):
            tok = " " + tok
        pending = 2 if tok == "--split" else max(pending - 1, 0)
        out.append(tok)
    return out


def add_input_args(parser) -> None:
    """Add the options for reading DXF and SVG drawings to an argparse parser."""
    g = parser.add_argument_group("drawing input (DXF, SVG; lengths in drawing units)")
    g.add_argument("--layers", type=_roles, metavar="ROLE=NAME,...",
                   help="layer (DXF) or id/class (SVG) of each role: lower, upper, target, contour "
                        "(default LOWER, UPPER, TARGET, CONTOUR)")
    g.add_argument("--split", type=_point, nargs=2, metavar=("XA,YA", "XB,YB"),
                   help="one closed contour: the lower curve runs between the contour points nearest these")
    g.add_argument("--split-tol", type=float, metavar="D",
                   help="with --split, the largest distance of A and B from the contour (default 2%% of its size)")
    g.add_argument("--lower-side", choices=SIDES, default="shorter",
                   help="with --split, which way round from A to B is the lower curve (default shorter)")
    g.add_argument("--target-arc", type=float, metavar="SAGITTA",
                   help="target: an arc as long as the lower curve, tangent to AB at its midpoint; "
                        "SAGITTA > 0 bends its ends towards the section")
    g.add_argument("--bbox", type=_box, metavar="XMIN,YMIN,XMAX,YMAX", help="keep only the pieces inside this box")
    g.add_argument("--snap", type=float, metavar="D", help="snap free ends closer than D together (reported)")
    g.add_argument("--close-gap", type=float, metavar="MAXLEN",
                   help="close gaps up to MAXLEN with a straight piece (reported)")
    g.add_argument("--join-tol", type=float, metavar="D", help="ends closer than D are one point (default 1e-6 of the drawing)")
    g.add_argument("--simplify", type=float, metavar="TOL", help="simplify polylines within TOL (Douglas-Peucker)")
    g.add_argument("--chordal-error", type=float, metavar="TOL", help="chordal error of polylines made from curves")
    g.add_argument("--units", metavar="UNIT", help="convert the case to these units (mm, cm, m, in...)")


def input_options(args) -> dict:
    """Reader options (:class:`~sectiondeform.io.drawing.DrawingOptions` names) from parsed arguments.

    ``--area-ratio`` gives the law; a default ``--lower-side`` is left out.
    """
    opts = {key: getattr(args, key, None) for key in FLAGS}
    opts = {k: v for k, v in opts.items() if v is not None}
    if opts.get("lower_side") == "shorter":
        del opts["lower_side"]
    if getattr(args, "area_ratio", None) is not None:
        opts["law"] = area_ratio_law(args)
    return opts


def read_input_case(path, args, report: list | None = None):
    """Read the case at ``path`` with the drawing options of ``args`` (errors name the option: the command
    line spells it as its flag, :data:`~sectiondeform.commands._common.OPTION_FLAGS`).
    """
    return read_case(path, report=report, **input_options(args))


def add_output_args(parser) -> None:
    """Add the output options of ``deform``: ``--mesh-out``, ``--initial-mesh-out``, ``--dxf-spline``."""
    g = parser.add_argument_group("output")
    g.add_argument("--mesh-out", type=Path, action="append", default=[], metavar="FILE",
                   help="also write the final mesh (.vtu, .vtk, .msh, .xdmf, .inp); repeatable")
    g.add_argument("--initial-mesh-out", type=Path, action="append", default=[], metavar="FILE",
                   help="also write the initial mesh (.vtu, .vtk, .msh, .xdmf, .inp); repeatable")
    g.add_argument("--dxf-spline", action="store_true",
                   help="DXF output: the deformed section as SPLINEs fitted within the chordal error")


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
        check_output_path(plot, "--plot", FIGURE_FORMATS, "figure")
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


def output_options(args, path: Path) -> dict:
    """Writer options for ``path`` from parsed arguments (see :func:`add_output_args`)."""
    ext = Path(path).suffix.lower()
    if ext == ".dxf" and getattr(args, "dxf_spline", False):
        return {"spline": True, "chordal_error": getattr(args, "chordal_error", None)}
    return {}


def write_meshes(args, result) -> list[Path]:
    """Write the meshes asked for by ``--mesh-out`` and ``--initial-mesh-out``; the paths written."""
    from ..io.meshes import write_mesh

    written = []
    for which, paths in (("final", getattr(args, "mesh_out", [])), ("initial", getattr(args, "initial_mesh_out", []))):
        for p in paths:
            write_mesh(p, result, which, fields=getattr(args, "fields", False))
            written.append(p)
    return written
