"""Homogeneous tests of an incompressible rubber: nominal stress against stretch.

For an incompressible isotropic rubber with W(Ī₁, Ī₂) the nominal (first
Piola, force over initial area) stress in the loading direction is

- uniaxial tension, F = diag(λ, λ^-½, λ^-½):  P = 2 (λ − λ⁻²) (W₁ + W₂ / λ)
- equibiaxial tension, F = diag(λ, λ, λ⁻²):   P = 2 (λ − λ⁻⁵) (W₁ + λ² W₂)
- planar tension (pure shear), F = diag(λ, 1, λ⁻¹): P = 2 (λ − λ⁻³) (W₁ + W₂)

with W₁ = ∂W/∂Ī₁, W₂ = ∂W/∂Ī₂. For the three models W₁ and W₂ are linear in
the constants, so P is too: :func:`stress_basis` gives the matrix.
The volumetric part plays no role (J = 1).
"""

from __future__ import annotations

import numpy as np

from ..errors import CaseError
from .models import MATERIAL_MODELS

__all__ = ["MODES", "MODE_ALIASES", "mode_name", "stretch_invariants", "stress_basis", "nominal_stress", "unstable_modes"]

MODES = ("uniaxial", "equibiaxial", "planar")
MODE_ALIASES = {
    "uniaxial": "uniaxial", "ut": "uniaxial", "uniaxial_tension": "uniaxial",
    "equibiaxial": "equibiaxial", "et": "equibiaxial", "biaxial": "equibiaxial", "equibiaxial_tension": "equibiaxial",
    "planar": "planar", "ps": "planar", "pure_shear": "planar", "pure-shear": "planar", "planar_tension": "planar",
}


def mode_name(text, field: str = "mode") -> str:
    """The canonical mode name of ``text`` (case-insensitive; ``UT``, ``pure_shear``... accepted)."""
    key = str(text).strip().lower()
    if key not in MODE_ALIASES:
        raise CaseError(field, f"unknown test mode {str(text)!r}; use one of {', '.join(MODES)}")
    return MODE_ALIASES[key]


def _g_h(mode: str, lam: np.ndarray):
    """g(λ) and h(λ) with P = 2 g (W₁ + h W₂)."""
    if mode == "uniaxial":
        return lam - lam**-2, 1.0 / lam
    if mode == "equibiaxial":
        return lam - lam**-5, lam**2
    if mode == "planar":
        return lam - lam**-3, np.ones_like(lam)
    raise CaseError("mode", f"unknown test mode {mode!r}; use one of {', '.join(MODES)}")


def stretch_invariants(mode: str, stretch) -> tuple[np.ndarray, np.ndarray]:
    """I₁ and I₂ of the incompressible homogeneous test ``mode`` at ``stretch`` (arrays like it)."""
    lam = np.asarray(stretch, dtype=np.float64)
    if mode == "uniaxial":
        return lam**2 + 2.0 / lam, 2.0 * lam + lam**-2
    if mode == "equibiaxial":
        return 2.0 * lam**2 + lam**-4, lam**4 + 2.0 * lam**-2
    if mode == "planar":
        i = lam**2 + 1.0 + lam**-2
        return i, i.copy()
    raise CaseError("mode", f"unknown test mode {mode!r}; use one of {', '.join(MODES)}")


def stress_basis(model: str, mode: str, stretch) -> np.ndarray:
    """Matrix B with nominal stress P = B @ constants, constants in the model's order.

    Parameters
    ----------
    model : {"neo-hookean", "mooney-rivlin", "yeoh"}
        Constants (shear_modulus), (c10, c01), (c10, c20, c30).
    mode : {"uniaxial", "equibiaxial", "planar"}
    stretch : (N,) float64 array_like
        Stretch in the loading direction, > 0.

    Returns
    -------
    (N, n_constants) float64 ndarray
        Dimensionless.
    """
    lam = np.atleast_1d(np.asarray(stretch, dtype=np.float64))
    g, h = _g_h(mode, lam)
    x = stretch_invariants(mode, lam)[0] - 3.0
    if model == "neo-hookean":
        cols = [g]
    elif model == "mooney-rivlin":
        cols = [2.0 * g, 2.0 * g * h]
    elif model == "yeoh":
        cols = [2.0 * g, 4.0 * g * x, 6.0 * g * x * x]
    else:
        raise CaseError("model", f"unknown material model {model!r}; use one of {', '.join(MATERIAL_MODELS)}")
    return np.stack(cols, axis=-1)


def nominal_stress(material, mode: str, stretch) -> np.ndarray:
    """Nominal stress of ``material`` in the incompressible homogeneous test ``mode``.

    Parameters
    ----------
    material : NeoHookean or MooneyRivlin or Yeoh
    mode : {"uniaxial", "equibiaxial", "planar"}
    stretch : (N,) float64 array_like
        Stretch λ in the loading direction.

    Returns
    -------
    (N,) float64 ndarray
        Force over initial area, units of the moduli.

    Examples
    --------
    >>> from sectiondeform.materials import NeoHookean
    >>> float(nominal_stress(NeoHookean(1.0), "uniaxial", [2.0])[0])  # μ (λ − λ⁻²)
    1.75
    """
    constants = np.array([getattr(material, name) for name in material.constants])
    return stress_basis(material.model, mode, stretch) @ constants


def unstable_modes(material, max_stretch: float, points: int = 400) -> list[str]:
    """Where the homogeneous tests lose stability (Drucker: the stress–stretch slope ≤ 0).

    Each mode is checked on λ from 1 / ``max_stretch`` to ``max_stretch``
    (compression and tension), as Abaqus checks a fitted material; a
    neo-Hookean, and Mooney–Rivlin or Yeoh rubbers with no negative
    constant, are stable everywhere.

    Parameters
    ----------
    material : NeoHookean or MooneyRivlin or Yeoh
    max_stretch : float
        Largest stretch of interest, > 1.
    points : int
        Grid points per mode (geometric spacing).

    Returns
    -------
    list of str
        One line per unstable mode, e.g. ``"equibiaxial: unstable beyond stretch 3.12"``; empty if stable.
    """
    lam = np.geomspace(1.0 / max_stretch, max_stretch, points)
    out = []
    for mode in MODES:
        slope = np.diff(nominal_stress(material, mode, lam))
        bad = np.flatnonzero(slope <= 0.0)
        if bad.size:
            first_t = bad[lam[bad] >= 1.0]
            first_c = bad[lam[bad + 1] <= 1.0]
            if first_t.size:
                out.append(f"{mode}: unstable beyond stretch {lam[first_t[0]]:.3g}")
            if first_c.size:
                out.append(f"{mode}: unstable below stretch {lam[first_c[-1] + 1]:.3g}")
    return out
