"""The reference's contact with rigid parts: a penalty at the free boundary's quadrature points.

Formulation
-----------
Every free boundary facet of the P2 mesh (not on the support, not shared
by two bodies) is integrated with Gauss points. At a point of initial
position X and current position x, each rigid part at load fraction t
(its outline ``contour − (1 − t) travel``) gives the penetration g(x)
(positive inside the part, from the closest point of its outline,
:class:`~sectiondeform.fem.contact.Obstacle`) and its outward normal n.
The contact energy and its variation are

    Π_c = ∫ (1 / 2ε) ⟨λ + ε g⟩₊² w ds₀,   δΠ_c = −∫ p n · δx w ds₀,   p = ⟨λ + ε g⟩₊,

with w the initial radius (body of revolution) or 1, ds₀ the initial arc
length, ε a penalty (:data:`PENALTY` μ / h of the facet's body) and λ the
augmented-Lagrangian multiplier of the point (0 while loading; updated at
the end, λ ← p, until the penetration left is below ``tol``). The tangent is
ε (n · φ_a)(n · φ_b) w ds₀ at the points in contact (the outline's
curvature left out: Newton's line search covers it). A point's terms
involve only its triangle's degrees of freedom, so the contact adds no
entry to the elastic sparsity pattern.

It is the classical pointwise penalty, written independently of the fast
model's node-wise (mortar) contact (:mod:`sectiondeform.fem.contact`):
only the outline's geometry (distance, normal, arc length) is shared.

Coulomb friction (a part's ``friction`` μ_f > 0) is a tangential penalty
with the classical return mapping, no rounding: each point has an anchor
s_a along the part's outline; with d = s − s_a (s the point's closest
place) the tangential force per reference length along τ = (−n_y, n_x)
is q = −ε_t d while |ε_t d| ≤ μ_f p, else −μ_f p sign(d) (slip);
ε_t = :data:`TANGENT_PENALTY` ε. The tangent gains ε_t (τ · φ_a)(τ · φ_b)
where a point sticks and −μ_f sign(d) ε (τ · φ_a)(n · φ_b) where it slips
(not symmetric). The anchors are history, moved after each accepted load
step (:meth:`ReferenceContact.commit`): a sticking point keeps its anchor,
a slipping one is anchored μ_f p / ε_t behind where it is, a point not
pressed where it is.

The figures (:meth:`ReferenceContact.figures`): the force the bodies exert on each part
(per unit depth, or the whole ring's for a body of revolution, 2π × the
per-radian integral), the contact length (where the trial pressure
λ + ε g is positive, its ends interpolated linearly between the points),
the peak and mean true pressure (per current length), the penetration
left and the pressure along the contact.
"""

from __future__ import annotations

import numpy as np

from ..errors import require
from ..fem.contact import Obstacle, PartContact

__all__ = ["PENALTY", "TANGENT_PENALTY", "ReferenceContact"]

#: Penalty as a multiple of μ / h (the facet's body's initial shear modulus over its element size).
PENALTY = 1000.0
#: The tangential (stick) penalty of friction, as a multiple of the normal one.
TANGENT_PENALTY = 1.0
#: Gauss points per facet: scikit-fem's ``intorder`` (5: three points, exact for degree 5).
INTORDER = 5


class ReferenceContact:
    """The rigid parts' contact terms on a :class:`~sectiondeform.reference.solver.MixedProblem`.

    Parameters
    ----------
    mixed : MixedProblem
        Its mesh, bases, support facets and axis.
    parts : sequence of Rigid
        The problem's rigid parts (:class:`~sectiondeform.problem.Rigid`).
    tol : float
        Discretisation tolerance of the parts' outlines, units.

    Attributes
    ----------
    t : float
        The load fraction the parts stand at (0 drawn, 1 at their end).
    lam : (K, nf, nq) float64 ndarray
        Each part's multiplier at each point (pressure units, per initial length); replaced by an update, never
        changed in place (:meth:`touch` keeps its last answer for the same multipliers).
    """

    def __init__(self, mixed, parts, *, tol: float):
        skfem = require("skfem", "fem", "the finite-element reference")
        m = mixed.skmesh
        facets = np.setdiff1d(m.boundary_facets(), mixed.lower_facets)
        fb = skfem.FacetBasis(m, skfem.ElementVector(skfem.ElementTriP2()), facets=facets, intorder=INTORDER)
        self.names = tuple(part.name for part in parts)
        self.obstacles = [Obstacle(part.contour.discretise(tol)[0], part.travel) for part in parts]
        self.dofs = np.asarray(fb.element_dofs)  # (12, nf): the facet's triangle's displacement dofs
        self.cell = np.asarray(fb.tind)  # (nf,)
        self.phi = np.stack([np.asarray(fb.basis[a][0]) for a in range(fb.Nbfun)])  # (12, 2, nf, nq)
        grad = np.stack([np.asarray(fb.basis[a][0].grad) for a in range(fb.Nbfun)])  # (12, 2, 2, nf, nq)
        normal = np.asarray(fb.normals)  # (2, nf, nq), outward, initial
        self.t0 = np.moveaxis(np.stack((-normal[1], normal[0])), 0, -1)  # (nf, nq, 2): initial unit tangent
        self.dphi = np.einsum("aijfq,fqj->aifq", grad, self.t0)  # d/ds₀ along the facet
        self.X = np.moveaxis(np.asarray(fb.global_coordinates()), 0, -1)  # (nf, nq, 2)
        ends = m.p[:, m.facets[:, facets]].T  # (nf, 2 ends, 2)
        along = ends[:, 1] - ends[:, 0]
        self.xi = np.einsum("fqi,fi->fq", self.X - ends[:, None, 0], along) / np.einsum("fi,fi->f", along, along)[:, None]
        self.ds0 = np.asarray(fb.dx)  # (nf, nq): initial length share
        self.axis = mixed.axis
        self.weight = self.ds0 * (mixed.axis.radius(self.X) if mixed.axis is not None else 1.0)
        body = mixed.groups[self.cell]
        mu = np.array([r.shear_modulus for r in mixed.rubbers], dtype=np.float64)[body]
        self.size = np.asarray(mixed.section_mesh.sizes, dtype=np.float64)[body]  # (nf,)
        self.eps = (PENALTY * mu / self.size)[:, None] * np.ones_like(self.ds0)  # (nf, nq)
        self.reach = 2.0 * float(self.size.max())
        self.n_u = mixed.n_u
        self.t = 0.0
        self.lam = np.zeros((len(parts),) + self.ds0.shape)
        self.friction = np.array([part.friction for part in parts], dtype=np.float64)
        self.anchor = np.full(self.lam.shape, np.nan)  # friction: where along each part each point sticks
        self._touched = None  # (displacements, t, lam, answer) of the last :meth:`touch`

    # --- kinematics -------------------------------------------------------------

    def positions(self, x: np.ndarray) -> np.ndarray:
        """Current positions of the points, ``(nf, nq, 2)``."""
        return self.X + np.einsum("af,aifq->fqi", x[: self.n_u][self.dofs], self.phi)

    def touch(self, x: np.ndarray):
        """Per part, ``(trial, n, s)`` at every point, ``(nf, nq)``, ``(nf, nq, 2)``, ``(nf, nq)``.

        ``trial`` is the trial pressure λ + ε g (−inf where the part is out of reach). The last
        answer is kept: a Newton iteration's residual and tangent, and the figures, ask at the same state.
        """
        u = x[: self.n_u]
        key = (self.t, self.lam)
        if self._touched is not None and self._touched[1] == key[0] and self._touched[2] is key[1] \
                and np.array_equal(self._touched[0], u):
            return self._touched[3]
        xq = self.positions(x).reshape(-1, 2)
        out = []
        for k, obs in enumerate(self.obstacles):
            trial = np.full(len(xq), -np.inf)
            n = np.zeros((len(xq), 2))
            s = np.full(len(xq), np.nan)
            idx, g, nk, sk = obs.query(xq, obs.at(self.t), self.reach)
            trial[idx] = self.lam[k].ravel()[idx] + self.eps.ravel()[idx] * g
            n[idx], s[idx] = nk, sk
            out.append((trial.reshape(self.ds0.shape), n.reshape(self.X.shape), s.reshape(self.ds0.shape)))
        self._touched = (u.copy(), key[0], key[1], out)
        return out

    # --- residual and tangent ---------------------------------------------------

    def tangential(self, k: int, trial: np.ndarray, s: np.ndarray):
        """Part ``k``'s friction at every point: ``(q, slip, sign)``, each ``(nf, nq)``.

        ``q`` is the tangential force per reference length along the
        outline's direction τ = (−n_y, n_x), on the body: −ε_t d while it
        sticks (d = s − s_a, the slip from the anchor, the shorter way round
        the outline), −μ_f p sign(d) once |ε_t d| exceeds μ_f p (Coulomb's
        return mapping, no rounding); zero where the part does not press.
        """
        p = np.maximum(trial, 0.0)
        d = np.nan_to_num(s - self.anchor[k])
        per = self.obstacles[k].perimeter
        d = d - per * np.round(d / per)
        stick = -TANGENT_PENALTY * self.eps * d
        limit = self.friction[k] * p
        slip = np.abs(stick) > limit
        sign = np.sign(d)
        return np.where(p > 0, np.where(slip, -limit * sign, stick), 0.0), slip, sign

    def residual(self, x: np.ndarray) -> np.ndarray:
        """The contact's part of the residual, ``(n_u,)``: −∫ (p n + q τ) · φ_a w ds₀."""
        r = np.zeros(self.n_u)
        for k, (trial, n, s) in enumerate(self.touch(x)):
            p = np.maximum(trial, 0.0)
            if not p.any():
                continue
            traction = p[..., None] * n
            if self.friction[k] > 0:
                q = self.tangential(k, trial, s)[0]
                traction = traction + q[..., None] * np.stack((-n[..., 1], n[..., 0]), axis=-1)
            np.add.at(r, self.dofs, -np.einsum("aifq,fqi,fq->af", self.phi, traction, self.weight))
        return r

    def blocks(self, x: np.ndarray) -> np.ndarray:
        """The contact's tangent per facet, ``(12, 12, nf)``, where the point is pressed.

        ε (n · φ_a)(n · φ_b) w ds₀; with friction, sticking ε_t (τ · φ_a)(τ · φ_b) w ds₀ and slipping
        −μ_f sign(d) ε (τ · φ_a)(n · φ_b) w ds₀ (not symmetric), the outline's curvature left out.
        """
        out = np.zeros((self.dofs.shape[0],) * 2 + (self.dofs.shape[1],))
        for k, (trial, n, s) in enumerate(self.touch(x)):
            on = trial > 0
            if not on.any():
                continue
            nphi = np.einsum("aifq,fqi->afq", self.phi, n)
            w = np.where(on, self.eps * self.weight, 0.0)
            out += np.einsum("afq,bfq,fq->abf", nphi, nphi, w)
            if self.friction[k] > 0:
                _, slip, sign = self.tangential(k, trial, s)
                tphi = np.einsum("aifq,fqi->afq", self.phi, np.stack((-n[..., 1], n[..., 0]), axis=-1))
                out += np.einsum("afq,bfq,fq->abf", tphi, tphi, np.where(slip, 0.0, TANGENT_PENALTY * w))
                out -= np.einsum("afq,bfq,fq->abf", tphi, nphi, np.where(slip, self.friction[k] * sign * w, 0.0))
        return out

    def commit(self, x: np.ndarray) -> None:
        """Move the friction anchors to the solved state ``x``: a sticking point keeps its anchor, a slipping one
        is anchored μ_f p / ε_t behind where it is, a point not pressed where it is (the return mapping's history).
        """
        if not self.friction.any():
            return
        anchor = self.anchor.copy()
        xq = self.positions(x).reshape(-1, 2)
        for k, (trial, _, s) in enumerate(self.touch(x)):
            if self.friction[k] <= 0:
                continue
            obs = self.obstacles[k]
            q = self.tangential(k, trial, s)[0]
            everywhere = obs.query(xq, obs.at(self.t), np.inf)[3].reshape(s.shape)  # every point's place
            anchor[k] = np.where(trial > 0, s + q / (TANGENT_PENALTY * self.eps), everywhere)
        self.anchor = anchor

    # --- augmented Lagrangian ---------------------------------------------------

    def penetration(self, x: np.ndarray) -> float:
        """The largest penetration of a pressed point into a part, units (0 without contact)."""
        worst = 0.0
        for k, (trial, _, _) in enumerate(self.touch(x)):
            on = trial > 0
            if on.any():
                g = (trial - self.lam[k]) / self.eps
                worst = max(worst, float(np.abs(g[on]).max()))
        return worst

    def update(self, x: np.ndarray) -> None:
        """λ ← ⟨λ + ε g⟩₊ at every point (Uzawa's update)."""
        self.lam = np.stack([np.maximum(trial, 0.0) for trial, _, _ in self.touch(x)])

    # --- figures ----------------------------------------------------------------

    def stretch(self, x: np.ndarray) -> np.ndarray:
        """Current over initial length along the facets at the points, ``(nf, nq)``."""
        tangent = self.t0 + np.einsum("af,aifq->fqi", x[: self.n_u][self.dofs], self.dphi)
        return np.hypot(tangent[..., 0], tangent[..., 1])

    def forces(self, x: np.ndarray, ring: float) -> list[tuple[float, float]]:
        """Each part's force ``(fx, fy)``: −ring ∫ (p n + q τ) w ds₀ (``ring`` 1, or 2π for a body of revolution)."""
        out = []
        for k, (trial, n, s) in enumerate(self.touch(x)):
            traction = np.maximum(trial, 0.0)[..., None] * n
            if self.friction[k] > 0:
                traction = traction + self.tangential(k, trial, s)[0][..., None] * np.stack((-n[..., 1], n[..., 0]), axis=-1)
            f = -ring * np.einsum("fq,fqi->i", self.weight, traction)
            out.append((float(f[0]) + 0.0, float(f[1]) + 0.0))  # no negative zero
        return out

    def figures(self, x: np.ndarray, ring: float) -> tuple:
        """Each part's :class:`~sectiondeform.fem.contact.PartContact` at the solved state ``x``.

        The true pressure is p ds₀ w / (ds r), per current length (and
        current radius r for a body of revolution). The contact length sums,
        facet by facet, where the trial pressure λ + ε g, linear between
        the points (and constant from the end points to the facet's ends),
        is positive, times the facet's current length.
        """
        xq = self.positions(x)
        stretch = self.stretch(x)
        radius = self.axis.radius(xq) / self.axis.radius(self.X) if self.axis is not None else 1.0
        dl = self.ds0 * stretch  # current length share of each point
        true_over = 1.0 / (stretch * radius)  # p → the true pressure
        length_f = dl.sum(axis=1)  # (nf,)
        out = []
        forces = self.forces(x, ring)
        for k, (trial, _, s) in enumerate(self.touch(x)):
            p = np.maximum(trial, 0.0)
            on = p > 0
            floor = -float(self.eps.max()) * self.reach  # out of reach: far from contact
            v = np.where(np.isfinite(trial), trial, floor)
            v = np.concatenate((v[:, :1], v, v[:, -1:]), axis=1)  # (nf, nq + 2)
            xi = np.concatenate((np.zeros((len(v), 1)), self.xi, np.ones((len(v), 1))), axis=1)
            a, b, d = v[:, :-1], v[:, 1:], np.diff(xi, axis=1)
            with np.errstate(invalid="ignore", divide="ignore"):
                frac = np.where((a > 0) & (b > 0), 1.0,
                                np.where((a > 0) != (b > 0), np.maximum(a, b) / np.abs(a - b), 0.0))
            length = float(((frac * d).sum(axis=1) * length_f).sum())
            true = p * true_over
            order = np.argsort(s[on], kind="stable")
            g = (trial - self.lam[k]) / self.eps
            out.append(PartContact(
                name=self.names[k], force=forces[k], length=length,
                pressure_max=float(true[on].max(initial=0.0)),
                pressure_mean=float((p * self.ds0 / radius)[on].sum() / length) if length > 0 else 0.0,
                penetration_max=float(np.maximum(g[on], 0.0).max(initial=0.0)),
                pressure=np.column_stack((xq[on], true[on]))[order],
                outline=self.obstacles[k].ring + self.obstacles[k].at(self.t)))
        return tuple(out)
