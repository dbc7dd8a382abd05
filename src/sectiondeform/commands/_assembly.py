"""The ``deform`` command on an assembly (``section-case/2``): JSON result and figure."""

from __future__ import annotations

from ..assembly import Assembly
from ..assembly_deform import AssemblyDeformer
from ..errors import CaseError
from ..io import write_result

__all__ = ["run_assembly", "assembly_summary"]


def _refuse_unsupported(args) -> None:
    """Refuse, before any work, what an assembly cannot do yet (non-JSON output, meshes, one law)."""
    if getattr(args, "area_ratio", None) is not None:
        raise CaseError("--area-ratio", "an assembly has one law per body; set each body's law in the case")
    if args.output.suffix.lower() != ".json":
        raise CaseError("--output", f"an assembly's result is written as JSON (section-result/2) so far, not {args.output.suffix!r}")
    for option in ("mesh_out", "initial_mesh_out"):
        if getattr(args, option, None):
            raise CaseError(f"--{option.replace('_', '-')}", "not available for assemblies yet; the meshes are in the result JSON")
    if getattr(args, "element_size", None) is not None and not args.element_size > 0:
        raise CaseError("--element-size", f"must be > 0, got {args.element_size}")


def assembly_summary(result) -> str:
    """A few lines on an assembly's result: each body's areas and error, and the time."""
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
    for w in result.warnings:
        lines.append(f"  warning: {w}")
    return "\n".join(lines)


def run_assembly(args, assembly: Assembly, report: list) -> int:
    _refuse_unsupported(args)
    if getattr(args, "model", None):
        assembly = assembly.replace(options=assembly.options.replace(model=args.model))
    result = AssemblyDeformer(assembly, element_size=args.element_size).deform()
    write_result(args.output, result, meshes=not args.no_meshes, fields=getattr(args, "fields", False))
    if args.plot:
        from .deform import save_plot

        save_plot(args, result)
    for line in report:
        print(f"  {line}")
    print(assembly_summary(result))
    print(f"  wrote {', '.join(str(p) for p in [args.output, *([args.plot] if args.plot else [])])}")
    return 0
