"""Arguments and helpers shared by several subcommands."""

from __future__ import annotations

import dataclasses
import sys

from ..errors import CaseError
from ..laws import AreaRatio
from ..models import MODEL_NAMES


def add_model_args(parser) -> None:
    """``--model``, ``--area-ratio`` and ``--element-size``."""
    parser.add_argument("--model", choices=MODEL_NAMES, help="deformation model (default: the case's options.model, else paper)")
    parser.add_argument("--area-ratio", type=float, metavar="R", help="override the law: final area = R x initial area")
    parser.add_argument("--element-size", type=float, metavar="H", help="element size of the layered mesh, in the case's units")


def apply_overrides(case, args):
    """The case with the command line's ``--area-ratio`` and ``--model`` applied."""
    if getattr(args, "area_ratio", None) is not None:
        case = dataclasses.replace(case, law=AreaRatio(args.area_ratio))
    if getattr(args, "model", None):
        case = dataclasses.replace(case, options=case.options.replace(model=args.model))
    if getattr(args, "element_size", None) is not None and not args.element_size > 0:
        raise CaseError("--element-size", f"must be > 0, got {args.element_size}")
    return case


def summary(result, warnings: bool = True) -> str:
    """A few lines on a result: areas, error, mesh and time; its warnings too unless ``warnings`` is False."""
    u = result.units
    q = result.quality
    lines = [
        f"{result.name} ({result.model} model)",
        f"  initial area  {result.area_initial:12.4f} {u}²",
        f"  target area   {result.area_target:12.4f} {u}²",
        f"  final area    {result.area_final:12.4f} {u}²   relative error {result.relative_error:+.2e}",
    ]
    if q is not None:
        text = f"  mesh          {q.initial.describe()}"
        if q.initial.jacobian_min is not None and q.final.jacobian_min is not None:
            text += (f", Jacobian {q.initial.jacobian_min:.4g}..{q.initial.jacobian_max:.4g} initial, "
                     f"{q.final.jacobian_min:.4g}..{q.final.jacobian_max:.4g} final")
        lines.append(text)
    t = result.timings
    lines.append(f"  time          prepare {1e3 * t['prepare_s']:.2f} ms, deform {1e3 * t['place_s']:.3f} ms")
    for w in result.warnings if warnings else ():
        lines.append(f"  warning: {w}")
    return "\n".join(lines)


def print_warnings(warnings) -> None:
    """Each warning on stderr as one line, ``warning: <text>``."""
    for w in warnings:
        eprint("warning: " + " ".join(str(w).split()))


def eprint(*args) -> None:
    """Print to stderr."""
    print(*args, file=sys.stderr)
