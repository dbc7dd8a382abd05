"""Solve a case with an external finite-element solver (CalculiX) and write the section result.

Writes the case's deck (as export-fe), runs CalculiX's ccx in a temporary
folder with its increments on stderr, reads the displacements back and maps
the upper curve's characteristic points through the deformed elements. The
result is written in the case's dialect: a section-result/1 (model
"calculix") for a section-case/1 case, a section-result/2 for a
section-case/2 case (bonded bodies, bodies of revolution: each body's
points, areas, and volumes about the axis). Needs ccx (Debian/Ubuntu:
apt-get install calculix-ccx).

Example: sectiondeform solve-fe case.json --solver calculix -o result.json --plot fe.png
"""

from __future__ import annotations

import json
from pathlib import Path

from ..errors import CaseError
from ..io.json import atomic_write
from ._common import eprint
from .export_fe import add_contact_penalty_arg, add_fe_args, contact_penalty, read_fe_case


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, help="case file")
    parser.add_argument("--solver", choices=("calculix",), default="calculix", help="the solver (default calculix)")
    parser.add_argument("-o", "--output", type=Path, metavar="RESULT", help="write the result (.json)")
    parser.add_argument("--plot", type=Path, metavar="FIG", help="figure of the result (.png, .svg or .pdf)")
    parser.add_argument("--keep", type=Path, metavar="DIR", help="copy the solver's files (.inp, .frd, .sta, .dat) here")
    parser.add_argument("--timeout", type=float, metavar="S", help="stop ccx after S seconds (a failed run)")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    add_contact_penalty_arg(parser)
    add_fe_args(parser)


def run(args) -> int:
    from ..external.solve import solve_calculix
    from ..io import check_figure_path

    for path, flag in ((args.output, "--output"), (args.keep, "--keep")):
        if path is not None and not (path if flag == "--keep" else path.parent).is_dir():
            raise CaseError(flag, f"the folder {str(path if flag == '--keep' else path.parent)!r} does not exist")
    if args.timeout is not None and not args.timeout > 0:
        raise CaseError("--timeout", f"must be > 0 seconds, got {args.timeout:g}")
    if args.output is not None and args.output.suffix.lower() != ".json":
        raise CaseError("--output", f"a result is a .json file, got {args.output.name!r}")
    if args.plot is not None:
        check_figure_path(args.plot)
    problem = read_fe_case(args.case, args)
    result = solve_calculix(problem, element=args.element, mesh_size=args.mesh_size,
                            progress=None if args.quiet else eprint, keep=args.keep, timeout=args.timeout,
                            contact_penalty=contact_penalty(args))
    for line in result.warnings:
        eprint(f"sectiondeform solve-fe: warning: {line}")
    if args.output is not None:
        text = json.dumps(result.to_json(), indent=1) + "\n"
        atomic_write(args.output, lambda tmp: tmp.write_text(text, encoding="utf-8"))
    if args.plot is not None:
        from ..plot import save_figure

        save_figure(result, args.plot)
    info = result.bodies[0].info
    print(f"{result.name} (CalculiX, {sum(b.quality.initial.elements for b in result.bodies)} {info.element_type} "
          f"elements, {len(result.bodies)} bod{'y' if len(result.bodies) == 1 else 'ies'})")
    for b in result.bodies:
        text = f"  {b.name:<12} area {b.area_initial:.4f} -> {b.area_final:.4f} {result.units}²"
        if b.volume_initial is not None:
            text += f", volume {b.volume_initial:.6g} -> {b.volume_final:.6g} {result.units}³"
        print(text + f"  (relative error to the law {b.relative_error:+.2e})")
    from .deform import contact_lines

    for line in contact_lines(result):
        print(f"  {line}")
    print(f"  {info.increments} increments, {info.iterations} iterations, {info.cutbacks} cut-backs, "
          f"{result.timings['solve_s']:.1f} s")
    written = [str(p) for p in (args.output, args.plot) if p is not None]
    if written:
        print(f"  wrote {' and '.join(written)}")
    return 0
