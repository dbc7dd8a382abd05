"""Calibration of the paper model's applicability warnings against the finite-element reference.

For every case, and for variations of it whose target is an arc as long as
the lower curve with a deeper or reversed sagitta (a fraction of the lower
curve's length; > 0 bends the ends towards the section), prints one row:
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
from sectiondeform.reference.validation import validate_case


def variations(case, sagittas):
    """The case itself, then its arc-target variations."""
    yield case.name, case
    sec = sd.build_section(case)
    a, b = case.lower.start, case.lower.end
    side = float(sec.orientation)
    for s in sagittas:
        target = make_target_arc(a, b, case.lower.length, s * case.lower.length, side)
        yield f"{case.name}, arc {s:+g} L", case.replace(target=target)


def row(name, case) -> str:
    try:
        v = validate_case(case, model="paper", fast_runs=1)
    except SectionDeformError as exc:
        return f"| {name} | refused: {str(exc)[:80]} |"
    f, s = v.fast, v.shape
    i = f.info
    cols = sum(f.quality.initial.virtual_columns)
    warned = [w.split(":")[0] + ": " + w.split(":")[1].split(" by ")[0].split(",")[0].strip() for w in f.warnings]
    applic = any(w.startswith("applicability") for w in f.warnings)
    return (
        f"| {name} | {v.height:.2f} | {i.overhang:.2f} | {i.bend_change:.2f} | {cols} | {i.height_scale:.2f} "
        f"| {i.stretch_min:.2f}–{i.stretch_max:.2f} | {i.aspect_change:.2f} "
        f"| {s.hausdorff:.3f} | {s.hausdorff / v.height:.1%} | {'yes' if applic else 'no'} "
        f"| {'; '.join(sorted(set(warned))) or '–'} |"
    )


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
            print(row(name, case), flush=True)
            print(f"done {name}", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    np.seterr(all="ignore")
    sys.exit(main())
