"""The hyperelastic model's cost: how it grows with the mesh, and what its peers cost in the same run.

Two tables, printed as markdown (docs/benchmarks.md keeps them, section 10):

* **growth**: the full solve (``Deformer(case, "hyperelastic").deform()``)
  against its unknowns, each case at 2 to 16 elements through the
  thickness, CPU-time medians, and the exponent of time on unknowns (least
  squares on the logarithms);
* **peers**: per shared case, the project's finite-element reference at its
  default mesh (0.1 of the mesh scale, one run) against the model's full
  solve and solve again (the issue's targets: at least 100× and 1,000×);
  and one Newton iteration of the model (tangent assembled and factorised,
  a residual, a back-substitution) against one of a general-purpose
  Taylor–Hood P2/P1 solver on scikit-fem's bases (the reference's
  :class:`~sectiondeform.reference.solver.MixedProblem`: its own
  assembly, ``spsolve`` on the free block) on the model's own triangles,
  the same unknowns.

::

    PYTHONPATH=src python benchmarks/hyperelastic_cost.py            # both tables
    PYTHONPATH=src python benchmarks/hyperelastic_cost.py --quick    # three cases, fewer repeats

Needs the extra ``[fem]`` (scikit-fem, triangle) for the peers.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from speed import BUMP, bumped, cpu_median, growth_exponent, shared_case_paths  # noqa: E402

GROWTH_CASES = ("paper-example", "two-layer-strip", "tread-alone-on-drum")
GROWTH_THROUGH = (2, 3, 4, 6, 8, 12, 16)
LARGE_MESH = 1500
"""The growth's exponent is also fitted from this many unknowns on, where the mesh's fixed costs no longer dominate."""
PEER_RATIOS = {"full": 100.0, "again": 1000.0}
"""The reference at least this many times the model's full solve and solve again (the issue's targets)."""


def _with_through(case, n: int):
    """``case`` meshed at ``n`` elements through the thickness."""
    return dataclasses.replace(case, options=case.options.replace(elements_through_thickness=n))


def bench_growth(paths, throughs=GROWTH_THROUGH, repeats: int = 5) -> list[dict]:
    """Per case, the full solve's CPU median at each mesh and the exponent of time on unknowns.

    A mesh the model refuses (a bound, a failed solve) is left out, with its one line.
    """
    from sectiondeform import SectionDeformError, load_case
    from sectiondeform.deform import Deformer

    rows = []
    for path in paths:
        case = load_case(path)
        points, refused = [], []
        for n in throughs:
            problem = _with_through(case, n)
            try:
                first = Deformer(problem, "hyperelastic").deform()
            except SectionDeformError as exc:
                refused.append((n, str(exc)))
                continue
            unknowns = int(first.bodies[0].quality.initial.unknowns)
            seconds = cpu_median(lambda p=problem: Deformer(p, "hyperelastic").deform(), repeats, 1)
            points.append((n, unknowns, seconds))
        exponent = growth_exponent([u for _, u, _ in points], [s for *_, s in points]) if len(points) > 1 else None
        large = [(u, s) for _, u, s in points if u >= LARGE_MESH]
        rows.append({"case": path.stem, "points": points, "exponent": exponent, "refused": refused,
                     "exponent_large": growth_exponent(*zip(*large)) if len(large) > 1 else None})
    return rows


def growth_markdown(rows: list[dict]) -> list[str]:
    """The growth table: one row per case and mesh, the exponent per case."""
    lines = ["| case | elements through | unknowns | full solve | |", "|---|---:|---:|---:|---|"]
    for r in rows:
        for n, unknowns, seconds in r["points"]:
            lines.append(f"| {r['case']} | {n} | {unknowns} | {seconds * 1e3:.1f} ms | |")
        for n, why in r["refused"]:
            lines.append(f"| {r['case']} | {n} | – | refused | {why[:120]} |")
        if r["exponent"] is not None:
            large = "" if r["exponent_large"] is None else f", {r['exponent_large']:.2f} from {LARGE_MESH:,} unknowns on"
            lines.append(f"| **{r['case']}** | | | | exponent **{r['exponent']:.2f}**{large} |")
    return lines


def _same_mesh_peer(deformer):
    """The reference's Taylor–Hood problem on the model's own corner triangles, its support the model's support nodes."""
    import shapely

    from sectiondeform.reference import body_material
    from sectiondeform.reference.mesh import ReferenceMesh
    from sectiondeform.reference.revolution import axis_from_points
    from sectiondeform.reference.solver import MixedProblem

    prep, problem = deformer.prepared, deformer.problem
    mesh = prep.mesh
    nv = mesh.n_vertices
    fixed = np.unique(np.asarray(prep.solver.pattern.fixed) // 2)
    lower = fixed[fixed < nv]
    support = shapely.LineString(problem.layout.fine["support"])
    s = shapely.line_locate_point(support, shapely.points(mesh.nodes[lower])) / support.length
    order = np.argsort(s, kind="stable")
    ref_mesh = ReferenceMesh(points=mesh.nodes[:nv].copy(), triangles=np.asarray(mesh.cells[:, :3], dtype=np.int64),
                             body=np.asarray(mesh.body, dtype=np.int64), lower_nodes=lower[order],
                             lower_fractions=s[order], upper_nodes=(), contour_nodes=(), sizes=np.array([mesh.size]))
    contour = np.concatenate([sec.contour for sec in deformer.stack.sections])
    axis = None if problem.revolution is None else axis_from_points(problem.revolution.axis, contour)
    rubbers = [body_material(problem, b) for b in range(len(problem.bodies))]
    return MixedProblem(ref_mesh, rubbers, axis=axis)


def _peer_iteration(pr) -> None:
    """One Newton iteration of the reference's solver at rest: material and tangent, the free block solved, a residual."""
    from scipy.sparse.linalg import spsolve

    x = np.zeros(pr.n_u + pr.n_p)
    mat = pr.material(x, 1.0, extras=False)
    r = pr.residual(x, 1.0, mat)
    K = pr.tangent(mat, x)
    Kf = K[pr.free][:, pr.free]
    x[pr.free] = 1e-9 * spsolve(Kf.tocsc(), -r[pr.free])  # (at rest the step is zero: a trial point near it)
    pr.residual(x, 1.0, pr.material(x, 1.0, extras=False))


def _our_iteration(deformer) -> None:
    """One Newton iteration of the model at rest: the tangent assembled and factorised, a residual, a back-substitution."""
    prep = deformer.prepared
    solver, z = prep.solver, prep.reference.z
    physics = solver.physics
    fields = physics.fields(z, 1.0)
    tangent = solver.tangent(fields)
    r, _ = solver.residual(z, 1.0)
    tangent.solve(r)


def bench_peers(paths, repeats: int = 5) -> list[dict]:
    """Per case: the reference against the full solve and the solve again, and one Newton iteration against the peer's."""
    from sectiondeform import SectionDeformError, load_case
    from sectiondeform.deform import Deformer
    from sectiondeform.reference import solve_reference

    rows = []
    for path in paths:
        case = load_case(path)
        deformer = Deformer(case, "hyperelastic")
        first = deformer.deform()
        thickness = min(sec.thickness for sec in deformer.stack.sections)
        moved = bumped(case.target, BUMP * thickness)
        row = {"case": path.stem, "unknowns": int(first.bodies[0].quality.initial.unknowns),
               "full_s": cpu_median(lambda c=case: Deformer(c, "hyperelastic").deform(), repeats, 1),
               "again_s": cpu_median(lambda: deformer.deform(moved, start=first), 3 * repeats, 1),
               "ours_iteration_s": cpu_median(lambda: _our_iteration(deformer), 3 * repeats, 1)}
        try:
            peer = _same_mesh_peer(deformer)
            row["peer_unknowns"] = len(peer.free)
            row["peer_iteration_s"] = cpu_median(lambda: _peer_iteration(peer), 3 * repeats, 1)
        except (SectionDeformError, ValueError, RuntimeError) as exc:
            row["peer_note"] = f"{type(exc).__name__}: {exc}"
        t0 = time.process_time()
        try:
            solve_reference(case)
            row["reference_s"] = time.process_time() - t0
        except SectionDeformError as exc:
            row["reference_note"] = str(exc)
        rows.append(row)
    return rows


def peers_markdown(rows: list[dict]) -> list[str]:
    """The peers table: the reference's ratios against their targets (**bold** a miss), the per-iteration yardstick."""
    lines = [f"Targets: the reference at least {PEER_RATIOS['full']:g}× the full solve and {PEER_RATIOS['again']:g}× a "
             "solve again; **bold** a miss.", "",
             "| case | unknowns | full | again | reference | reference / full | reference / again | "
             "Newton iteration: ours / peer (same triangles) | peer / ours |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        ref = r.get("reference_s")
        cells = []
        for key in ("full", "again"):
            if ref is None:
                cells.append("–")
                continue
            ratio = ref / r[f"{key}_s"]
            cells.append(f"{ratio:,.0f}×" if ratio >= PEER_RATIOS[key] else f"**{ratio:,.0f}×**")
        peer = r.get("peer_iteration_s")
        yard = (f"{r['ours_iteration_s'] * 1e3:.2f} / {peer * 1e3:.2f} ms ({r['peer_unknowns']} unknowns) | "
                f"{peer / r['ours_iteration_s']:.2f}×"
                if peer is not None else f"{r['ours_iteration_s'] * 1e3:.2f} ms / – | –")
        lines.append(f"| {r['case']} | {r['unknowns']} | {r['full_s'] * 1e3:.1f} ms | {r['again_s'] * 1e3:.2f} ms | "
                     f"{'–' if ref is None else f'{ref:.1f} s'} | {cells[0]} | {cells[1]} | {yard} |")
    return lines


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="three cases, three meshes, fewer repeats")
    parser.add_argument("--only", choices=("growth", "peers"), help="one table")
    args = parser.parse_args(argv)
    paths = {p.stem: p for p in shared_case_paths()}
    repeats = 3 if args.quick else 7
    if args.only in (None, "growth"):
        names = GROWTH_CASES[:1] if args.quick else GROWTH_CASES
        throughs = (2, 4, 8) if args.quick else GROWTH_THROUGH
        rows = bench_growth([paths[n] for n in names], throughs, repeats)
        print("\n".join(growth_markdown(rows)), "\n", flush=True)
    if args.only in (None, "peers"):
        chosen = list(paths.values())
        if args.quick:
            chosen = [paths[n] for n in ("paper-example", "two-layer-strip", "bumper-under-plate")]
        print("\n".join(peers_markdown(bench_peers(chosen, repeats))), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
