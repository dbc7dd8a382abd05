"""A version-2 case (bonded bodies, bodies of revolution) solved by CalculiX, as a ``section-result/2``.

The deck is :func:`~sectiondeform.external.deck.build_assembly_deck`; ``ccx``
runs it; the nodal displacements of the last increment (in (r, z) for a
body of revolution, mapped back to the case's plane) move the mesh. Per
body, its lower nodes, its upper characteristic points and its contour (also
through the points where other bodies rest on it) are mapped through that
body's deformed elements with their shape functions, so a point of a shared
piece has one image for both bodies (the shape functions agree on a shared
edge). Areas are those of the isoparametric elements; for a body of
revolution the volume is 2π ∫ r dA over them (Green's theorem on each
element edge, exact for quadratic edges with three Gauss points).
"""

from __future__ import annotations

import time

import numpy as np
import shapely

from ..assembly_result import AssemblyResult, BodyResult
from ..models.base import MeshData, MeshQuality
from ..result import ResultQuality
from ..section import build_section
from .calculix import SolverFailedError, run_ccx
from .deck import DEFAULT_MESH_SIZE, build_assembly_deck, deck_text
from .interpolate import map_points
from .mesh import element_areas
from .solve import CalculixInfo

__all__ = ["revolved_volumes", "solve_calculix_assembly"]

_GAUSS = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


def revolved_volumes(rz: np.ndarray, cells: np.ndarray, corners: int) -> np.ndarray:
    """2π ∫ r dA of each element in the (r, z) plane, ``(M,)``, units³ (signed: positive when counter-clockwise).

    Green's theorem, ∫∫ r dr dz = ∮ r²/2 dz, on each edge (corner, mid-edge
    node, corner) as a quadratic curve; a straight edge takes its middle.

    Examples
    --------
    >>> sq = np.array([[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]])  # r from 1 to 2, z from 0 to 1
    >>> round(float(revolved_volumes(sq, np.array([[0, 1, 2, 3]]), 4)[0] / np.pi), 12)  # π (2² − 1²)
    3.0
    """
    rz = np.asarray(rz, dtype=np.float64)
    a = rz[cells[:, :corners]]
    b = rz[np.roll(cells[:, :corners], -1, axis=1)]
    m = rz[cells[:, corners:2 * corners]] if cells.shape[1] == 2 * corners else 0.5 * (a + b)
    total = np.zeros(len(cells))
    for t, w in zip(*_GAUSS):
        x = a * (t * (t - 1) / 2) + m * (1 - t * t) + b * (t * (t + 1) / 2)
        dx = a * (t - 0.5) - 2 * m * t + b * (t + 0.5)
        total += w * np.sum(0.5 * x[..., 0] ** 2 * dx[..., 1], axis=1)
    return 2.0 * np.pi * total


def _compact(points: np.ndarray, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The nodes a set of cells uses, and the cells renumbered to them."""
    used, inverse = np.unique(cells, return_inverse=True)
    return points[used], inverse.reshape(cells.shape).astype(np.int64)


def _contour_points(section, resting_lowers, tol: float) -> np.ndarray:
    """A body's initial contour: lower nodes, then its upper points with the points resting on it inserted."""
    upper = np.asarray(section.upper, dtype=np.float64)
    line = shapely.LineString(upper)
    extra = [p[shapely.distance(shapely.points(p), line) <= tol] for p in resting_lowers]
    extra = np.concatenate(extra) if extra else np.zeros((0, 2))
    if len(extra):
        pos = np.concatenate((shapely.line_locate_point(line, shapely.points(upper)),
                              shapely.line_locate_point(line, shapely.points(extra))))
        allp = np.concatenate((upper, extra))[np.argsort(pos, kind="stable")]
        keep = np.concatenate(([True], np.hypot(*np.diff(allp, axis=0).T) > tol))
        upper = allp[keep]
    return np.concatenate((np.asarray(section.lower, dtype=np.float64), upper[1:-1]))


def solve_calculix_assembly(fe, *, element: str | None = None, mesh_size: float = DEFAULT_MESH_SIZE,
                            progress=None, keep=None, timeout=None) -> AssemblyResult:
    """Solve a version-2 case with CalculiX.

    Parameters
    ----------
    fe : FeAssembly
    element : str, optional
        By default CPE6, or CAX6 for a body of revolution.
    mesh_size : float
        Triangle size over each body's mean thickness.
    progress : callable, optional
    keep : Path, optional
        Folder to copy the ccx job files into.
    timeout : float, optional
        Seconds after which ccx is stopped (:class:`SolverFailedError`).

    Returns
    -------
    AssemblyResult
        Model ``"calculix"``; bodies are :class:`~sectiondeform.assembly_result.BodyResult` (with volumes for bodies of revolution).

    Raises
    ------
    SolverNotFoundError, SolverFailedError
        Without ``ccx``, when it fails, or when its mesh comes back inverted.
    """
    t0 = time.perf_counter()
    deck = build_assembly_deck(fe, element, mesh_size)
    el, m = deck.element, deck.mesh
    if not el.calculix:
        raise SolverFailedError(f"CalculiX 2.20 has no hybrid elements such as {el.name}; use {el.name[:3]}6 or "
                                f"{el.name[:3]}8R")
    if progress is not None:
        progress(f"calculix: {len(m.cells)} {el.name} elements in {len(deck.bodies)} bodies, {len(m.points)} nodes")
    results, info = run_ccx(deck_text(deck), job="assembly", progress=progress, keep=keep, timeout=timeout)
    _, ids, disp = results.last("DISP")
    if ids.min() < 1 or ids.max() > len(m.points):
        raise SolverFailedError("ccx returned displacements of nodes the deck does not have")
    u = np.zeros((len(m.points), 2))
    u[ids - 1] = disp[:, :2]
    if deck.axis is not None:  # (u_r, u_z) back to the case's plane
        u = deck.axis.from_rz(u) - np.asarray(deck.axis.origin)
    final = deck.placed_points + u
    areas0 = element_areas(m.points, m.cells, m.corners)
    areas1 = element_areas(final, m.cells, m.corners)
    if areas1.min() <= 0:
        raise SolverFailedError(f"ccx's deformed mesh has {int((areas1 <= 0).sum())} inverted elements")
    a = fe.assembly
    ccx_info = {k: v for k, v in info.items() if k != "seconds"}
    bodies = []
    for i, (body, law) in enumerate(zip(deck.bodies, fe.laws)):
        cells = m.cells[body.elements]
        section = build_section(a.body_case(i))
        resting = [np.asarray(build_section(a.body_case(j)).lower) for j in a.layout.resting_on(i)]
        contour0 = _contour_points(section, resting, a.layout.tolerance)
        upper0 = np.asarray(section.upper, dtype=np.float64)
        lower0 = np.asarray(section.lower, dtype=np.float64)
        mapped = [map_points(m.points, final, cells, m.kind, p) for p in (lower0, upper0, contour0)]
        p0, c = _compact(m.points, cells)
        p1, _ = _compact(final, cells)
        area0, area1 = float(areas0[body.elements].sum()), float(areas1[body.elements].sum())
        volumes = {}
        if deck.axis is not None:
            v0 = revolved_volumes(deck.axis.to_rz(p0), c, m.corners)
            v1 = revolved_volumes(deck.axis.to_rz(p1), c, m.corners)
            sign = -1.0 if deck.axis.mirrored else 1.0
            volumes = {"volume_initial": sign * float(v0.sum()), "volume_final": sign * float(v1.sum())}
            if law.key == "volume_ratio":
                volumes["volume_target"] = law.ratio * volumes["volume_initial"]
        for arr in (*mapped, p1):
            arr.setflags(write=False)
        bodies.append(BodyResult(
            name=a.bodies[i].name, lower=mapped[0], upper=mapped[1], contour=mapped[2],
            initial_lower=lower0, initial_upper=upper0, initial_contour=contour0,
            area_initial=area0, area_target=law.ratio * area0 if law.key == "area_ratio" else None,
            area_final=area1, initial_mesh=MeshData(p0, c, m.kind), final_mesh=MeshData(p1, c, m.kind),
            quality=ResultQuality(MeshQuality(elements=len(c), element_size=float(np.sqrt(area0 / max(len(c), 1))))),
            info=CalculixInfo(element_type=el.name, **ccx_info, ccx_seconds=info["seconds"]),
            **volumes,
        ))
    seconds = time.perf_counter() - t0
    return AssemblyResult(name=a.name, units=a.units, model="calculix", bodies=tuple(bodies),
                          timings={"solve_s": seconds}, warnings=deck.unexpressed)
