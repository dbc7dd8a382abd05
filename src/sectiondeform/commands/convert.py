"""Convert a case between formats: case JSON, DXF and SVG, chosen by extension.

Reads IN (.json, .dxf, .svg; drawings with the same options as deform) and
writes OUT (.json, .dxf, .svg). The output file is written whole or not at all.

A case of several bodies (section-case/2) converts the same way: its drawing
has the layers SUPPORT, TARGET and one per body (BODY-<name>-LOWER and
-UPPER, or BODY-<name> as one closed contour, and BODY-<name>-HOLE for its
holes: closed contours inside a body on any layer are its holes, reported);
--area-ratio then sets every body's law (a JSON case of several bodies keeps
each body's own).

Examples
--------
  sectiondeform convert case.json case.dxf
  sectiondeform convert layup.dxf layup.json --area-ratio 0.95
  sectiondeform convert profile.dxf case.json --area-ratio 0.8
  sectiondeform convert scan.dxf case.json --area-ratio 0.8 --split -20,0.4 -16.4,0.4 --target-arc 0.3
"""

from __future__ import annotations

from pathlib import Path

from ..io import write_case
from ._common import apply_overrides
from ._io_args import add_input_args, read_input_case


def add_args(parser) -> None:
    parser.add_argument("input", type=Path, help="case file (.json, .dxf, .svg)")
    parser.add_argument("output", type=Path, help="case file to write (.json, .dxf, .svg)")
    parser.add_argument("--area-ratio", type=float, metavar="R", help="the law: final area = R x initial area (a drawing of several bodies: every body's)")
    add_input_args(parser)


def run(args) -> int:
    report: list[str] = []
    problem = apply_overrides(read_input_case(args.input, args, report), args)
    write_case(args.output, problem)
    for line in report:
        print(f"  {line}")
    print(f"  wrote {args.output}")
    return 0
