"""The free extrusion of a growing extruded body: the axial stretch that leaves no axial force.

An extruded body whose material grows isotropically (``{"volume_ratio": r}``
without an axis: F = Fe r^(1/3)) is in generalised plane strain with one
unknown axial stretch ``lz`` per body, set by a scalar condition: the
extrusion is free along its length, its axial force ``N(lz) = ∫ P_zz dA``
vanishes. A free body's root is the growth's cube root; a bonded body's
lies near it. Every finite-element code of the project that solves such a
body (the hyperelastic model, the finite-element reference) finds it the
same way, :func:`free_axial_stretch`: secant steps on ``ln lz``, the first
from the stiffness of a free bar (dN / d ln lz = 3 μ A), each step a solve
of the section at the new stretches continued from the last (halved when
that solve fails).
"""

from __future__ import annotations

import numpy as np

from .errors import ConvergenceError

__all__ = ["free_axial_stretch", "AXIAL_TOLERANCE", "AXIAL_STEPS", "MAX_STEP"]

AXIAL_TOLERANCE = 1e-8
"""A growing extruded body's axial force is zero when below this times its shear modulus x area."""
AXIAL_STEPS = 30
"""Solves allowed before the axial stretch is given up."""
MAX_STEP = 0.2
"""Largest change of ``ln lz`` in one secant step."""
MAX_DEVIATION = float(np.log(2.0))
"""A growing body's ``ln lz`` is sought within this of where the search starts (its free root): beyond a factor 2 of
its free axial stretch the body is held by the bodies bonded to it, not freed (refused, naming the force left)."""
STEP_HALVINGS = 6
"""A secant step whose solve fails is halved, from the last solved state, at most this many times.

The step changes the stretch at once (the solve's own load steps move the support, not the stretch): a generated
assembly of four bodies side by side, one of them 1,000 times softer and growing 5 %, had its third step's solve
fail at every load step of its own, its start 0.19 of its residual's scale off equilibrium; a quarter of that step
was solved, and the stretch found."""


def free_axial_stretch(ln_stretch: np.ndarray, force: np.ndarray, solve, growing: np.ndarray, scale: np.ndarray,
                       what: str = "body") -> np.ndarray:
    """Each growing body's ``ln lz`` at which its axial force vanishes, by secant steps.

    Parameters
    ----------
    ln_stretch : (B,) float64 ndarray
        ``ln lz`` of every body at which ``force`` was computed.
    force : (B,) float64 ndarray
        Each body's axial force there, ``∫ P_zz dA`` (moduli x units²).
    solve : callable
        ``solve(ln_stretch) -> force``: solves the section at new stretches
        (continuing from the last solve) and returns the forces; the caller
        keeps the state it reached.
    growing : (g,) int ndarray
        The bodies whose stretch is free (the others keep theirs).
    scale : (B,) float64 ndarray
        Each body's shear modulus x area: the force scale, moduli x units².
    what : str
        The body named in the error.

    Returns
    -------
    (B,) float64 ndarray
        ``ln lz`` of the last solve, the forces of the growing bodies below
        :data:`AXIAL_TOLERANCE` x ``scale``.

    Raises
    ------
    ConvergenceError
        If the forces do not vanish within :data:`AXIAL_STEPS` solves.

    Examples
    --------
    A bar of stiffness 3 μ A whose force is linear in ``ln lz``, zero at ``ln 1.1``:

    >>> f = lambda ln: 3.0 * (ln - np.log(1.1))
    >>> ln = free_axial_stretch(np.zeros(1), f(np.zeros(1)), f, np.array([0]), np.ones(1))
    >>> round(float(np.exp(ln[0])), 12)
    1.1
    """
    ln = np.array(ln_stretch, dtype=np.float64)
    force = np.asarray(force, dtype=np.float64)
    low, high = ln[growing] - MAX_DEVIATION, ln[growing] + MAX_DEVIATION
    previous = None
    for _ in range(AXIAL_STEPS):
        if (np.abs(force[growing]) <= AXIAL_TOLERANCE * scale[growing]).all():
            return ln
        if previous is None:
            slope = 3.0 * scale
        else:
            d_ln, d_force = ln - previous[0], force - previous[1]
            slope = np.where(np.abs(d_ln) > 0, d_force / np.where(d_ln == 0, 1.0, d_ln), 3.0 * scale)
        step = np.clip(force[growing] / slope[growing], -MAX_STEP, MAX_STEP)
        held = ((ln[growing] - step < low) & (ln[growing] <= low + 1e-12)) | \
            ((ln[growing] - step > high) & (ln[growing] >= high - 1e-12))
        if held.any():
            k = int(growing[np.flatnonzero(held)[0]])
            raise ConvergenceError(
                f"{what}: no axial stretch within a factor 2 of its free one frees the growing extruded body: its "
                f"axial force is still {force[k] / scale[k]:.3g} x its shear modulus x area at lz {np.exp(ln[k]):.4g} "
                f"(free: {np.exp(ln_stretch[k]):.4g}); the bodies bonded to it hold it",
                "a milder growth, or bonded bodies less stiff than it by fewer orders of magnitude")
        step = ln[growing] - np.clip(ln[growing] - step, low, high)
        previous = (ln.copy(), force)
        for halving in range(STEP_HALVINGS + 1):
            trial = ln.copy()
            trial[growing] -= step
            try:
                force = np.asarray(solve(trial.copy()), dtype=np.float64)
                break
            except ConvergenceError:
                if halving == STEP_HALVINGS:
                    raise
                step = 0.5 * step  # the caller kept the last solved state: continued from there
        ln = trial
    raise ConvergenceError(f"{what}: the axial stretch of the growing extruded body leaves an axial force after "
                           f"{AXIAL_STEPS} solves; the growth is too severe for it")
