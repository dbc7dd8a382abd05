"""Calibration of the paper model's applicability warnings against the finite-element reference.

For every case, and for variations of it whose target is an arc as long as
the support with a deeper or reversed sagitta (a fraction of the support's
length; > 0 bends the ends towards the section), prints one row per body:
the indicators of :mod:`sectiondeform.applicability` (overhang over height,
bend change, virtual columns), the paper model's Hausdorff distance to the
reference (units and % of the section's height) and whether a warning fired.

    .venv/bin/python benchmarks/applicability.py tests/data/cases/*.json seal.json --sagitta -0.15 0.15 0.25

(``seal.json``: the seal scan converted as in ``docs/cad.md``.) Needs the
extra ``[fem]``; about a second or two per row.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

import sectiondeform as sd
from sectiondeform.errors import SectionDeformError
from sectiondeform.io.drawing import make_target_arc
from sectiondeform.problem import V1
from sectiondeform.reference.validation import validate


def variations(problem, sagittas):
    """The problem itself, then its arc-target variations (an arc as long as the support)."""
    yield problem.name, problem
    support = problem.support
    side = float(sd.build_section(problem.body_case(0)).orientation)  # the bodies lie on one side of the support
    for s in sagittas:
        target = make_target_arc(support.start, support.end, support.length, s * support.length, side)
        yield f"{problem.name}, arc {s:+g} L", problem.replace(target=target)


def _short(warning: str) -> str:
    """A warning cut to its kind and subject (``applicability: overhang``)."""
    head, _, rest = warning.partition(": ")
    if head.startswith("bodies["):  # a warning of one body of several: ``bodies[i] 'name': kind: ...``
        head, _, rest = rest.partition(": ")
    return head + ": " + rest.split(":")[0].split(" by ")[0].split(",")[0].strip()


def rows(name, problem) -> list[str]:
    """One row per body: the indicators, the distance to the reference, the warnings."""
    try:
        v = validate(problem, model="paper", fast_runs=1)
    except SectionDeformError as exc:
        return [f"| {name} | refused: {str(exc)[:80]} |"]
    warned = sorted({_short(w) for w in v.fast.warnings})
    applic = any(w.startswith("applicability") for w in warned)
    out = []
    for bv, f in zip(v.bodies, v.fast.bodies):
        i, s = f.info, bv.shape
        cols = sum(f.quality.initial.virtual_columns)
        label = name if problem.dialect == V1 else f"{name}, {bv.name}"
        out.append(
            f"| {label} | {v.height:.2f} | {i.overhang:.2f} | {i.bend_change:.2f} | {cols} | {i.height_scale:.2f} "
            f"| {i.stretch_min:.2f}–{i.stretch_max:.2f} | {i.aspect_change:.2f} "
            f"| {s.hausdorff:.3f} | {s.hausdorff / v.height:.1%} | {'yes' if applic else 'no'} "
            f"| {'; '.join(warned) or '–'} |"
        )
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="+")
    parser.add_argument("--sagitta", nargs="*", type=float, default=[-0.15, 0.15, 0.25],
                        help="arc-target sagittas, fractions of the lower curve's length")
    args = parser.parse_args(argv)
    print("| case | height | overhang / height | bend change (rad) | virtual columns | k | stretch | aspect change "
          "| Hausdorff | / height | applicability warning | warnings |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|")
    for path in args.cases:
        for name, case in variations(sd.load_case(path), args.sagitta):
            print(*rows(name, case), sep="\n", flush=True)
            print(f"done {name}", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    np.seterr(all="ignore")
    sys.exit(main())
