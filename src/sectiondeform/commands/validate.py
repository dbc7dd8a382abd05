"""Check the fast method against a finite-element reference on a case (needs [fem]; --reference calculix needs ccx).

Runs the fast model (the case's, or --model) and a finite-element solution
of the same physics on CASE: each body's nearly incompressible rubber
(neo-Hookean unless its material says otherwise) in generalised plane
strain (out-of-plane stretch 1/r; a body grown by volume_ratio r grows by
r^(1/3) in every direction, its extrusion free) or of revolution, bonded to
the target, pressed by the rigid parts, solved on fine P2/P1 triangles; a
body's holes are free boundaries of the mesh. Prints both areas, the Hausdorff distance
between the two deformed upper curves (absolute and over the mean thickness
T), the largest gap between corresponding upper points, both times and
their ratio. Progress of the reference goes to stderr.

Any case, one body or several bonded ones, plane or of revolution, is
checked body by body against one solve of all of them (one mesh of the
union, shared nodes on the shared pieces, each body's material and law):
per body its Hausdorff distance over its mean thickness and over the
case's height, and its law's relative error (area, or volume for a body of
revolution), fast and reference, and each hole's distance over the
height. With rigid parts, each part's force, contact length and peak
pressure against the reference's. --reference calculix solves the same
problem with CalculiX instead (needs ccx). A model that refuses the case
exits 2 with one line.

Example: sectiondeform validate case.json --plot check.png -o report.json
"""

from __future__ import annotations

import json
from pathlib import Path

from ..errors import CaseError
from ..io import read_case
from ..io.json import atomic_write
from ._common import add_model_args, apply_overrides, eprint


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, help="case file (.json)")
    parser.add_argument("-o", "--output", type=Path, metavar="REPORT", help="write the report (section-validation/1 JSON)")
    parser.add_argument("--plot", type=Path, metavar="FIG", help="overlay of both deformed sections (.png, .svg or .pdf)")
    parser.add_argument("--mesh-size", type=float, metavar="H", default=None,
                        help="reference element size as a fraction of the mean thickness T (default 0.1)")
    parser.add_argument("--bulk-to-shear", type=float, metavar="K",
                        help="bulk over shear modulus of the reference, >= 100 (default: the case's, else 1000)")
    parser.add_argument("--reference", choices=("fem", "calculix"), default="fem",
                        help="the reference: the project's own finite elements (default) or CalculiX (needs ccx)")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    add_model_args(parser)


def _check_output(path: Path, flag: str) -> None:
    if not path.parent.is_dir():
        raise CaseError(flag, f"the folder {str(path.parent)!r} does not exist")


def run(args) -> int:
    from ..io import check_figure_path
    from ..reference import DEFAULT_MESH_SIZE
    from ..reference.validation import save_validation_figure, validate

    problem = apply_overrides(read_case(args.case), args)
    if args.element_size is not None:
        problem = problem.replace(options=problem.options.replace(element_size=args.element_size))
    if args.output is not None:
        _check_output(args.output, "--output")
    if args.plot is not None:
        check_figure_path(args.plot, "--plot")
    progress = None if args.quiet else eprint
    reference = None
    if args.reference == "calculix":
        from ..external.validation import calculix_run

        reference = calculix_run(problem, mesh_size=args.mesh_size, progress=progress)
    mesh_size = DEFAULT_MESH_SIZE if args.mesh_size is None else args.mesh_size
    validation = validate(problem, mesh_size=mesh_size, bulk_to_shear=args.bulk_to_shear, reference=reference,
                          progress=progress)
    if args.output is not None:
        report = validation.to_json()
        atomic_write(args.output, lambda tmp: tmp.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8"))
    if args.plot is not None:
        save_validation_figure(validation, args.plot)
    print("\n".join(validation.lines()))
    written = [str(p) for p in (args.output, args.plot) if p is not None]
    if written:
        print(f"  wrote {' and '.join(written)}")
    return 0
