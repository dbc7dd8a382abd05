"""Independent checks of a result: what a correct deformation must satisfy, recomputed from its output.

The checks use only the result's points and meshes and the case's curves,
never the model's own figures, so the fuzz tests, ``validate`` and the
command line can share them:

- ``finite``: no NaN or infinity in points, meshes or areas;
- ``area_law``: the area of the deformed contour, recomputed from the output
  points, meets the law's target area within :data:`AREA_LAW_TOLERANCE`,
  and the reported final area is that area;
- ``initial_area``: the initial contour's area is within
  :data:`INITIAL_AREA_TOLERANCE` of the curves' exact area (Green's theorem);
- ``simple``: the deformed contour is a simple polygon (shapely);
- ``ends``: the deformed lower curve starts and ends on the target's ends, and
  the upper points run from its end back to its start;
- ``upper_on_curve``: the initial upper points lie on the case's upper curve:
  within twice the chordal error of a polyline of it at a quarter of the
  case's nominal chordal error, plus rounding;
- ``inverted``: no element of either mesh is inverted anywhere: for the P2
  triangles ``det J > 0`` at the corners, the mid-edge nodes and the
  quadrature points; for bilinear quads at the corners (enough: ``det J`` is
  linear there).

>>> import sectiondeform as sd
>>> case = sd.load_case(sd.example_case_path())
>>> check_result(sd.deform(case), case)
[]
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from .curves import DEFAULT_CHORDAL_FRACTION
from .errors import SectionDeformError

__all__ = [
    "AREA_LAW_TOLERANCE",
    "INITIAL_AREA_TOLERANCE",
    "area_of",
    "check_result",
    "det_j_p2",
    "det_j_quads",
]

AREA_LAW_TOLERANCE = 1e-8
"""Relative tolerance of the area law recomputed from the output points (the models meet 1e-9)."""

INITIAL_AREA_TOLERANCE = 2e-5
"""Relative tolerance of the initial contour's area against the curves' exact area.

The section refines its discretisation until the polygon is within 1e-5 of
the exact area; the final discretisation only adds lower nodes, which can
move the area by rounding, hence twice that.
"""

ENDS_TOLERANCE = 1e-7
"""Distance, relative to the section's size, within which two points are the same."""

# Triangle points (xi, eta) where det J of a P2 triangle is tested: corners,
# mid-edges, centroid, the 6-point rule's points.
_A, _B = 0.445948490915965, 0.091576213509771
_P2_PROBES = np.array(
    [[0, 0], [1, 0], [0, 1], [0.5, 0], [0.5, 0.5], [0, 0.5], [1 / 3, 1 / 3],
     [_A, _A], [1 - 2 * _A, _A], [_A, 1 - 2 * _A], [_B, _B], [1 - 2 * _B, _B], [_B, 1 - 2 * _B]],
    dtype=np.float64,
)


def area_of(points: np.ndarray) -> float:
    """Unsigned area of a closed polygon, shoelace about the mean point, with ``math.fsum``.

    Parameters
    ----------
    points : (N, 2) float64 ndarray

    Returns
    -------
    float
        Area, units².

    Examples
    --------
    >>> area_of(np.array([[1e8, 1e8], [1e8 + 2, 1e8], [1e8 + 2, 1e8 + 1], [1e8, 1e8 + 1]]))
    2.0
    """
    p = points - points.mean(axis=0)
    q = np.roll(p, -1, axis=0)
    return abs(0.5 * math.fsum((p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]).tolist()))


def det_j_p2(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Det J of six-node triangles at :data:`_P2_PROBES`, ``(M, 13)``.

    ``cells`` is ``(M, 6)``: corners counter-clockwise, then the mid-nodes of
    edges 0-1, 1-2, 2-0 (meshio's ``triangle6``).
    """
    m = len(cells)
    x = points[cells.T].reshape(6, 2 * m)  # node k of every cell, x and y interleaved
    jx = (_P2_DXI @ x).reshape(-1, m, 2)  # (13, M, 2): one product, not M small ones
    je = (_P2_DETA @ x).reshape(-1, m, 2)
    return (jx[..., 0] * je[..., 1] - jx[..., 1] * je[..., 0]).T


def _p2_shape_derivatives(probes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """dN/dxi and dN/deta of the six P2 shape functions at ``probes``, each ``(P, 6)``."""
    xi, eta = probes[:, 0], probes[:, 1]
    l0, l1, l2 = 1.0 - xi - eta, xi, eta
    dxi = np.stack([-(4 * l0 - 1), 4 * l1 - 1, 0 * xi, 4 * (l0 - l1), 4 * l2, -4 * l2], axis=1)
    deta = np.stack([-(4 * l0 - 1), 0 * xi, 4 * l2 - 1, -4 * l1, 4 * l1, 4 * (l0 - l2)], axis=1)
    return dxi, deta


_P2_DXI, _P2_DETA = _p2_shape_derivatives(_P2_PROBES)


_NEXT, _PREV = [1, 2, 3, 0], [3, 0, 1, 2]


def det_j_quads(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Twice the corner triangle areas of counter-clockwise quads, ``(M, 4)`` (det J at the corners, x4)."""
    x = points[cells]
    a, b = x[:, _NEXT] - x, x[:, _PREV] - x
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def inverted(mesh) -> str | None:
    """What is inverted in ``mesh`` (a :class:`~sectiondeform.models.base.MeshData`), as one line, or None."""
    return _inverted(mesh)


def check_placement(result) -> list[str]:
    """The checks of :func:`check_result` that a new placement of a prepared section can fail.

    Used on every deformation, where the rest is known already: the area
    law and the simple contour are checked by the deformer itself, and the
    initial mesh once per section. Finite values, and no final element
    inverted anywhere.
    """
    if not (np.isfinite(result.upper).all() and np.isfinite(result.final_mesh.points).all()):
        return ["finite: the result holds NaN or infinite values"]
    final = result.quality.final if result.quality is not None else None
    if result.final_mesh.kind == "quad" and final is not None and final.jacobian_min is not None:
        # A bilinear quad is sound iff its four corner Jacobians are > 0, which the layered
        # model has just computed for its own refusal: the same figure, not recomputed.
        ok = final.jacobian_min > 0
        return [] if ok else [f"final_mesh: quad elements inverted (smallest corner Jacobian {final.jacobian_min:.3g})"]
    bad = _inverted(result.final_mesh)
    return [f"final_mesh: {bad}"] if bad else []


def _inverted(mesh) -> str | None:
    cells, pts = np.asarray(mesh.cells), np.asarray(mesh.points)
    if len(cells) == 0:
        return None
    if mesh.kind == "triangle6":
        det = det_j_p2(pts, cells)
    elif mesh.kind == "quad":
        det = det_j_quads(pts, cells)
    elif mesh.kind == "triangle":
        det = det_j_quads(pts, cells)[:, :1]
    else:
        return None
    bad = ~(det > 0).all(axis=1)
    if bad.any():
        return f"{int(bad.sum())}/{len(cells)} {mesh.kind} elements inverted (det J <= 0 on part of element {int(np.argmax(bad))})"
    return None


def _distance_to_polyline(points: np.ndarray, line: np.ndarray) -> np.ndarray:
    return shapely.distance(shapely.points(points), shapely.linestrings(line))


def check_result(result, case=None) -> list[str]:
    """Every failed check of ``result``, as one-line strings; empty when it passes.

    Parameters
    ----------
    result : Result
    case : Case, optional
        The case deformed; enables the checks against its curves (initial
        area, upper points on the upper curve, lower on the target).

    Returns
    -------
    list of str
    """
    fails = []
    arrays = [result.lower, result.upper, result.initial_lower, result.initial_upper,
              result.initial_mesh.points, result.final_mesh.points]
    scalars = [result.area_initial, result.area_target, result.area_final]
    if not all(np.isfinite(np.asarray(a, dtype=np.float64)).all() for a in arrays) or not np.isfinite(scalars).all():
        return ["finite: the result holds NaN or infinite values"]
    contour, initial = result.contour, result.initial_contour
    size = float(np.hypot(*np.ptp(np.concatenate((contour, initial)), axis=0)))
    final = area_of(contour)
    if abs(final - result.area_target) > AREA_LAW_TOLERANCE * result.area_target:
        fails.append(f"area_law: final {final!r} vs target {result.area_target!r}")
    if abs(final - result.area_final) > AREA_LAW_TOLERANCE * final:
        fails.append(f"area_reported: reported {result.area_final!r} vs recomputed {final!r}")
    # The reported initial area is the curves' exact one (the law holds against it); the initial contour is
    # their polygon within the chordal error, so the two agree to the section's area tolerance, not to 1e-8.
    if abs(area_of(initial) - result.area_initial) > INITIAL_AREA_TOLERANCE * result.area_initial:
        fails.append(f"initial_reported: reported {result.area_initial!r} vs recomputed {area_of(initial)!r}")
    if not shapely.is_simple(shapely.linearrings(contour)):
        fails.append("simple: the deformed contour crosses itself")
    tol = ENDS_TOLERANCE * size
    lo, up = result.lower, result.upper
    if np.hypot(*(up[0] - lo[-1])) > tol or np.hypot(*(up[-1] - lo[0])) > tol:
        fails.append("ends: the upper points do not run from the lower curve's end back to its start")
    for mesh, name in ((result.initial_mesh, "initial_mesh"), (result.final_mesh, "final_mesh")):
        bad = _inverted(mesh)
        if bad:
            fails.append(f"{name}: {bad}")
    if case is not None:
        fails.extend(_case_checks(result, case, size))
    return fails


def _case_checks(result, case, size: float) -> list[str]:
    fails = []
    # About the lower curve's start: in absolute coordinates far from the origin, rounding dominates.
    about = -np.asarray(case.lower.ends[0], dtype=np.float64)
    exact = abs(case.lower.transformed(np.eye(2), about).green() + case.upper.transformed(np.eye(2), about).green())
    if abs(result.area_initial - exact) > INITIAL_AREA_TOLERANCE * exact:
        fails.append(f"initial_area: {result.area_initial!r} vs the curves' exact area {exact!r}")
    tol = 1e-6 * size
    t0, t1 = case.target.start, case.target.end
    if np.hypot(*(result.lower[0] - t0)) > tol or np.hypot(*(result.lower[-1] - t1)) > tol:
        fails.append("ends: the deformed lower curve does not start and end on the target's ends")
    scale = float(np.hypot(*np.ptp(result.initial_contour, axis=0)))
    off, slack = _off_curve(result.initial_upper, case, scale, size)
    if off.max() > slack:
        i = int(np.argmax(off))
        fails.append(f"upper_on_curve: initial upper point {i} is {off[i]:.3g} from the upper curve (allowed {slack:.3g})")
    return fails


def _off_curve(points: np.ndarray, case, scale: float, size: float) -> tuple[np.ndarray, float]:
    """Distances of ``points`` to the case's upper curve, ``(m,)``, and the distance allowed.

    The upper points are points of the curve, so their distance to a
    polyline of the curve within chordal error ``e`` is at most ``e`` (twice
    that allowed: the discretisation probes its chords at three points), plus
    rounding. ``e`` is a quarter of the case's nominal chordal error
    (``options.chordal_error``, or :data:`~sectiondeform.curves.DEFAULT_CHORDAL_FRACTION`
    of ``scale``, the initial section's diagonal), recomputed here, not read
    from the model; ``size`` sets the rounding.
    """
    nominal = case.options.chordal_error
    if nominal is None:
        nominal = DEFAULT_CHORDAL_FRACTION * scale
    e = 0.25 * float(nominal)
    rounding = 1e-9 * size
    try:
        line, _ = case.upper.discretise(e)
    except SectionDeformError:  # over the curve's point bound at e: fall back to a dense sampling
        line = case.upper.at_fractions(np.linspace(0.0, 1.0, 4097))
        seg = np.hypot(*np.diff(line, axis=0).T)
        return _distance_to_polyline(points, line), max(float(seg.max(initial=0.0)), rounding)
    return _distance_to_polyline(points, line), 2.0 * e + rounding
