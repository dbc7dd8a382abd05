"""The converged finite-element reference of a problem: the whole mesh and one :class:`BodyReference` per body."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..models.base import MeshData
from .revolution import Axis

__all__ = ["BodyReference", "Reference", "solution"]


@dataclass(frozen=True, eq=False)
class BodyReference:
    """The finite-element reference's figures of one body.

    Attributes
    ----------
    name : str
    upper : (m, 2) float64 ndarray
        Deformed upper characteristic points, B' to A', in the order of the
        body's section ``upper``, units.
    initial_upper : (m, 2) float64 ndarray
        The same points before deformation.
    area_initial, area_final : float
        Area of the body's triangles before, and ∫ det F2D dA after
        (exact for the deformed quadratic triangles), units².
    area_target : float or None
        r × initial area under an area law (an extruded body grown by v:
        v / λz × initial area, λz its solved axial stretch); None for a body
        of revolution.
    volume_initial, volume_target, volume_final : float or None
        2π ∫ R dA, v × initial and 2π ∫ r dA of the deformed body (a body
        of revolution), units³; None in plane strain.
    load : float
        The body's load parameter: λz = 1 / r (plane) or the growth v.
    volume_change : float
        ∫ (Je − 1) w dA / ∫ w dA over the body (w = 1, or the radius): the
        volume its finite bulk modulus gave up.
    max_volume_change : float
        Largest |p| / κ at a vertex of the body (it peaks where a bonded
        curve meets a free one).
    elements : int
        The body's triangles.
    material : NeoHookean or MooneyRivlin or Yeoh
        The body's rubber.
    mesh_size : float
        The body's element size h, units.
    growth : float
        The isotropic growth v of an extruded body's material (1: none; a
        body of revolution's is ``load``).
    holes, initial_holes : tuple of (k_h, 2) float64 ndarray
        Each hole's points (the section's ``holes``), deformed and initial, units.
    """

    name: str
    upper: np.ndarray
    initial_upper: np.ndarray
    area_initial: float
    area_final: float
    area_target: float | None
    volume_initial: float | None
    volume_target: float | None
    volume_final: float | None
    load: float
    volume_change: float
    max_volume_change: float
    elements: int
    material: object
    mesh_size: float
    growth: float = 1.0
    holes: tuple = ()
    initial_holes: tuple = ()

    @property
    def measure(self) -> str:
        """``"area"`` or ``"volume"`` (a body of revolution): what the body's law sets."""
        return "area" if self.volume_target is None else "volume"

    @property
    def target(self) -> float:
        """The law's target of :attr:`measure`."""
        return self.area_target if self.volume_target is None else self.volume_target

    @property
    def final(self) -> float:
        """:attr:`measure` after deformation."""
        return self.area_final if self.volume_target is None else self.volume_final

    @property
    def relative_error(self) -> float:
        """Relative error of the body's law's measure (area, or volume for a body of revolution)."""
        return (self.final - self.target) / self.target

    @property
    def bulk_to_shear(self) -> float:
        """κ / μ₀ of the body's rubber."""
        return float(self.material.kappa / self.material.shear_modulus)

    def summary(self) -> dict:
        """The body's scalar figures as a plain dictionary (for reports)."""
        revolution = self.volume_target is not None
        out = {"name": self.name, "area_initial": self.area_initial, "area_target": self.area_target,
               "area_final": self.area_final, "volume_change": self.volume_change,
               "max_volume_change": self.max_volume_change, "stretch_z": None if revolution else self.load,
               "bulk_to_shear": self.bulk_to_shear, "shear_modulus": float(self.material.shear_modulus),
               "mesh_size": self.mesh_size, "elements": self.elements, "load": self.load,
               "relative_area_error": None if revolution else self.relative_error,
               "relative_error": self.relative_error}
        if self.growth != 1.0:
            out["growth"] = self.growth
        out["material"] = self.material.to_json()
        out["material"].setdefault("model", self.material.model)
        if revolution:
            out.update(volume_initial=self.volume_initial, volume_target=self.volume_target,
                       volume_final=self.volume_final, volume_ratio=self.load,
                       relative_volume_error=self.relative_error)
        return out


@dataclass(frozen=True, eq=False)
class Reference:
    """The converged finite-element solution of a problem.

    Attributes
    ----------
    bodies : tuple of BodyReference
    initial_mesh, mesh : MeshData
        The whole mesh before and after, ``kind="triangle6"`` (corners then
        mid-edge nodes; the deformed edges are the chords of the quadratic ones).
    body : (M,) int64 ndarray
        Body of each cell of ``mesh``.
    mesh_data : ReferenceMesh
        The corner triangulation.
    pressure : (N,) float64 ndarray
        Pressure at each mesh vertex, units of the moduli; at a vertex of an
        interface, the pressure on the side of the body of lowest index (it
        jumps across).
    cauchy : (M, 3, 3) float64 ndarray
        Cauchy stress in each triangle (mean over its quadrature points),
        axes x, y and the out-of-plane (hoop) direction.
    corner_pressure : (M, 3) float64 ndarray
        The pressure unknown at each triangle's corners, its own body's
        (the same sign and units as ``pressure``; at an interface each side
        has its own value): what the stresses recovered at the nodes read
        (:func:`~sectiondeform.strain_fields.nodal_stresses`).
    jacobian_min : float
        Smallest det F2D at any quadrature point (> 0: no inversion).
    strain_energy : float
        Stored energy: per unit depth in plane strain, of the whole body of
        revolution (2π ∫ Ψ R dA).
    axis : Axis or None
    elements, dofs, iterations, steps, cuts : int
        Triangles, unknowns (displacement + pressure), Newton iterations,
        accepted load steps, load steps cut in half.
    seconds : float
    timings : dict
        ``mesh_s``, ``setup_s``, ``solve_s``.
    rigid : tuple of PartContact
        Each rigid part's force and contact figures (:mod:`sectiondeform.reference.contact`); empty without parts.
    support_force : (float, float) or None
        The force the bodies exert on the support (per unit depth, or the whole ring's), with rigid parts.
    history : tuple of HistoryStep
        The forces at each accepted load step, with rigid parts.
    """

    bodies: tuple
    initial_mesh: MeshData
    mesh: MeshData
    body: np.ndarray
    mesh_data: object
    pressure: np.ndarray
    cauchy: np.ndarray
    jacobian_min: float
    strain_energy: float
    axis: Axis | None
    elements: int
    dofs: int
    iterations: int
    steps: int
    cuts: int
    seconds: float
    timings: dict = field(default_factory=dict)
    corner_pressure: np.ndarray | None = None
    rigid: tuple = ()
    support_force: tuple | None = None
    history: tuple = ()

    @property
    def revolution(self) -> bool:
        """True for bodies of revolution."""
        return self.axis is not None

    @property
    def materials(self) -> tuple:
        """Each body's rubber."""
        return tuple(b.material for b in self.bodies)

    def summary(self) -> dict:
        """The scalar figures as a plain dictionary (for reports): the whole, then ``bodies``."""
        out = {k: getattr(self, k) for k in ("jacobian_min", "strain_energy", "elements", "dofs", "iterations",
                                               "steps", "cuts", "seconds")}
        out["bodies"] = [b.summary() for b in self.bodies]
        if self.revolution:
            normal = self.axis.normal
            out["revolution"] = {"axis": [self.axis.point.tolist(), (self.axis.point + [-normal[1], normal[0]]).tolist()]}
        out["timings"] = dict(self.timings)
        if self.rigid:
            out["rigid"] = [part.to_json() for part in self.rigid]
            out["support"] = {"force": [float(v) for v in self.support_force]}
            out["history"] = [step.to_json() for step in self.history]
        return out


def _body(b, body, sec, mixed, mesh, mat, p1, pressure, ratio, load, growth) -> BodyReference:
    """The figures of body ``b`` from the solved state ``mat`` (the material at every quadrature point)."""
    on = mesh.body == b
    dx, wdx = mixed.dx[on], mixed.wdx[on]
    revolution = mixed.revolution
    two_pi = 2.0 * math.pi
    vol0 = two_pi * float(wdx.sum()) if revolution else None
    area0 = float(dx.sum())
    rubber = mixed.rubbers[b]
    p_body = pressure[mixed.pressure_body == b]
    return BodyReference(
        name=body.name,
        upper=p1[mesh.upper_nodes[b]].copy(),
        initial_upper=np.array(sec.upper, dtype=np.float64),
        area_initial=area0,
        area_final=float(np.sum(mat["det2"][on] * dx)),
        area_target=None if revolution else float(ratio * area0),
        volume_initial=vol0,
        volume_target=float(ratio * vol0) if revolution else None,
        volume_final=two_pi * float(np.sum(mat["stretch3"][on] * mat["det2"][on] * wdx)) if revolution else None,
        load=float(load),
        volume_change=float(np.sum((mat["Je"][on] - 1.0) * wdx) / wdx.sum()),
        max_volume_change=float(np.abs(p_body).max(initial=0.0)) / float(rubber.kappa),
        elements=int(on.sum()),
        material=rubber,
        mesh_size=float(mesh.sizes[b]),
        growth=1.0 if revolution else float(growth),
        holes=tuple(p1[h].copy() for h in mesh.hole_nodes[b]) if mesh.hole_nodes else (),
        initial_holes=tuple(np.array(h, dtype=np.float64) for h in sec.holes),
    )


def solution(problem, mixed, mesh, sections, x, report, ratios, load, timings, seconds) -> Reference:
    """The :class:`Reference` of the solved unknowns ``x`` of ``mixed`` (a :class:`~.solver.MixedProblem`)."""
    ub, skm = mixed.ubasis, mixed.skmesh
    u = x[: mixed.n_u]
    p0 = np.concatenate((mesh.points, skm.p[:, skm.facets].mean(axis=1).T))
    cells = np.column_stack((mesh.triangles, len(mesh.points) + skm.t2f.T)).astype(np.int64)
    p1 = p0 + np.concatenate((u[ub.nodal_dofs].T, u[ub.facet_dofs].T))
    mat = mixed.material(x, load, tangent=False)
    dofs_p = x[mixed.n_u:]
    # One value per vertex: at an interface, the body of the lowest index (the pressure jumps there).
    pressure = np.empty(len(mesh.points))
    pressure[mixed.pressure_vertex[::-1]] = dofs_p[::-1]
    dx = mixed.dx
    cauchy = np.einsum("eqij,eq->eij", mat["cauchy"], dx) / dx.sum(axis=1)[:, None, None]
    stretch, growth = mixed.split(load)
    per_body = growth if mixed.revolution else np.broadcast_to(np.asarray(stretch, dtype=np.float64), growth.shape)
    bodies = tuple(_body(b, body, sec, mixed, mesh, mat, p1, dofs_p, ratios[b], per_body[b], growth[b])
                   for b, (body, sec) in enumerate(zip(problem.bodies, sections)))
    corner_pressure = dofs_p[mixed.pdofs.T]
    for arr in (p0, p1, cells, pressure, cauchy, corner_pressure):
        arr.setflags(write=False)
    return Reference(
        bodies=bodies,
        initial_mesh=MeshData(points=p0, cells=cells, kind="triangle6"),
        mesh=MeshData(points=p1, cells=cells, kind="triangle6"),
        body=mesh.body,
        mesh_data=mesh,
        pressure=pressure,
        cauchy=cauchy,
        jacobian_min=float(mat["det2"].min()),
        strain_energy=float(np.sum(mat["psi"] * mixed.wdx)) * (2.0 * math.pi if mixed.revolution else 1.0),
        axis=mixed.axis,
        elements=int(len(mesh.triangles)),
        dofs=int(mixed.n_u + mixed.n_p),
        iterations=report.iterations,
        steps=report.steps,
        cuts=report.cuts,
        seconds=float(seconds),
        timings=timings,
        corner_pressure=corner_pressure,
    )
