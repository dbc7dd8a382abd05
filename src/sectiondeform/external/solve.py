"""A problem solved by CalculiX: deck out, ``ccx`` run, displacements back, a :class:`~sectiondeform.result.Result`.

:func:`solve_calculix` writes the problem's deck (:func:`~sectiondeform.external.deck.build_deck`),
runs ``ccx`` (:mod:`sectiondeform.external.calculix`) and reads the nodal
displacements of the last increment (in (r, z) for bodies of revolution,
mapped back to the case's plane). Per body, its lower nodes, its upper
characteristic points and its contour (also through the points where other
bodies rest on it) are mapped through that body's deformed elements with
their shape functions (:mod:`sectiondeform.external.interpolate`), so a
point of a shared piece has one image for both bodies (the shape functions
agree on a shared edge). Areas are those of the isoparametric elements; for
a body of revolution the volume is 2π ∫ r dA over them (Green's theorem on
each element edge, exact for quadratic edges with three Gauss points). The
result is written in the problem's dialect (``section-result/1`` for a
``section-case/1`` problem).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import shapely

from ..models.base import Info, MeshData, MeshQuality
from ..problem import V1
from ..result import RESULT_V1, RESULT_V2, BodyResult, Result, ResultQuality
from ..section import build_section
from .calculix import SolverFailedError, run_ccx
from .deck import DEFAULT_MESH_SIZE, Deck, build_deck, deck_text
from .interpolate import map_points
from .mesh import element_areas

__all__ = ["CalculixInfo", "revolved_volumes", "solve_calculix"]


@dataclass(frozen=True)
class CalculixInfo(Info):
    """Figures of a CalculiX run.

    Attributes
    ----------
    solver : str
        ``"calculix"``.
    element_type : str
        Abaqus/CalculiX element type of the deck (``"CPE6"``...).
    increments, iterations, cutbacks : int
        Load increments, Newton iterations and increment cut-backs of ``ccx``.
    ccx_seconds : float
        Wall time of the ``ccx`` process, s.
    """

    element_type: str
    increments: int = 0
    iterations: int = 0
    cutbacks: int = 0
    ccx_seconds: float = 0.0
    solver: str = "calculix"


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


def _displacements(deck: Deck, results) -> np.ndarray:
    """The deformed nodes of the deck's mesh in the case's plane, ``(N, 2)``."""
    m = deck.mesh
    _, ids, disp = results.last("DISP")
    if deck.rigid:  # the rigid parts' nodes follow the bodies' in the deck
        keep = ids <= len(m.points)
        ids, disp = ids[keep], disp[keep]
    if ids.min() < 1 or ids.max() > len(m.points):
        raise SolverFailedError("ccx returned displacements of nodes the deck does not have")
    u = np.zeros((len(m.points), 2))
    u[ids - 1] = disp[:, :2]
    if deck.axis is not None:  # (u_r, u_z) back to the case's plane
        u = deck.axis.from_rz(u) - np.asarray(deck.axis.origin)
    return deck.placed_points + u


def _body(problem, deck: Deck, i: int, final: np.ndarray, info: CalculixInfo) -> BodyResult:
    """Body ``i``'s result: its points mapped through its deformed elements, its areas and volumes."""
    m = deck.mesh
    elements = deck.bodies[i].elements
    cells = m.cells[elements]
    section = build_section(problem.body_case(i))
    resting = [np.asarray(build_section(problem.body_case(j)).lower) for j in problem.layout.resting_on(i)]
    contour0 = _contour_points(section, resting, problem.layout.tolerance)
    upper0 = np.asarray(section.upper, dtype=np.float64)
    lower0 = np.asarray(section.lower, dtype=np.float64)
    holes0 = tuple(np.asarray(h, dtype=np.float64) for h in section.holes)
    mapped = [map_points(m.points, final, cells, m.kind, p) for p in (lower0, upper0, contour0, *holes0)]
    p0, c = _compact(m.points, cells)
    p1, _ = _compact(final, cells)
    area0 = float(element_areas(p0, c, m.corners).sum())
    area1 = float(element_areas(p1, c, m.corners).sum())
    law = problem.bodies[i].law
    volumes = {}
    if deck.axis is not None:
        sign = -1.0 if deck.axis.mirrored else 1.0
        v0, v1 = (sign * float(revolved_volumes(deck.axis.to_rz(p), c, m.corners).sum()) for p in (p0, p1))
        volumes = {"volume_initial": v0, "volume_final": v1}
        if law.measure == "volume":
            volumes["volume_target"] = law.ratio * v0
    for arr in (*mapped, p1):
        arr.setflags(write=False)
    return BodyResult(
        name=problem.bodies[i].name, lower=mapped[0], upper=mapped[1], contour=mapped[2],
        initial_lower=lower0, initial_upper=upper0, initial_contour=contour0,
        area_initial=area0, area_target=law.target_area(area0) if law.measure == "area" else None,
        area_final=area1, initial_mesh=MeshData(p0, c, m.kind), final_mesh=MeshData(p1, c, m.kind),
        quality=ResultQuality(MeshQuality(elements=len(c), element_size=float(np.sqrt(area0 / max(len(c), 1))))),
        info=info, holes=tuple(mapped[3:]), initial_holes=holes0, **volumes,
    )


def solve_calculix(problem, *, element: str | None = None, mesh_size: float = DEFAULT_MESH_SIZE,
                   progress=None, keep=None, timeout=None, contact_penalty=None) -> Result:
    """Solve a problem with CalculiX.

    Parameters
    ----------
    problem : Problem
        One body or several, plane or of revolution.
    element : str, optional
        By default CPE6, or CAX6 for bodies of revolution (CalculiX has no hybrid elements).
    mesh_size : float
        Triangle size over each body's mesh scale.
    progress : callable, optional
        One line per stage and ccx increment.
    keep : Path, optional
        Folder to copy the ccx job files into.
    timeout : float, optional
        Seconds after which ccx is stopped (:class:`SolverFailedError`).
    contact_penalty : float or "hard", optional
        With rigid parts: the contact's penalty slope (see :func:`~.deck.build_deck`).

    Returns
    -------
    Result
        Model ``"calculix"``, one body per body of the problem (with volumes
        for bodies of revolution), in the problem's dialect; with rigid
        parts, their forces and contact (``rigid``), the support's force and
        the forces at every increment (``history``).

    Raises
    ------
    SolverNotFoundError, SolverFailedError
        Without ``ccx``, when it fails, or when its mesh comes back inverted.
    CaseError
        For a bad element or mesh size.
    """
    t0 = time.perf_counter()
    deck = build_deck(problem, element, mesh_size, contact_penalty)
    el, m = deck.element, deck.mesh
    if not el.calculix:
        raise SolverFailedError(f"CalculiX 2.20 has no hybrid elements such as {el.name}; use {el.name[:3]}6 or "
                                f"{el.name[:3]}8R")
    if progress is not None:
        progress(f"calculix: {len(m.cells)} {el.name} elements in {len(deck.bodies)} "
                 f"bod{'y' if len(deck.bodies) == 1 else 'ies'}, {len(m.points)} nodes")
    results, run = run_ccx(deck_text(deck), job="section", progress=progress, keep=keep, timeout=timeout)
    final = _displacements(deck, results)
    inverted = int((element_areas(final, m.cells, m.corners) <= 0).sum())
    if inverted:
        raise SolverFailedError(f"ccx's deformed mesh has {inverted} inverted elements")
    info = CalculixInfo(element_type=el.name, **{k: v for k, v in run.items() if k not in ("seconds", "dat")},
                        ccx_seconds=run["seconds"])
    bodies = tuple(_body(problem, deck, i, final, info) for i in range(len(problem.bodies)))
    contact, warnings = {}, deck.unexpressed
    if deck.rigid:  # the parts' forces from the .dat, the contact pressures from the .frd
        from .contact_read import AXISYMMETRIC_NOTE, contact_of_parts

        parts, support, history = contact_of_parts(deck, results, final, run["dat"])
        contact = {"rigid": parts, "support_force": support, "history": history}
        if deck.axis is not None:
            warnings = (*warnings, AXISYMMETRIC_NOTE)
    return Result(name=problem.name, units=problem.units, model="calculix", bodies=bodies,
                  timings={"solve_s": time.perf_counter() - t0}, warnings=tuple(warnings),
                  axis=problem.revolution.axis if problem.revolution is not None else None,
                  dialect=RESULT_V1 if problem.dialect == V1 else RESULT_V2, **contact)
