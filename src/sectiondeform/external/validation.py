"""CalculiX as the reference of ``sectiondeform validate --reference calculix``.

:func:`calculix_run` solves the problem with CalculiX
(:func:`~sectiondeform.external.solve.solve_calculix`) and hands it to
:func:`~sectiondeform.reference.validation.validate` as a
:class:`~sectiondeform.reference.validation.ReferenceRun`: the same
validation, body by body, as against the project's own finite elements.
"""

from __future__ import annotations

from ..reference.validation import ReferenceRun
from .deck import DEFAULT_MESH_SIZE
from .solve import solve_calculix

__all__ = ["calculix_run"]


def calculix_run(problem, *, mesh_size: float | None = None, element: str | None = None, progress=None) -> ReferenceRun:
    """Solve a problem with CalculiX, as a reference for :func:`~sectiondeform.reference.validation.validate`.

    Parameters
    ----------
    problem : Problem
        One body or several, plane or of revolution.
    mesh_size : float, optional
        Triangle size over each body's mesh scale (default 0.1).
    element : str, optional
        By default CPE6, or CAX6 for bodies of revolution.
    progress : callable, optional
        One line per stage and ccx increment, and the deck's warnings.

    Returns
    -------
    ReferenceRun

    Raises
    ------
    SolverNotFoundError, SolverFailedError
        Without ``ccx``, or when it fails.
    """
    result = solve_calculix(problem, element=element, mesh_size=DEFAULT_MESH_SIZE if mesh_size is None else mesh_size,
                            progress=progress)
    if progress is not None:
        for line in result.warnings:
            progress(f"validate: warning: {line}")
    info = result.bodies[0].info
    rubbers = ", ".join(dict.fromkeys(b.material_data.get("model", "neo-hookean") for b in problem.bodies))
    kind = "axisymmetric" if problem.revolution is not None else "plane strain"
    elements = sum(b.quality.initial.elements for b in result.bodies)
    summary = {"solver": "calculix", "element": info.element_type, "elements": elements,
               "increments": info.increments, "iterations": info.iterations, "cutbacks": info.cutbacks,
               "ccx_seconds": info.ccx_seconds, "seconds": result.timings["solve_s"], "warnings": list(result.warnings),
               "bodies": [{"name": b.name, "area_initial": b.area_initial, "area_final": b.area_final,
                           "relative_error": b.relative_error} for b in result.bodies]}
    return ReferenceRun(solution=result, bodies=result.bodies, meshes=tuple(b.final_mesh for b in result.bodies),
                        model=f"CalculiX: {rubbers}, {kind}, {info.element_type}", summary=summary,
                        note=f"{elements} {info.element_type} elements, {info.increments} increments, "
                             f"{info.iterations} iterations",
                        seconds=result.timings["solve_s"])

