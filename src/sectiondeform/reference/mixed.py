"""The mixed (displacement–pressure) form of a rubber model, with volumetric growth.

A rubber of :mod:`sectiondeform.materials` has the energy density

    W(F) = W_iso(F) + κ/2 (J − 1)²,

``W_iso`` depending on F only through the isochoric invariants. The
reference writes it in perturbed-Lagrangian form, the pressure ``p`` an
unknown of its own so the nearly incompressible rubber does not lock:

    Ŵ(F, p) = W_iso(F) + p (J − 1) − p² / (2κ),

and eliminating ``p`` (``p = κ (J − 1)``) gives back W.

A body that grows (cure shrinkage, swelling) by the volume ratio ``v``
does so isotropically: ``F = Fe · g I`` with ``g = v^(1/3)``; the elastic
part ``Fe = F / g`` carries the energy, per unit volume of the grown
material, so per unit initial volume

    ψ(F, p) = g³ Ŵ(F / g, p),
    ∂ψ/∂F = g² P̂(Fe),  ∂²ψ/∂F² = g Â(Fe),  ∂ψ/∂p = g³ (Je − 1 − p / κ).

With ``v = 1`` (g = 1) this is plain near-incompressibility.
"""

from __future__ import annotations

import numpy as np

__all__ = ["mixed_state"]


def mixed_state(material, F: np.ndarray, p: np.ndarray, growth: float = 1.0, tangent: bool = True,
                components: np.ndarray | None = None, extras: bool = True) -> dict:
    """Stress, tangent and energy of the mixed form at each point.

    Parameters
    ----------
    material : NeoHookean or MooneyRivlin or Yeoh
        Any rubber of :mod:`sectiondeform.materials.models` (its isochoric
        part and its bulk modulus ``kappa`` are used).
    F : (..., 3, 3) float64 ndarray
        Deformation gradient, det F > 0.
    p : (...) float64 ndarray
        Pressure, units of the moduli.
    growth : float
        Volume ratio of the isotropic growth, ``v`` > 0 (1: none).
    tangent : bool
        Also compute the tangents.
    components : (c, 2) int ndarray, optional
        Only these components (i, J) of F vary (the in-plane block and the
        out-of-plane stretch of a plane or axisymmetric code): ``A`` is then
        (..., c, c), ``A[..., m, n] = ∂P_m/∂F_n``.
    extras : bool
        Also compute ``psi`` and ``cauchy`` (not needed by Newton).

    Returns
    -------
    dict
        ``P`` (..., 3, 3) ∂ψ/∂F, first Piola stress per unit initial
        volume; ``A`` (..., 3, 3, 3, 3) ∂P/∂F at fixed p (if ``tangent``),
        ``A[..., i, J, k, L] = ∂P_iJ/∂F_kL``; ``dPdp`` (..., 3, 3);
        ``constraint`` (...) ∂ψ/∂p; ``Je`` (...) elastic volume ratio
        det F / v; ``kpp`` the scalar ∂²ψ/∂p² = −g³ / κ; with ``extras``,
        ``psi`` (...) ψ and ``cauchy`` (..., 3, 3) the Cauchy stress
        (∂ψ/∂F) Fᵀ / det F.

    Examples
    --------
    >>> from sectiondeform.materials import NeoHookean
    >>> s = mixed_state(NeoHookean(1.0), 1.1 * np.eye(3)[None], np.zeros(1), growth=1.1**3)
    >>> float(abs(s["P"]).max()) < 1e-12, round(float(s["Je"][0]), 12)   # free growth: no stress
    (True, 1.0)
    """
    g = float(growth) ** (1.0 / 3.0)
    F = np.asarray(F, dtype=np.float64)
    Fe = F / g
    Je = np.linalg.det(Fe)
    Fit = np.swapaxes(np.linalg.inv(Fe), -1, -2)
    kappa = material.kappa
    pJ = (p * Je)[..., None, None]
    P = g * g * (material.first_piola(Fe, volumetric=False) + pJ * Fit)
    out = {
        "P": P,
        "dPdp": g * g * Je[..., None, None] * Fit,
        "constraint": g**3 * (Je - 1.0 - p / kappa),
        "Je": Je,
        "kpp": -(g**3) / kappa,
    }
    if extras:
        out["psi"] = g**3 * (material.energy(Fe, volumetric=False) + p * (Je - 1.0) - p * p / (2.0 * kappa))
        out["cauchy"] = P @ np.swapaxes(F, -1, -2) / (g**3 * Je)[..., None, None]
    if tangent:
        A = material.tangent(Fe, volumetric=False)
        if components is None:
            FiFi = np.einsum("...ij,...kl->...ijkl", Fit, Fit)
            T = np.einsum("...il,...kj->...ijkl", Fit, Fit)
        else:
            i, j = np.asarray(components).T
            im, jm, kn, ln = i[:, None], j[:, None], i[None, :], j[None, :]
            A = A[..., im, jm, kn, ln]
            FiFi = Fit[..., im, jm] * Fit[..., kn, ln]
            T = Fit[..., im, ln] * Fit[..., kn, jm]
        scale = pJ if components is not None else pJ[..., None, None]
        out["A"] = g * (A + scale * (FiFi - T))
    return out
