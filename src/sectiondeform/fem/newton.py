"""Newton's method with line search, a linear predictor and automatic load stepping.

The problem is a path in the prescribed data: the lower dofs ``xd`` and the
out-of-plane stretch ``lz`` go from a solved state (``t = 0``) to the wanted
one (``t = 1``). Each step is

1. a *predictor*: the tangent at the solved state answers linearly to the
   change of ``xd`` and of ``ln lz`` (one back-substitution with a
   factorisation already at hand);
2. a *corrector*: Newton iterations, first reusing that factorisation
   (modified Newton, cheap when the change is small), then with a fresh
   tangent each iteration when the cheap ones stop contracting; a
   backtracking line search keeps every point's J > 0 and decreases the
   residual norm.

If a step fails it is halved, down to ``1 / 2**MAX_HALVINGS`` of the path;
then :class:`~sectiondeform.errors.ConvergenceError` is raised. The whole
path has a work budget (:func:`~sectiondeform.limits.newton_budget`: Newton
iterations, each load step's predictor counted as one, at most
``MAX_NEWTON_ITERATIONS`` and at most ``MAX_SOLVE_WORK`` / unknowns^1.5), so a
path whose steps keep failing and succeeding stops in bounded time with the
same error. Never a quiet unconverged result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from ..errors import ConvergenceError
from ..limits import MAX_NEWTON_ITERATIONS, MAX_SOLVE_WORK, newton_budget
from .neohooke import MixedNeoHooke, Pattern

__all__ = ["State", "Tangent", "NewtonSolver", "MAX_HALVINGS"]

MAX_HALVINGS = 8
MAX_ITERATIONS = 25
MODIFIED_ITERATIONS = 6
MODIFIED_RATE = 0.3
SWITCH_STEP = 1e-2


class _Ordered:
    """A SuperLU factorisation of ``K[order][:, order]`` answering for ``K``: ``solve`` permutes in and out.

    SuperLU's column order (COLAMD) depends on the pattern alone, and every
    tangent of a mesh has the same pattern: the order is computed with the
    first factorisation and the later ones factorise the matrix already
    permuted in that order (``permc_spec="NATURAL"``), skipping the ordering
    (the same fill, the same pivots).
    """

    __slots__ = ("lu", "order")

    def __init__(self, lu, order: np.ndarray):
        self.lu = lu
        self.order = order

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        out = np.empty_like(rhs)
        out[self.order] = self.lu.solve(np.ascontiguousarray(rhs[self.order]))
        return out


class _Reordering:
    """The gather from ``K_ff``'s CSC data to that of ``K_ff[order][:, order]``, and its index arrays."""

    def __init__(self, kff: sp.csc_matrix, order: np.ndarray):
        probe = sp.csc_matrix((np.arange(1, kff.nnz + 1, dtype=np.float64), kff.indices, kff.indptr), shape=kff.shape)
        permuted = probe[order][:, order].tocsc()
        permuted.sort_indices()
        self.order = order
        self.source = permuted.data.astype(np.int64) - 1
        self.indices, self.indptr, self.shape = permuted.indices, permuted.indptr, permuted.shape

    def matrix(self, kff: sp.csc_matrix) -> sp.csc_matrix:
        return sp.csc_matrix((kff.data[self.source], self.indices, self.indptr), shape=self.shape)


@dataclass(frozen=True, eq=False)
class Tangent:
    """A factorised tangent and its free-fixed block, at some state.

    A tangent may be a *rotated* copy of another: the problem is frame
    indifferent, so at the state ``Q x`` the tangent is ``R K R^T`` with
    ``R`` applying ``Q`` to every node's pair of position dofs. Its
    factorisation is the original one, rotated on the way in and out.

    Attributes
    ----------
    lu : scipy.sparse.linalg.SuperLU or _Ordered
        Factorisation of ``K_ff`` (free dofs in increasing order, position
        dofs first, in node pairs): anything with ``solve``.
    kfd : scipy.sparse.csc_matrix
        ``K_fd``, free rows by fixed columns.
    n_free_x : int
        Number of free position dofs (they come first).
    rotation : (2, 2) float64 ndarray or None
        ``Q``, or None for no rotation.
    """

    lu: object
    kfd: sp.csc_matrix
    n_free_x: int
    rotation: np.ndarray | None = None

    def rotated(self, q: np.ndarray) -> Tangent:
        """The same tangent, carried to the state rotated by ``q`` ((2, 2))."""
        base = self.rotation if self.rotation is not None else np.eye(2)
        return Tangent(self.lu, self.kfd, self.n_free_x, q @ base)

    def _rot(self, v: np.ndarray, k: int, inverse: bool) -> np.ndarray:
        q = self.rotation
        v = v.copy()
        v[:k] = (v[:k].reshape(-1, 2) @ (q if inverse else q.T)).ravel()
        return v

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """``K_ff^-1 rhs``, ``rhs`` of shape ``(f,)`` or ``(f, k)`` (no rotation only)."""
        if self.rotation is None:
            return self.lu.solve(rhs)
        k = self.n_free_x
        return self._rot(self.lu.solve(self._rot(rhs, k, True)), k, False)

    def kfd_dot(self, v: np.ndarray) -> np.ndarray:
        """``K_fd v`` for a change ``v`` ((d,)) of the fixed dofs."""
        if self.rotation is None:
            return self.kfd @ v
        return self._rot(self.kfd @ self._rot(v, len(v), True), self.n_free_x, False)


@dataclass(frozen=True, eq=False)
class State:
    """A solved (equilibrium) state.

    Attributes
    ----------
    z : (n_dofs,) float64 ndarray
        Node positions (node-major) then pressures.
    lz : float
        Out-of-plane stretch.
    tangent : Tangent
        A factorised tangent at (or next to) this state.
    iterations : tuple of int
        Newton iterations it took (fresh factorisations, modified ones[, load steps]).
    fields : Fields or None
        The kinematics at ``z``, if computed.
    """

    z: np.ndarray
    lz: float
    tangent: Tangent
    iterations: tuple = (0, 0)
    fields: object = None


STABILITY_MARGIN = 1.25
"""How far beyond the stretches of the last solved state a rubber's stability is checked when Newton stops: the
load step that failed went further."""


def _stretch_reach(fields, idx: np.ndarray) -> float:
    """The largest principal stretch, or inverse one, at the quadrature points of elements ``idx``."""
    sv = np.linalg.svd(fields.F[idx], compute_uv=False)
    lz = (fields.J / fields.det)[idx]
    both = np.concatenate((sv.ravel(), lz.ravel()))
    both = both[np.isfinite(both) & (both > 0)]
    return float(np.max(np.maximum(both, 1.0 / both))) if both.size else 1.0


def _raise_if_unstable(physics, state: State, t: float) -> None:
    """Raise a :class:`ConvergenceError` naming the rubber if it loses stability within reach of the stopped solve.

    A rubber whose homogeneous tests lose stability (Drucker:
    :func:`~sectiondeform.materials.homogeneous.unstable_modes`) at
    stretches the deformation reaches makes Newton stop for want of an
    equilibrium, not of a mesh: the message says so, and from which stretch.
    Nothing is raised for a stable rubber, or for the closed-form
    neo-Hookean physics (always stable).
    """
    from ..materials.homogeneous import unstable_modes

    groups = getattr(physics, "_groups", None)
    fields = state.fields if state.fields is not None else physics.fields(state.z, state.lz)
    if not groups or fields is None:
        return
    for material, idx in groups:
        if not len(idx):
            continue
        reach = _stretch_reach(fields, idx)
        lost = unstable_modes(material, max(reach * STABILITY_MARGIN, 1.01))
        if lost:
            constants = ", ".join(f"{k} = {getattr(material, k):g}" for k in material.constants)
            raise ConvergenceError(
                f"hyperelastic: the rubber ({material.model}, {constants}) is unstable {_onsets(lost)}, and this "
                f"deformation reaches stretches of {reach:.3g} (Newton stopped {t:.3g} of the way to the target): "
                "there is no equilibrium to find; give a rubber stable over the stretches of interest (check its "
                "constants or their fit, e.g. a smaller negative c20)")


def _onsets(lost: list[str]) -> str:
    """``"beyond stretch 1.12 (equibiaxial) and below 0.886 (equibiaxial)"`` from lines of :func:`unstable_modes`."""
    tension = [(float(line.rsplit(" ", 1)[1]), line.split(":")[0]) for line in lost if "beyond" in line]
    compression = [(float(line.rsplit(" ", 1)[1]), line.split(":")[0]) for line in lost if "below" in line]
    parts = []
    if tension:
        at, mode = min(tension)
        parts.append(f"beyond stretch {at:.3g} ({mode})")
    if compression:
        at, mode = max(compression)
        parts.append(f"below stretch {at:.3g} ({mode})")
    return " and ".join(parts)


class NewtonSolver:
    """Equilibrium solver of one mesh's mixed problem.

    Parameters
    ----------
    physics : MixedNeoHooke
    pattern : Pattern
        Its ``fixed`` dofs are the prescribed lower-curve positions.
    length : float
        Length scale (the section's mean thickness T), units: the tolerance
        on the position increments is ``tol * length``.
    tol : float
        Relative tolerance on the last position increment.
    permc_spec : str
        Column ordering of SuperLU.
    """

    def __init__(self, physics: MixedNeoHooke, pattern: Pattern, length: float, tol: float = 1e-9,
                 permc_spec: str = "COLAMD"):
        self.physics = physics
        self.pattern = pattern
        self.length = float(length)
        self.tol = float(tol)
        self.permc_spec = permc_spec
        n = physics.n_nodes
        free = pattern.free
        self.free_x = free < 2 * n
        if np.any(np.diff(free) <= 0):
            raise ValueError("NewtonSolver needs the pattern's free dofs in increasing order")
        # Pressure rows scaled by 1/length so the residual norm mixes like units.
        self.row_scale = np.where(self.free_x, 1.0, 1.0 / self.length)
        wm = physics._wM.sum(axis=1)  # (E, 3): integral of each pressure function
        mp = np.bincount(physics.edofs[:, 12:].ravel() - 2 * n, weights=wm.ravel(), minlength=pattern.n_dofs - 2 * n)
        full = np.zeros(pattern.n_dofs)
        full[2 * n :] = mp
        self.dres_dlnlz = full[free]  # d R_f / d ln lz at J = 1 (R_p = J - 1 - p / kappa, J = lz det F)
        self.assemblies = 0
        self.factorisations = 0
        self._reordering = None  # set by the first factorisation: the column order of every later one

    # -- building blocks -------------------------------------------------
    def residual(self, z: np.ndarray, lz: float):
        """``(R_f, fields)`` at ``z``, or ``(None, None)`` if a point is inverted."""
        f = self.physics.fields(z, lz)
        if f is None:
            return None, None
        self.assemblies += 1
        return self.physics.residual(f)[self.pattern.free], f

    def tangent(self, fields) -> Tangent:
        """Assemble and factorise the tangent for ``fields``."""
        coupled = self.pattern.coupling is not None and hasattr(self.physics, "coupling_matrices")
        kff, kfd = self.pattern.matrices(self.physics.element_matrices(fields),
                                         self.physics.coupling_matrices(fields) if coupled else None)
        self.factorisations += 1
        reordering = self._reordering
        try:
            if reordering is None:
                lu = splu(kff, permc_spec=self.permc_spec, diag_pivot_thresh=0.01, options={"SymmetricMode": True})
                if self.permc_spec != "NATURAL":
                    # SuperLU factorised K Pc with Pc[i, perm_c[i]] = 1: column j of K Pc is column argsort(perm_c)[j] of K.
                    self._reordering = _Reordering(kff, np.argsort(lu.perm_c))
            else:
                lu = _Ordered(splu(reordering.matrix(kff), permc_spec="NATURAL", diag_pivot_thresh=0.01,
                                   options={"SymmetricMode": True}), reordering.order)
        except RuntimeError as exc:  # exactly singular
            raise ConvergenceError(f"hyperelastic: singular tangent ({exc}); is a part of the mesh unconstrained?") from None
        except (MemoryError, SystemError) as exc:  # SuperLU out of memory, or given non-finite entries
            raise ConvergenceError(
                f"hyperelastic: the tangent of {kff.shape[0]} unknowns could not be factorised ({type(exc).__name__}: {exc}); "
                "the section's scale or its smallest features are too extreme for the mesh"
            ) from None
        return Tangent(lu, kfd, int(self.free_x.sum()))

    def _merit(self, r: np.ndarray) -> float:
        return float(np.linalg.norm(r * self.row_scale))


    def _state(self, z_free: np.ndarray, xd: np.ndarray, template: np.ndarray) -> np.ndarray:
        z = template.copy()
        z[self.pattern.free] = z_free
        z[self.pattern.fixed] = xd
        return z

    # -- one corrector ---------------------------------------------------
    def correct(self, z: np.ndarray, lz: float, tangent: Tangent | None, max_iter: int = MAX_ITERATIONS):
        """Newton corrector from ``z`` (prescribed dofs already in place).

        Iterations reuse ``tangent`` (modified Newton) while the residual
        norm falls by at least ``1 / MODIFIED_RATE`` per step, and switch to
        a fresh tangent otherwise; after a full step shorter than
        ``SWITCH_STEP`` T they go back to reusing it. Converged when the
        error left after a step, estimated from the contraction of the last
        two steps, is below ``tol`` T.

        Returns
        -------
        State or None
            None if the iterations fail (inverted points, no decrease, too many).
        """
        return self._correct(z, lz, tangent, max_iter)[0]

    def _correct(self, z: np.ndarray, lz: float, tangent: Tangent | None, max_iter: int, at=None):
        """:meth:`correct`, and the number of iterations it ran (``at``: the residual and fields at ``z``, if known)."""
        free = self.pattern.free
        r, f = self.residual(z, lz) if at is None else at
        if r is None:
            return None, 0
        merit = self._merit(r)
        modified = tangent is not None
        counts = [0, 0]
        last = tangent
        prev = math.inf
        target = self.tol * self.length
        for it in range(max_iter):
            if not modified:
                last = self.tangent(f)
            dz = -last.solve(r)
            counts[1 if modified else 0] += 1
            step = float(np.abs(dz[self.free_x]).max(initial=0.0))
            alpha, accepted = 1.0, False
            while alpha >= 1.0 / 64:
                zt = z.copy()
                zt[free] += alpha * dz
                rt, ft = self.residual(zt, lz)
                if rt is not None:
                    mt = self._merit(rt)
                    if mt <= (1.0 - 1e-4 * alpha) * merit or step * alpha <= target:
                        accepted = True
                        break
                if modified:
                    break
                alpha *= 0.5
            if not accepted:
                if modified:
                    modified = False  # fall back to full Newton from the current point
                    continue
                return None, it + 1
            rate = step / prev
            left = step if (rate >= 1.0 or prev == math.inf) else step * rate / (1.0 - rate)
            if alpha == 1.0 and (step <= target or left <= target):
                return State(zt, lz, last, tuple(counts), ft), it + 1
            if modified and mt > MODIFIED_RATE * merit:
                modified = False
            elif not modified and alpha == 1.0 and step <= SWITCH_STEP * self.length:
                modified = True
            z, r, f, merit, prev = zt, rt, ft, mt, step * alpha
        return None, max_iter

    # -- the path ----------------------------------------------------------
    def predict(self, state: State, xd: np.ndarray, lz: float, xd0: np.ndarray | None = None,
                load: np.ndarray | None = None) -> np.ndarray:
        """Linear predictor from ``state`` to the data ``(xd, lz)``; returns the full ``z``.

        ``load`` ((f,), optional): the first-order change of the free residual from anything else that moves
        on the way (a rigid part: :meth:`~sectiondeform.fem.contact.ContactPhysics.residual_rate`).
        """
        d0 = state.z[self.pattern.fixed] if xd0 is None else xd0
        rhs = state.tangent.kfd_dot(xd - d0) + (np.log(lz) - np.log(state.lz)) * self.dres_dlnlz
        if load is not None:
            rhs = rhs + load
        dz = -state.tangent.solve(rhs)
        return self._state(state.z[self.pattern.free] + dz, xd, state.z)

    def solve(self, start: State, xd: np.ndarray, lz: float, modified: bool = True, halvings: int | None = None,
              load: np.ndarray | None = None, budget: int | None = None) -> State:
        """Equilibrium for the prescribed ``xd`` and ``lz``, continuing from ``start``.

        Parameters
        ----------
        start : State
            A solved state (with its tangent) to start the path from.
        xd : (d,) float64 ndarray
            Wanted values of the fixed dofs, units.
        lz : float
            Wanted out-of-plane stretch.
        modified : bool
            Try modified Newton with the predictor's factorisation first.
        halvings : int, optional
            Halvings of the load step before giving up (default
            :data:`MAX_HALVINGS`; a caller that steps another parameter
            itself, as the contact loading does the parts, gives up sooner
            and halves its own step instead).
        load : (f,) float64 ndarray, optional
            The first-order change of the free residual over the whole path
            from anything else that moves along it (the parts of a contact
            loading), for the predictor of each load step (its share).
        budget : int, optional
            At most this many Newton iterations (fewer than the solve's own
            bound, :func:`~sectiondeform.limits.newton_budget`: what a
            caller's own bound leaves).

        Returns
        -------
        State

        Raises
        ------
        ConvergenceError
            If the path cannot be followed even in ``2**halvings`` steps,
            or within the work budget (:func:`~sectiondeform.limits.newton_budget`).
        """
        halvings = MAX_HALVINGS if halvings is None else halvings
        xd0 = start.z[self.pattern.fixed]
        lnl0, lnl1 = np.log(start.lz), np.log(lz)
        t, dt, state = 0.0, 1.0, start
        total = [0, 0]
        steps = 0
        unknowns = len(self.pattern.free)
        budget = newton_budget(unknowns) if budget is None else min(budget, newton_budget(unknowns))
        used = 0
        while t < 1.0:
            if used >= budget:
                _raise_if_unstable(self.physics, state, t)
                raise ConvergenceError(
                    f"hyperelastic: Newton stopped at its bound of {budget} iterations for {unknowns} unknowns "
                    f"(at most {MAX_NEWTON_ITERATIONS}, and {MAX_SOLVE_WORK:.3g} iterations x unknowns^1.5), {t:.3g} of the way "
                    "to the target",
                    "the target or the law is too severe for this mesh (try a lower options.elements_through_thickness)",
                    state,
                )
            t1 = min(1.0, t + dt)
            xd_t = xd0 + t1 * (xd - xd0)
            lz_t = float(np.exp(lnl0 + t1 * (lnl1 - lnl0)))
            z, at = self.predict(state, xd_t, lz_t), None
            if load is not None:  # with the other loads' first-order response, if that leaves less residual
                zl = self.predict(state, xd_t, lz_t, load=(t1 - t) * load)
                at, at_l = self.residual(z, lz_t), self.residual(zl, lz_t)
                if at_l[0] is not None and (at[0] is None or self._merit(at_l[0]) < self._merit(at[0])):
                    z, at = zl, at_l
            new, ran = self._correct(z, lz_t, state.tangent if modified else None, min(MAX_ITERATIONS, budget - used), at)
            used += 1 + ran  # the predictor counts as one
            if new is None:
                dt *= 0.5
                if dt < 0.5**halvings:
                    _raise_if_unstable(self.physics, state, t)
                    stepped = f" even with load steps of 1/{2**halvings}" if halvings else ""
                    raise ConvergenceError(
                        f"hyperelastic: Newton did not converge{stepped} (stopped at {t:.3g} of the way to the target)",
                        "the target or the law is too severe", state)
                continue
            total[0] += new.iterations[0]
            total[1] += new.iterations[1]
            state, t, steps = new, t1, steps + 1
            dt = min(1.0 - t, 2.0 * dt) if t < 1.0 else dt
        return State(state.z, state.lz, state.tangent, (total[0], total[1], steps), state.fields)
