"""Speed of re-deforming an assembly, beside the single body, in one run.

For each model (paper, hyperelastic), medians over repeated interleaved runs
(after a warm-up) of:

* ``prepare``: ``AssemblyDeformer(assembly, model)`` on
  ``tests/data/cases/v2/two-layer-strip.json`` (two bonded bodies), and
  ``Deformer(case, model)`` on the paper example (one body);
* ``deform``: ``deformer.deform()`` onto the case's own target (cold: the
  hyperelastic solve starts from the undeformed shape moved rigidly onto
  the target);
* ``warm``: ``deformer.deform(moved, start=result)``, the target moved by a
  smooth bump of 0.5 % of the thinnest body's thickness, from the result on
  the case's target (the paper model has no path: it ignores ``start``);
* ``preview``: ``deformer.preview(moved, start=result)`` (the hyperelastic
  model's one linear step; the paper model's exact answer), and its largest
  distance to the warm result's contour, relative to the thinnest body's
  thickness T.

For the paper model a third subject is timed in the same run: the
assembly's bodies placed alone, each through its own prepared single-body
placement (``prepared.place`` of the body's section, the path a one-body
deformation takes) with the lower nodes of the assembly's answer: the floor
an assembly's deformation can reach, every check and bookkeeping left out.

Every figure goes through the public calls with a target curve (the
deformers sample it). Printed as a Markdown table with the assembly's
figures per body and its ratio to the single body; the hyperelastic rows
also give the unknowns of each problem, since the assembly's mesh is the
larger one. No figure is asserted: the benchmark reports, the reader judges.

Usage::

    python benchmarks/assembly_speed.py [--repeats 21] [--clock wall|cpu] [--json OUT]
    python benchmarks/assembly_speed.py --summarise RUN.json [RUN.json ...]

``--summarise`` prints the table of the medians, figure by figure, of
several reports written with ``--json`` (runs of one version of the
library taken in turn with another's on a shared machine).
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np

from sectiondeform import Deformer, load_case
from sectiondeform.assembly import assembly_from_dict
from sectiondeform.assembly_deform import AssemblyDeformer
from sectiondeform.curves import Polyline

CLOCKS = {"wall": time.perf_counter, "cpu": time.process_time}
"""``cpu`` counts the process's CPU time (all its threads): on a loaded shared machine a
millisecond call is often put aside by the scheduler, which the wall clock counts and the
CPU clock does not."""


def median_time(fn, repeats: int, warmup: int = 1, clock=time.perf_counter) -> float:
    """Median time of ``fn()`` over ``repeats`` runs after ``warmup`` runs, seconds of ``clock``."""
    return median_times({0: fn}, repeats, warmup, clock)[0]


def median_times(fns: dict, repeats: int, warmup: int = 1, clock=time.perf_counter) -> dict:
    """Median time of each callable, runs interleaved (a burst of load hits them all alike), seconds of ``clock``."""
    for _ in range(warmup):
        for fn in fns.values():
            fn()
    times = {name: [] for name in fns}
    for _ in range(repeats):
        for name, fn in fns.items():
            t0 = clock()
            fn()
            times[name].append(clock() - t0)
    return {name: float(np.median(t)) for name, t in times.items()}

ROOT = Path(__file__).resolve().parents[1]
STRIP = ROOT / "tests" / "data" / "cases" / "v2" / "two-layer-strip.json"
PAPER = ROOT / "tests" / "data" / "cases" / "paper-example.json"
MODELS = ("paper", "hyperelastic")
BUMP = 0.005  # of the thinnest body's thickness


def moved(curve, height: float) -> Polyline:
    """``curve`` with a smooth bump of ``height`` (units) in y, as a 401-point polyline."""
    s = np.linspace(0.0, 1.0, 401)
    return Polyline(curve.at_fractions(s) + height * np.sin(np.pi * s)[:, None] * np.array([0.0, 1.0]))


def _unknowns(quality) -> int | None:
    return int(quality.initial.unknowns) if quality is not None and quality.initial.unknowns is not None else None


def subjects(model: str) -> dict:
    """The single body and the assembly, prepared, with the calls to time."""
    case = load_case(PAPER)
    assembly = assembly_from_dict(json.loads(STRIP.read_text()))
    single = Deformer(case, model)
    joint = AssemblyDeformer(assembly, model)
    r1, r2 = single.deform(), joint.deform()
    T1, T2 = single.section.thickness, min(b.section.thickness for b in joint.bodies)
    t1, t2 = moved(case.target, BUMP * T1), moved(assembly.target, BUMP * T2)
    err1 = float(np.abs(single.preview(t1, start=r1).contour - single.deform(t1, start=r1).contour).max()) / T1
    err2 = max(float(np.abs(p.contour - w.contour).max())
               for p, w in zip(joint.preview(t2, start=r2).bodies, joint.deform(t2, start=r2).bodies)) / T2
    out = {
        "single": {"bodies": 1, "unknowns": _unknowns(r1.quality), "preview_error": err1,
                   "prepare": lambda: Deformer(case, model), "deform": single.deform,
                   "warm": lambda: single.deform(t1, start=r1), "preview": lambda: single.preview(t1, start=r1)},
        "assembly": {"bodies": len(assembly.bodies), "unknowns": _unknowns(r2.bodies[0].quality), "preview_error": err2,
                     "prepare": lambda: AssemblyDeformer(assembly, model), "deform": joint.deform,
                     "warm": lambda: joint.deform(t2, start=r2), "preview": lambda: joint.preview(t2, start=r2)},
    }
    if model == "paper":  # the paper model places body by body: its bodies' own placements are the floor
        laws = [b.law for b in assembly.bodies]
        w2 = joint.deform(t2, start=r2)

        def placements(result):
            return lambda: [body.prepared.place(r.lower, law) for body, r, law in zip(joint.bodies, result.bodies, laws)]

        out["placements"] = {"bodies": len(assembly.bodies), "unknowns": None, "preview_error": 0.0, "prepare": None,
                             "deform": placements(r2), "warm": placements(w2), "preview": placements(w2)}
    return out


def run(repeats: int, clock: str = "wall") -> dict:
    """Medians, seconds of ``clock`` (a key of :data:`CLOCKS`), per model and subject; prepare timed apart (fewer runs)."""
    tick = CLOCKS[clock]
    out = {"python": platform.python_version(), "machine": platform.machine(), "repeats": repeats, "clock": clock, "rows": []}
    for model in MODELS:
        subj = subjects(model)
        calls = {(name, key): s[key] for name, s in subj.items() for key in ("deform", "warm", "preview")}
        times = median_times(calls, repeats, warmup=2, clock=tick)
        for name, s in subj.items():
            row = {"model": model, "subject": name, "bodies": s["bodies"], "unknowns": s["unknowns"], "preview_error": s["preview_error"],
                   "prepare_s": median_time(s["prepare"], max(3, repeats // 4), warmup=1, clock=tick) if s["prepare"] else None}
            row.update({f"{key}_s": times[name, key] for key in ("deform", "warm", "preview")})
            out["rows"].append(row)
    return out


def _ms(t: float | None) -> str:
    return f"{1e3 * t:.3g} ms" if t is not None else "–"


def _ratio(a: float | None, b: float | None, scale: float = 1.0) -> str:
    return f"{a * scale / b:.2g}×" if a is not None and b is not None else ""


def to_markdown(report: dict) -> str:
    """The table: per model the single body, the assembly, its time per body and its ratio per body to the single body."""
    keys = ("prepare_s", "deform_s", "warm_s", "preview_s")
    lines = [
        "| model | subject | bodies | unknowns | prepare | deform (cold) | warm re-deform (`start=`) | preview (`start=`) | preview's distance to the warm result / T |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for model in MODELS:
        rows = {r["subject"]: r for r in report["rows"] if r["model"] == model}
        single, joint = rows["single"], rows["assembly"]
        unk = lambda r: str(r["unknowns"]) if r["unknowns"] is not None else "–"  # noqa: E731
        lines.append(f"| {model} | paper example (one body) | 1 | {unk(single)} | " + " | ".join(_ms(single[k]) for k in keys)
                     + f" | {single['preview_error']:.2g} |")
        lines.append(f"| {model} | two-layer-strip | {joint['bodies']} | {unk(joint)} | " + " | ".join(_ms(joint[k]) for k in keys)
                     + f" | {joint['preview_error']:.2g} |")
        nb = joint["bodies"]
        lines.append(f"| {model} | two-layer-strip, per body / one body | | | "
                     + " | ".join(_ratio(joint[k], single[k], 1.0 / nb) for k in keys) + " | |")
        if "placements" in rows:
            alone = rows["placements"]
            lines.append(f"| {model} | two-layer-strip's bodies placed alone (`prepared.place`) | {nb} | – | "
                         + " | ".join(_ms(alone[k]) for k in keys) + " | |")
            lines.append(f"| {model} | two-layer-strip / its bodies placed alone | | | "
                         + " | ".join(_ratio(joint[k], alone[k]) for k in keys) + " | |")
        if single["unknowns"] and joint["unknowns"]:
            per = single["unknowns"] / joint["unknowns"]
            lines.append(f"| {model} | two-layer-strip, per unknown / one body | | | "
                         + " | ".join(f"{joint[k] * per / single[k]:.2g}×" for k in keys) + " | |")
    return "\n".join(lines)


def summarise(reports: list[dict]) -> dict:
    """One report whose every time is the median of that time over ``reports`` (same rows, in order)."""
    out = dict(reports[0], rows=[], runs=len(reports))
    for rows in zip(*(r["rows"] for r in reports)):
        row = dict(rows[0])
        for key, value in row.items():
            if key.endswith("_s") and value is not None:
                row[key] = float(np.median([r[key] for r in rows]))
        out["rows"].append(row)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=21)
    parser.add_argument("--json", type=Path, default=None)
    parser.add_argument("--clock", choices=tuple(CLOCKS), default="wall",
                        help="wall time, or the process's CPU time (steadier on a loaded shared machine)")
    parser.add_argument("--summarise", type=Path, nargs="+", default=None, metavar="RUN.json")
    args = parser.parse_args()
    if args.summarise:
        report = summarise([json.loads(p.read_text()) for p in args.summarise])
        print(to_markdown(report))
        print(f"\nMedians over {report['runs']} runs of medians of {report['repeats']} interleaved runs each "
              f"({report.get('clock', 'wall')} clock).")
        return
    t0 = time.perf_counter()
    report = run(args.repeats, args.clock)
    report["wall_s"] = time.perf_counter() - t0
    if args.json is not None:
        args.json.write_text(json.dumps(report, indent=1))
    print(to_markdown(report))
    print(f"\nPython {report['python']} on {report['machine']}; {args.clock} clock; medians of {args.repeats} interleaved runs "
          f"(prepare: {max(3, args.repeats // 4)}); {report['wall_s']:.0f} s in all.")


if __name__ == "__main__":
    main()
