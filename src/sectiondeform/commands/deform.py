"""Deform a case and write the result (JSON, or any format its extension names).

Reads CASE (a section-case/1 or /2 JSON file, or another supported format), deforms
the section onto its target under its law, and writes RESULT. The output
file is written whole or not at all.

Example: sectiondeform deform case.json -o result.json --plot result.png
         sectiondeform deform profile.dxf --area-ratio 0.8 -o deformed.dxf --mesh-out final.vtu
"""

from __future__ import annotations

from pathlib import Path

from ..assembly import Assembly
from ..deform import Deformer
from ..errors import CaseError
from ..io import write_result
from ._assembly import run_assembly
from ._common import add_model_args, apply_overrides, print_warnings, summary
from ._io_args import add_input_args, add_output_args, check_outputs, output_options, read_input_case, write_meshes


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, help="case file (.json, .dxf, .svg)")
    parser.add_argument("-o", "--output", type=Path, required=True,
                        help="result file (.json, .dxf, .svg; .vtu, .vtk, .msh, .xdmf, .inp: the final mesh)")
    parser.add_argument("--plot", type=Path, metavar="FIG", help="also draw the figure (.png, .svg or .pdf)")
    parser.add_argument("--no-meshes", action="store_true", help="leave the meshes out of the result JSON")
    parser.add_argument("--fields", action="store_true",
                        help="add per-element fields to the result JSON and the meshes written: principal stretches, J, "
                             "Green-Lagrange strain, von Mises stress and pressure (hyperelastic model); the paper "
                             "model's geometric ones")
    parser.add_argument("--plot-field", metavar="FIELD",
                        help="draw the --plot figure as a colour map of FIELD on the deformed mesh: max_principal_strain, J, "
                             "max_principal_stretch, min_principal_stretch (geometric for the paper model), von_mises_stress or "
                             "pressure (hyperelastic model)")
    add_model_args(parser)
    add_input_args(parser)
    add_output_args(parser)


FIELD_FORMATS = (".json", ".vtu", ".vtk", ".msh", ".xdmf")


def check_fields_args(args) -> None:
    """Refuse ``--fields`` when no output written can carry them (DXF, SVG, Abaqus INP), before any work."""
    if not getattr(args, "fields", False):
        return
    paths = [args.output, *(getattr(args, "mesh_out", None) or []), *(getattr(args, "initial_mesh_out", None) or [])]
    if not any(p.suffix.lower() in FIELD_FORMATS for p in paths):
        raise CaseError("--fields", f"no output carries them; write the result as .json or a mesh as "
                        f"{', '.join(FIELD_FORMATS[1:])} (-o or --mesh-out)")


def check_plot_field_args(args) -> None:
    """Refuse a ``--plot-field`` without ``--plot``, or naming an unknown field, before any work."""
    if getattr(args, "plot_field", None) is None:
        return
    from ..field_plot import check_plot_field

    check_plot_field(args.plot_field)
    if args.plot is None:
        raise CaseError("--plot-field", "draws the --plot figure; give its file with --plot FIG.png")


def save_plot(args, result) -> None:
    """The ``--plot`` figure: the standard panels, or the colour map of ``--plot-field``."""
    if getattr(args, "plot_field", None):
        from ..field_plot import save_field_figure

        save_field_figure(result, args.plot_field, args.plot)
    else:
        from ..plot import save_figure

        save_figure(result, args.plot)


def run(args) -> int:
    check_outputs(args)
    check_plot_field_args(args)
    check_fields_args(args)
    report: list[str] = []
    case = read_input_case(args.case, args, report)
    if isinstance(case, Assembly):
        return run_assembly(args, case, report)
    case = apply_overrides(case, args)
    result = Deformer(case, element_size=args.element_size).deform()
    options = {"meshes": False} if args.no_meshes and args.output.suffix.lower() == ".json" else output_options(args, args.output)
    if args.fields and args.output.suffix.lower() in FIELD_FORMATS:
        options["fields"] = True
    write_result(args.output, result, **options)
    meshes = write_meshes(args, result)
    if args.plot:
        save_plot(args, result)
    for line in report:
        print(f"  {line}")
    print(summary(result, warnings=False))
    print(f"  wrote {', '.join(str(p) for p in [args.output, *meshes, *([args.plot] if args.plot else [])])}")
    print_warnings(result.warnings)
    return 0
