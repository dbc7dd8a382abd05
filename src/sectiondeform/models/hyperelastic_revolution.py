"""The hyperelastic model of bodies of revolution: all bodies in one axisymmetric solve.

Everything is the plane problem's (:mod:`~sectiondeform.models.hyperelastic`:
one union mesh, the support bonded to the target, shared pieces bonded by
their shared nodes, one Newton solve) except two things:

* the mechanics are axisymmetric (the pressure one P1 field per body, as in
  the plane case)
  (:class:`~sectiondeform.fem.axisymmetric.AxisymmetricNeoHooke` for
  neo-Hookean bodies, in closed form, else
  :class:`~sectiondeform.fem.axisymmetric.AxisymmetricRubber`: each body's
  neo-Hookean, Mooney–Rivlin or Yeoh rubber, moduli as given): the hoop
  stretch at each point is its current distance from the case's axis over
  its initial one, integrals are weighted by the radius, and a body's
  ``volume_ratio`` v is an isotropic volumetric growth of that body (cure
  shrinkage, swelling; v = 1 is plain near-incompressibility). A body of a
  revolution case under an area law grows by nothing; its law is met by the
  correction alone;
* the exact law correction meets each body's own law, the volume of
  revolution (Pappus: 2π × area × centroid distance), by one common normal
  offset of its free upper points: the volume of the offset polygon is a
  cubic in the offset (:meth:`~sectiondeform.laws.Law.coefficients`),
  solved exactly (:func:`offset_to_law`). From the support up, as in the
  plane case, so the interfaces stay bonded.
"""

from __future__ import annotations

import copy

import numpy as np

from ..errors import CaseError, LawError
from ..fem.axisymmetric import AxisymmetricNeoHooke, AxisymmetricRubber
from ..fem.mapping import offset_normals, rigid_fit
from ..materials import NeoHookean
from ..pappus import axis_frame, signed_distance

__all__ = ["RevolutionPhysics", "offset_to_law"]


def offset_to_law(ring: np.ndarray, movable: np.ndarray, law, wanted: float) -> tuple[np.ndarray, float]:
    """Offset the movable points of a closed polyline along their normals so its law's quantity is ``wanted``.

    The quantity of ``ring + k v`` (``v`` the normals) is a polynomial in
    ``k`` (a quadratic for an area, a cubic for a volume of revolution); of
    its real roots the one nearest 0 (the smallest correction) is taken,
    polished by two Newton steps.

    Parameters
    ----------
    ring : (k, 2) float64 ndarray
        Closed polyline (the closing edge implied), units.
    movable : (k,) bool ndarray
        The points that may move; each along the normal of the chord
        between its two neighbours, by one common distance.
    law : Law
        Gives :meth:`~sectiondeform.laws.Law.coefficients` (signed).
    wanted : float
        Wanted signed quantity (units² or units³).

    Returns
    -------
    ring : (k, 2) float64 ndarray
    offset : float
        The distance applied, units (positive: outward for a
        counter-clockwise ring).

    Raises
    ------
    LawError
        If no offset meets the law (no movable point, or no real root).

    Examples
    --------
    A unit square at distance 1 to 2 from the axis y = 0, the two inner points of its top raised
    to double its volume (first moment 3/2 + 4k/3 + 5k²/18 = 3).

    >>> from sectiondeform.laws import VolumeRatio
    >>> ring = np.array([[0.0, 1], [1, 1], [1, 2], [2 / 3, 2], [1 / 3, 2], [0, 2]])
    >>> law = VolumeRatio(2.0, ((0.0, 0.0), (1.0, 0.0)))
    >>> top = np.array([False, False, False, True, True, False])
    >>> out, k = offset_to_law(ring, top, law, law.target(law.quantity(ring)))
    >>> round(k, 12) == round((31 ** 0.5 - 4) * 3 / 5, 12), round(law.quantity(out) / law.quantity(ring), 12)
    (True, 2.0)
    """
    v = offset_normals(ring, movable)
    c = np.array(law.coefficients(ring, v), dtype=np.float64)
    c[0] -= wanted
    scale = float(np.abs(c).max())
    if not np.abs(c[1:]).max() > 1e-14 * scale:
        raise LawError(f"law: no point of the upper curve is free to move to meet the {law.measure}")
    trimmed = c.copy()
    while len(trimmed) > 2 and abs(trimmed[-1]) <= 1e-14 * scale:
        trimmed = trimmed[:-1]
    raw = np.roots(trimmed[::-1])
    real = [float(r.real) for r in raw if abs(r.imag) <= 1e-9 * (1.0 + abs(r))]
    if not real:
        raise LawError(f"law: no normal offset of the upper curve gives the {law.measure} {abs(wanted):.6g}")
    k = min(real, key=abs)
    dc = c[1:] * np.arange(1, len(c))
    for _ in range(2):
        slope = np.polynomial.polynomial.polyval(k, dc)
        if slope == 0:
            break
        k -= np.polynomial.polynomial.polyval(k, c) / slope
    return ring + k * v, float(k)


class RevolutionPhysics:
    """The axisymmetric physics of bodies of revolution, mixed into the plane problem's preparation.

    :class:`~sectiondeform.models.hyperelastic.RevolutionPrepared` is
    ``HyperelasticPrepared`` with these methods: the growths that play the
    out-of-plane stretches, the axisymmetric physics, and the exact volume
    law; everything else (the mesh, the solve, the checks) is the plane
    problem's. It reads the preparation's ``problem``, ``sections``,
    ``mesh`` and ``physics``.

    Notes
    -----
    The placements' ``out_of_plane_stretch`` is 1: a body of revolution has
    no out-of-plane stretch of its own, its hoop stretch varies point by point.
    """

    plane = False

    def stretches_of(self, laws) -> tuple:
        """Each body's volumetric growth ``v`` under ``laws``: its volume ratio, 1 under an area law.

        It plays the plane problem's out-of-plane stretch in the path and
        the warm start (a start solved under other growths is no path).
        """
        return tuple(float(law.ratio) if law.measure == "volume" else 1.0 for law in laws)

    def _on_axis(self, mesh, support_ids: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The nodes on the axis (a solid body of revolution) held there: their radial dofs, values and contour vertices.

        A body of revolution that reaches its axis (a ball, a bump stop)
        keeps the points there on it: their distance from the axis is held
        at 0 (a node on the support is held already). The radial dof is one
        coordinate, so the axis must be drawn along x or y.

        Raises
        ------
        CaseError
            If bodies reach an axis that is drawn along neither x nor y.
        """
        axis = self.problem.revolution.axis
        tol = self.layout.tolerance
        on = np.flatnonzero(np.abs(signed_distance(mesh.nodes, axis)) <= tol)
        on = on[~np.isin(on, support_ids)]
        vertices = np.flatnonzero(np.abs(signed_distance(mesh.points, axis)) <= tol)
        if not len(on):
            return np.zeros(0, np.int64), np.zeros(0), vertices
        origin, rot = axis_frame(axis)
        radial = int(np.argmax(np.abs(rot[1])))  # the coordinate the normal to the axis runs along
        if abs(rot[1][radial]) < 1.0 - 1e-12:
            raise CaseError("revolution.axis", f"{len(on)} mesh nodes lie on the axis, which is drawn at an angle; draw it "
                            "along x or y so that their distance from it can be held at 0")
        return 2 * on + radial, np.full(len(on), origin[radial]), vertices

    def _start_motion(self, points: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The best rigid motion of the support nodes, if it keeps every node on its side of the axis; else a
        translation along the axis (bodies held on the axis, or a fit that would turn a body across it: its
        hoop stretch would change sign, no state to start from).
        """
        axis = self.problem.revolution.axis
        if not len(self.axis_values):
            q, t = rigid_fit(points, targets)
            before = signed_distance(self.mesh.nodes, axis)
            after = signed_distance(self.mesh.nodes @ q.T + t, axis)
            if np.all(before * after > 0):
                return q, t
        e = axis_frame(axis)[1][0]
        return np.eye(2), e * float(np.mean((targets - points) @ e))

    def _physics(self, cells, geom, kappa, mu):
        """The axisymmetric problem: neo-Hookean bodies in closed form, any other rubber through the materials."""
        a = self.problem
        axis = a.revolution.axis
        origin, rot = axis_frame(axis)
        side = signed_distance(np.concatenate([s.contour for s in self.sections]), axis)
        normal = rot[1] if side[np.argmax(np.abs(side))] > 0 else -rot[1]
        self.stretches = self.stretches_of(tuple(body.law for body in a.bodies))
        ln_growth = np.log(self.stretches)[self.mesh.body]
        if all(type(m) is NeoHookean for m in self.materials):
            return AxisymmetricNeoHooke(cells, self.mesh.nodes, geom, origin, normal, kappa, mu, ln_growth,
                                        self.mesh.pressure_cells)
        return AxisymmetricRubber(cells, self.mesh.nodes, geom, origin, normal, self.materials, self.mesh.body, ln_growth,
                                  self.mesh.pressure_cells)

    def _physics_for(self, stretches: tuple):
        physics = copy.copy(self.physics)
        physics.ln_growth = np.log(np.asarray(stretches))[self.mesh.body][:, None]
        physics.ln_stretch = -physics.ln_growth
        return physics

    def _law_offset(self, b: int, ring: np.ndarray, movable: np.ndarray, law, wanted: float) -> tuple[np.ndarray, float]:
        return offset_to_law(ring, movable, law, wanted)
