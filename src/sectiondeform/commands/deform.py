"""Deform a case and write the result (JSON, or any format its extension names).

Reads CASE (a section-case/1 JSON file, or another supported format), deforms
the section onto its target under its law, and writes RESULT. The output
file is written whole or not at all.

Example: sectiondeform deform case.json -o result.json --plot result.png
"""

from __future__ import annotations

from pathlib import Path

from ..deform import Deformer
from ..io import read_case, write_result
from ._common import add_model_args, apply_overrides, summary


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, help="case file (.json)")
    parser.add_argument("-o", "--output", type=Path, required=True, help="result file (.json)")
    parser.add_argument("--plot", type=Path, metavar="FIG", help="also draw the figure (.png, .svg or .pdf)")
    parser.add_argument("--no-meshes", action="store_true", help="leave the meshes out of the result JSON")
    add_model_args(parser)


def run(args) -> int:
    case = apply_overrides(read_case(args.case), args)
    result = Deformer(case, element_size=args.element_size).deform()
    options = {"meshes": False} if args.no_meshes and args.output.suffix.lower() == ".json" else {}
    write_result(args.output, result, **options)
    if args.plot:
        from ..plot import save_figure

        save_figure(result, args.plot)
    print(summary(result))
    print(f"  wrote {args.output}" + (f" and {args.plot}" if args.plot else ""))
    return 0
