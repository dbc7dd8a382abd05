"""Stress and strain measures for result output, from F and a stress.

Arrays of tensors have shape (..., 3, 3); a plane or axisymmetric code
builds them with :func:`~sectiondeform.materials.models.gradient_3d` (the
out-of-plane or hoop stretch in the (2, 2) slot).
"""

from __future__ import annotations

import numpy as np

from ..errors import CaseError

__all__ = ["principal_stretches", "max_principal_strain", "von_mises", "pressure", "STRAIN_MEASURES"]

STRAIN_MEASURES = ("nominal", "log", "green")


def principal_stretches(F) -> np.ndarray:
    """Principal stretches λ₁ ≥ λ₂ ≥ λ₃: the square roots of the eigenvalues of C = FᵀF.

    Parameters
    ----------
    F : (..., 3, 3) float64 ndarray

    Returns
    -------
    (..., 3) float64 ndarray
        Dimensionless, in decreasing order.

    Examples
    --------
    >>> principal_stretches(np.diag([0.5, 2.0, 1.0])).tolist()
    [2.0, 1.0, 0.5]
    """
    F = np.asarray(F, dtype=np.float64)
    C = np.swapaxes(F, -1, -2) @ F
    return np.sqrt(np.clip(np.linalg.eigvalsh(C), 0.0, None))[..., ::-1]


def max_principal_strain(F, measure: str = "nominal") -> np.ndarray:
    """The largest principal strain, from the largest principal stretch λ₁.

    Parameters
    ----------
    F : (..., 3, 3) float64 ndarray
    measure : {"nominal", "log", "green"}
        ``nominal``: λ₁ − 1 (engineering strain, the rubber-testing
        convention); ``log``: ln λ₁ (true strain, Abaqus LE); ``green``:
        (λ₁² − 1) / 2 (Green–Lagrange).

    Returns
    -------
    (...) float64 ndarray
        Dimensionless.

    Examples
    --------
    >>> float(max_principal_strain(np.diag([1.5, 0.8, 0.8])))
    0.5
    """
    if measure not in STRAIN_MEASURES:
        raise CaseError("strain measure", f"unknown {measure!r}; use one of {', '.join(STRAIN_MEASURES)}")
    lam = principal_stretches(F)[..., 0]
    if measure == "nominal":
        return lam - 1.0
    if measure == "log":
        return np.log(lam)
    return 0.5 * (lam * lam - 1.0)


def pressure(sigma) -> np.ndarray:
    """Hydrostatic pressure p = −tr σ / 3, positive in compression (Abaqus PRESS).

    Parameters
    ----------
    sigma : (..., 3, 3) float64 ndarray
        Cauchy stress, MPa or relative.

    Returns
    -------
    (...) float64 ndarray
        Units of ``sigma``.

    Examples
    --------
    >>> float(pressure(-2.0 * np.eye(3)))
    2.0
    """
    return -np.trace(np.asarray(sigma, dtype=np.float64), axis1=-2, axis2=-1) / 3.0


def von_mises(sigma) -> np.ndarray:
    """Von Mises equivalent stress √(3/2 s:s), s the deviator of σ.

    Parameters
    ----------
    sigma : (..., 3, 3) float64 ndarray
        Cauchy stress, MPa or relative.

    Returns
    -------
    (...) float64 ndarray
        Units of ``sigma``; equals |σ₁₁| in uniaxial stress.

    Examples
    --------
    >>> float(von_mises(np.diag([3.0, 0.0, 0.0])))
    3.0
    """
    sigma = np.asarray(sigma, dtype=np.float64)
    s = sigma + pressure(sigma)[..., None, None] * np.eye(3)
    return np.sqrt(1.5 * np.einsum("...ij,...ij->...", s, s))
