"""Arguments and helpers shared by several subcommands."""

from __future__ import annotations

import sys

from ..errors import CaseError, spelled
from ..laws import AreaRatio
from ..models import MODEL_NAMES
from ..result import RESULT_V1

OPTION_FLAGS = {
    "layers": "--layers ROLE=NAME,...", "split": "--split XA,YA XB,YB", "split_tol": "--split-tol D",
    "lower_side": "--lower-side SIDE", "target_arc": "--target-arc SAGITTA", "bbox": "--bbox XMIN,YMIN,XMAX,YMAX",
    "snap": "--snap D", "close_gap": "--close-gap MAXLEN", "join_tol": "--join-tol D", "simplify": "--simplify TOL",
    "chordal_error": "--chordal-error TOL", "units": "--units UNIT", "law": "--area-ratio R",
    "model": "--model NAME",
}
"""The command line's spelling of each library option a message may name (``option simplify``, or a
field ``simplify: ...``): :func:`~sectiondeform.errors.spelled` writes every error the command line prints
with these."""


def add_model_args(parser) -> None:
    """``--model``, ``--area-ratio`` and ``--element-size``."""
    parser.add_argument("--model", choices=MODEL_NAMES, help="deformation model (default: the case's options.model, else paper)")
    parser.add_argument("--area-ratio", type=float, metavar="R", help="override the law: final area = R x initial area")
    parser.add_argument("--element-size", type=float, metavar="H", help="element size of the layered mesh, in the case's units")


def area_ratio_law(args) -> AreaRatio | None:
    """The law ``--area-ratio R`` gives, or None; a bad R is refused naming the option (not the case's field)."""
    ratio = getattr(args, "area_ratio", None)
    if ratio is None:
        return None
    try:
        return AreaRatio(ratio)
    except CaseError as exc:
        raise CaseError("--area-ratio", exc.problem) from None


def apply_overrides(problem, args):
    """The problem with the command line's ``--area-ratio`` and ``--model`` applied (``--element-size`` checked).

    ``--area-ratio`` is the law of a one-body problem. A problem of several
    bodies has one law per body: it is refused there, unless every body has
    that law already (a drawing's reader gives it to every body).

    Raises
    ------
    CaseError
        One line naming the option.
    """
    law = area_ratio_law(args)
    if law is not None:
        if len(problem.bodies) == 1:
            problem = problem.replace(law=law)
        elif any(b.law != law for b in problem.bodies):
            raise CaseError("--area-ratio", f"the case has {len(problem.bodies)} bodies, each with its own law; "
                                            "set each body's law in the case")
    if getattr(args, "model", None):
        problem = problem.replace(options=problem.options.replace(model=args.model))
    if getattr(args, "element_size", None) is not None and not args.element_size > 0:
        raise CaseError("--element-size", f"must be > 0, got {args.element_size}")
    return problem


def _body_lines(body, units: str) -> list[str]:
    """A body's areas (and volumes of revolution) with the law's relative error, and its mesh."""
    u, q = units, body.quality
    lines = [f"initial area  {body.area_initial:12.4f} {u}²"]
    if body.area_target is not None:
        lines.append(f"target area   {body.area_target:12.4f} {u}²")
    error = f"   relative error {body.relative_error:+.2e}"
    lines.append(f"final area    {body.area_final:12.4f} {u}²" + (error if body.measure == "area" else ""))
    if body.volume_initial is not None:
        lines.append(f"initial volume {body.volume_initial:11.6g} {u}³")
        if body.volume_target is not None:
            lines.append(f"target volume {body.volume_target:12.6g} {u}³")
        lines.append(f"final volume  {body.volume_final:12.6g} {u}³" + (error if body.measure == "volume" else ""))
    if q is not None:
        text = f"mesh          {q.initial.describe()}"
        if q.initial.jacobian_min is not None and q.final.jacobian_min is not None:
            text += (f", Jacobian {q.initial.jacobian_min:.4g}..{q.initial.jacobian_max:.4g} initial, "
                     f"{q.final.jacobian_min:.4g}..{q.final.jacobian_max:.4g} final")
        lines.append(text)
    return lines


def summary(result, warnings: bool = True) -> str:
    """A few lines on a result: each body's areas, error and mesh, and the time; its warnings too unless False.

    The bodies of a ``section-result/2`` result are each under their name;
    the one body of a ``section-result/1`` result is the result itself.
    """
    named = result.dialect != RESULT_V1
    count = f", {len(result.bodies)} bodies" if named else ""
    lines = [f"{result.name} ({result.model} model{count})"]
    for body in result.bodies:
        if named:
            lines.append(f"  {body.name}")
        indent = "    " if named else "  "
        lines += [indent + line for line in _body_lines(body, result.units)]
    t = result.timings
    lines.append(f"  time          prepare {1e3 * t['prepare_s']:.2f} ms, deform {1e3 * t['place_s']:.3f} ms")
    for w in result.warnings if warnings else ():
        lines.append(f"  warning: {w}")
    return "\n".join(lines)


def print_warnings(warnings) -> None:
    """Each warning on stderr as one line, ``warning: <text>``."""
    for w in warnings:
        eprint("warning: " + spelled(" ".join(str(w).split()), OPTION_FLAGS))


def eprint(*args) -> None:
    """Print to stderr."""
    print(*args, file=sys.stderr)
