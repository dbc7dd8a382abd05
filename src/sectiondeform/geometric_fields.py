"""Geometric fields of a layered result: how each element of the paper model's mesh changed.

The paper model builds its final mesh on the target with the same layers
and columns as the initial one; comparing the two element by element gives
*geometric* measures of the deformation. They are not mechanical strains
(the paper model has no material), and are labelled so wherever they are
written. Per element (cell data, in element order):

``corner_jacobians`` ``(M, 4)``
    The final corner Jacobians (cross product of the two edges at each
    corner, counter-clockwise corners as in the mesh's cells), units².
``corner_jacobian_ratio`` ``(M, 4)``
    Final over initial corner Jacobian: the local change of area.
``layer_stretch`` ``(M, 2)``
    Final over initial length of the element's two edges along the layers
    (its bottom edge, nearer the lower curve, then its top edge).
``height_stretch`` ``(M, 2)``
    Final over initial length of its two edges up the columns.

A body stretched homogeneously by ``lambda`` along a flat target with an
area ratio ``r`` has ``layer_stretch`` ``lambda``, ``height_stretch``
``r / lambda`` and ``corner_jacobian_ratio`` ``r`` in every element.
"""

from __future__ import annotations

import numpy as np

from .layers import quad_jacobians
from .models.base import MeshData

__all__ = ["geometric_fields", "fields_to_json", "GEOMETRIC_NOTE"]

GEOMETRIC_NOTE = "geometric measures of the paper model's layered meshes, not mechanical strains or stresses"


def _edge_lengths(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Length of edge i (corner i to corner i + 1) of each quad, ``(M, 4)``."""
    p = points[cells]
    return np.hypot(*(np.roll(p, -1, axis=1) - p).transpose(2, 0, 1))


def geometric_fields(initial: MeshData, final: MeshData) -> dict[str, np.ndarray]:
    """The per-element geometric fields of a layered result (see the module docstring).

    Parameters
    ----------
    initial, final : MeshData
        The result's meshes.

    Returns
    -------
    dict of str to ndarray
        Empty unless both meshes are the same structured layered quad mesh
        (the paper model's); then the four fields, float64, one row per element.

    Examples
    --------
    >>> sq = MeshData(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), np.array([[0, 1, 2, 3]]), "quad", (1, 1))
    >>> wide = MeshData(sq.points * [2.0, 0.5], sq.cells, "quad", (1, 1))
    >>> f = geometric_fields(sq, wide)
    >>> f["layer_stretch"].tolist(), f["height_stretch"].tolist(), f["corner_jacobian_ratio"].tolist()
    ([[2.0, 2.0]], [[0.5, 0.5]], [[1.0, 1.0, 1.0, 1.0]])
    """
    layered = initial.kind == final.kind == "quad" and initial.shape is not None and final.shape == initial.shape
    if not layered or initial.points.shape != final.points.shape or not np.array_equal(initial.cells, final.cells):
        return {}
    cells = np.asarray(final.cells)
    jac0, jac1 = quad_jacobians(initial.points, cells), quad_jacobians(final.points, cells)
    stretch = _edge_lengths(final.points, cells) / _edge_lengths(initial.points, cells)
    return {
        "corner_jacobians": jac1,
        "corner_jacobian_ratio": jac1 / jac0,
        "layer_stretch": stretch[:, [0, 2]],  # edges 0 and 2 run along the layers (bottom, top)
        "height_stretch": stretch[:, [3, 1]],  # edges 3 and 1 run up the columns
    }


MECHANICAL_NOTE = ("strains of the hyperelastic model's solution; von_mises_stress in units of the shear modulus "
                   "(the model's modulus is relative)")


def fields_to_json(fields: dict[str, np.ndarray], kind: str = "geometric") -> dict:
    """The result's ``fields`` object: the fields as lists, labelled by kind (geometric or mechanical), per cell."""
    if not fields:
        return {}
    note = GEOMETRIC_NOTE if kind == "geometric" else MECHANICAL_NOTE
    return {"kind": kind, "location": "cell", "note": note, **{name: values.tolist() for name, values in fields.items()}}
