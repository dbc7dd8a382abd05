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

from dataclasses import dataclass, field

import numpy as np

from .fem.elements import p2_gradients
from .materials.measures import max_principal_strain, principal_stretches, von_mises
from .materials.models import gradient_3d
from .models.base import MeshData
from .pappus import signed_distance
from .problem import RESULT_V1

__all__ = ["element_gradients", "element_centres", "strain_fields", "result_fields", "result_mechanics", "Mechanics",
           "fields_json", "STRAIN_NOTE", "STRESS_NOTES", "node_gradients", "nodal_stresses", "SingularPoint",
           "singular_points", "RECOVERY_NOTE", "REENTRANT_TURN_DEG", "SINGULAR_RADIUS_ELEMENTS"]

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
    nodal : dict of str to (N,) float64 ndarray
        The stresses recovered at the nodes of the body's final mesh
        (:func:`nodal_stresses`): ``von_mises_stress``, and ``pressure``
        for a solution.
    singular_points : tuple of SingularPoint
        Where the body's exact stress is singular (:func:`singular_points`).
    """

    material: object
    mean_stress: np.ndarray | None = None
    growth: float = 1.0
    relative: bool = False
    nodal: dict = field(default_factory=dict)
    singular_points: tuple = ()

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


# --- stresses recovered at the nodes ---------------------------------------------------------------

_P2_NODES = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]])
_P2_NODE_GRADIENTS = p2_gradients(_P2_NODES)  # (node a, shape function k, 2)


def node_gradients(initial: MeshData, final: MeshData) -> np.ndarray:
    """In-plane deformation gradient of each P2 element at each of its six nodes, ``(M, 6, 2, 2)``.

    The gradient of the element's quadratic map (isoparametric: curved
    edges too) evaluated at its corners and mid-edge nodes, in the order of
    its cells; exact for an affine map (then every entry is its matrix).

    Parameters
    ----------
    initial, final : MeshData
        The same ``triangle6`` cells on the initial and final nodes, units.
    """
    cells = np.asarray(initial.cells)
    dX = np.einsum("eki,akj->eaij", initial.points[cells], _P2_NODE_GRADIENTS)
    dx = np.einsum("eki,akj->eaij", final.points[cells], _P2_NODE_GRADIENTS)
    return dx @ np.linalg.inv(dX)


def _node_mean(cells: np.ndarray, values: np.ndarray, weights: np.ndarray, n: int) -> np.ndarray:
    """The weighted mean over the elements sharing each node of per-element-node ``values`` ``(M, k, ...)``.

    ``weights`` is one per element ``(M,)`` or per element node ``(M, k)``; a node whose weights are all zero gets NaN.
    """
    flat = cells.ravel()
    w = np.broadcast_to(weights[:, None] if np.ndim(weights) == 1 else weights, cells.shape).ravel()
    rows = values.reshape(len(flat), -1)
    total = np.zeros((n, rows.shape[1]))
    np.add.at(total, flat, rows * w[:, None])
    count = np.bincount(flat, weights=w, minlength=n)
    with np.errstate(invalid="ignore", divide="ignore"):
        return (total / count[:, None]).reshape((n,) + values.shape[2:])


def nodal_stresses(initial: MeshData, final: MeshData, material, corner_mean_stress=None, out_of_plane: float = 1.0,
                   axis=None, growth: float = 1.0) -> dict[str, np.ndarray]:
    """Von Mises stress and pressure recovered at every node of one body's P2 mesh.

    Per body, never across bodies: the mesh is one body's (its own nodes
    on a bonded interface), so the pressure keeps its jump there.

    * ``pressure`` ``(N,)``: the solution's own P1 pressure field read at
      the nodes (its corner values at the vertices, the mean of an edge's
      two ends at its mid-edge node), **positive in compression**: no
      smoothing, the field equilibrium holds with.
    * ``von_mises_stress`` ``(N,)``: √(3/2 s:s), s the deviator of the
      rubber's Cauchy stress at F evaluated at the node *in each element
      around it* (F of the quadratic displacement, linear in the element,
      so exact at its nodes), averaged over those elements weighted by
      their areas, then its norm. A uniform stress is recovered exactly at
      every node.

    Parameters
    ----------
    initial, final : MeshData
        One body's ``triangle6`` meshes (same cells), units.
    material : NeoHookean or MooneyRivlin or Yeoh
        The body's rubber (``cauchy(F)``), moduli in MPa or relative.
    corner_mean_stress : (M, 3) float64 ndarray, optional
        The solution's pressure unknown at each element's corners: the mean
        Cauchy stress tr σ / 3, positive in tension, units of the moduli.
        Without it (a drag preview), no ``pressure``.
    out_of_plane : float
        Out-of-plane stretch of a plane section (ignored with ``axis``).
    axis : ((float, float), (float, float)), optional
        Revolution axis: the out-of-plane stretch is each node's hoop
        stretch r / R.
    growth : float
        Volumetric growth: the stress is the rubber's at ``growth^(-1/3) F``.

    Returns
    -------
    dict of str to (N,) float64 ndarray
        One value per node of ``initial.points``; empty unless both meshes
        are the same ``triangle6`` mesh. An element turned over at one of
        its nodes (a quadratic element can be, at a pressed singular corner,
        while valid at its quadrature points) is left out of that node's
        von Mises mean; a node left with no element has NaN.

    Examples
    --------
    >>> from sectiondeform.materials import NeoHookean
    >>> tri = MeshData(np.array([[0, 0], [1, 0], [0, 1], [.5, 0], [.5, .5], [0, .5]]), np.array([[0, 1, 2, 3, 4, 5]]), "triangle6")
    >>> out = nodal_stresses(tri, MeshData(tri.points * [1.2, 1 / 1.2], tri.cells, "triangle6"), NeoHookean(1.0))
    >>> bool(np.ptp(out["von_mises_stress"]) < 1e-12), round(float(out["von_mises_stress"][0]), 5)  # μ √(3/2) |dev b|, b = diag(1.44, 1/1.44, 1)
    (True, 0.64916)
    """
    if not _same_mesh(initial, final) or initial.kind != "triangle6":
        return {}
    cells = np.asarray(initial.cells)
    n = len(initial.points)
    F2 = node_gradients(initial, final)  # (M, 6, 2, 2)
    if axis is not None:
        r0 = signed_distance(initial.points, axis)
        r1 = signed_distance(final.points, axis)
        on_axis = np.abs(r0) <= 1e-12 * max(float(np.abs(r0).max()), 1.0)
        hoop = np.divide(r1, r0, out=np.ones_like(r0), where=~on_axis)[cells]  # (M, 6)
        if on_axis.any():  # on the axis the hoop stretch is the radial one: the element's centre's
            centre = (signed_distance(element_centres(final), axis) / signed_distance(element_centres(initial), axis))
            hoop = np.where(on_axis[cells], centre[:, None], hoop)
        stretch_z = hoop
    else:
        stretch_z = float(out_of_plane)
    F = gradient_3d(F2, stretch_z)
    # A quadratic element valid at its quadrature points may still turn over at a node (a singular corner
    # pressed hard): that element's value is left out of the node's mean (NaN if no element is left).
    valid = np.linalg.det(F) > 0.0
    F = np.where(valid[..., None, None], F, np.eye(3))
    elastic = F if growth == 1.0 else F * float(growth) ** (-1.0 / 3.0)
    sigma = material.cauchy(elastic)
    deviator = sigma - np.trace(sigma, axis1=-2, axis2=-1)[..., None, None] / 3.0 * np.eye(3)
    X = initial.points[cells[:, :3]]
    area = 0.5 * np.abs((X[:, 1, 0] - X[:, 0, 0]) * (X[:, 2, 1] - X[:, 0, 1])
                        - (X[:, 2, 0] - X[:, 0, 0]) * (X[:, 1, 1] - X[:, 0, 1]))
    s = _node_mean(cells, deviator, area[:, None] * valid, n)
    out = {"von_mises_stress": np.sqrt(1.5 * np.einsum("nij,nij->n", s, s))}
    if corner_mean_stress is not None:
        corner = np.asarray(corner_mean_stress, dtype=np.float64)
        if corner.shape != (len(cells), 3):
            raise ValueError(f"corner_mean_stress: expected (M, 3) = ({len(cells)}, 3), got shape {corner.shape}")
        six = np.column_stack((corner, 0.5 * (corner + corner[:, [1, 2, 0]])))  # P1 at the mid-edge nodes
        out["pressure"] = -_node_mean(cells, six, np.ones(len(cells)), n)
    return out


RECOVERY_NOTE = ("at the nodes of meshes.final, per body: pressure the solution's P1 field at the nodes; von_mises_stress "
                 "from the deviator at F evaluated at the node in each element around it, area-weighted mean; not "
                 "resolved within `radius` of a singular point")
#: A contour vertex turning by more than this (degrees) into the body is a re-entrant corner.
REENTRANT_TURN_DEG = 15.0
#: The neighbourhood of a singular point the coarse mesh does not resolve, in the body's element sizes.
SINGULAR_RADIUS_ELEMENTS = 2.0


@dataclass(frozen=True)
class SingularPoint:
    """A point of a body where the exact stress is singular (infinite), so no mesh converges there.

    Attributes
    ----------
    point : (float, float)
        Its deformed position, units.
    initial : (float, float)
        Its initial position, units.
    kind : str
        ``"bonded corner"`` (an end of the body's lower curve, where its
        bonded base meets its free upper curve), ``"bond end"`` (an end of
        another body's lower curve bonded on this body's upper curve) or
        ``"re-entrant corner"`` (the contour turns into the body).
    why : str
        One line naming the corner.
    radius : float
        The neighbourhood where the coarse mesh's nodal stresses are not
        resolved: :data:`SINGULAR_RADIUS_ELEMENTS` element sizes, units.
    """

    point: tuple
    initial: tuple
    kind: str
    why: str
    radius: float

    def to_json(self) -> dict:
        """``{"point", "initial", "kind", "why", "radius"}``."""
        return {"point": list(self.point), "initial": list(self.initial), "kind": self.kind, "why": self.why,
                "radius": self.radius}


def singular_points(result, b: int, radius: float) -> tuple:
    """The singular points of body ``b`` of a result: bonded corners, bond ends of bodies on it, re-entrant corners.

    Parameters
    ----------
    result : Result
    b : int
        The body.
    radius : float
        Each point's :attr:`SingularPoint.radius`, units.

    Returns
    -------
    tuple of SingularPoint
        In the order of the body's initial contour, each point once (a
        bonded corner that is also re-entrant is named a bonded corner).

    Notes
    -----
    Where a bonded boundary meets a free one the elastic stress of a
    nearly incompressible body is singular (σ ~ r^(λ − 1), 0 < λ < 1: the
    ends A and B of a body's lower curve; the ends of a bond on its upper
    curve); so it is at a re-entrant corner of a free boundary. A contour
    vertex is re-entrant when it turns into the body by more than
    :data:`REENTRANT_TURN_DEG` degrees (a smooth curve's discretisation
    turns by less). Contact edges will be added with contact.
    """
    body = result.bodies[b]
    X, x = np.asarray(body.initial_contour), np.asarray(body.contour)
    size = float(np.ptp(X, axis=0).max()) or 1.0

    def vertex(p):
        d = np.hypot(*(X - p).T)
        i = int(np.argmin(d))
        return i if d[i] <= 1e-9 * size else None

    named: dict[int, tuple] = {}
    for end in (0, -1):
        i = vertex(np.asarray(body.initial_lower)[end])
        if i is not None:
            named.setdefault(i, ("bonded corner", f"{'A' if end == 0 else 'B'}, an end of the lower curve: its bonded "
                                 "base meets its free upper curve"))
    for k, other in enumerate(result.bodies):
        if k == b:
            continue
        for end in (0, -1):
            i = vertex(np.asarray(other.initial_lower)[end])
            if i is not None:
                named.setdefault(i, ("bond end", f"an end of body {other.name!r}'s lower curve, bonded on this body"))
    ring = np.asarray(X)
    e0, e1 = ring - np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0) - ring
    area = 0.5 * float(np.sum(ring[:, 0] * np.roll(ring[:, 1], -1) - np.roll(ring[:, 0], -1) * ring[:, 1]))
    turn = np.degrees(np.arctan2(e0[:, 0] * e1[:, 1] - e0[:, 1] * e1[:, 0], np.einsum("ij,ij->i", e0, e1)))
    for i in np.flatnonzero(-np.sign(area) * turn > REENTRANT_TURN_DEG):
        named.setdefault(int(i), ("re-entrant corner", f"the contour turns {abs(turn[i]):.0f}° into the body"))
    return tuple(SingularPoint(tuple(map(float, x[i])), tuple(map(float, X[i])), kind, why, float(radius))
                 for i, (kind, why) in sorted(named.items()))


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
        corners = None if preview else state.state.z[state.pressure_dofs[b]]
        growth = float(state.stretches[b]) if state.growth else float(state.growths[b]) if getattr(state, "growths", ()) else 1.0
        nodal = nodal_stresses(body.initial_mesh, body.final_mesh, material, corners,
                               getattr(body.info, "out_of_plane_stretch", 1.0), result.axis, growth)
        size = getattr(getattr(body.quality, "initial", None), "element_size", None)
        radius = SINGULAR_RADIUS_ELEMENTS * (size if size else _element_size(body.initial_mesh))
        out.append(Mechanics(material, None if corners is None else corners.mean(axis=1), growth,
                             relative=result.dialect == RESULT_V1, nodal=nodal,
                             singular_points=singular_points(result, b, radius)))
    return out


def _element_size(mesh: MeshData) -> float:
    """The median edge length of a mesh's corner triangles, units."""
    p = mesh.points[np.asarray(mesh.cells)[:, :3]]
    return float(np.median(np.hypot(*(p - np.roll(p, 1, axis=1)).transpose(2, 0, 1))))


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
        if mechanics.nodal:
            out["nodal"] = {"location": "point", "note": RECOVERY_NOTE,
                            **{k: v.tolist() for k, v in mechanics.nodal.items()}}
        out["singular_points"] = [p.to_json() for p in mechanics.singular_points]
    return out
