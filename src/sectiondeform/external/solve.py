"""A case solved by CalculiX: deck out, ``ccx`` run, displacements back, a section result.

:func:`solve_calculix` writes the case's deck (:mod:`sectiondeform.external.deck`),
runs ``ccx`` (:mod:`sectiondeform.external.calculix`), reads the nodal
displacements of the last increment, and maps each characteristic point of
the case's upper curve through the deformed elements with their shape
functions (:mod:`sectiondeform.external.interpolate`). The
:class:`CalculixSolution` has the attributes ``validate`` reads from a
reference (``upper``, ``mesh``, ``area_final``...), and
:meth:`CalculixSolution.to_result` makes it a ``section-result/1``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..models.base import Info, MeshData, MeshQuality
from ..result import Result, ResultQuality
from ..section import build_section
from .calculix import SolverFailedError, run_ccx
from .deck import DEFAULT_ELEMENT, DEFAULT_MESH_SIZE, Deck, build_deck, deck_text
from .interpolate import map_points
from .mesh import element_areas

__all__ = ["CalculixSolution", "solve_calculix"]


@dataclass(frozen=True, eq=False)
class CalculixSolution:
    """The CalculiX solution of a case.

    Attributes
    ----------
    name, units : str
    deck : Deck
    upper : (m, 2) float64 ndarray
        Image of each upper characteristic point of the case, B' to A', units.
    initial_upper : (m, 2) float64 ndarray
    lower, initial_lower : (n_l, 2) float64 ndarray
        The support's nodes after and before, A to B, units.
    initial_mesh, mesh : MeshData
    area_initial, area_target, area_final : float
        Mesh areas (exact for the isoparametric elements), units².
    seconds : float
        Wall time, case to deformed upper points (deck, ccx, read-back).
    info : dict
        ``increments``, ``iterations``, ``cutbacks``, ``ccx_seconds``.
    warnings : tuple of str
    """

    name: str
    units: str
    deck: Deck
    upper: np.ndarray
    initial_upper: np.ndarray
    lower: np.ndarray
    initial_lower: np.ndarray
    initial_mesh: MeshData
    mesh: MeshData
    area_initial: float
    area_target: float
    area_final: float
    seconds: float
    info: dict = field(default_factory=dict)
    warnings: tuple = ()

    # What validate reads from a reference solution.
    @property
    def bulk_to_shear(self) -> float:
        return self.deck.bodies[0].bulk_to_shear

    @property
    def material(self):
        """The rubber of the (one) body: a model of :mod:`sectiondeform.materials.models`."""
        return self.deck.bodies[0].material

    @property
    def revolution(self) -> bool:
        """True for a body of revolution (an axisymmetric deck)."""
        return self.deck.axis is not None

    @property
    def volume_change(self) -> float:
        """(final − initial) / initial area: at area ratio 1, what compressibility gave up."""
        return (self.area_final - self.area_initial) / self.area_initial

    @property
    def elements(self) -> int:
        return len(self.deck.mesh.cells)

    @property
    def dofs(self) -> int:
        return int(2 * len(self.deck.mesh.points))

    @property
    def iterations(self) -> int:
        return int(self.info.get("iterations", 0))

    def _element_size(self) -> float:
        """Square root of the mean element area, units."""
        return float(np.sqrt(self.area_initial / max(self.elements, 1)))

    def summary(self) -> dict:
        """Scalar figures for reports."""
        return {"solver": "calculix", "element": self.deck.element.name, "elements": self.elements,
                "nodes": len(self.deck.mesh.points), "area_initial": self.area_initial,
                "area_final": self.area_final, "bulk_to_shear": self.bulk_to_shear, "seconds": self.seconds,
                **self.info, "warnings": list(self.warnings)}

    def to_result(self) -> Result:
        """The solution as a :class:`~sectiondeform.result.Result` (model ``"calculix"``)."""
        return Result(
            name=self.name, units=self.units, model="calculix", lower=self.lower, upper=self.upper,
            initial_lower=self.initial_lower, initial_upper=self.initial_upper,
            area_initial=self.area_initial, area_target=self.area_target, area_final=self.area_final,
            initial_mesh=self.initial_mesh, final_mesh=self.mesh,
            quality=ResultQuality(MeshQuality(elements=self.elements, element_size=self._element_size())),
            info=CalculixInfo(element_type=self.deck.element.name, **self.info), timings={"solve_s": self.seconds},
            warnings=self.warnings,
        )


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


def solve_calculix(case, *, element: str = DEFAULT_ELEMENT, mesh_size: float = DEFAULT_MESH_SIZE,
                   progress=None, keep=None, timeout=None) -> CalculixSolution:
    """Solve a case with CalculiX.

    Parameters
    ----------
    case : Case
    element : str
        Element type (CalculiX has no hybrid ones).
    mesh_size : float
        Triangle size over the section's mesh scale.
    progress : callable, optional
        One line per stage and ccx increment.
    keep : Path, optional
        Folder to copy the ccx job files into.
    timeout : float, optional
        Seconds after which ccx is stopped (:class:`SolverFailedError`).

    Returns
    -------
    CalculixSolution

    Raises
    ------
    SolverNotFoundError, SolverFailedError
        Without ``ccx``, or when it fails.
    CaseError
        For a bad element or mesh size.
    """
    t0 = time.perf_counter()
    deck = build_deck(case, element, mesh_size)
    if not deck.element.calculix:
        raise SolverFailedError(f"CalculiX 2.20 has no hybrid elements such as {deck.element.name}; use CPE6 or CPE8R")
    m = deck.mesh
    if progress is not None:
        progress(f"calculix: {len(m.cells)} {deck.element.name} elements, {len(m.points)} nodes")
    results, info = run_ccx(deck_text(deck), job="section", progress=progress, keep=keep, timeout=timeout)
    _, ids, disp = results.last("DISP")
    u = np.zeros((len(m.points), 2))
    if ids.min() < 1 or ids.max() > len(m.points):
        raise SolverFailedError("ccx returned displacements of nodes the deck does not have")
    u[ids - 1] = disp[:, :2]
    final = deck.placed_points + u
    section = build_section(case)
    upper0 = np.asarray(section.upper, dtype=np.float64)
    upper = map_points(m.points, final, m.cells, m.kind, upper0)
    area1 = element_areas(final, m.cells, m.corners)
    if area1.min() <= 0:
        raise SolverFailedError(f"ccx's deformed mesh has {int((area1 <= 0).sum())} inverted elements")
    seconds = time.perf_counter() - t0
    for arr in (upper, final):
        arr.setflags(write=False)
    return CalculixSolution(
        name=case.name, units=case.units, deck=deck, upper=upper, initial_upper=upper0,
        lower=final[m.lower_nodes], initial_lower=m.points[m.lower_nodes],
        initial_mesh=MeshData(m.points, m.cells, m.kind), mesh=MeshData(final, m.cells, m.kind),
        area_initial=deck.area_initial, area_target=deck.area_target, area_final=float(area1.sum()),
        seconds=seconds, info={**{k: v for k, v in info.items() if k != "seconds"}, "ccx_seconds": info["seconds"]},
        warnings=deck.unexpressed,
    )
