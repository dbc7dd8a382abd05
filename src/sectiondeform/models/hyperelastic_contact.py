"""Rigid parts in the hyperelastic model: the loading from the parts' start to their end, and the forces.

:class:`Contact` is built once per prepared problem
(:class:`~sectiondeform.models.hyperelastic.HyperelasticPrepared`) when the
problem has rigid parts: the free boundary (made with the prepared problem,
whose sparse pattern its nodes' pressures shape: :func:`contact_boundary`)
and each part's outline (:mod:`~sectiondeform.fem.contact`). :meth:`Contact.solve` replaces
the plain Newton solve of a placement:

* **from the undeformed bodies** (no warm start): the support (from the
  bodies' rigid fit to the target) and every part (from ``contour − travel``
  to ``contour``) move together in load steps, each step a Newton solve
  with the parts held where the step puts them; a step that fails is
  halved, down to 1/64 of the first step, and then the loading is refused
  naming the step and the part that penetrates most;
* **from an earlier result** (a warm start): the parts are at their end,
  the multipliers are the result's, one solve;
* then the augmented-Lagrangian updates, until the largest weighted
  penetration is at most :data:`~sectiondeform.fem.contact.PENETRATION_FRACTION`
  of the element size (a warning when the updates leave more than
  :data:`PENETRATION_WARNING` of it: :data:`MAX_UPDATES` of them, or fewer
  when an update's solve fails, which keeps the answer before it).

The forces at every step (each part's and the support's) are the history,
a load–deflection curve.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field, replace

import numpy as np
import shapely

from ..errors import ConvergenceError
from ..fem.contact import (
    MAX_UPDATES,
    PENALTY,
    PENETRATION_FRACTION,
    SMOOTHING,
    Boundary,
    ContactPhysics,
    Obstacle,
    PartContact,
    contact_figures,
    free_boundary,
    part_forces,
    ring_factor,
)
from ..limits import MAX_SOLVE_WORK, work_budget

__all__ = ["auto_refinement", "contact_zones", "contact_boundary", "Contact", "ContactState", "HistoryStep", "PENETRATION_WARNING", "MAX_HALVINGS"]

ZONE_REACH = 2.0
"""A body's contour within this many of its element sizes of a part's start is meshed finer (:func:`contact_zones`)."""
RESOLVED_ELEMENTS = 2
"""A contact shorter than this many of the smallest elements is a warning: its peak pressure is smeared (a lip seal's
0.3 mm contact: its peak 17 % under the finer meshes' over 1.5 elements, within 3 % of them from 2 on)."""
PENETRATION_WARNING = 1e-2
"""A penetration left above this fraction of the element size is a warning."""
MAX_HALVINGS = 6
"""A load step is halved at most this many times before the loading is refused."""


class _LoadingBound(ConvergenceError):
    """The contact loading reached :data:`~sectiondeform.limits.MAX_SOLVE_WORK`: refused as it is, no smaller step tried."""


MIN_STEPS, MAX_STEPS = 2, 32
PREVIEW_UPDATES = 2
"""Linear augmented-Lagrangian updates of a preview that moves the parts (one back-substitution each)."""
STEP_HALVINGS = 0
"""Halvings a load step's solve makes of its own step (the support's motion) before the loading halves the step,
which moves the parts and the support together: none. The parts do not move within a solve, so its own halvings
cannot ease a part's step, and they cost factorisations (measured: failed solves took 36 to 61 factorisations
each, 142 of the bumper's 196 at 8 elements through; without them 71, the O-ring 144 instead of 462, every
result the same to the bit)."""
STEP_FRACTION = 0.7
"""A load step moves a part by at most this fraction of the smallest element size (within MIN_STEPS..MAX_STEPS steps).

The smallest is the halved size where the parts press (``contact_refinement`` 2). Over thirteen contact problems
(the public cases, the worked O-rings, the Hertz blocks and hemispheres, the bumper and sleeve at 8 and 16 elements
through, the block under a sliding plate with and without friction): 232 factorisations at 0.7, 238 at 0.5, 299 at
0.5 of the body's unhalved size (the O-ring with κ = 100 μ alone 82, its steps failing and halved)."""


@dataclass(frozen=True)
class HistoryStep:
    """The forces at one load step.

    Attributes
    ----------
    travel : float
        The fraction of the loading done, 0 (start) to 1 (end).
    forces : dict
        Each part's name, and ``"support"``, to the force ``(fx, fy)`` on it.
    """

    travel: float
    forces: dict

    def to_json(self) -> dict:
        """The result's ``history[]`` object."""
        return {"travel": self.travel, "forces": {k: [float(v[0]), float(v[1])] for k, v in self.forces.items()}}


@dataclass(frozen=True, eq=False)
class ContactState:
    """The contact part of a solved state.

    Attributes
    ----------
    lam : (K, V) float64 ndarray
        The multipliers for the next solve, per part and boundary node (a warm start carries them).
    parts : tuple of PartContact
    support_force : (float, float)
        The force the bodies exert on the support (per unit length, or the whole ring's).
    history : tuple of HistoryStep
    warnings : tuple of str
    anchor : (K, P) float64 ndarray or None
        Friction's anchors (a warm start carries them too).
    travels : tuple of (float, float)
        Each part's travel the state was solved for, units.
    tangent : dict
        The tangent factorised at this state and these multipliers, once a
        preview asked for it (:meth:`Contact.tangent_at`); empty before.
    """

    lam: np.ndarray
    parts: tuple
    support_force: tuple
    history: tuple
    warnings: tuple = ()
    anchor: np.ndarray = None
    travels: tuple = ()
    tangent: dict = field(default_factory=dict, repr=False, compare=False)


AUTO_REFINE_VERTICES = 400
"""The mesh is halved where parts press by default only while the uniform one has at most about this many vertices."""


def auto_refinement(contours, sizes, parts) -> int:
    """The default ``contact_refinement``: 2 (halved where the parts press) for frictionless parts on a small mesh, else 1.

    Measured on 147 generated contact cases (docs/reliability.md): halved,
    meshes of 670 to 1,200 vertices ran into the loading's work bound or past
    20 s, and bodies of revolution under a plate with friction 0.3 were
    refused at their first load steps with no physical reason named, where
    the uniform mesh answered or named one. The public and worked cases
    (55 to 190 vertices, frictionless) are halved. ``contact_refinement`` 2
    halves any case.

    ``contours``, ``sizes`` and ``parts`` are :func:`contact_zones`'s; the
    vertices are :func:`~sectiondeform.fem.union_mesh.vertex_estimate`'s.
    Returns 1 or 2.
    """
    if any(part.friction > 0.0 for part in parts):
        return 1
    from ..fem.union_mesh import vertex_estimate  # here: deform.py imports this module, the mesher's scipy is heavy

    vertices = vertex_estimate([shapely.Polygon(ring) for ring in contours], sizes)
    return 2 if vertices <= AUTO_REFINE_VERTICES else 1


def contact_zones(contours, sizes, parts, tol: float) -> list:
    """Where each body will touch the rigid parts: the mesh is made finer there.

    A body's zone is the piece of its contour within :data:`ZONE_REACH` of
    its element sizes of any part where the part *starts* (its contour less
    its travel; inside it included): where a contact begins, spreads and its
    pressure varies most. The start, not the end: a travel given later (a
    drag on the page, a study's sweep, ``deform(travel=...)``) moves a
    part's end and keeps its start, so the mesh and the answer are the case
    with that travel's, to the bit. A part drawn farther than that from
    every body at its start gets no finer mesh.

    Parameters
    ----------
    contours : sequence of (k_b, 2) float64 ndarray
        Each body's closed contour, units.
    sizes : (B,) float64 ndarray
        Each body's element size, units.
    parts : sequence of RigidPart
        The rigid parts, each with its ``contour`` at its end and its ``travel``.
    tol : float
        Discretisation tolerance of the parts' contours, units.

    Returns
    -------
    list of (shapely geometry or None)
        Per body, its zone, None where no part starts near it.
    """
    starts = [shapely.Polygon(part.contour.discretise(tol)[0] - np.asarray(part.travel, dtype=np.float64)) for part in parts]
    zones = []
    for ring, h in zip(contours, sizes):
        line = shapely.LineString(np.concatenate((ring, ring[:1])))
        near = shapely.union_all([shapely.intersection(line, shapely.buffer(o, ZONE_REACH * float(h))) for o in starts])
        zones.append(None if shapely.is_empty(near) else near)
    return zones


def _radius(prepared):
    """The distance from the axis of points ``(..., 2)`` for a body of revolution (its physics'); None for a plane section."""
    return None if prepared.plane else prepared.physics.distance


def contact_boundary(prepared) -> Boundary:
    """The free boundary of a prepared problem's mesh (its physics, support nodes, materials and sizes set)."""
    mesh = prepared.mesh
    mu = np.array([m.shear_modulus for m in prepared.materials], dtype=np.float64)
    return free_boundary(mesh.nodes, mesh.cells, mesh.body, prepared.fixed_ids, mu, mesh.cell_size, _radius(prepared))


class Contact:
    """The rigid parts of a prepared problem and how to load them.

    Parameters
    ----------
    prepared : HyperelasticPrepared
        Its mesh, sizes, materials, support nodes and physics.

    """

    def __init__(self, prepared):
        problem = prepared.problem
        self.plane = prepared.plane
        self.radius = _radius(prepared)
        self.boundary = prepared.boundary
        tol = 1e-6 * problem.size
        self.obstacles = [Obstacle(part.contour.discretise(tol)[0], part.travel, part.friction) for part in problem.rigid]
        self.names = tuple(part.name for part in problem.rigid)
        self.labels = tuple(f"rigid[{i}] {part.name!r}" for i, part in enumerate(problem.rigid))
        self.ring = ring_factor(self.plane)
        self.size = float(prepared.mesh.cell_size.min())

    def obstacles_for(self, travels=None) -> list:
        """The parts travelling ``travels`` (one ``(dx, dy)`` each, units; None: the problem's), each from where it starts.

        A part starts at its contour less its travel in the problem; another
        travel moves its end, not its start (as a designer drags a part).
        """
        if travels is None:
            return self.obstacles
        return [obs.moved(np.asarray(tr, dtype=np.float64) - obs.travel, tr) for obs, tr in zip(self.obstacles, travels)]

    @staticmethod
    def travels_of(obstacles) -> tuple:
        """Each part's travel, ``((dx, dy), ...)``, units."""
        return tuple((float(o.travel[0]), float(o.travel[1])) for o in obstacles)

    def end_shifts(self, warm: ContactState, travels=None) -> np.ndarray:
        """How far each part's end moves from where ``warm`` was solved to ``travels`` (None: the problem's), ``(K, 2)``."""
        now = self.travels_of(self.obstacles) if travels is None else travels
        return np.asarray(now, dtype=np.float64) - np.asarray(warm.travels, dtype=np.float64)

    def steps(self, obstacles, share: float = 1.0) -> int:
        """Load steps moving each of ``obstacles`` by at most :data:`STEP_FRACTION` of the smallest element size
        over ``share`` of their travel.
        """
        travel = share * max(float(np.hypot(*obs.travel)) for obs in obstacles)
        return int(np.clip(math.ceil(travel / (STEP_FRACTION * self.size)), MIN_STEPS, MAX_STEPS))

    def untouched(self, cphys: ContactPhysics, x: np.ndarray) -> float:
        """How much of the loading the parts travel before any of them presses on the bodies held at ``x``, 0 to 1.

        A point's penetration grows by at most the part's move, so no point
        is pressed (beyond the ramp's rounding) before the part has moved by
        its smallest gap: the bodies, held by a support that does not move,
        are then exactly as drawn.
        """
        band = SMOOTHING / PENALTY * float(self.boundary.size.max(initial=0.0))
        free = 1.0
        for obs, deepest in zip(cphys.obstacles, self.deepest(cphys.obstacles, x, 0.0)):
            move = float(np.hypot(*obs.travel))
            if move > 0:  # a part that stays does not come closer while nothing else moves
                free = min(free, max(0.0, (-deepest - 2.0 * band) / move))
        return free

    def deepest(self, obstacles, x: np.ndarray, t: float) -> list[float]:
        """Each part's largest penetration into the bodies at node positions ``x`` and load fraction ``t``, units
        (negative: its smallest gap), over the boundary's points.
        """
        xq = self.boundary.points(x)
        return [float(obs.query(xq, obs.at(t), np.inf)[1].max(initial=-np.inf)) for obs in obstacles]

    def physics(self, physics, lam=None, anchor=None, obstacles=None) -> ContactPhysics:
        """``physics`` with the contact terms, multipliers ``lam`` (zeros by default) and friction anchors, the parts
        (``obstacles``, the problem's by default) at their end.
        """
        return ContactPhysics(physics, self.boundary, self.obstacles if obstacles is None else obstacles, lam, anchor)

    def tangent_at(self, physics, solver, state, warm: ContactState):
        """``state`` with the tangent at itself and ``warm``'s multipliers, factorised once per solved state.

        Newton's last factorisation may be a load step older than the state
        it converged to; a preview from it is then off by about 1 % of the
        parts' move (first order), against 0.3 % from this one. A solve
        again does not need it (Newton corrects), so it is made only when a
        preview asks, and kept with ``warm``.
        """
        if "state" not in warm.tangent:
            cphys = self.physics(physics, warm.lam, warm.anchor, self.obstacles_for(warm.travels))
            fresh = copy.copy(solver)
            fresh.physics = cphys
            warm.tangent["state"] = replace(state, tangent=fresh.tangent(cphys.fields(state.z, state.lz)))
        return warm.tangent["state"]

    def preview(self, physics, solver, state, z: np.ndarray, warm: ContactState, travels) -> np.ndarray:
        """``z`` (a preview from ``state``) with the linear response to the parts moved from ``warm``'s travels to ``travels``.

        A back-substitution with the factorisation ``state`` carries (its
        contact stiffness included), for the first-order change of the
        contact forces as the parts' ends move
        (:meth:`~sectiondeform.fem.contact.ContactPhysics.residual_rate`),
        then :data:`PREVIEW_UPDATES` linear augmented-Lagrangian updates, one
        back-substitution each: the penalty alone lets the parts sink into
        the bodies by its compliance (2 % of a move of the bumper's plate;
        each update takes that about fiftyfold down). The contact set is
        ``state``'s, so a node the parts reach only now does not push back
        yet (the full solve on release does).
        """
        shifts = self.end_shifts(warm, travels)
        if not shifts.any():
            return z
        n = physics.n_nodes
        x = state.z[: 2 * n].reshape(n, 2)
        cphys = self.physics(physics, warm.lam, warm.anchor, self.obstacles_for(warm.travels))
        contact = cphys.evaluate(x)
        free = solver.pattern.free
        change = np.zeros(len(z))
        move = np.zeros(len(z))
        for k in range(PREVIEW_UPDATES + 1):
            dx = None if k == 0 else move[: 2 * n].reshape(n, 2)
            change[: 2 * n] = cphys.residual_rate(x, shifts, dx, contact)
            move[free] -= state.tangent.solve(change[free])
        out = z.copy()
        out[free] += move[free]
        return out

    @staticmethod
    def _load_rate(cphys: ContactPhysics, solver, state, t0: float, t1: float) -> np.ndarray | None:
        """The first-order change of the free residual at ``state`` (solved with the parts at load fraction ``t0``) as
        they move on to ``t1``, for the step's predictor; None if they stay.
        """
        shifts = np.array([obs.at(t1) - obs.at(t0) for obs in cphys.obstacles])
        if not shifts.any():
            return None
        n = cphys.inner.n_nodes
        now, cphys.t = cphys.t, t0
        try:
            rate = cphys.residual_rate(cphys.positions(state.z), shifts)
        finally:
            cphys.t = now
        full = np.zeros(len(state.z))
        full[: 2 * n] = rate
        return full[solver.pattern.free]

    def _forces(self, cphys: ContactPhysics, solver, state, figures: bool = True) -> tuple[list, tuple]:
        """Each part's contact (its force alone unless ``figures``) and the support's force at ``state``."""
        f = state.fields if cphys.computed(state.fields) else cphys.fields(state.z, state.lz)
        if f is None:  # a state with an element turned over has no forces (the start, never a solved state)
            raise ConvergenceError("contact: an element is turned over in the state the loading starts from; "
                                   "the target moves the bodies too far from where they are drawn")
        r = cphys.residual(f)[solver.pattern.fixed]
        support = (-self.ring * float(r[0::2].sum()), -self.ring * float(r[1::2].sum()))
        contact = cphys._contact_of(f)  # as the residual had it
        if not figures:
            return part_forces(cphys, contact, self.ring), support
        return contact_figures(cphys, cphys.positions(state.z), self.names, self.ring, self.radius, contact), support

    def _step(self, t: float, forces, support) -> HistoryStep:
        """The history's step at ``t``: each part's force and the support's."""
        out = dict(zip(self.names, forces))
        out["support"] = support
        return HistoryStep(float(t), out)

    def solve(self, physics, solver, base, xd: np.ndarray, lz: float, warm, travels=None) -> tuple:
        """Solve with contact from ``base`` to the data ``(xd, lz)``, the parts travelling ``travels`` (None: the problem's).

        Parameters
        ----------
        physics : object
            The prepared physics (without contact) for these laws.
        solver : NewtonSolver
            Its solver (copied here, not changed).
        base : State
            The state to start from.
        xd : (d,) float64 ndarray
            The support's nodes at the end, units.
        lz : float
            The path parameter at the end.
        warm : ContactState or None
            The contact of the state ``base`` is (a warm start, solved for
            the same ``travels``): the parts are then at their end from the
            start.
        travels : sequence of (float, float), optional
            Each part's travel, units, if not the problem's
            (:meth:`obstacles_for`).

        Returns
        -------
        state : State
        contact : ContactState

        Raises
        ------
        ConvergenceError
            Naming the load step and the part when the loading cannot go on.
        """
        obstacles = self.obstacles_for(travels)
        cphys = self.physics(physics, warm.lam if warm is not None else None, warm.anchor if warm is not None else None,
                             obstacles)
        given, solver = solver, copy.copy(solver)
        solver.physics = cphys
        fixed = solver.pattern.fixed
        xd0 = base.z[fixed]
        ln0, ln1 = math.log(base.lz), math.log(lz)
        totals = [0, 0, 0]
        state = base
        history = []

        unknowns = len(base.z)

        first = solver.factorisations
        allowed = work_budget(unknowns)

        def bound(t, to) -> _LoadingBound:
            return _LoadingBound(
                f"contact: the loading took {solver.factorisations - first} factorisations of {unknowns} unknowns, "
                f"{t:.3g} of the way, beyond its bound of {allowed} at this size ({MAX_SOLVE_WORK:.3g} factorisations x "
                "unknowns^1.5)", "the parts' travel is too severe for these bodies and this mesh (a shorter travel, "
                "a stiffer rubber, or fewer elements through the thickness, options.elements_through_thickness)", to)

        def run(t, to, halvings=None, t0=None):
            done = solver.factorisations - first
            if done > allowed:  # checked before each solve, and each solve takes no more than is left
                raise bound(t, to)
            try:
                new = solver.solve(to, xd0 + t * (xd - xd0), math.exp(ln0 + t * (ln1 - ln0)), halvings=halvings,
                                   load=None if t0 is None else self._load_rate(cphys, solver, to, t0, t),
                                   budget=allowed + 1 - done)
            except ConvergenceError:
                if solver.factorisations - first >= allowed:  # stopped by what the loading had left
                    raise bound(t, to) from None
                raise
            totals[0] += new.iterations[0]
            totals[1] += new.iterations[1]
            totals[2] += new.iterations[2]
            return new

        if warm is None:
            cphys.t = 0.0
            cphys.commit(cphys.positions(state.z))
            history.append(self._step(0.0, *self._forces(cphys, solver, state, figures=False)))
            # With the support still, the first step ends where a part first touches, and the steps of
            # STEP_FRACTION h share the travel left; the contact then starts at a step's start, not inside it.
            t, free = 0.0, 0.0
            if np.array_equal(xd, xd0):
                free = min(self.untouched(cphys, cphys.positions(state.z)), 1.0 - 1.0 / MAX_STEPS)
                if free < 0.5 / self.steps(obstacles):  # touching nearly from the start: steps as usual
                    free = 0.0
            dt0 = (1.0 - free) / self.steps(obstacles, 1.0 - free)
            dt = free if free > 0.0 else dt0
            while t < 1.0:
                t1 = min(1.0, t + dt)
                cphys.t = t1
                try:
                    state = run(t1, state, STEP_HALVINGS, t)
                except _LoadingBound as exc:
                    raise ConvergenceError(exc.stopped, exc.advice, exc.state) from None
                except ConvergenceError as exc:
                    dt *= 0.5
                    if dt < dt0 / 2**MAX_HALVINGS:
                        raise self._refusal(cphys, state, t, t1, len(history), exc) from None
                    continue
                t = t1
                if t < 1.0:  # the forces before the anchors move (at the end: after the updates, below)
                    history.append(self._step(t, *self._forces(cphys, solver, state, figures=False)))
                cphys.commit(cphys.positions(state.z))
                dt = min(dt0, 2.0 * dt)
            if state.iterations[0] == 0 and state.fields is not None:
                # The last step reused an older step's factorisation: one at the end, for the updates below and
                # for the solves again that start from this state.
                state = replace(state, tangent=solver.tangent(state.fields))
        else:
            cphys.t = 1.0
            state = run(1.0, state)
        for done in range(MAX_UPDATES + 1):
            x = cphys.positions(state.z)
            # The multipliers' update below is this evaluation too: the solve's last residual's, when it has it.
            touching = cphys._contact_of(state.fields) if cphys.computed(state.fields) else cphys.evaluate(x)
            left = cphys.penetration(x, touching)
            if left <= PENETRATION_FRACTION or done == MAX_UPDATES:
                break
            kept = (cphys.lam, cphys.anchor)
            cphys.commit(x)
            cphys.update(x, touching)
            try:
                state = run(1.0, state)
            except ConvergenceError:  # the loading's answer stands, with the penetration it has (warned if too much)
                cphys.lam, cphys.anchor = kept
                break
        parts, support = self._forces(cphys, solver, state)
        history.append(self._step(1.0, [p.force for p in parts], support))
        warnings = []
        if left > PENETRATION_WARNING:
            warnings.append(f"contact: a penetration of {left:.3g} element sizes is left after {done} "
                            "augmented-Lagrangian updates; the forces are less accurate there")
        untouched = any(part.length == 0.0 for part in parts)
        depths = self.deepest(cphys.obstacles, x, 1.0) if untouched else [0.0] * len(parts)
        for label, part, depth in zip(self.labels, parts, depths):
            if part.length == 0.0 and depth > 0.0:
                warnings.append(f"{label}: enters the bodies by {depth:.3g} at most, too little for the contact on "
                                f"this mesh (elements of {self.size:.3g}) to press: no force; refine the mesh under it "
                                "(options.elements_through_thickness)")
            elif part.length == 0.0:
                warnings.append(f"{label}: touches no body from start to end; check its contour and travel")
            elif part.length < RESOLVED_ELEMENTS * self.size:
                warnings.append(f"{label}: its contact is {part.length:.3g} long, under {RESOLVED_ELEMENTS} elements "
                                f"({self.size:.3g} each): its peak pressure is smeared over them (reported at least "
                                "its mean); refine the mesh under it (options.elements_through_thickness)")
        cphys.commit(x)
        cphys.update(x, touching)  # the multipliers and anchors of this state, for the next warm start
        given.assemblies, given.factorisations = solver.assemblies, solver.factorisations  # the work counted as without contact
        out = type(state)(state.z, state.lz, state.tangent, tuple(totals), None)
        return out, ContactState(cphys.lam, tuple(parts), support, tuple(history), tuple(warnings), cphys.anchor,
                                 self.travels_of(obstacles))

    def _refusal(self, cphys, state, t, t1, step, exc) -> ConvergenceError:
        """The loading cannot go on: name the step and the part that would penetrate most."""
        k = int(np.argmax(self.deepest(self.obstacles, cphys.positions(state.z), t1)))
        # A solve stopped by its work bound names the coarser mesh itself: refining it would be the wrong way.
        stopped, advice = getattr(exc, "stopped", str(exc)), getattr(exc, "advice", "")
        advice = f"{advice} or shorten the travel" if "stopped at its bound" in stopped else \
            f"{advice}; shorten the travel or refine the mesh (options.elements_through_thickness)".lstrip("; ")
        return ConvergenceError(f"{self.labels[k]}: the loading cannot go on at load step {step} "
                                f"(from {t:.3g} to {t1:.3g} of the travel, the step halved {MAX_HALVINGS} times): "
                                f"{stopped}", advice, state)


def contact_results(state) -> tuple:
    """``(parts, support_force, history, warnings)`` of a placed state, or empty ones without contact."""
    contact = getattr(state, "contact", None)
    if not isinstance(contact, ContactState):
        return (), None, (), ()
    return contact.parts, contact.support_force, contact.history, contact.warnings


__all__ += ["contact_results", "PartContact"]
