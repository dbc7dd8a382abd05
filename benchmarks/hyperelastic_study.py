"""Accuracy-time curve of the hyperelastic model over its coarseness.

For each case of ``tests/data/cases`` and each coarseness (elements through the mean
thickness T), prints and writes:

* ``unknowns``: free unknowns of the coarse problem;
* ``prepare_ms``: mesh, pattern, factorised undeformed tangent, locations;
* ``full_ms``: ``deformer.deform(target_nodes=...)``, a cold solve (Newton
  from the undeformed section moved rigidly onto the target);
* ``redeform_cold_ms``: ``deform`` after a small change of the target (a
  bump of 0.5 % T), cold again: without ``start=`` the answer depends on
  the arguments alone;
* ``redeform_ms``: the same change warm-started,
  ``deform(..., start=previous_result)``;
* ``preview_ms`` and ``preview_err``: the drag preview for that change from
  the previous result and its largest distance to the full solve, relative
  to T;
* ``mean``/``max``: distance of the upper curve to the truth, relative to T
  (mean over the curve, and Hausdorff); ``raw_mean``/``raw_max`` the same
  before the area correction (the reference's points are not corrected).

Any problem works, one body or several: each body's distances are relative
to its own T, and a row gives the worst body's.

The truth is the fine finite-element reference (:mod:`sectiondeform.reference`,
extra ``[fem]``, element size ``T / --reference-div``) when it is installed,
else the model itself at ``--fine`` elements through the thickness (a
self-convergence check, labelled as such). Times are medians of
``--repeat`` runs on this machine.

Usage::

    python benchmarks/hyperelastic_study.py [--levels 2 3 4 6 8 12] [--repeat 21]
        [--out benchmarks/results/hyperelastic_study.json]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np
import shapely

import sectiondeform as sd
from sectiondeform.errors import MissingExtraError
from sectiondeform.reference import solve_reference

from speed import median_time  # benchmarks/, beside this file

ROOT = Path(__file__).resolve().parents[1]
CASES = sorted((ROOT / "tests" / "data" / "cases").glob("*.json"))


def distances(a: np.ndarray, b: np.ndarray, T: float) -> tuple[float, float]:
    """(mean, Hausdorff) distance between the polylines ``a`` and ``b``, relative to ``T``."""
    la, lb = shapely.LineString(a), shapely.LineString(b)
    pts = shapely.points(shapely.get_coordinates(shapely.segmentize(la, T / 50)))
    return float(np.mean(shapely.distance(pts, lb))) / T, shapely.hausdorff_distance(la, lb, densify=0.02) / T


def truth(case, fine: float, reference_div: float) -> tuple[list, str]:
    """Each body's upper curve in the reference solution (or, without it, in a fine run of the model), and its label."""
    try:
        reference = solve_reference(case, mesh_size=1.0 / reference_div)
        return [np.asarray(b.upper) for b in reference.bodies], f"reference (h = T/{reference_div:g})"
    except MissingExtraError:
        c = case.replace(options=case.options.replace(elements_through_thickness=fine))
        return [b.upper for b in sd.Deformer(c, model="hyperelastic").deform().bodies], f"self (n={fine:g})"


def _median_ms(fn, repeat: int) -> float:
    return 1e3 * median_time(fn, repeat, warmup=1)


def _worst(uppers, truths, thicknesses) -> tuple[float, float]:
    """The largest (mean, Hausdorff) distance of a body's upper curve to its truth, over the bodies, relative to its T."""
    pairs = [distances(u, t, T) for u, t, T in zip(uppers, truths, thicknesses)]
    return max(p[0] for p in pairs), max(p[1] for p in pairs)


def raw_uppers(prepared, result) -> list:
    """Each body's upper points of the coarse solve before the area correction."""
    n = len(prepared.mesh.nodes)
    x = result.state.state.z[: 2 * n].reshape(n, 2)
    images = prepared.mesh.vertex_weights @ x
    return [images[ids] for ids in prepared.upper_ids]


def study(path: Path, levels, repeat: int, fine: float, reference_div: float) -> list[dict]:
    case = sd.load_case(path)
    upper_true, label = truth(case, fine, reference_div)
    rows = []
    for n in levels:
        c = case.replace(options=case.options.replace(elements_through_thickness=n))
        t0 = time.perf_counter()
        deformer = sd.Deformer(c, model="hyperelastic", check=False)
        prepare_ms = 1e3 * (time.perf_counter() - t0)
        prep = deformer.prepared
        T = [sec.thickness for sec in deformer.stack.sections]
        nodes = deformer.target_nodes()

        full_ms = _median_ms(lambda: deformer.deform(target_nodes=nodes), repeat)
        result = deformer.deform(target_nodes=nodes)
        mean, worst = _worst([b.upper for b in result.bodies], upper_true, T)
        raw_mean, raw_max = _worst(raw_uppers(prep, result), upper_true, T)
        moved = nodes + 0.005 * min(T) * np.sin(np.linspace(0.0, np.pi, len(nodes)))[:, None] * np.array([0.0, 1.0])
        redeform_cold_ms = _median_ms(lambda: deformer.deform(target_nodes=moved), repeat)
        redeform_ms = _median_ms(lambda: deformer.deform(target_nodes=moved, start=result), repeat)
        preview_ms = _median_ms(lambda: deformer.preview(target_nodes=moved, start=result), repeat)
        exact = deformer.deform(target_nodes=moved, start=result).bodies
        preview = deformer.preview(target_nodes=moved, start=result).bodies
        preview_err = max(float(np.abs(p.upper - e.upper).max()) / t for p, e, t in zip(preview, exact, T))
        rows.append({
            "case": case.name, "through_thickness": n, "truth": label,
            "unknowns": int(prep.bodies[0].quality.unknowns), "elements": sum(b.quality.elements for b in prep.bodies),
            "prepare_ms": prepare_ms, "full_ms": full_ms, "redeform_cold_ms": redeform_cold_ms, "redeform_ms": redeform_ms,
            "preview_ms": preview_ms, "preview_err": preview_err, "mean": mean, "max": worst,
            "raw_mean": raw_mean, "raw_max": raw_max,
            "area_correction": max(b.info.area_correction for b in result.bodies),
        })
        r = rows[-1]
        print(f"{case.name:22s} n={n:<4g} unknowns={r['unknowns']:5d} prepare={prepare_ms:7.2f}ms "
              f"full={full_ms:6.2f}ms redeform cold={redeform_cold_ms:6.2f}ms warm={redeform_ms:5.2f}ms preview={preview_ms:5.3f}ms "
              f"(err {preview_err:.1e} T)  mean={mean:.4f} T  max={worst:.4f} T  "
              f"(before area correction {raw_mean:.4f} / {raw_max:.4f})  [{label}]", flush=True)
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", type=float, nargs="+", default=[2, 3, 4, 6, 8, 12])
    ap.add_argument("--repeat", type=int, default=21)
    ap.add_argument("--fine", type=float, default=16.0, help="elements through T of the self-convergence truth")
    ap.add_argument("--reference-div", type=float, default=16.0, help="reference element size T / this")
    ap.add_argument("--cases", nargs="*", help="case files (default: tests/data/cases/*.json)")
    ap.add_argument("--out", type=Path, help="write the rows as JSON here")
    args = ap.parse_args(argv)
    rows = []
    for path in [Path(p) for p in args.cases] if args.cases else CASES:
        rows += study(path, args.levels, args.repeat, args.fine, args.reference_div)
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
