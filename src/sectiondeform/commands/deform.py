"""Deform a case and write the result (JSON, or any format its extension names).

Reads CASE (a section-case/1 or /2 JSON file, or another supported format), deforms
every body onto the target under its law, and writes RESULT. The output
file is written whole or not at all. --area-ratio sets the law of a case of
one body; a case of several bodies has one law per body, set in the case.

Example: sectiondeform deform case.json -o result.json --plot result.png
         sectiondeform deform profile.dxf --area-ratio 0.8 -o deformed.dxf --mesh-out final.vtu
"""

from __future__ import annotations

from pathlib import Path

from ..deform import Deformer
from ..errors import CaseError
from ..io import write_result
from ._common import add_model_args, apply_overrides, print_warnings, summary
from ._io_args import add_input_args, add_output_args, check_outputs, output_options, read_input_case, write_meshes


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, help="case file (.json, .dxf, .svg)")
    parser.add_argument("-o", "--output", type=Path, required=True,
                        help="result file (.json, .dxf, .svg; .vtu, .vtk, .msh, .xdmf, .inp: the final mesh)")
    parser.add_argument("--plot", type=Path, metavar="FIG", help="also draw the figure (.png, .svg or .pdf)")
    parser.add_argument("--plot-history", type=Path, metavar="FIG",
                        help="with rigid parts: draw the load-deflection curve, each part's force over the loading "
                             "(.png, .svg or .pdf)")
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


def result_options(args, problem) -> dict:
    """The writer's options for ``-o``: the JSON's meshes and fields, DXF splines, the case drawn under a DXF or SVG."""
    ext = args.output.suffix.lower()
    if ext == ".json":
        return {"meshes": not args.no_meshes, "fields": bool(args.fields)}
    options = output_options(args, args.output)
    if ext in (".dxf", ".svg"):
        options["case"] = problem
    elif args.fields and ext in FIELD_FORMATS:
        options["fields"] = True
    return options


def contact_lines(result) -> list[str]:
    """One line per rigid part (its force, contact length, peak and mean pressure, penetration) and the support's force."""
    if not result.rigid:
        return []
    from ..result import contact_units

    units = contact_units(result.units, result.axis is not None)
    u, f, p = units["length"], units["force"], units["pressure"]
    whole = " (the whole ring)" if result.axis is not None else ""
    lines = []
    for part in result.rigid:
        fx, fy = part.force
        lines.append(f"rigid {part.name:<8} force [{fx:.6g}, {fy:.6g}] {f}{whole}, contact {part.length:.4g} {u}, pressure "
                     f"max {part.pressure_max:.4g} {p} mean {part.pressure_mean:.4g} {p}, penetration "
                     f"{part.penetration_max:.3g} {u}")
    fx, fy = result.support_force
    lines.append(f"support        force [{fx:.6g}, {fy:.6g}] {f}{whole}, {len(result.history)} load steps")
    return lines


def write_outputs(args, result, problem) -> list:
    """Write the result, its meshes and figures; if one cannot be written, none is left. The meshes' paths."""
    written = [args.output]
    try:
        write_result(args.output, result, **result_options(args, problem))
        meshes = write_meshes(args, result)
        written += list(meshes)
        if args.plot:
            written.append(args.plot)
            save_plot(args, result)
        if args.plot_history is not None:
            from ..plot import draw_load_deflection, write_figure

            written.append(args.plot_history)
            write_figure(draw_load_deflection(result), args.plot_history)
    except BaseException:
        for path in written:
            Path(path).unlink(missing_ok=True)
        raise
    return meshes


def run(args) -> int:
    check_outputs(args)
    check_plot_field_args(args)
    check_fields_args(args)
    if args.plot_history is not None:
        from ..io import check_figure_path

        check_figure_path(args.plot_history, "--plot-history")
    report: list[str] = []
    problem = apply_overrides(read_input_case(args.case, args, report), args)
    if args.plot_history is not None and not problem.rigid:
        raise CaseError("--plot-history", "the load-deflection curve needs rigid parts; the case has none")
    result = Deformer(problem, element_size=args.element_size).deform()
    if getattr(args, "plot_field", None):  # a field this result has no values of: refused before anything is written
        from ..field_plot import field_values

        field_values(result, args.plot_field)
    meshes = write_outputs(args, result, problem)
    for line in report:
        print(f"  {line}")
    print(summary(result, warnings=False))
    for line in contact_lines(result):
        print(f"  {line}")
    figures = [p for p in (args.plot, args.plot_history) if p is not None]
    print(f"  wrote {', '.join(str(p) for p in [args.output, *meshes, *figures])}")
    print_warnings(result.warnings)
    return 0
