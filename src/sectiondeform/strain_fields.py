"""Strain fields of a result: each element's deformation gradient, principal stretches, J and Green–Lagrange strain.

F is the gradient of the map from the initial mesh to the final one (same
nodes, same cells) at each element's centre: the local point (0, 0) of a
bilinear quad, the centroid of a linear or quadratic (P2) triangle. Its
out-of-plane slot is, for a body of revolution, the hoop stretch r / R of
the element's centre (its final over its initial distance from the axis);
otherwise the out-of-plane stretch given (the hyperelastic model's λz = 1/r
of generalised plane strain, 1 for the paper model). Per element (cell
data, in element order):

``principal_stretches`` ``(M, 3)``
    λ₁ ≥ λ₂ ≥ λ₃, the square roots of the eigenvalues of C = FᵀF.
``J`` ``(M,)``
    det F: the local volume ratio (the area ratio times the out-of-plane stretch).
``green_lagrange_strain`` ``(M, 9)``
    E = (C − I) / 2, row-major xx, xy, xz, yx, …, zz (a 3 × 3 tensor as
    VTK and ParaView read nine components).
``max_principal_strain`` ``(M,)``
    λ₁ − 1 (nominal, the rubber-testing convention).
``von_mises_stress`` ``(M,)``
    Hyperelastic model only: √(3/2 s:s), s the deviator of the Cauchy
    stress of the element's rubber at F (at ``c^(-1/3) F`` for a body of
    revolution grown by ``c``: the elastic part). The deviator is the
    solution's: F gives it exactly.
``pressure`` ``(M,)``
    Hyperelastic model only, solved results: the hydrostatic pressure
    p = −tr σ / 3, **positive in compression** (Abaqus PRESS). It is the
    solution's own pressure field (the mixed formulation's independent
    unknown, linear on each element, read at the element's centre), not
    κ (J − 1) from F: in a nearly incompressible solve J − 1 is of the
    order of the stress over κ and its rounding and discretisation errors
    are multiplied by κ, while the pressure field is the one equilibrium
    holds with. Its sign in the solver is the opposite (the unknown is the
    mean stress tr σ / 3, positive in tension).

Stress units: those of the rubber's moduli. Each body has its own rubber
(``material``, in the unit the case gives, MPa by convention); a body
without one (every ``section-case/1`` body) has the model's neo-Hookean
rubber of shear modulus 1, a relative modulus (the shape does not depend on
it): its stresses are in units of the shear modulus ("× shear modulus"). A drag preview carries strains only (its
state is not a solution). The stresses need :func:`result_mechanics`.

For the hyperelastic model these are the solution's strains. The paper
model has no material: the same measures of its constructed mesh are
*geometric*, and are written with the prefix ``geometric_``
(:func:`result_fields`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .fem.elements import p2_gradients
from .materials.measures import max_principal_strain, principal_stretches, von_mises
from .materials.models import gradient_3d
from .models.base import MeshData
from .pappus import signed_distance
from .result import RESULT_V1

__all__ = ["element_gradients", "element_centres", "strain_fields", "result_fields", "result_mechanics", "Mechanics",
           "fields_json", "STRAIN_NOTE", "STRESS_NOTES"]

STRAIN_NOTE = "deformation gradient at each element's centre; hoop stretch r/R for bodies of revolution"
STRESS_NOTES = {
    True: ("strains of the hyperelastic model's solution; von_mises_stress and pressure (-tr(sigma)/3, positive in "
           "compression, the solution's pressure field) in units of the shear modulus (x shear modulus: the "
           "model's modulus is relative)"),
    False: ("strains of the hyperelastic model's solution; von_mises_stress and pressure (-tr(sigma)/3, positive in "
            "compression, the solution's pressure field) in the unit of each body's material moduli (MPa as the "
            "case gives them; relative to a shear modulus of 1 for a body without a material)"),
}
"""The ``note`` of a hyperelastic result's ``fields`` object, by whether its modulus is relative."""


@dataclass(frozen=True, eq=False)
class Mechanics:
    """What the stresses of a hyperelastic result's elements need beyond its meshes.

    Attributes
    ----------
    material : NeoHookean or MooneyRivlin or Yeoh
        The rubber of the elements (moduli in MPa, or relative).
    mean_stress : (M,) float64 ndarray or None
        The solution's pressure unknown at each element's centre: the mean
        Cauchy stress tr σ / 3, positive in tension, units of the moduli.
        None for a state that is not a solution (a drag preview).
    growth : float
        Volumetric growth c of the elements (bodies of revolution under a
        volume law); 1 otherwise.
    relative : bool
        The moduli are relative (the body of a ``section-case/1`` problem,
        which has no material: the model's rubber of shear modulus 1):
        stresses in units of the shear modulus.
    """

    material: object
    mean_stress: np.ndarray | None = None
    growth: float = 1.0
    relative: bool = False

_QUAD_CENTRE = 0.25 * np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])  # dN/d(xi, eta) at (0, 0)
_TRI_CENTRE = np.array([[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])  # linear: constant
_CENTRE_GRADIENTS = {"quad": _QUAD_CENTRE, "triangle": _TRI_CENTRE,
                     "triangle6": p2_gradients(np.array([[1.0 / 3.0, 1.0 / 3.0]]))[0]}


def _same_mesh(initial: MeshData, final: MeshData) -> bool:
    return (initial.kind == final.kind and initial.kind in _CENTRE_GRADIENTS
            and initial.points.shape == final.points.shape and np.array_equal(initial.cells, final.cells))


def element_gradients(initial: MeshData, final: MeshData) -> np.ndarray:
    """In-plane deformation gradient dx/dX at each element's centre, ``(M, 2, 2)``.

    Parameters
    ----------
    initial, final : MeshData
        The same cells (``quad``, ``triangle`` or ``triangle6``) on the
        initial and final nodes, units.

    Returns
    -------
    (M, 2, 2) float64 ndarray
        Dimensionless; exact for an affine map x = A X + b (then every row is A).

    Examples
    --------
    >>> sq = MeshData(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), np.array([[0, 1, 2, 3]]), "quad")
    >>> element_gradients(sq, MeshData(sq.points * [2.0, 0.5], sq.cells, "quad"))[0].tolist()
    [[2.0, 0.0], [0.0, 0.5]]
    """
    dref = _CENTRE_GRADIENTS[initial.kind]  # (nodes per cell, 2)
    cells = np.asarray(initial.cells)
    dX = np.einsum("eai,aj->eij", initial.points[cells], dref)  # dX/dxi
    dx = np.einsum("eai,aj->eij", final.points[cells], dref)  # dx/dxi
    return dx @ np.linalg.inv(dX)


def element_centres(mesh: MeshData) -> np.ndarray:
    """Each element's centre (the image of the reference centre), ``(M, 2)``, units."""
    cells = np.asarray(mesh.cells)
    if mesh.kind == "triangle6":  # the P2 centroid: -1/9 of each corner, 4/9 of each mid-side node
        w = np.array([-1.0, -1.0, -1.0, 4.0, 4.0, 4.0]) / 9.0
        return np.einsum("a,eai->ei", w, mesh.points[cells])
    return mesh.points[cells].mean(axis=1)


def strain_fields(initial: MeshData, final: MeshData, out_of_plane: float = 1.0, axis=None,
                  material=None, mean_stress=None, growth: float = 1.0) -> dict[str, np.ndarray]:
    """The strain fields of the module docstring, one row per element.

    Parameters
    ----------
    initial, final : MeshData
        The result's meshes (same cells).
    out_of_plane : float
        Out-of-plane stretch of a plane section (ignored with ``axis``).
    axis : ((float, float), (float, float)), optional
        Revolution axis: the out-of-plane stretch is then each element's hoop
        stretch, its centre's final over initial distance from the axis.
    material : optional
        A rubber of :mod:`sectiondeform.materials` (``cauchy(F)``): adds
        ``von_mises_stress`` in the units of its moduli.
    mean_stress : (M,) float64 ndarray, optional
        The solution's pressure unknown at each element's centre (tr σ / 3,
        units of the moduli): adds ``pressure``, its opposite.
    growth : float
        Volumetric growth of the elements: the stress is the rubber's at
        ``growth^(-1/3) F``.

    Returns
    -------
    dict of str to ndarray
        Empty unless both meshes have the same cells of a known kind.
    """
    if not _same_mesh(initial, final):
        return {}
    F2 = element_gradients(initial, final)
    if axis is not None:
        stretch_z = signed_distance(element_centres(final), axis) / signed_distance(element_centres(initial), axis)
    else:
        stretch_z = float(out_of_plane)
    F = gradient_3d(F2, stretch_z)
    C = np.swapaxes(F, -1, -2) @ F
    out = {
        "principal_stretches": principal_stretches(F),
        "J": np.linalg.det(F),
        "green_lagrange_strain": (0.5 * (C - np.eye(3))).reshape(len(F), 9),
        "max_principal_strain": max_principal_strain(F),
    }
    if material is not None:
        elastic = F if growth == 1.0 else F * float(growth) ** (-1.0 / 3.0)
        out["von_mises_stress"] = von_mises(material.cauchy(elastic))
    if mean_stress is not None:
        mean_stress = np.asarray(mean_stress, dtype=np.float64)
        if mean_stress.shape != (len(F),):
            raise ValueError(f"mean_stress: expected one value per element ({len(F)}), got shape {mean_stress.shape}")
        out["pressure"] = -mean_stress
    return out


def _mean_stress(z: np.ndarray, dofs: np.ndarray) -> np.ndarray:
    """The P1 pressure unknown at each element's centre: the mean of its corners', ``(M,)``."""
    return z[dofs].mean(axis=1)


def result_mechanics(result) -> list:
    """Per body of a hyperelastic result, what its stresses need (:class:`Mechanics`); None where there is none.

    Parameters
    ----------
    result : Result

    Returns
    -------
    list of Mechanics or None
        One entry per body, read from the solved state
        (:class:`~sectiondeform.models.hyperelastic.HyperelasticState`): the
        body's rubber (a body without a ``material`` has the model's
        neo-Hookean rubber of shear modulus 1; relative for the body of a
        ``section-result/1`` result), its pressure field and its growth. None for the paper model and for a drag preview
        without a state; a preview's ``mean_stress`` is None (its state is
        not a solution).
    """
    state = getattr(result, "state", None)
    if result.model != "hyperelastic" or not getattr(state, "materials", ()):
        return [None] * len(result.bodies)
    out = []
    for b, body in enumerate(result.bodies):
        material = state.materials[b]
        preview = getattr(body.info, "preview", False)
        mean = None if preview else _mean_stress(state.state.z, state.pressure_dofs[b])
        growth = float(state.stretches[b]) if state.growth else float(state.growths[b]) if getattr(state, "growths", ()) else 1.0
        out.append(Mechanics(material, mean, growth, relative=result.dialect == RESULT_V1))
    return out


def result_fields(initial: MeshData, final: MeshData, model: str, out_of_plane: float = 1.0,
                  axis=None, mechanics: Mechanics | None = None) -> tuple[str, dict[str, np.ndarray]]:
    """All per-element fields of a result, and their kind.

    Parameters
    ----------
    initial, final : MeshData
    model : str
        ``"paper"`` or ``"hyperelastic"``.
    out_of_plane : float
        The hyperelastic model's out-of-plane stretch (its ``info``).
    axis : optional
        The revolution axis of a body of revolution.
    mechanics : Mechanics, optional
        The hyperelastic body's rubber, pressure field and growth
        (:func:`result_mechanics`): adds ``von_mises_stress`` and, for a
        solution, ``pressure``. Without it, strains only.

    Returns
    -------
    kind : str
        ``"mechanical"`` for the hyperelastic model, ``"geometric"`` otherwise.
    fields : dict of str to ndarray
        The hyperelastic model's strain fields and stresses; for the paper
        model its geometric fields (:mod:`sectiondeform.geometric_fields`)
        and the strain fields of its mesh (out-of-plane stretch 1, or the
        hoop stretch), prefixed ``geometric_``.
    """
    if model == "hyperelastic":
        if mechanics is None:
            return "mechanical", strain_fields(initial, final, out_of_plane, axis)
        return "mechanical", strain_fields(initial, final, out_of_plane, axis, mechanics.material,
                                           mechanics.mean_stress, mechanics.growth)
    from .geometric_fields import geometric_fields

    strains = strain_fields(initial, final, 1.0, axis)
    return "geometric", {**geometric_fields(initial, final), **{f"geometric_{k}": v for k, v in strains.items()}}


def fields_json(kind: str, values: dict, mechanics: Mechanics | None) -> dict:
    """The ``fields`` object of one body (:func:`~sectiondeform.geometric_fields.fields_to_json`), its note naming the stress units."""
    from .geometric_fields import fields_to_json

    out = fields_to_json(values, kind)
    if out and mechanics is not None:
        out["note"] = STRESS_NOTES[mechanics.relative]
    return out
