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
    Hyperelastic model only: √(3/2 s:s) of the Cauchy stress of its
    neo-Hookean rubber at F, in units of the shear modulus (the model's
    modulus is relative: a one-body case's shape does not depend on it).
    The von Mises stress needs only the stress deviator, which F gives
    exactly; the pressure, set by the solution's independent pressure
    field, is not written.

For the hyperelastic model these are the solution's strains. The paper
model has no material: the same measures of its constructed mesh are
*geometric*, and are written with the prefix ``geometric_``
(:func:`result_fields`).
"""

from __future__ import annotations

import numpy as np

from .fem.elements import p2_gradients
from .materials.measures import max_principal_strain, principal_stretches, von_mises
from .materials.models import NeoHookean, gradient_3d
from .models.base import MeshData
from .pappus import signed_distance

__all__ = ["element_gradients", "element_centres", "strain_fields", "result_fields", "STRAIN_NOTE"]

STRAIN_NOTE = "deformation gradient at each element's centre; hoop stretch r/R for bodies of revolution"

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
                  material=None) -> dict[str, np.ndarray]:
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
        out["von_mises_stress"] = von_mises(material.cauchy(F))
    return out


def result_fields(initial: MeshData, final: MeshData, model: str, out_of_plane: float = 1.0,
                  axis=None, stress: bool = True) -> tuple[str, dict[str, np.ndarray]]:
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
    stress : bool
        Add the hyperelastic model's von Mises stress (a one-body section:
        its neo-Hookean rubber, relative modulus). False for a body of an
        assembly, whose own rubber, modulus and growth the stress would
        need: it is left out rather than written wrong.

    Returns
    -------
    kind : str
        ``"mechanical"`` for the hyperelastic model, ``"geometric"`` otherwise.
    fields : dict of str to ndarray
        The hyperelastic model's strain fields and von Mises stress
        (relative to its shear modulus); for the paper model its
        geometric fields (:mod:`sectiondeform.geometric_fields`) and the
        strain fields of its mesh (out-of-plane stretch 1, or the hoop
        stretch), prefixed ``geometric_``.
    """
    if model == "hyperelastic":  # its rubber: neo-Hookean, shear modulus 1 (relative)
        return "mechanical", strain_fields(initial, final, out_of_plane, axis, NeoHookean(1.0) if stress else None)
    from .geometric_fields import geometric_fields

    strains = strain_fields(initial, final, 1.0, axis)
    return "geometric", {**geometric_fields(initial, final), **{f"geometric_{k}": v for k, v in strains.items()}}
