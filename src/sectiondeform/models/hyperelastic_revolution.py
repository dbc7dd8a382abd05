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
  solved exactly (:func:`~sectiondeform.fem.mapping.offset_to_law`). From the support up, as in the
  plane case, so the interfaces stay bonded.
"""

from __future__ import annotations

import copy

import numpy as np

from ..errors import CaseError
from ..fem.axisymmetric import AxisymmetricNeoHooke, AxisymmetricRubber
from ..fem.mapping import rigid_fit
from ..materials import NeoHookean
from ..pappus import axis_frame, signed_distance

__all__ = ["RevolutionPhysics"]


START_HOOP = 0.1
"""The largest relative change of a node's distance from the axis the start of a solve may take at once (a rigid
motion of the section onto the target); a target farther out or in is reached along the path."""


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
        """The best rigid motion of the support nodes, if it changes no node's distance from the axis by more than
        :data:`START_HOOP`; else a translation along the axis.

        A motion of the section is rigid in its plane only: moved away from
        the axis, a body of revolution is stretched round it. A start moved
        so far is no equilibrium, and the first load step would carry that
        whole hoop stretch at once, whatever its size; from a translation
        along the axis the path carries it instead, in load steps. (Bodies
        held on the axis, or a fit that would turn a body across it, start
        from the translation as well.)
        """
        axis = self.problem.revolution.axis
        if not len(self.axis_values):
            q, t = rigid_fit(points, targets)
            before = signed_distance(self.mesh.nodes, axis)
            after = signed_distance(self.mesh.nodes @ q.T + t, axis)
            if np.all(before * after > 0) and np.all(np.abs(after - before) <= START_HOOP * np.abs(before)):
                return q, t
        e = axis_frame(axis)[1][0]
        return np.eye(2), e * float(np.mean((targets - points) @ e))

    def _axis_side(self, points: np.ndarray) -> np.ndarray:
        """Distance of ``points`` from the axis, positive on the side the bodies are drawn, units."""
        axis = self.problem.revolution.axis
        side = signed_distance(self.mesh.points, axis)
        return signed_distance(points, axis) * (1.0 if side[np.argmax(np.abs(side))] > 0 else -1.0)

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
