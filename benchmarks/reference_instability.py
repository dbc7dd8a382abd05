"""Why the finite-element reference stops on the paper example at area ratio 1 (docs/validation.md, "Against CalculiX").

Solves the case with the reference's own mesh, problem and load stepping
(:func:`sectiondeform.reference.solver.solve_mixed`), with its Newton step
replaced by a copy that records why each refused step was refused (an
element turned inside out by the support's step or by a Newton update, a
line search that cannot lower the residual, too many iterations). At the
last converged load it reports:

* the smallest principal in-plane stretch at any quadrature point and where
  it is (initial position), and the smallest tangential stretch of the free
  upper surface (deformed over initial length of its mesh edges);
* the lowest eigenvalues of the displacement stiffness with the pressure
  condensed out, S = K_uu − K_up K_pp⁻¹ K_pu (shift-invert Lanczos about 0,
  each solve through the full mixed tangent; units of μ): a stable
  equilibrium has S positive definite, and S turns singular where the
  solution path meets a bifurcation or a limit point (``--modes``: at the
  stop, with where the lowest mode is largest; ``--trend``: the lowest one
  at every converged load).

``--upper-every k`` meshes the upper curve through every k-th
characteristic point only (coarser triangles along it, at the corners too).

With ``--calculix`` it also runs ``ccx`` on the deck ``export-fe`` writes and
reports CalculiX's increment nearest the reference's stopping load (``--at``)
and its final state: the same surface stretches, from the ``.frd``
displacements (ccx 2.20 writes the last increment only, so "nearest" is then
the final state), the Hausdorff distance between the reference's deformed
upper curve and CalculiX's at the shared characteristic points, and between
consecutive CalculiX meshes after the best rigid fit.

Usage: python benchmarks/reference_instability.py [--case tests/data/cases/paper-example.json]
       [--mesh-size 0.1 ...] [--bulk-to-shear 1000] [--initial-step 1] [--min-step 0.0009765625]
       [--upper-every 1 4 ...] [--trend] [--modes] [--calculix 0.1 ...] [--at 0.786]
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import math
import time

import numpy as np

import sectiondeform as sd
from sectiondeform.compare import compare_curves
from sectiondeform.errors import ConvergenceError
from sectiondeform.laws import AreaRatio, VolumeRatio
from sectiondeform.reference import body_material, body_ratio
from sectiondeform.reference import solver as solver_module
from sectiondeform.reference.mesh import triangulate
from sectiondeform.reference.revolution import axis_from_points
from sectiondeform.reference.solver import MixedProblem, solve_mixed

_original_newton = solver_module._newton


def _newton_why(pr, x, load, lift, free, length_scale, tol, max_iterations, log):
    """:func:`solver._newton`, same steps, but appends why a step is refused to ``log``."""
    from scipy.sparse.linalg import spsolve

    n_u = pr.n_u
    mat = pr.material(x, load, extras=False)
    if not mat["valid"]:
        log.append(("rigid predictor inverts an element", _inverted(pr, mat)))
        return False, 0, math.inf, x
    r = pr.residual(x, load, mat)
    norm = float(np.linalg.norm(r[free]))
    first = bool(lift.any())
    for it in range(1, max_iterations + 1):
        K = pr.tangent(mat)
        dx = np.zeros_like(x)
        if first:
            dx += lift
            rhs = -(r + K @ lift)
        else:
            rhs = -r
        with np.errstate(all="ignore"):
            dx[free] = spsolve(K[free][:, free].tocsc(), rhs[free])
        if not np.all(np.isfinite(dx)):
            log.append(("singular tangent", it))
            return False, it, norm, x
        small = (np.abs(dx[:n_u]).max() <= tol * length_scale and np.abs(dx[n_u:]).max(initial=0.0) <= tol * pr.mu)
        alpha = 1.0
        for _ in range(6):
            cand = x + alpha * dx
            with np.errstate(all="ignore"):
                mat_c = pr.material(cand, load, extras=False)
            if mat_c["valid"]:
                r_c = pr.residual(cand, load, mat_c)
                norm_c = float(np.linalg.norm(r_c[free]))
                if first or norm_c <= norm or small:
                    break
            if first:
                log.append(("the support's step (first iteration) inverts an element", _inverted(pr, mat_c)))
                return False, it, norm, x
            alpha *= 0.5
        else:
            why = "line search: residual does not decrease" if mat_c["valid"] else "line search: update inverts an element"
            log.append((why, f"iteration {it}, residual {norm:.3g}"))
            return False, it, norm, x
        x, mat, r, norm = cand, mat_c, r_c, norm_c
        if first:
            first = False
            continue
        if small and alpha == 1.0:
            return True, it, norm, x
    log.append(("no convergence in max iterations", f"residual {norm:.3g}"))
    return False, max_iterations, norm, x


def _inverted(pr, mat):
    """Initial centroids of the triangles with det F2D <= 0 somewhere, as text."""
    bad = np.flatnonzero((mat["det2"] <= 0).any(axis=1))
    cent = pr.section_mesh.points[pr.section_mesh.triangles[bad]].mean(axis=1)
    return f"{len(bad)} triangles, initial centroids {np.round(cent[:4], 1).tolist()}"


def stretches(pr, x):
    """Smallest principal in-plane stretch at each quadrature point, ``(nel, nq)``, and their initial positions."""
    g = pr.grad_u(x[: pr.n_u])
    F = np.moveaxis(g, (0, 1), (-2, -1)) + np.eye(2)
    C = np.einsum("...ki,...kj->...ij", F, F)
    lam = np.sqrt(np.linalg.eigvalsh(C)[..., 0])
    X = np.moveaxis(np.asarray(pr.ubasis.global_coordinates()), 0, -1)
    return lam, X


def surface_stretch(initial, deformed):
    """Deformed over initial length of each upper edge, and the edges' initial midpoints.

    ``initial`` and ``deformed`` are lists of polylines (one per body, ``(m_b, 2)``); the edges of all, in order.
    """
    d0 = np.concatenate([np.hypot(*np.diff(a, axis=0).T) for a in initial])
    d1 = np.concatenate([np.hypot(*np.diff(b, axis=0).T) for b in deformed])
    mids = np.concatenate([0.5 * (a[1:] + a[:-1]) for a in initial])
    return d1 / d0, mids


def lowest_modes(pr, x, load, k=3):
    """The k eigenvalues of the condensed stiffness S nearest 0, and the lowest one's mode (displacement dofs)."""
    from scipy.sparse.linalg import LinearOperator, eigsh, splu

    mat = pr.material(x, load, extras=False)
    K = pr.tangent(mat).tocsc()
    n_u = pr.n_u
    fu = pr.free[pr.free < n_u]
    fp = np.arange(n_u, n_u + pr.n_p)
    Kuu, Kup, Kpp = K[fu][:, fu], K[fu][:, fp], K[fp][:, fp]
    lu_p = splu(Kpp.tocsc())
    full = np.concatenate((fu, fp))
    lu = splu(K[full][:, full].tocsc())
    n = len(fu)

    def s_mv(v):
        v = np.ravel(v)
        return Kuu @ v - Kup @ lu_p.solve(np.asarray(Kup.T @ v))

    def s_inv(v):
        rhs = np.concatenate((np.ravel(v), np.zeros(len(fp))))
        return lu.solve(rhs)[:n]

    S = LinearOperator((n, n), matvec=s_mv, dtype=np.float64)
    Sinv = LinearOperator((n, n), matvec=s_inv, dtype=np.float64)
    vals, vecs = eigsh(S, k=k, sigma=0.0, which="LM", OPinv=Sinv)
    order = np.argsort(vals)
    mode = np.zeros(n_u)
    mode[fu] = vecs[:, order[0]]
    return vals[order], mode


def _coarser(section, every: int):
    """The section with its upper polyline through every k-th characteristic point, both ends kept."""
    if every <= 1:
        return section
    up = np.asarray(section.upper)
    keep = np.unique(np.r_[np.arange(0, len(up), every), len(up) - 1])
    return dataclasses.replace(section, upper=up[keep])


def run_reference(case, mesh_size, bulk_to_shear, initial_step, min_step, modes=False, trend=False, every=1):
    """The reference's own load stepping on the problem (every body), its refusals recorded; figures at the stop."""
    bodies = range(len(case.bodies))
    sections = [_coarser(sd.build_section(case.body_case(b)), every) for b in bodies]
    rubbers = [body_material(case, b, bulk_to_shear) for b in bodies]
    ax = None if case.revolution is None else axis_from_points(case.revolution.axis, np.concatenate([s.contour for s in sections]))
    ratios = np.array([body_ratio(case.bodies[b].law, revolution=ax is not None, area=sections[b].area) for b in bodies])
    load = ratios if ax is not None else 1.0 / ratios
    scale = min(s.mesh_scale for s in sections)
    mesh = triangulate(case, mesh_size, sections)
    pr = MixedProblem(mesh, rubbers, axis=ax)
    support = np.asarray(case.target.at_fractions(pr.dirichlet_fractions), dtype=np.float64)
    log, accepted = [], []

    def newton(pr_, x, load, lift, free, length_scale, tol, max_iterations):
        out = _newton_why(pr_, x, load, lift, free, length_scale, tol, max_iterations, log)
        if out[0]:
            accepted.append(out[3])
        return out

    t0 = time.perf_counter()
    solver_module._newton = newton
    steps = []
    try:
        solve_mixed(pr, support, load, length_scale=scale, initial_step=initial_step, min_step=min_step,
                    progress=lambda line: steps.append(line))
        stop = None
    except ConvergenceError as exc:
        stop = str(exc)
    finally:
        solver_module._newton = _original_newton
    loads = [float(s.split("load")[1].split("%")[0]) for s in steps if "converged" in s]
    out = {"mesh_size": mesh_size, "kappa/mu": bulk_to_shear, "initial_step": initial_step, "min_step": min_step,
           "elements": len(mesh.triangles), "h": [float(h) for h in mesh.sizes], "seconds": time.perf_counter() - t0,
           "last_load_%": loads[-1] if loads else 0.0, "finished": stop is None,
           "refusals": log[-3:], "problem": pr, "x": accepted[-1] if accepted else None, "mesh": mesh,
           "sections": sections}
    x = out["x"]
    if x is not None:
        lam, X = stretches(pr, x)
        e, q = np.unravel_index(np.argmin(lam), lam.shape)
        out["min_stretch"] = (float(lam[e, q]), np.round(X[e, q], 2).tolist())
        corners = mesh.points[[i for ids in mesh.upper_nodes for i in (ids[0], ids[-1])]]
        far = np.min(np.hypot(*(X[..., None, :] - corners).transpose(3, 0, 1, 2)), axis=-1) > 0.25 * scale
        e, q = np.unravel_index(np.argmin(np.where(far, lam, np.inf)), lam.shape)
        out["min_stretch_away_from_corners"] = (float(lam[e, q]), np.round(X[e, q], 2).tolist())
        u_nodes = x[: pr.n_u][pr.ubasis.nodal_dofs].T
        p0 = [mesh.points[ids] for ids in mesh.upper_nodes]
        p1 = [mesh.points[ids] + u_nodes[ids] for ids in mesh.upper_nodes]
        s, mid = surface_stretch(p0, p1)
        i = int(np.argmin(s))
        out["surface_stretch"] = (float(s[i]), np.round(mid[i], 2).tolist())
        out["upper0"], out["upper"] = np.concatenate(p0), np.concatenate(p1)
        top = int(np.argmax(mid[:, 1]))
        out["surface_stretch_at_top"] = (float(s[top]), np.round(mid[top], 2).tolist())
        if trend:
            out["lowest_eigenvalue_by_load"] = [(load_, float(lowest_modes(pr, xa, load, k=1)[0][0]))
                                                for load_, xa in zip(loads, accepted)]
        if modes:
            vals, mode = lowest_modes(pr, x, load)
            m = np.hypot(*mode.reshape(-1, 2).T)
            node = int(np.argmax(m))
            out["eigenvalues"] = np.round(vals, 5).tolist()
            out["mode_peak_at"] = np.round(pr.doflocs[0::2][node], 2).tolist()
            out["mode_share_near_top"] = float((m ** 2)[pr.doflocs[0::2][:, 1] > 30.0].sum() / (m ** 2).sum())
    return out


def run_calculix(case, mesh_size, at_load):
    from sectiondeform.external.calculix import run_ccx
    from sectiondeform.external.deck import build_deck, deck_text
    from sectiondeform.external.interpolate import map_points

    deck = build_deck(case, None, mesh_size)
    t0 = time.perf_counter()
    results, info = run_ccx(deck_text(deck), job="section", timeout=900)
    m = deck.mesh
    uppers = [np.asarray(sd.build_section(case.body_case(b)).upper, dtype=np.float64) for b in range(len(case.bodies))]
    upper0 = np.concatenate(uppers)
    ends = np.cumsum([len(u) for u in uppers])[:-1]
    rows = []
    for time_, ids, disp in results.blocks["DISP"]:
        u = np.zeros((len(m.points), 2))
        u[ids - 1] = disp[:, :2]
        up = map_points(m.points, deck.placed_points + u, m.cells, m.kind, upper0)
        s, mid = surface_stretch([u @ deck.rotation.T + deck.translation for u in uppers], np.split(up, ends))
        i = int(np.argmin(s))
        top = int(np.argmax(mid[:, 1]))
        rows.append((float(time_), float(s[i]), np.round(mid[i], 2).tolist(), float(s[top]), up))
    near = min(rows, key=lambda r: abs(r[0] - at_load))
    return {"mesh_size": mesh_size, "elements": len(m.cells), "seconds": time.perf_counter() - t0,
            "increments": info.get("increments"), "near": near, "final": rows[-1], "upper0": upper0}


def _fitted_distance(a, b):
    """Largest distance between matching points of a and b (m, 2) after the best rigid fit of a onto b."""
    from sectiondeform.reference.solver import _rotation, kabsch

    angle, ca, cb = kabsch(a, b)
    return float(np.hypot(*((a - ca) @ _rotation(angle).T + cb - b).T).max())


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="tests/data/cases/paper-example.json")
    ap.add_argument("--mesh-size", type=float, nargs="*", default=[0.1])
    ap.add_argument("--bulk-to-shear", type=float, nargs="+", default=[1000.0])
    ap.add_argument("--initial-step", type=float, default=1.0)
    ap.add_argument("--min-step", type=float, default=1.0 / 1024.0)
    ap.add_argument("--modes", action="store_true", help="lowest eigenvalues of the condensed stiffness at the stop")
    ap.add_argument("--upper-every", type=int, nargs="+", default=[1],
                    help="mesh the upper curve through every k-th characteristic point (k = 1: all, 0.39 mm apart)")
    ap.add_argument("--trend", action="store_true", help="lowest eigenvalue of S at every converged load")
    ap.add_argument("--calculix", type=float, nargs="*", default=[], help="ccx mesh sizes to run")
    ap.add_argument("--at", type=float, default=None,
                    help="load (fraction) at which to read CalculiX; by default where the last reference run stopped")
    args = ap.parse_args(argv)
    problem = sd.load_case(args.case)
    law = VolumeRatio(1.0) if problem.revolution is not None else AreaRatio(1.0)
    case = problem.replace(bodies=tuple(dataclasses.replace(b, law=law) for b in problem.bodies))
    last = None
    for h, k, every in itertools.product(args.mesh_size, args.bulk_to_shear, args.upper_every):
        r = run_reference(case, h, k, args.initial_step, args.min_step, modes=args.modes, trend=args.trend,
                          every=every)
        r["upper_every"] = every
        last = r
        keep = ("mesh_size", "upper_every", "kappa/mu", "initial_step", "min_step", "elements", "h", "seconds",
                "last_load_%", "finished", "min_stretch", "min_stretch_away_from_corners", "surface_stretch",
                "surface_stretch_at_top", "lowest_eigenvalue_by_load", "eigenvalues", "mode_peak_at",
                "mode_share_near_top",
                "refusals")
        print({key: r[key] for key in keep if key in r}, flush=True)
    at = args.at if args.at is not None else (last["last_load_%"] / 100.0 if last else 1.0)
    finals = []
    for h in args.calculix:
        c = run_calculix(case, h, at)
        finals.append(c["final"][4])
        text = {k: (v[:4] if k in ("near", "final") else v) for k, v in c.items() if k != "upper0"}
        text["note"] = "near/final: (time, smallest surface stretch, where, surface stretch at the top)"
        if last is not None and "upper" in last:
            # The reference's upper nodes that are characteristic points, and those points' images in CalculiX.
            d = np.hypot(*(last["upper0"][:, None, :] - c["upper0"][None, :, :]).transpose(2, 0, 1))
            mine, theirs = np.flatnonzero(d.min(axis=1) < 1e-9), d.argmin(axis=1)[d.min(axis=1) < 1e-9]
            key = "reference_at_its_stop_vs" if not last["finished"] else "reference_vs"
            picked = c["near"][4] if abs(c["near"][0] - at) < 0.01 else c["final"][4]
            when = "increment" if picked is c["near"][4] and not last["finished"] else "final"
            text[f"{key}_this_{when}_hausdorff_mm"] = compare_curves(last["upper"][mine], picked[theirs]).hausdorff
        if len(finals) > 1:
            text["final_vs_previous_mesh_mm"] = _fitted_distance(finals[-2], finals[-1])
        print(text, flush=True)


if __name__ == "__main__":
    main()
