"""The project's models against CalculiX on the shared cases: the table of docs/validation.md, "Against CalculiX".

Every case at area (volume) ratio 1, the only law a hyperelastic solver
expresses. Per case: CalculiX (default element, ``--mesh-size``), the
project's finite-element reference and fast models (one body or several), the
Hausdorff distance between deformed upper curves in units and over the
height of the bodies above the support (:func:`sectiondeform.compare.section_height`;
the worst body's for several), and the wall times. Needs ``ccx``.

Usage: python benchmarks/calculix_table.py tests/data/cases/*.json tests/data/cases/v2/*.json [--mesh-size 0.1]
       [--v2-mesh-size 0.3] [--case-mesh grooved-tread=0.2 ...]
"""

from __future__ import annotations

import argparse
import dataclasses
import re
import statistics
import time
from pathlib import Path

import numpy as np

import sectiondeform as sd
from sectiondeform.compare import compare_curves, section_height
from sectiondeform.errors import SectionDeformError
from sectiondeform.laws import AreaRatio, VolumeRatio
from sectiondeform.problem import V1

TIMEOUT = 300.0
"""Seconds after which a ccx run counts as failed."""


def _timed(fn, runs=1):
    times, out = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, statistics.median(times)


def at_ratio_one(problem):
    """The problem with every body's law at ratio 1 (area, or volume for a body of revolution)."""
    law = VolumeRatio(1.0) if problem.revolution is not None else AreaRatio(1.0)
    return problem.replace(bodies=tuple(dataclasses.replace(b, law=law) for b in problem.bodies))


def _worst(bodies, others) -> float:
    """The largest Hausdorff distance between two deformations' upper curves, body by body."""
    return max(compare_curves(np.asarray(a.upper), np.asarray(b.upper)).hausdorff for a, b in zip(bodies, others))


def _cell(bodies, others, height: float, how: str) -> str:
    worst = _worst(bodies, others)
    return f"{worst:.3f} mm ({100 * worst / height:.2f} %), {how}"


def row(problem, mesh_size: float) -> str:
    """The table's row of a problem at ratio 1: CalculiX, then the reference and the fast models against it."""
    from sectiondeform.external.solve import solve_calculix
    from sectiondeform.reference import solve_reference

    problem = at_ratio_one(problem)
    name = problem.name if problem.dialect == V1 else f"{problem.name} (v2)"
    uppers = np.concatenate([np.asarray(sd.build_section(problem.body_case(b)).upper) for b in range(len(problem.bodies))])
    height = section_height(problem.layout.fine["support"], uppers)  # of all the bodies above the support
    try:
        ccx = solve_calculix(problem, mesh_size=mesh_size, timeout=TIMEOUT)
    except SectionDeformError as exc:
        return f"| {name} | {height:.2f} | mesh {mesh_size:g}: fails: {str(exc)[:80]} | — | — | — |"
    info = ccx.bodies[0].info
    extra = ""
    if ccx.bodies[0].volume_initial is not None:
        extra = "; volume change " + ", ".join(f"{b.name} {b.volume_final / b.volume_initial - 1:+.1e}" for b in ccx.bodies)
    elements = sum(b.quality.initial.elements for b in ccx.bodies)
    cells = [f"mesh {mesh_size:g}: {elements} {info.element_type}, {ccx.timings['solve_s']:.1f} s "
             f"({info.increments} increments){extra}"]
    try:
        ref, t_ref = _timed(lambda: solve_reference(problem))
        cells.append(_cell(ref.bodies, ccx.bodies, height, f"reference {t_ref:.1f} s"))
    except SectionDeformError as exc:
        stop = re.search(r"beyond load ([0-9.]+) ?%", str(exc))
        cells.append(f"reference stops at {stop.group(1)} % of the load" if stop else f"reference fails: {str(exc)[:60]}")
    for model in ("paper", "hyperelastic"):
        try:
            fast, t = _timed(lambda m=model: sd.Deformer(problem, model=m).deform(), runs=3)
        except SectionDeformError as exc:
            cells.append(f"fails: {str(exc)[:60]}")
            continue
        cells.append(_cell(fast.bodies, ccx.bodies, height, f"{1e3 * t:.0f} ms"))
    return f"| {name} | {height:.2f} | " + " | ".join(cells) + " |"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="+", type=Path)
    parser.add_argument("--mesh-size", type=float, default=0.1)
    parser.add_argument("--v2-mesh-size", type=float, default=0.3)
    parser.add_argument("--case-mesh", action="append", default=[], metavar="STEM=H",
                        help="mesh size of one case (file stem), e.g. grooved-tread=0.2")
    args = parser.parse_args()
    own = {k: float(v) for k, v in (item.split("=") for item in args.case_mesh)}
    print("| case | height (mm) | CalculiX (elements, time) | CalculiX vs reference | paper model vs CalculiX "
          "| hyperelastic model vs CalculiX |")
    print("|---|---:|---|---|---|---|")
    for path in args.cases:
        problem = sd.load_case(path)
        default = args.mesh_size if problem.dialect == V1 else args.v2_mesh_size
        print(row(problem, own.get(path.stem, default)), flush=True)


if __name__ == "__main__":
    main()
