"""The fast method against CalculiX on one case (``sectiondeform validate --reference calculix``).

The same :class:`~sectiondeform.reference.validation.Validation` as against
the project's own finite elements, with a :class:`~sectiondeform.external.solve.CalculixSolution`
as the reference: it has the attributes the report and the figure read.
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from ..compare import compare_curves, section_height
from ..deform import Deformer
from ..section import polygon_area
from .deck import DEFAULT_MESH_SIZE
from .solve import solve_calculix

__all__ = ["validate_with_calculix"]


def validate_with_calculix(case, *, model: str | None = None, mesh_size: float | None = None, fast_runs: int = 5,
                           progress=None):
    """Run the fast model and CalculiX on a case and compare the deformed upper curves.

    Parameters
    ----------
    case : Case
    model : str, optional
        ``"paper"`` or ``"hyperelastic"``; by default the case's.
    mesh_size : float, optional
        CalculiX triangle size over the mean thickness (default 0.1).
    fast_runs : int
        Runs of the fast model; its time is their median.
    progress : callable, optional

    Returns
    -------
    Validation
    """
    from ..reference.validation import Validation

    times, fast = [], None
    for _ in range(max(1, int(fast_runs))):
        t0 = time.perf_counter()
        fast = Deformer(case, model=model).deform()
        times.append(time.perf_counter() - t0)
    ref = solve_calculix(case, mesh_size=DEFAULT_MESH_SIZE if mesh_size is None else mesh_size, progress=progress)
    if progress is not None:
        for line in ref.warnings:
            progress(f"validate: warning: {line}")
    thickness = fast.area_initial / case.lower.length
    return Validation(
        case=case, fast=fast, reference=ref, shape=compare_curves(fast.upper, ref.upper, scale=thickness),
        thickness=thickness, height=section_height(fast.initial_lower, fast.initial_upper),
        area_reference=ref.area_final,
        area_reference_polygon=abs(polygon_area(np.concatenate((fast.lower, ref.upper[1:-1])))),
        fast_seconds=statistics.median(times), reference_seconds=ref.seconds,
    )
