"""The reference's check on a body of revolution: a thick incompressible ring expanded radially.

The section is the annular rectangle A ≤ y ≤ A + t, 0 ≤ x ≤ L, of a ring
about the x axis; its inner surface (the lower curve) is bonded to the
radius a, the rest is free. Far from the free ends nothing depends on x and
the ring does not move axially, so the volume between the inner surface and
any material radius R is kept (times v, the volume law):

    r(R)² − a² = v (R² − A²)      (every annular strip keeps area × radius).

Two figures are measured on the reference solution:

- the largest distance of a node of the middle part (|x − L/2| ≤ t) from
  that closed form, over t (the free ends, 11 t away, disturb it by about
  2e-5 t there: the end effect decays like exp(−0.8 z / t));
- the largest relative error of the Pappus volume of four strips of
  elements (by initial radius) against v × their initial volume, each
  computed from the deformed quadratic triangles alone
  (:func:`~sectiondeform.reference.revolution.p2_first_moments`), over the
  whole ring, ends included: a material region keeps its volume whatever
  the ends do, so this error is the discretisation's (and the finite bulk
  modulus's).

``python -m sectiondeform.reference.ring`` prints the table of
``docs/validation.md`` (section "Bodies of revolution").
"""

from __future__ import annotations

import sys
import time

import numpy as np

from ..io.case import case_from_dict
from ..problem import Problem
from .revolution import axis_from_points, p2_first_moments

__all__ = ["ring_case", "ring_figures", "AXIS"]

AXIS = ((0.0, 0.0), (1.0, 0.0))
"""The x axis: the radius is y."""


def ring_case(volume_ratio: float = 1.0, inner: float = 10.0, wall: float = 4.0, length: float = 96.0,
              expanded: float = 12.0, bulk_to_shear: float = 1e5) -> Problem:
    """The ring's section as a body of revolution about :data:`AXIS`: inner surface bonded, moved to ``expanded``.

    Parameters
    ----------
    volume_ratio : float
        v, the body's volume law.
    inner, wall, length, expanded : float
        A, t, L and a, units.
    bulk_to_shear : float
        κ / μ of the neo-Hookean rubber.

    Returns
    -------
    Problem
    """
    top = [[x, inner + wall] for x in np.linspace(length, 0.0, 13)]
    lower = {"polyline": [[0.0, inner], [length, inner]]}
    return case_from_dict({
        "format": "section-case/2", "name": "thick-ring", "support": lower,
        "target": {"polyline": [[0.0, expanded], [length, expanded]]},
        "revolution": {"axis": [list(p) for p in AXIS]},
        "bodies": [{"name": "ring", "lower": lower, "upper": {"polyline": [[length, inner]] + top + [[0.0, inner]]},
                    "law": {"volume_ratio": volume_ratio}, "material": {"bulk_to_shear": bulk_to_shear}}],
    })


def ring_figures(ref, volume_ratio: float, inner: float = 10.0, wall: float = 4.0, length: float = 96.0,
                 expanded: float = 12.0, strips: int = 4) -> dict:
    """The two errors of a reference solution of :func:`ring_case` (see the module's text).

    Returns
    -------
    dict
        ``analytic`` (largest distance from the closed form in the middle,
        over t) and ``strips`` (largest relative strip-volume error).
    """
    p0, p1, cells = ref.initial_mesh.points, ref.mesh.points, ref.initial_mesh.cells
    mid = np.abs(p0[:, 0] - length / 2) <= wall
    exact = np.sqrt(expanded**2 + volume_ratio * (p0[mid, 1] ** 2 - inner**2))
    analytic = float(np.max(np.hypot(p1[mid, 1] - exact, p1[mid, 0] - p0[mid, 0]))) / wall
    axis = axis_from_points(AXIS, p0)
    before = p2_first_moments(p0, p0, cells, axis)
    after = p2_first_moments(p0, p1, cells, axis)
    r_mid = p0[cells[:, :3]].mean(axis=1)[:, 1]
    band = np.minimum(((r_mid - inner) / wall * strips).astype(int), strips - 1)
    ratio = np.bincount(band, after, minlength=strips) / np.bincount(band, before, minlength=strips)
    return {"analytic": analytic, "strips": float(np.abs(ratio / volume_ratio - 1.0).max())}


def main(argv=None) -> int:
    """Print the ring study as a markdown table."""
    from . import solve_reference

    sizes = [float(a) for a in (argv if argv is not None else sys.argv[1:])] or [0.8, 0.4, 0.2, 0.1]
    print("| volume ratio v | h / t | triangles | unknowns | Newton its | max distance from r² − a² = v (R² − A²), middle / t "
          "| max strip volume error | body volume error | time |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for v in (1.0, 0.9):
        for h in sizes:
            t0 = time.perf_counter()
            ref = solve_reference(ring_case(v), mesh_size=h)
            seconds = time.perf_counter() - t0
            f = ring_figures(ref, v)
            print(f"| {v:g} | {h:g} | {ref.elements} | {ref.dofs} | {ref.iterations} | {f['analytic']:.2e} | "
                  f"{f['strips']:.2e} | {ref.bodies[0].relative_error:+.1e} | {seconds:.2f} s |", flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
