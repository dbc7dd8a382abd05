"""Holes and growth against the finite-element reference, the closed form and CalculiX: a table of docs/validation.md.

Per case: each fast model against the project's reference
(:func:`~sectiondeform.reference.validation.validate`, what
``sectiondeform validate CASE --model M`` prints), the hyperelastic model
against CalculiX (``--reference calculix``), and, for a case whose closed
form is known (a free body grown by r: every point scaled by r^(1/3) about
the point the support grows from), every model against it. Distances are
the largest Hausdorff distance over the bodies' upper curves and holes, as
a percentage of the section's height (:func:`sectiondeform.compare.section_height`).

Usage: python benchmarks/holes_growth_table.py [--mesh-size 0.1] [--ccx-mesh-size 0.3] [--write docs/validation.md]
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import numpy as np

import sectiondeform as sd
from sectiondeform.compare import compare_curves
from sectiondeform.external.validation import calculix_run
from sectiondeform.reference import solve_reference
from sectiondeform.reference.validation import fem_run, validate

ROOT = Path(__file__).resolve().parents[1]
CASES = ("tests/data/cases/v2/grown-tube.json", "tests/data/cases/v2/grown-tube-on-mandrel.json",
         "tests/data/cases/v2/hollow-on-arc.json")
CLOSED_FORM = {"grown-tube": np.zeros(2)}
"""Cases of a free body grown about a point: every point x goes to c + r^(1/3) (x - c)."""
MARK = "validation:holes-growth"


def _worst(v) -> float:
    """The largest Hausdorff distance over the bodies' upper curves and holes, over the height."""
    return max(max([b.shape.hausdorff, *(h.hausdorff for h in b.holes)]) for b in v.bodies) / v.height


def _closed(result, centre, height, stretch: dict) -> float:
    """The largest distance of the bodies' upper points and holes to the closed form, over the height.

    ``stretch`` is each body's growth stretch r^(1/3), by name.
    """
    worst = 0.0
    for b in result.bodies:
        for now, before in [(b.upper, b.initial_upper), *zip(b.holes, b.initial_holes)]:
            exact = centre + stretch[b.name] * (np.asarray(before) - centre)
            worst = max(worst, compare_curves(np.asarray(now), exact).hausdorff)
    return worst / height


def rows(mesh_size: float, ccx_mesh_size: float) -> list[str]:
    out = []
    for path in CASES:
        problem = sd.load_case(ROOT / path)
        stretch = {b.name: b.law.ratio ** (1.0 / 3.0) for b in problem.bodies}
        ref = fem_run(solve_reference(problem, mesh_size=mesh_size))
        ccx = calculix_run(problem, mesh_size=ccx_mesh_size)
        centre = CLOSED_FORM.get(problem.name)
        for model in ("paper", "hyperelastic"):
            v = validate(problem, model=model, reference=ref, fast_runs=3)
            w = validate(problem, model=model, reference=ccx, fast_runs=1) if model == "hyperelastic" else None
            closed = "–" if centre is None else (f"{_closed(v.fast, centre, v.height, stretch):.3%} fast, "
                                                 f"{_closed(ref.solution, centre, v.height, stretch):.3%} reference")
            if w is not None and centre is not None:
                closed += f", {_closed(ccx.solution, centre, v.height, stretch):.3%} CalculiX"
            law = ", ".join(f"{b.law.key} {b.law.ratio:g}" for b in problem.bodies)
            holes = sum(len(b.holes) for b in problem.bodies)
            name = Path(path).stem
            cmd = f"`sectiondeform validate {path} --model {model}`"
            if w is not None:
                cmd += f"; `... --reference calculix --mesh-size {ccx_mesh_size:g}`"
            out.append(f"| {name} | {law}{', ' + str(holes) + ' hole' if holes else ''} | {model} | {v.height:.4g} | "
                       f"{_worst(v):.2%} | {'–' if w is None else f'{_worst(w):.2%}'} | {closed} | "
                       f"{ref.note}; CalculiX {ccx.note} | {cmd} |")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mesh-size", type=float, default=0.1)
    parser.add_argument("--ccx-mesh-size", type=float, default=0.3)
    parser.add_argument("--write", type=Path, help="replace the table between the markers of this file")
    args = parser.parse_args()
    table = ["| case | law | model | height (mm) | vs reference (% of height) | vs CalculiX | vs closed form | "
             "reference, CalculiX | command |", "|---|---|---|---:|---:|---:|---|---|---|",
             *rows(args.mesh_size, args.ccx_mesh_size)]
    text = "\n".join(table)
    print(text)
    if args.write is not None:
        doc = args.write.read_text()
        block = f"<!-- {MARK} -->\n{text}\n<!-- /{MARK} -->"
        doc, n = re.subn(rf"<!-- {MARK} -->.*?<!-- /{MARK} -->", lambda _: block, doc, flags=re.S)
        if n != 1:
            raise SystemExit(f"{args.write}: no <!-- {MARK} --> markers")
        args.write.write_text(doc)


if __name__ == "__main__":
    main()
