"""The project's models against CalculiX on the shared cases: the table of docs/validation.md, "Against CalculiX".

Every case at area (volume) ratio 1, the only law a hyperelastic solver
expresses. Per case: CalculiX (default element, ``--mesh-size``), the
project's finite-element reference (one body, or an assembly) and fast models, the
Hausdorff distance between deformed upper curves in units and over the
section's height (:func:`sectiondeform.compare.section_height`), and the
wall times. Needs ``ccx``.

Usage: python benchmarks/calculix_table.py tests/data/cases/*.json tests/data/cases/v2/*.json [--mesh-size 0.1]
       [--v2-mesh-size 0.3] [--case-mesh grooved-tread=0.2 ...]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import re
import statistics
import time
from pathlib import Path

import numpy as np

import sectiondeform as sd
from sectiondeform.compare import compare_curves, section_height
from sectiondeform.errors import SectionDeformError
from sectiondeform.laws import AreaRatio

TIMEOUT = 300.0
"""Seconds after which a ccx run counts as failed."""


def _timed(fn, runs=1):
    times, out = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, statistics.median(times)


def _d(a, b, height, units="mm"):
    c = compare_curves(a, b)
    return f"{c.hausdorff:.3f} {units} ({100 * c.hausdorff / height:.2f} %)"


def row_v1(path: Path, mesh_size: float) -> str:
    from sectiondeform.external.solve import solve_calculix
    from sectiondeform.reference import solve_reference

    case = dataclasses.replace(sd.load_case(path), law=AreaRatio(1.0))
    section = sd.build_section(case)
    height = section_height(np.asarray(section.lower), np.asarray(section.upper))
    try:
        ccx = solve_calculix(case, mesh_size=mesh_size, timeout=TIMEOUT)
    except SectionDeformError as exc:
        return f"| {case.name} | {height:.2f} | mesh {mesh_size:g}: fails: {str(exc)[:80]} | — | — | — |"
    info = ccx.info
    cells = [f"mesh {mesh_size:g}: {ccx.elements} {ccx.deck.element.name}, {ccx.seconds:.1f} s "
             f"({info['increments']} increments)"]
    try:
        ref, t_ref = _timed(lambda: solve_reference(case))
        cells.append(f"{_d(ref.upper, ccx.upper, height)}, reference {t_ref:.1f} s")
    except SectionDeformError as exc:
        stop = re.search(r"beyond load ([0-9.]+) ?%", str(exc))
        cells.append(f"reference stops at {stop.group(1)} % of the load" if stop else f"reference fails: {str(exc)[:60]}")
    for model in ("paper", "hyperelastic"):
        fast, t = _timed(lambda m=model: sd.Deformer(case, model=m).deform(), runs=3)
        cells.append(f"{_d(fast.upper, ccx.upper, height)}, {1e3 * t:.0f} ms")
    return f"| {case.name} | {height:.2f} | " + " | ".join(cells) + " |"


def _at_ratio_one(data: dict) -> dict:
    """The case with every body's law at ratio 1 (area, or volume for a body of revolution)."""
    out = json.loads(json.dumps(data))
    key = "volume_ratio" if "revolution" in out else "area_ratio"
    for body in out["bodies"]:
        body["law"] = {key: 1.0}
    return out


def row_v2(path: Path, mesh_size: float) -> str:
    from sectiondeform.assembly import assembly_from_dict
    from sectiondeform.assembly_deform import AssemblyDeformer
    from sectiondeform.external.fe_assembly import read_fe_assembly
    from sectiondeform.external.solve_assembly import solve_calculix_assembly

    data = _at_ratio_one(json.loads(Path(path).read_text()))
    fe = read_fe_assembly(data)
    a = fe.assembly
    uppers = np.concatenate([np.asarray(sd.build_section(a.body_case(i)).upper) for i in range(len(a.bodies))])
    height = section_height(a.layout.fine["support"], uppers)  # of the whole assembly above its support
    try:
        ccx = solve_calculix_assembly(fe, mesh_size=mesh_size, timeout=TIMEOUT)
    except SectionDeformError as exc:
        return f"| {a.name} (v2) | {height:.2f} | mesh {mesh_size:g}: fails: {str(exc)[:80]} | — | — | — |"
    b0 = ccx.bodies[0].info
    n = sum(b.quality.initial.elements for b in ccx.bodies)
    extra = ""
    if ccx.bodies[0].volume_initial is not None:
        extra = "; volume change " + ", ".join(f"{b.name} {b.volume_final / b.volume_initial - 1:+.1e}" for b in ccx.bodies)
    cells = [f"mesh {mesh_size:g}: {n} {b0.element_type}, {ccx.timings['solve_s']:.1f} s ({b0.increments} increments)"
             f"{extra}"]
    project = assembly_from_dict(data)  # the project's reader, with the axis of a body of revolution
    from sectiondeform.reference.assembly import solve_assembly_reference

    try:
        ref, t_ref = _timed(lambda: solve_assembly_reference(project))
        worst = max(compare_curves(r.upper, c.upper).hausdorff for r, c in zip(ref.bodies, ccx.bodies))
        cells.append(f"{worst:.3f} mm ({100 * worst / height:.2f} %) (worst body), reference {t_ref:.1f} s")
    except SectionDeformError as exc:
        stop = re.search(r"beyond load ([0-9.]+) ?%", str(exc))
        cells.append(f"reference stops at {stop.group(1)} % of the load" if stop else f"reference fails: {str(exc)[:60]}")
    for model in ("paper", "hyperelastic"):
        try:
            fast, t = _timed(lambda m=model: AssemblyDeformer(project, model=m).deform(), runs=3)
        except SectionDeformError as exc:
            cells.append(f"fails: {str(exc)[:60]}")
            continue
        worst = max(compare_curves(f.upper, c.upper).hausdorff for f, c in zip(fast.bodies, ccx.bodies))
        cells.append(f"{worst:.3f} mm ({100 * worst / height:.2f} %) (worst body), {1e3 * t:.0f} ms")
    return f"| {a.name} (v2) | {height:.2f} | " + " | ".join(cells) + " |"


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
        data = json.loads(path.read_text())
        if data.get("format") == "section-case/2":
            print(row_v2(path, own.get(path.stem, args.v2_mesh_size)), flush=True)
        else:
            print(row_v1(path, own.get(path.stem, args.mesh_size)), flush=True)


if __name__ == "__main__":
    main()
