"""The speed benchmark: pipeline, re-deformation, scaling, peers, command line, drawings and bodies, in one run.

:func:`run_benchmark` measures, in one process, medians over repeated runs
after a warm-up, and returns a JSON-ready report; :func:`to_markdown` turns
it into the table of ``docs/benchmarks.md``, every figure beside its target.
``benchmarks/run.py`` runs it and writes the report. It lives outside the
package: it holds the project's targets and times the command line as a
process, which are the project's business, not a user's.

What is timed:

1. ``pipeline``: ``Deformer(case).deform()`` on each case (discretise,
   initial mesh, location, final mesh with the area solve, placement), with
   the stages (section, prepare, deform) timed apart to show where time goes;
2. ``redeform``: ``deformer.deform(target)`` on the prepared section, the
   target bent a little further at each step (interactive use);
3. ``scaling``: locating and placing N points sampled inside the section,
   N = 10² ... 10⁶ (time, tracemalloc peak), and the pipeline as the element
   size is halved; the growth exponent is the slope of log time on log N;
4. ``peers``: an RBF morph (scipy's thin-plate ``RBFInterpolator``) of the
   same upper points driven by the lower curve's displacement, and the
   finite-element reference (``sectiondeform.reference.solve_reference``)
   where it is installed; ratios ours / peer;
5. ``cli``: wall time of ``sectiondeform deform CASE -o OUT`` as a process;
6. ``io``: chaining 5,600 shuffled DXF LINEs into one ring, and reading the
   real seal scan kept in ``tests/data/real`` (chaining, snapping, closing
   its gap, simplifying).
7. ``bodies``: the same calls (prepare, deform, warm re-deformation,
   preview) on a problem of one body and on one of two bonded bodies, per
   model, interleaved; the several bodies' time per body over the one body's.
8. ``hyperelastic``: the hyperelastic model on every shared case
   (``tests/data/cases/*.json`` and ``v2/*.json``; one body and several,
   plane and revolution): full solve ``Deformer(case).deform()``, solve
   again after a small move of the target (``start=``), drag preview, each
   against its target; on the process's CPU clock (``time.process_time``),
   which a shared machine's other work disturbs less than the wall clock.

Times are seconds in the JSON; the Markdown shows ms or µs. No figure is
asserted anywhere: the benchmark reports, the reader judges.
"""

from __future__ import annotations

import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

__all__ = ["run_benchmark", "to_markdown", "TARGETS", "growth_exponent", "median_time", "median_times"]

# Targets on a 2-core machine (medians); seconds unless named otherwise.
TARGETS = {
    "pipeline_paper_s": 2e-3,
    "redeform_paper_s": 0.2e-3,
    "locate_place_per_point_s": 0.5e-6,
    "locate_place_peak_mb": 500.0,
    "locate_place_exponent": 1.1,
    "cli_s": 0.4,
    "chain_5600_s": 1.5,
    "seal_read_s": 5.0,
    "rbf_area_error_factor": 1e4,
    "fe_full_speedup": 1e3,
    "fe_redeform_speedup": 1e4,
}

ROOT = Path(__file__).resolve().parents[1]
SEAL = ROOT / "tests" / "data" / "real" / "vr6000_seal_scan.dxf"

FULL = {"repeats": 60, "warmup": 3, "redeform_steps": 200, "sizes": (100, 1000, 10_000, 100_000, 1_000_000),
        "refinements": 5, "cli_repeats": 7, "peer_repeats": 20, "fe_repeats": 2}
QUICK = {"repeats": 3, "warmup": 1, "redeform_steps": 5, "sizes": (100, 1000), "refinements": 2,
         "cli_repeats": 1, "peer_repeats": 2, "fe_repeats": 1}
REFERENCE_CASE = "paper-example"


def median_time(fn, repeats: int, warmup: int = 1) -> float:
    """Median wall time of ``fn()`` over ``repeats`` runs after ``warmup`` runs, seconds."""
    return median_times({0: fn}, repeats, warmup)[0]


def median_times(fns: dict, repeats: int, warmup: int = 1) -> dict:
    """Median wall time of each callable, runs interleaved (a burst of load hits them all alike), seconds."""
    for _ in range(warmup):
        for fn in fns.values():
            fn()
    times = {name: [] for name in fns}
    for _ in range(repeats):
        for name, fn in fns.items():
            t0 = time.perf_counter()
            fn()
            times[name].append(time.perf_counter() - t0)
    return {name: statistics.median(t) for name, t in times.items()}


def peak_memory(fn) -> float:
    """Peak memory allocated (tracemalloc) while ``fn()`` runs, MB."""
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        fn()
        return tracemalloc.get_traced_memory()[1] / 1e6
    finally:
        tracemalloc.stop()


def growth_exponent(sizes, times) -> float:
    """Slope of log(time) on log(size), least squares.

    Examples
    --------
    >>> round(growth_exponent([10, 100, 1000], [1.0, 10.0, 100.0]), 6)
    1.0
    """
    return float(np.polyfit(np.log(np.asarray(sizes, float)), np.log(np.asarray(times, float)), 1)[0])


def machine_info() -> dict:
    """Machine, Python and library versions."""
    import scipy
    import shapely

    from sectiondeform import __version__

    return {
        "date": time.strftime("%Y-%m-%d %H:%M:%S"),
        "platform": platform.platform(),
        "processor": platform.processor() or platform.machine(),
        "cpus": os.cpu_count(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "shapely": shapely.__version__,
        "sectiondeform": __version__,
    }


# --------------------------------------------------------------------------
# 1. Pipeline and 2. re-deformation


def bench_pipeline(cases: list, cfg: dict) -> list[dict]:
    """Full pipeline and its stages on each case, medians in seconds.

    Every (case, stage) is timed in turn within each repetition, so a burst
    of load from elsewhere falls on all of them alike.
    """
    from sectiondeform.deform import Deformer
    from sectiondeform.stack import Stack

    rows, fns = [], {}
    for i, case in enumerate(cases):
        deformer = Deformer(case)
        stack, model = deformer.stack, deformer.model
        options = case.options.for_model(model.name)
        rows.append({
            "case": case.name,
            "bodies": len(case.bodies),
            "elements": sum(int(b.quality.elements) for b in deformer.prepared.bodies),
            "upper_points": sum(int(len(sec.upper)) for sec in stack.sections),
            "relative_area_error": max(float(abs(b.relative_error)) for b in deformer.deform().bodies),
        })
        fns[i, "full_s"] = lambda case=case: Deformer(case).deform()
        fns[i, "section_s"] = lambda case=case: Stack(case)
        fns[i, "prepare_s"] = lambda model=model, stack=stack, options=options: model.prepare(stack, options)
        fns[i, "deform_s"] = deformer.deform
    for (i, name), t in median_times(fns, cfg["repeats"], cfg["warmup"]).items():
        rows[i][name] = t
    return rows


def bent_targets(deformer, steps: int, extra: float = 0.1) -> list:
    """Targets bent a little further each step: support + (1 + extra * i / steps) (target - support).

    Returned as polylines (curves), so each re-deformation resamples its target.
    """
    from sectiondeform.curves import Polyline

    lower = deformer.problem.support.at_fractions(deformer.fractions)
    target = deformer.target_nodes()
    return [Polyline(lower + (1.0 + extra * i / max(steps - 1, 1)) * (target - lower)) for i in range(steps)]


def _working_targets(deformer, steps: int) -> tuple[list, float]:
    """Bent targets the section accepts: 10 % further bending, else 2 %, else none."""
    from sectiondeform.errors import SectionDeformError

    for extra in (0.1, 0.02, 0.0):
        targets = bent_targets(deformer, steps, extra)
        try:
            for t in targets:
                deformer.deform(t)
            return targets, extra
        except SectionDeformError:
            continue
    return targets, extra


def bench_redeform(cases: list, cfg: dict) -> list[dict]:
    """Median time of ``deformer.deform(target)`` over targets bent further at each step, per case.

    Also without the contour's simplicity check (``check=False``). The
    passes over the targets alternate between the cases and both checks.
    """
    from sectiondeform.deform import Deformer

    runs, rows = [], []
    for case in cases:
        deformer, unchecked = Deformer(case), Deformer(case, check=False)
        targets, extra = _working_targets(deformer, cfg["redeform_steps"])
        rows.append({"case": case.name, "steps": len(targets), "extra_bend": extra,
                     "normal_smoothing_last": max(float(getattr(b.info, "normal_smoothing", 0.0))
                                                  for b in deformer.deform(targets[-1]).bodies)})
        runs += [(len(rows) - 1, "redeform_s", deformer, targets), (len(rows) - 1, "redeform_unchecked_s", unchecked, targets)]
    times = {(i, key): [] for i, key, _, _ in runs}
    for _ in range(max(1, cfg["repeats"] // 10)):
        for i, key, d, targets in runs:
            for t in targets[: cfg["warmup"]]:
                d.deform(t)
            for t in targets:
                t0 = time.perf_counter()
                d.deform(t)
                times[i, key].append(time.perf_counter() - t0)
    for (i, key), t in times.items():
        rows[i][key] = statistics.median(t)
    return rows


# --------------------------------------------------------------------------
# 3. Scaling


def sample_inside(deformer, n: int, seed: int = 0) -> np.ndarray:
    """``(n, 2)`` points drawn uniformly inside both the first body's section and its initial mesh (paper model)."""
    import shapely

    section_poly = shapely.Polygon(deformer.stack.sections[0].contour)
    nodes = deformer.prepared.bodies[0].mesh.nodes
    ring = np.concatenate((nodes[0], nodes[1:, -1], nodes[-1, ::-1][1:], nodes[-2:0:-1, 0]))
    region = section_poly.intersection(shapely.Polygon(ring).buffer(0))
    rng = np.random.default_rng(seed)
    lo, hi = np.array(region.bounds[:2]), np.array(region.bounds[2:])
    out, count = [], 0
    while count < n:
        x = lo + (hi - lo) * rng.random((max(2 * (n - count), 64), 2))
        x = x[shapely.contains_xy(region, x[:, 0], x[:, 1])]
        out.append(x)
        count += len(x)
    return np.concatenate(out)[:n]


def bench_locate_scaling(case, cfg: dict) -> dict:
    """Locating N points in the first body's initial mesh and placing them in its final one (paper model)."""
    from sectiondeform.deform import Deformer
    from sectiondeform.locate import locate, place

    deformer = Deformer(case, "paper")
    mesh = deformer.prepared.bodies[0].mesh
    final = deformer.deform().bodies[0].final_mesh.points
    rows = []
    for n in cfg["sizes"]:
        x = sample_inside(deformer, n)

        def run(x=x):
            return place(final, locate(mesh.points, mesh.quads, x))

        reps = max(3, min(cfg["repeats"], int(3e5 // n)))
        t = median_time(run, reps, 1)
        rows.append({"n": int(n), "time_s": t, "per_point_s": t / n, "peak_mb": peak_memory(run)})
    sizes = [r["n"] for r in rows]
    big = [r for r in rows if r["n"] >= 1000] or rows
    return {
        "case": case.name,
        "elements": int(len(mesh.quads)),
        "rows": rows,
        "exponent": growth_exponent(sizes, [r["time_s"] for r in rows]),
        "exponent_n_ge_1000": growth_exponent([r["n"] for r in big], [r["time_s"] for r in big]) if len(big) > 1 else None,
    }


def bench_refinement(case, cfg: dict) -> dict:
    """The full pipeline as the element size is halved again and again (until the method refuses)."""
    from sectiondeform.deform import Deformer
    from sectiondeform.errors import SectionDeformError

    h0 = min(sec.element_size for sec in Deformer(case).stack.sections)
    rows, refused = [], None
    for level in range(cfg["refinements"]):
        h = h0 / 2**level
        try:
            d = Deformer(case, element_size=h)
            d.deform()
        except SectionDeformError as exc:
            refused = {"element_size": h, "error": f"{type(exc).__name__}: {exc}"}
            break
        reps = max(1, cfg["repeats"] // 2**level)
        t = median_time(lambda h=h: Deformer(case, element_size=h).deform(), reps, 1)
        rows.append({
            "element_size": h,
            "elements": sum(int(b.quality.elements) for b in d.prepared.bodies),
            "full_s": t,
            "redeform_s": median_time(d.deform, reps, 1),
            "peak_mb": peak_memory(lambda h=h: Deformer(case, element_size=h).deform()),
        })
    els = [r["elements"] for r in rows]
    return {
        "case": case.name,
        "rows": rows,
        "refused": refused,
        "exponent": growth_exponent(els, [r["full_s"] for r in rows]) if len(rows) > 1 else None,
    }


# --------------------------------------------------------------------------
# 4. Peers


def rbf_morph(lower: np.ndarray, target_nodes: np.ndarray, upper: np.ndarray) -> tuple[np.ndarray, str]:
    """Points ``upper`` moved by a thin-plate RBF of the support nodes' displacement (``lower`` to ``target_nodes``).

    A straight lower curve makes the linear polynomial part singular; the
    morph then falls back to a constant one (noted in the returned string).
    """
    import warnings

    from scipy.interpolate import RBFInterpolator

    disp = target_nodes - lower
    try:
        rbf = RBFInterpolator(lower, disp, kernel="thin_plate_spline", degree=1)
        note = "degree 1"
    except np.linalg.LinAlgError:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            rbf = RBFInterpolator(lower, disp, kernel="thin_plate_spline", degree=0)
        note = "degree 0 (collinear lower nodes make the linear part singular)"
    return upper + rbf(upper), note


def bench_rbf(case, cfg: dict, ours: dict, ours_redeform: dict) -> dict:
    """The RBF morph of the same bodies onto the same target: time and the worst body's area error.

    Every body's contour (lower and upper points) is moved by the support's
    displacement; a body on the support has its lower points moved onto
    the target (the RBF interpolates its centres).
    """
    from sectiondeform.deform import Deformer
    from sectiondeform.section import polygon_area

    deformer = Deformer(case)
    support = case.support.at_fractions(deformer.fractions)
    nodes = deformer.target_nodes()
    sections = deformer.stack.sections
    points = np.concatenate([np.concatenate((sec.lower, sec.upper)) for sec in sections])
    moved, note = rbf_morph(support, nodes, points)
    err, start = 0.0, 0
    for sec, body in zip(sections, case.bodies):
        k, m = len(sec.lower), len(sec.upper)
        lower, upper = moved[start:start + k], moved[start + k:start + k + m]
        start += k + m
        wanted = body.law.target_area(sec.area)
        err = max(err, abs(abs(polygon_area(np.concatenate((lower, upper[1:-1])))) - wanted) / wanted)
    t = median_time(lambda: rbf_morph(support, nodes, points), cfg["peer_repeats"], 1)
    ours_err = max(ours["relative_area_error"], 1e-17)
    return {
        "case": case.name,
        "rbf_s": t,
        "rbf_note": note,
        "rbf_area_error": float(err),
        "ours_area_error": ours["relative_area_error"],
        "area_error_factor": float(err / ours_err),
        "ratio_full": ours["full_s"] / t,
        "ratio_redeform": ours_redeform["redeform_s"] / t,
    }


def bench_fe(case, cfg: dict, ours: dict, ours_redeform: dict) -> dict:
    """The finite-element reference, where installed: time and ratios."""
    try:
        from sectiondeform.reference import solve_reference
    except ImportError as exc:
        return {"case": case.name, "available": False, "note": f"sectiondeform.reference.solve_reference not importable ({exc})"}
    try:
        t = median_time(lambda: solve_reference(case), cfg["fe_repeats"], 0)
    except Exception as exc:  # the reference is someone else's work in progress: report, do not fail
        return {"case": case.name, "available": False, "note": f"solve_reference(case) failed: {type(exc).__name__}: {exc}"}
    return {
        "case": case.name,
        "available": True,
        "fe_s": t,
        "speedup_full": t / ours["full_s"],
        "speedup_redeform": t / ours_redeform["redeform_s"],
    }


# --------------------------------------------------------------------------
# 5. Command line


PARSER_ONLY = "from sectiondeform.cli import build_parser; build_parser()"


def _cli_command() -> list[str]:
    script = Path(sys.executable).with_name("sectiondeform")
    return [str(script)] if script.exists() else [sys.executable, "-m", "sectiondeform"]


def bench_cli(case_path: Path, cfg: dict) -> dict:
    """Wall time of ``sectiondeform deform CASE -o OUT`` and of a bare interpreter, medians.

    Run as an installed package runs: from byte-compiled modules (``pip
    install`` compiles them; a warm-up run writes them for a source checkout),
    whatever ``PYTHONDONTWRITEBYTECODE`` says in this shell, which would
    otherwise add the compilation of every module (about 0.25 s) to each run.
    """
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "result.json"
        cmd = _cli_command() + ["deform", str(case_path), "-o", str(out)]

        def run(args):
            subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)

        reps = cfg["cli_repeats"]
        return {
            "case": case_path.stem,
            "command": "sectiondeform deform CASE -o OUT",
            "cli_s": median_time(lambda: run(cmd), reps, 1),
            "python_bare_s": median_time(lambda: run([sys.executable, "-c", "pass"]), reps, 1),
            "import_s": median_time(lambda: run([sys.executable, "-c", "import sectiondeform.cli"]), reps, 1),
            # Building the parser imports every command module (and what they import).
            "parser_s": median_time(lambda: run([sys.executable, "-c", PARSER_ONLY]), reps, 1),
        }


# --------------------------------------------------------------------------
# 6. Drawings


def bench_io(cfg: dict) -> dict:
    """Chaining 5,600 shuffled LINEs into one ring; reading the real seal scan. Medians, seconds."""
    try:
        import ezdxf
    except ImportError as exc:
        return {"available": False, "note": f"ezdxf not importable ({exc})"}
    from sectiondeform.io import read_case
    from sectiondeform.io.chaining import one_chain
    from sectiondeform.io.dxf import read_drawing
    from sectiondeform.laws import AreaRatio

    n = 5600
    t = np.linspace(0, 2 * np.pi, n + 1)
    ring = np.column_stack((20 + 5 * np.cos(t), 5 * np.sin(t)))
    ring[-1] = ring[0]
    with tempfile.TemporaryDirectory() as tmp:
        doc = ezdxf.new("R2010")
        msp = doc.modelspace()
        for i in np.random.default_rng(3).permutation(n):
            a, b = (ring[i + 1], ring[i]) if i % 3 == 0 else (ring[i], ring[i + 1])
            msp.add_line(tuple(a), tuple(b))
        doc.saveas(Path(tmp) / "ring.dxf")
        drawing = read_drawing(Path(tmp) / "ring.dxf")
    reps = max(1, cfg["cli_repeats"])
    out = {"available": True, "chain_lines": n,
           "chain_s": median_time(lambda: one_chain(drawing.pieces, "layer 0", 1e-9, closed=True), reps, 1)}
    if SEAL.is_file():
        opts = dict(bbox=(-21, -1, -12, 10), snap=0.05, close_gap=2.5, split=((-19.6, 0.0), (-18.4, 0.0)),
                    simplify=0.01, target_arc=0.05, law=AreaRatio(0.8))
        out["seal_read_s"] = median_time(lambda: read_case(SEAL, **opts), reps, 0)
    return out


# --------------------------------------------------------------------------
# 7. One body and several


BODIES_CASES = (("one body", "paper-example.json"), ("two bonded bodies", "v2/two-layer-strip.json"))
BUMP = 0.005  # of the thinnest body's thickness


def bumped(curve, height: float):
    """``curve`` with a smooth bump of ``height`` (units) in y, as a 401-point polyline."""
    from sectiondeform.curves import Polyline

    s = np.linspace(0.0, 1.0, 401)
    return Polyline(curve.at_fractions(s) + height * np.sin(np.pi * s)[:, None] * np.array([0.0, 1.0]))


def _subject(case, model: str) -> dict:
    """A problem prepared for ``model``, with its figures and the calls to time."""
    from sectiondeform.deform import Deformer

    deformer = Deformer(case, model)
    first = deformer.deform()
    thickness = min(sec.thickness for sec in deformer.stack.sections)
    moved = bumped(case.target, BUMP * thickness)
    warm, preview = deformer.deform(moved, start=first), deformer.preview(moved, start=first)
    unknowns = first.bodies[0].quality.initial.unknowns
    return {
        "bodies": len(case.bodies), "unknowns": None if unknowns is None else int(unknowns),
        "preview_error": max(float(np.abs(p.contour - w.contour).max()) for p, w in zip(preview.bodies, warm.bodies))
        / thickness,
        "calls": {"deform_s": deformer.deform, "warm_s": lambda: deformer.deform(moved, start=first),
                  "preview_s": lambda: deformer.preview(moved, start=first)},
        "prepare": lambda: Deformer(case, model),
    }


def bench_bodies(cfg: dict) -> list[dict]:
    """One body against several bonded ones, per model: prepare, deform, warm re-deform, preview; medians, seconds.

    ``deform`` goes onto the case's own target (cold: the hyperelastic solve
    starts from the undeformed shape moved rigidly onto it); ``warm`` and
    ``preview`` onto the target moved by a smooth bump of 0.5 % of the
    thinnest body's thickness T, from the first result (``start=``; the
    paper model has no path and ignores it). ``preview_error`` is the
    preview's largest distance to the warm result's contour over T. The
    calls of one model on both problems are interleaved.
    """
    from sectiondeform import load_case

    folder = default_cases_dir()
    cases = [(label, load_case(folder / path)) for label, path in BODIES_CASES]
    rows = []
    for model in ("paper", "hyperelastic"):
        subjects = [(label, case, _subject(case, model)) for label, case in cases]
        calls = {(i, key): fn for i, (_, _, s) in enumerate(subjects) for key, fn in s["calls"].items()}
        times = median_times(calls, cfg["repeats"], cfg["warmup"])
        for i, (label, case, s) in enumerate(subjects):
            row = {"model": model, "case": case.name, "subject": label, "bodies": s["bodies"],
                   "unknowns": s["unknowns"], "preview_error": s["preview_error"],
                   "prepare_s": median_time(s["prepare"], max(1, cfg["repeats"] // 4), 1)}
            row.update({key: times[i, key] for key in s["calls"]})
            rows.append(row)
    return rows


def bodies_markdown(rows: list[dict]) -> list[str]:
    """Section 7's table: each problem, then per model the several bodies' time per body (and per unknown) over the one body's."""
    keys = ("prepare_s", "deform_s", "warm_s", "preview_s")
    lines = ["| model | case | bodies | unknowns | prepare | deform (cold) | warm re-deform (`start=`) "
             "| preview (`start=`) | preview's distance to the warm result / T |", "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        unknowns = "–" if r["unknowns"] is None else str(r["unknowns"])
        lines.append(f"| {r['model']} | {r['case']} ({r['subject']}) | {r['bodies']} | {unknowns} | "
                     + " | ".join(_fmt(r[k]) for k in keys) + f" | {r['preview_error']:.2g} |")
    for model in dict.fromkeys(r["model"] for r in rows):
        one, *others = [r for r in rows if r["model"] == model]
        for r in others:
            lines.append(f"| {model} | {r['case']}, per body / {one['case']} | | | "
                         + " | ".join(f"{r[k] / r['bodies'] / one[k]:.2g}×" for k in keys) + " | |")
            if r["unknowns"] and one["unknowns"]:  # a solve: its time per unknown too (the meshes differ in size)
                per = one["unknowns"] / r["unknowns"]
                lines.append(f"| {model} | {r['case']}, per unknown / {one['case']} | | | "
                             + " | ".join(f"{r[k] * per / one[k]:.2g}×" for k in keys) + " | |")
    return lines


# --------------------------------------------------------------------------
# 8. The hyperelastic model on every shared case

HYPERELASTIC_TARGETS = {"full_s": 20e-3, "again_s": 2e-3, "preview_s": 0.5e-3}


def cpu_median(fn, repeats: int, warmup: int = 1) -> float:
    """Median CPU time (``time.process_time``) of ``fn()`` over ``repeats`` runs after ``warmup``, seconds."""
    for _ in range(warmup):
        fn()
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return statistics.median(times)


def shared_case_paths() -> list[Path]:
    """Every shared case: ``tests/data/cases/*.json`` then ``v2/*.json``."""
    folder = default_cases_dir()
    return sorted(folder.glob("*.json")) + sorted((folder / "v2").glob("*.json"))


def bench_hyperelastic_cases(cfg: dict, paths=None) -> list[dict]:
    """Full solve, solve again and drag preview of the hyperelastic model per shared case, CPU-time medians, seconds.

    ``full`` is ``Deformer(case, "hyperelastic").deform()`` (section, mesh,
    pattern, reference tangent, cold solve); ``again`` the solve onto the
    target moved by a smooth bump of 0.5 % of the thinnest body's
    thickness T from the first result (``start=``); ``preview`` the drag
    preview onto that target from the first result. Also the unknowns, the
    factorisations each call makes and the preview's distance to the solve
    again over T.
    """
    from sectiondeform import load_case
    from sectiondeform.deform import Deformer

    rows = []
    reps = max(3, cfg["repeats"] // 4)
    for path in paths or shared_case_paths():
        case = load_case(path)
        deformer = Deformer(case, "hyperelastic")
        first = deformer.deform()
        thickness = min(sec.thickness for sec in deformer.stack.sections)
        moved = bumped(case.target, BUMP * thickness)
        again, preview = deformer.deform(moved, start=first), deformer.preview(moved, start=first)
        info, info_again = first.bodies[0].info, again.bodies[0].info
        rows.append({
            "case": path.stem, "bodies": len(case.bodies), "revolution": case.revolution is not None,
            "unknowns": int(first.bodies[0].quality.initial.unknowns),
            "factorisations_full": int(info.factorisations) + 1, "factorisations_again": int(info_again.factorisations),
            "preview_error": max(float(np.abs(p.contour - w.contour).max()) for p, w in zip(preview.bodies, again.bodies))
            / thickness,
            "full_s": cpu_median(lambda case=case: Deformer(case, "hyperelastic").deform(), reps, 1),
            "again_s": cpu_median(lambda d=deformer, m=moved, f=first: d.deform(m, start=f), 3 * reps, 1),
            "preview_s": cpu_median(lambda d=deformer, m=moved, f=first: d.preview(m, start=f), 9 * reps, 2),
        })
    return rows


def hyperelastic_markdown(rows: list[dict]) -> list[str]:
    """Section 8's table: per shared case the three times against their targets."""
    T = HYPERELASTIC_TARGETS
    lines = [f"Targets: full ≤ {_fmt(T['full_s'])}, again ≤ {_fmt(T['again_s'])}, preview ≤ {_fmt(T['preview_s'])}; "
             "**bold** a miss. CPU-time medians (`time.process_time`).", "",
             "| case | bodies | kind | unknowns | factorisations (full / again) | full | again | preview | preview − again / T |",
             "|---|---:|---|---:|---|---:|---:|---:|---:|"]
    for r in rows:
        cells = [(_fmt(r[k]) if r[k] <= T[k] else f"**{_fmt(r[k])}**") for k in ("full_s", "again_s", "preview_s")]
        lines.append(f"| {r['case']} | {r['bodies']} | {'revolution' if r['revolution'] else 'plane'} | {r['unknowns']} | "
                     f"{r['factorisations_full']} / {r['factorisations_again']} | " + " | ".join(cells)
                     + f" | {r['preview_error']:.2g} |")
    return lines


CONTACT_TARGET = 3.0
"""A contact case costs at most this many times the same case without its rigid parts (full solve and again)."""


def bench_contact(cfg: dict, paths=None) -> list[dict]:
    """Each shared case with rigid parts against the same case without them (hyperelastic), CPU-time medians, seconds.

    ``full`` and ``again`` as :func:`bench_hyperelastic_cases`: the peer is
    the same problem and target with ``rigid`` emptied, in the same run. The
    contact case is timed twice: as given (its mesh finer where the parts
    press, ``options.contact_refinement`` 2) and on the peer's own mesh
    (``contact_refinement`` 1). The ratios are what contact costs, with and
    without the finer mesh it asks for.
    """
    import dataclasses

    from sectiondeform import load_case
    from sectiondeform.deform import Deformer

    rows = []
    reps = max(3, cfg["repeats"] // 4)
    for path in paths or shared_case_paths():
        case = load_case(path)
        if not case.rigid or path.stem.startswith(("o-ring", "lip-seal")):  # nothing loads them without their parts
            continue
        row = {"case": path.stem, "parts": len(case.rigid)}
        same_mesh = dataclasses.replace(case, options=case.options.replace(contact_refinement=1))
        for label, problem in (("contact", case), ("same_mesh", same_mesh), ("without", dataclasses.replace(case, rigid=()))):
            deformer = Deformer(problem, "hyperelastic")
            first = deformer.deform()
            thickness = min(sec.thickness for sec in deformer.stack.sections)
            moved = bumped(problem.target, BUMP * thickness)
            row[f"{label}_full_s"] = cpu_median(lambda p=problem: Deformer(p, "hyperelastic").deform(), reps, 1)
            row[f"{label}_again_s"] = cpu_median(lambda d=deformer, m=moved, f=first: d.deform(m, start=f), 3 * reps, 1)
        row["ratio_full"] = row["contact_full_s"] / row["without_full_s"]
        row["ratio_again"] = row["contact_again_s"] / row["without_again_s"]
        row["same_mesh_ratio_full"] = row["same_mesh_full_s"] / row["without_full_s"]
        row["same_mesh_ratio_again"] = row["same_mesh_again_s"] / row["without_again_s"]
        rows.append(row)
    return rows


def contact_markdown(rows: list[dict]) -> list[str]:
    """Section 9's table: each contact case against itself without its parts."""
    lines = [f"Target: a contact case at most {CONTACT_TARGET:g}× the same case without its rigid parts; **bold** a miss. "
             "CPU-time medians, the same run. *Same mesh*: the contact case with `contact_refinement` 1, on the mesh "
             "of the case without its parts; *refined*: as given, its mesh twice as fine where the parts press.", "",
             "| case | parts | mesh | full with / without | ratio | again with / without | ratio |",
             "|---|---:|---|---|---:|---|---:|"]
    for r in rows:
        for mesh, key in (("same mesh", "same_mesh_"), ("refined", "")):
            cells = [(f"{r[k]:.2f}×" if r[k] <= CONTACT_TARGET else f"**{r[k]:.2f}×**")
                     for k in (f"{key}ratio_full", f"{key}ratio_again")]
            label = "contact" if not key else "same_mesh"
            lines.append(f"| {r['case']} | {r['parts']} | {mesh} | {_fmt(r[label + '_full_s'])} / {_fmt(r['without_full_s'])} | "
                         f"{cells[0]} | {_fmt(r[label + '_again_s'])} / {_fmt(r['without_again_s'])} | {cells[1]} |")
    return lines


# --------------------------------------------------------------------------
# The run


def default_cases_dir() -> Path:
    """``tests/data/cases``: the cases the tests use."""
    return ROOT / "tests" / "data" / "cases"


def profile_text(case, seconds: float = 2.0) -> str | None:
    """Pyinstrument's view of the pipeline on ``case`` (None without pyinstrument)."""
    try:
        from pyinstrument import Profiler
    except ImportError:
        return None
    from sectiondeform.deform import Deformer

    profiler = Profiler(interval=1e-4)
    profiler.start()
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        Deformer(case).deform()
    profiler.stop()
    lines = profiler.output_text(unicode=False, color=False, show_all=False).splitlines()
    first = next((i for i, line in enumerate(lines) if "profile_text" in line), 0)  # drop the banner
    return "\n".join(lines[first:])


def run_benchmark(cases_dir=None, quick: bool = False, profile: bool = True, log=print) -> dict:
    """Measure everything once; returns the report (JSON-ready dict).

    Parameters
    ----------
    cases_dir : path, optional
        Folder of case JSON files (default :func:`default_cases_dir`).
    quick : bool
        Few repetitions and small N: a smoke run for CI.
    profile : bool
        Add pyinstrument's profile of the pipeline (full mode only).
    log : callable
        Progress messages.
    """
    from sectiondeform import load_case

    cfg = QUICK if quick else FULL
    paths = sorted(Path(cases_dir or default_cases_dir()).glob("*.json"))
    cases = {p.stem: load_case(p) for p in paths}
    ref_name = REFERENCE_CASE if REFERENCE_CASE in cases else next(iter(cases))
    ref = cases[ref_name]
    report = {"format": "sectiondeform-bench/1", "quick": quick, "config": {k: list(v) if isinstance(v, tuple) else v for k, v in cfg.items()},
              "machine": machine_info(), "reference_case": ref_name}
    log("pipeline ...")
    report["pipeline"] = bench_pipeline(list(cases.values()), cfg)
    log("re-deformation ...")
    report["redeform"] = bench_redeform(list(cases.values()), cfg)
    log("scaling ...")
    report["locate_scaling"] = bench_locate_scaling(ref, cfg)
    report["refinement"] = bench_refinement(ref, cfg)
    log("peers ...")
    ours = next(r for r in report["pipeline"] if r["case"] == ref_name)
    ours_re = next(r for r in report["redeform"] if r["case"] == ref_name)
    report["rbf"] = bench_rbf(ref, cfg, ours, ours_re)
    report["fe"] = bench_fe(ref, cfg, ours, ours_re)
    log("command line ...")
    report["cli"] = bench_cli(paths[[p.stem for p in paths].index(ref_name)], cfg)
    log("drawings ...")
    report["io"] = bench_io(cfg)
    log("one body and several ...")
    report["bodies"] = bench_bodies(cfg)
    log("hyperelastic on every shared case ...")
    report["hyperelastic"] = bench_hyperelastic_cases(cfg)
    log("contact against the same cases without their parts ...")
    report["contact"] = bench_contact(cfg)
    report["targets"] = check_targets(report)
    if profile and not quick:
        report["profile"] = profile_text(ref)
    return report


def check_targets(report: dict) -> list[dict]:
    """Every target with the measured figure and whether it is met."""
    T = TARGETS
    ref = report["reference_case"]
    pipe = next(r for r in report["pipeline"] if r["case"] == ref)
    red = next(r for r in report["redeform"] if r["case"] == ref)
    loc = report["locate_scaling"]
    last = loc["rows"][-1]
    rbf, fe, cli = report["rbf"], report["fe"], report["cli"]
    rows = [
        ("full pipeline, " + ref, pipe["full_s"], "<=", T["pipeline_paper_s"], "s"),
        ("re-deformation, " + ref, red["redeform_s"], "<=", T["redeform_paper_s"], "s"),
        (f"locate + place per point, N = {last['n']:.0e}", last["per_point_s"], "<=", T["locate_place_per_point_s"], "s"),
        (f"locate + place peak memory, N = {last['n']:.0e}", last["peak_mb"], "<=", T["locate_place_peak_mb"], "MB"),
        ("locate + place growth exponent", loc["exponent"], "<=", T["locate_place_exponent"], ""),
        ("command line, whole process", cli["cli_s"], "<=", T["cli_s"], "s"),
        ("re-deformation / RBF morph time", rbf["ratio_redeform"], "<", 1.0, "x"),
        ("RBF area error / ours", rbf["area_error_factor"], ">=", T["rbf_area_error_factor"], "x"),
    ]
    io = report.get("io", {})
    if io.get("available"):
        rows.append((f"chaining {io['chain_lines']} DXF LINEs", io["chain_s"], "<=", T["chain_5600_s"], "s"))
        if "seal_read_s" in io:
            rows.append(("reading the real seal scan", io["seal_read_s"], "<=", T["seal_read_s"], "s"))
    if fe.get("available"):
        rows += [
            ("FE reference / full pipeline", fe["speedup_full"], ">=", T["fe_full_speedup"], "x"),
            ("FE reference / re-deformation", fe["speedup_redeform"], ">=", T["fe_redeform_speedup"], "x"),
        ]
    out = []
    for name, value, op, target, unit in rows:
        met = value <= target if op == "<=" else value < target if op == "<" else value >= target
        out.append({"figure": name, "value": float(value), "op": op, "target": float(target), "unit": unit, "met": bool(met)})
    return out


# --------------------------------------------------------------------------
# Markdown


def _fmt(value: float | None, unit: str = "s") -> str:
    if value is None or not math.isfinite(value):
        return "-"
    if unit == "s":
        if value >= 1:
            return f"{value:.2f} s"
        if value >= 1e-3:
            return f"{value * 1e3:.2f} ms"
        return f"{value * 1e6:.2f} µs" if value < 1e-4 else f"{value * 1e3:.3f} ms"
    if unit == "MB":
        return f"{value:.1f} MB"
    if unit == "x":
        return f"{value:.3g}×"
    return f"{value:.3g}"


def to_markdown(report: dict, changes: str = "") -> str:
    """The report as Markdown: machine, targets, then each section's table."""
    m = report["machine"]
    lines = [
        "# Benchmarks",
        "",
        f"Produced by `{report.get('command', 'python benchmarks/run.py')}` "
        f"on {m['date']}, in one process and one run; "
        "every time is a median over repeated runs after a warm-up.",
        "",
        f"Machine: {m['platform']}, {m['processor']}, {m['cpus']} CPUs (shared with other work). "
        f"Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, shapely {m['shapely']}, "
        f"sectiondeform {m['sectiondeform']}.",
        "",
        "Other benchmarks, each with its own command: parametric studies (rows per second, "
        "1 → 2 workers, Dask, a 10⁵-row study) in [studies.md](studies.md#benchmark); the interactive "
        "page (pointer move to redrawn section) in [benchmarks-page.md](benchmarks-page.md); the "
        "hyperelastic model's levels in [hyperelastic.md](hyperelastic.md).",
        "",
        "## Targets",
        "",
        "| figure | measured | target | |",
        "|---|---|---|---|",
    ]
    for t in report["targets"]:
        lines.append(f"| {t['figure']} | {_fmt(t['value'], t['unit'])} | {t['op']} {_fmt(t['target'], t['unit'])} | "
                     f"{'met' if t['met'] else '**missed**'} |")
    if not report["fe"].get("available"):
        lines += ["", f"FE reference: not measured ({report['fe']['note']})."]
    lines += ["", "## 1. Full pipeline (`Deformer(case).deform()`)", "",
              "| case | elements | upper points | full | section | prepare (mesh + location) | deform | area error |",
              "|---|---|---|---|---|---|---|---|"]
    for r in report["pipeline"]:
        lines.append(f"| {r['case']} | {r['elements']} | {r['upper_points']} | {_fmt(r['full_s'])} | {_fmt(r['section_s'])} | "
                     f"{_fmt(r['prepare_s'])} | {_fmt(r['deform_s'])} | {r['relative_area_error']:.1e} |")
    lines += ["", "## 2. Re-deformation (`deformer.deform(target)`, the target bent further at each step)", "",
              "| case | steps | extra bend | per re-deformation | without the simplicity check (`check=False`) | normal smoothing (last) |",
              "|---|---|---|---|---|---|"]
    for r in report["redeform"]:
        lines.append(f"| {r['case']} | {r['steps']} | {r['extra_bend']:.0%} | {_fmt(r['redeform_s'])} | "
                     f"{_fmt(r['redeform_unchecked_s'])} | {r['normal_smoothing_last']:g} |")
    loc = report["locate_scaling"]
    lines += ["", f"## 3. Scaling ({loc['case']})", "",
              f"Locating N points (sampled inside the section) in the initial mesh ({loc['elements']} elements) "
              "and placing them in the final mesh; peak memory by tracemalloc.", "",
              "| N | time | per point | peak memory |", "|---|---|---|---|"]
    for r in loc["rows"]:
        lines.append(f"| {r['n']:.0e} | {_fmt(r['time_s'])} | {_fmt(r['per_point_s'])} | {_fmt(r['peak_mb'], 'MB')} |")
    lines += ["", f"Growth exponent (log time on log N): {loc['exponent']:.3f} over all N"
              + (f", {loc['exponent_n_ge_1000']:.3f} for N ≥ 1000." if loc.get("exponent_n_ge_1000") is not None else ".")]
    ref = report["refinement"]
    lines += ["", "Full pipeline as the element size is halved:", "",
              "| element size | elements | full pipeline | re-deformation | peak memory |", "|---|---|---|---|---|"]
    for r in ref["rows"]:
        lines.append(f"| {r['element_size']:.4g} | {r['elements']} | {_fmt(r['full_s'])} | {_fmt(r['redeform_s'])} | {_fmt(r['peak_mb'], 'MB')} |")
    if ref["exponent"] is not None:
        lines += ["", f"Growth exponent (log time on log elements): {ref['exponent']:.3f}."]
    if ref.get("refused"):
        lines += ["", f"At element size {ref['refused']['element_size']:.4g} the method refuses: {ref['refused']['error']}"]
    rbf, fe = report["rbf"], report["fe"]
    lines += ["", f"## 4. Peers ({rbf['case']})", "",
              "| method | time | relative area error | ours / peer (full) | ours / peer (re-deformation) |", "|---|---|---|---|---|",
              f"| ours | {_fmt(next(r['full_s'] for r in report['pipeline'] if r['case'] == rbf['case']))} full, "
              f"{_fmt(next(r['redeform_s'] for r in report['redeform'] if r['case'] == rbf['case']))} re-deformation | "
              f"{rbf['ours_area_error']:.1e} | | |",
              f"| RBF morph, thin-plate, {rbf['rbf_note']} | {_fmt(rbf['rbf_s'])} | {rbf['rbf_area_error']:.1e} | "
              f"{rbf['ratio_full']:.3g} | {rbf['ratio_redeform']:.3g} |"]
    if fe.get("available"):
        lines.append(f"| FE reference | {_fmt(fe['fe_s'])} | | {1 / fe['speedup_full']:.3g} | {1 / fe['speedup_redeform']:.3g} |")
    else:
        lines.append("| FE reference | not measured | | | |")
    cli = report["cli"]
    lines += ["", "## 5. Command line", "",
              "| process | wall time |", "|---|---|",
              f"| `{cli['command']}` ({cli['case']}) | {_fmt(cli['cli_s'])} |",
              f"| `python -c '{PARSER_ONLY}'` (imports every command module) | {_fmt(cli['parser_s'])} |",
              f"| `python -c 'import sectiondeform.cli'` | {_fmt(cli['import_s'])} |",
              f"| `python -c pass` | {_fmt(cli['python_bare_s'])} |"]
    io = report.get("io", {})
    lines += ["", "## 6. Drawings", ""]
    if io.get("available"):
        lines += ["| work | time |", "|---|---|",
                  f"| chaining {io['chain_lines']} shuffled LINEs into one ring | {_fmt(io['chain_s'])} |"]
        if "seal_read_s" in io:
            lines.append(f"| reading the real seal scan (5,632 LINEs: chain, snap, close, simplify) | {_fmt(io['seal_read_s'])} |")
    else:
        lines.append(f"Not measured ({io.get('note', 'no figures')}).")
    lines += ["", "## 7. One body and several (per model, the same calls on a problem of one body and one of two)", ""]
    lines += bodies_markdown(report["bodies"])
    if report.get("hyperelastic"):
        lines += ["", "## 8. The hyperelastic model on every shared case", ""]
        lines += hyperelastic_markdown(report["hyperelastic"])
    if report.get("contact"):
        lines += ["", "## 9. Contact (each case with rigid parts against itself without them)", ""]
        lines += contact_markdown(report["contact"])
    if changes:
        lines += ["", changes.strip()]
    if report.get("profile"):
        lines += ["", f"## Profile of the full pipeline ({report['reference_case']}, pyinstrument)", "", "```",
                  report["profile"].strip(), "```"]
    return "\n".join(lines) + "\n"


def _json_default(obj):
    if isinstance(obj, (np.floating, np.integer)):
        return obj.item()
    raise TypeError(f"cannot write {type(obj).__name__} to JSON")


def write_report(report: dict, folder: Path, changes: str = "") -> tuple[Path, Path]:
    """Write ``benchmarks.json`` and ``benchmarks.md`` into ``folder``; returns their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    js, md = folder / "benchmarks.json", folder / "benchmarks.md"
    js.write_text(json.dumps(report, indent=1, default=_json_default) + "\n", encoding="utf-8")
    md.write_text(to_markdown(report, changes), encoding="utf-8")
    return js, md


def targets_text(report: dict) -> str:
    """One line per target: figure, measured, target, met or missed."""
    return "\n".join(
        f"{t['figure']:45s} {_fmt(t['value'], t['unit']):>12s}  {t['op']} {_fmt(t['target'], t['unit']):>10s}  "
        f"{'met' if t['met'] else 'MISSED'}"
        for t in report["targets"]
    )
