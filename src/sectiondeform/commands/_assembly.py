"""The ``deform`` command on an assembly (``section-case/2``): JSON result and figure."""

from __future__ import annotations

from ..assembly import Assembly
from ..assembly_deform import AssemblyDeformer
from ..errors import CaseError
from ..io import write_result
from ._common import print_warnings
from ._io_args import write_meshes

__all__ = ["run_assembly", "assembly_summary"]


def _refuse_unsupported(args) -> None:
    """Refuse, before any work, what an assembly cannot do yet (one law, spline DXF)."""
    drawing = getattr(args, "case", None) is not None and args.case.suffix.lower() in (".dxf", ".svg")
    if getattr(args, "area_ratio", None) is not None and not drawing:  # a drawing's reader gives it to every body
        raise CaseError("--area-ratio", "an assembly has one law per body; set each body's law in the case")
    if getattr(args, "dxf_spline", False):
        raise CaseError("--dxf-spline", "not available for assemblies; their DXF curves are polylines")
    if getattr(args, "element_size", None) is not None and not args.element_size > 0:
        raise CaseError("--element-size", f"must be > 0, got {args.element_size}")


def assembly_summary(result, warnings: bool = True) -> str:
    """A few lines on an assembly's result: each body's areas and error, and the time; its warnings unless False."""
    u = result.units
    lines = [f"{result.name} ({result.model} model, {len(result.bodies)} bodies)"]
    for b in result.bodies:
        if b.measure == "area":
            lines.append(f"  {b.name:<12} area {b.area_initial:.4f} -> {b.area_final:.4f} {u}² "
                         f"(target {b.area_target:.4f}, relative error {b.relative_error:+.2e})")
        else:
            lines.append(f"  {b.name:<12} volume {b.volume_initial:.6g} -> {b.volume_final:.6g} {u}³ "
                         f"(target {b.volume_target:.6g}, relative error {b.relative_error:+.2e}), "
                         f"area {b.area_initial:.4f} -> {b.area_final:.4f} {u}²")
    t = result.timings
    lines.append(f"  time          prepare {1e3 * t['prepare_s']:.2f} ms, deform {1e3 * t['place_s']:.3f} ms")
    for w in result.warnings if warnings else ():
        lines.append(f"  warning: {w}")
    return "\n".join(lines)


def run_assembly(args, assembly: Assembly, report: list) -> int:
    _refuse_unsupported(args)
    if getattr(args, "model", None):
        assembly = assembly.replace(options=assembly.options.replace(model=args.model))
    result = AssemblyDeformer(assembly, element_size=args.element_size).deform()
    ext = args.output.suffix.lower()
    if ext == ".json":
        write_result(args.output, result, meshes=not args.no_meshes, fields=getattr(args, "fields", False))
    else:  # DXF and SVG draw the support and target too; mesh formats tag each body (sectiondeform.io.assembly)
        options = {"case": assembly} if ext in (".dxf", ".svg") else {}
        if getattr(args, "fields", False) and ext in (".vtu", ".vtk", ".msh", ".xdmf"):
            options["fields"] = True
        write_result(args.output, result, **options)
    meshes = write_meshes(args, result)
    if args.plot:
        from .deform import save_plot

        save_plot(args, result)
    for line in report:
        print(f"  {line}")
    print(assembly_summary(result, warnings=False))
    print(f"  wrote {', '.join(str(p) for p in [args.output, *meshes, *([args.plot] if args.plot else [])])}")
    print_warnings(result.warnings)
    return 0
