"""Rubber models: neo-Hookean, Mooney–Rivlin and Yeoh, with a volumetric part.

Every model is a polynomial in the isochoric invariants plus a volumetric
penalty (the Abaqus form with ``D1 = 2 / κ``):

    W(F) = Σᵢ cᵢ₀ (Ī₁ − 3)ⁱ + c₀₁ (Ī₂ − 3) + κ/2 (J − 1)²,

    J = det F,  Ī₁ = J^(-2/3) tr C,  Ī₂ = J^(-4/3) ½ (tr² C − tr C²),  C = FᵀF,

with i = 1 for neo-Hookean (c₁₀ = μ/2) and Mooney–Rivlin (c₁₀, c₀₁), and
i = 1, 2, 3 for Yeoh (c₁₀, c₂₀, c₃₀). The neo-Hookean case is exactly the
reference solver's Ψ = μ/2 (J^(-2/3) tr C − 3) + κ/2 (J − 1)². The initial
shear modulus is μ₀ = 2 (c₁₀ + c₀₁); the bulk modulus κ is given directly
(``bulk_modulus``) or as a multiple of μ₀ (``bulk_to_shear``, default 1000).

Constants are in MPa, or relative (any consistent unit): the shape of one
body does not depend on the scale of its moduli, an assembly's does.

The functions of F take arrays of shape (..., 3, 3) (a plane or
axisymmetric code builds the 3 × 3 gradient with :func:`gradient_3d`) and
return energy densities (...), first Piola stresses P (..., 3, 3) and
tangents ∂P/∂F (..., 3, 3, 3, 3), indexed ``A[..., i, J, k, L] = ∂P_iJ/∂F_kL``.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..checks import number
from ..errors import CaseError, MeshError

__all__ = [
    "NeoHookean", "MooneyRivlin", "Yeoh", "Material", "MATERIAL_MODELS", "DEFAULT_BULK_TO_SHEAR",
    "material_from_json", "material_to_json", "gradient_3d",
]

DEFAULT_BULK_TO_SHEAR = 1000.0
MODULUS_LIMIT = 1e9
"""Largest accepted modulus or constant (any unit)."""


def gradient_3d(F2: np.ndarray, stretch_z) -> np.ndarray:
    """The 3 × 3 deformation gradient of a plane or axisymmetric state.

    Parameters
    ----------
    F2 : (..., 2, 2) float64 ndarray
        In-plane deformation gradient.
    stretch_z : float or (...) float64 ndarray
        Out-of-plane stretch: λz of generalised plane strain, or the hoop
        stretch r / R of an axisymmetric body.

    Returns
    -------
    (..., 3, 3) float64 ndarray

    Examples
    --------
    >>> gradient_3d(np.eye(2), 2.0)[2, 2]
    np.float64(2.0)
    """
    F2 = np.asarray(F2, dtype=np.float64)
    F = np.zeros(F2.shape[:-2] + (3, 3))
    F[..., :2, :2] = F2
    F[..., 2, 2] = stretch_z
    return F


@dataclass(frozen=True)
class _Rubber:
    """Common part: the volumetric constants and the polynomial machinery."""

    bulk_modulus: float | None = field(default=None, kw_only=True)
    bulk_to_shear: float | None = field(default=None, kw_only=True)

    model: ClassVar[str] = ""
    constants: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self):
        for name in self.constants:
            object.__setattr__(self, name, number(getattr(self, name), f"material.{name}",
                                                  low=-MODULUS_LIMIT, high=MODULUS_LIMIT))
        self._check()
        if self.bulk_modulus is not None and self.bulk_to_shear is not None:
            raise CaseError("material", "give bulk_modulus or bulk_to_shear, not both")
        if self.bulk_modulus is not None:
            object.__setattr__(self, "bulk_modulus", number(self.bulk_modulus, "material.bulk_modulus", low=0.0,
                                                            high=MODULUS_LIMIT, strict_low=True))
        if self.bulk_to_shear is not None:
            object.__setattr__(self, "bulk_to_shear", number(self.bulk_to_shear, "material.bulk_to_shear", low=0.0,
                                                             high=1e12, strict_low=True))

    def _check(self) -> None:
        if not self.shear_modulus > 0:
            raise CaseError(f"material.{self.constants[0]}", f"the initial shear modulus must be > 0, got {self.shear_modulus:g}")

    # -- constants -----------------------------------------------------------------------------
    @property
    def shear_modulus(self) -> float:
        """Initial shear modulus μ₀ = 2 (c₁₀ + c₀₁)."""
        return 2.0 * (self.c1 + self.c01)

    @property
    def kappa(self) -> float:
        """Bulk modulus κ (``bulk_modulus``, else ``bulk_to_shear`` × μ₀, default 1000 μ₀)."""
        if self.bulk_modulus is not None:
            return self.bulk_modulus
        ratio = DEFAULT_BULK_TO_SHEAR if self.bulk_to_shear is None else self.bulk_to_shear
        return ratio * self.shear_modulus

    @property
    def c1(self) -> float:
        return self.coefficients[0]

    @property
    def c01(self) -> float:
        return 0.0

    @property
    def coefficients(self) -> tuple[float, ...]:
        """(c₁₀, c₂₀, ...): the coefficients of (Ī₁ − 3)ⁱ."""
        raise NotImplementedError

    def scaled(self, factor: float):
        """The same rubber with every modulus multiplied by ``factor`` (> 0)."""
        values = {name: getattr(self, name) * factor for name in self.constants}
        bulk = None if self.bulk_modulus is None else self.bulk_modulus * factor
        return type(self)(**values, bulk_modulus=bulk, bulk_to_shear=self.bulk_to_shear)

    # -- derivatives of W with respect to the invariants ---------------------------------------
    def dW_dI1(self, I1bar):
        """∂W/∂Ī₁ and ∂²W/∂Ī₁² (arrays like ``I1bar``)."""
        x = np.asarray(I1bar, dtype=np.float64) - 3.0
        w1 = np.zeros_like(x)
        w11 = np.zeros_like(x)
        for i, c in enumerate(self.coefficients, start=1):
            w1 = w1 + i * c * x ** (i - 1)
            if i >= 2:
                w11 = w11 + i * (i - 1) * c * x ** (i - 2)
        return w1, w11

    # -- functions of F -----------------------------------------------------------------------
    def energy(self, F, volumetric: bool = True) -> np.ndarray:
        """Strain energy density W(F) per unit initial volume.

        Parameters
        ----------
        F : (..., 3, 3) float64 ndarray
            Deformation gradient, det F > 0.
        volumetric : bool
            Include κ/2 (J − 1)²; without it, the isochoric part only (for a
            mixed displacement–pressure code).

        Returns
        -------
        (...) float64 ndarray
            Units of the moduli (MPa = mJ/mm³).
        """
        k = _kinematics(F)
        x = k["I1bar"] - 3.0
        W = sum(c * x**i for i, c in enumerate(self.coefficients, start=1)) + self.c01 * (k["I2bar"] - 3.0)
        if volumetric:
            W = W + 0.5 * self.kappa * (k["J"] - 1.0) ** 2
        return W

    def first_piola(self, F, volumetric: bool = True) -> np.ndarray:
        """First Piola–Kirchhoff stress P = ∂W/∂F, (..., 3, 3), units of the moduli."""
        k = _kinematics(F)
        w1, _ = self.dW_dI1(k["I1bar"])
        P = w1[..., None, None] * k["dI1"] + self.c01 * k["dI2"]
        if volumetric:
            J = k["J"]
            P = P + (self.kappa * (J - 1.0) * J)[..., None, None] * k["Fit"]
        return P

    def tangent(self, F, volumetric: bool = True, plane: bool = False) -> np.ndarray:
        """Tangent ∂P/∂F, (..., 3, 3, 3, 3), ``A[..., i, J, k, L] = ∂P_iJ/∂F_kL``.

        With ``plane`` (``F`` block diagonal, ``diag(F2, F33)``: plane strain or
        its generalisation), only the in-plane block ``A[..., :2, :2, :2, :2]``,
        (..., 2, 2, 2, 2), computed from the in-plane blocks alone (every term is
        a product of block-diagonal tensors): a quarter of the work.
        """
        k = _kinematics(F)
        F = k["F"]
        Fit, J, I1, I2 = k["Fit"], k["J"], k["I1"], k["I2"]
        w1, w11 = self.dW_dI1(k["I1bar"])
        n = 2 if plane else 3
        if plane:
            F, Fit = F[..., :2, :2], Fit[..., :2, :2]
            k = {**k, "dI1": k["dI1"][..., :2, :2]}
        eye = np.eye(n)
        II = np.einsum("ik,jl->ijkl", eye, eye)
        FiFi = _outer(Fit, Fit)
        T = np.einsum("...il,...kj->...ijkl", Fit, Fit)
        Jm23 = (J ** (-2.0 / 3.0))[..., None, None, None, None]
        d2I1 = Jm23 * (2.0 * II - 4.0 / 3.0 * (_outer(F, Fit) + _outer(Fit, F))
                       + 4.0 / 9.0 * I1[..., None, None, None, None] * FiFi
                       + 2.0 / 3.0 * I1[..., None, None, None, None] * T)
        A = w1[..., None, None, None, None] * d2I1 + w11[..., None, None, None, None] * _outer(k["dI1"], k["dI1"])
        if self.c01 != 0.0:
            C = np.einsum("...ai,...aj->...ij", F, F)
            B = np.einsum("...ia,...ja->...ij", F, F)
            H = 2.0 * (I1[..., None, None] * F - F @ C)
            d2I2raw = 2.0 * (2.0 * _outer(F, F) + I1[..., None, None, None, None] * II
                             - np.einsum("ik,...lj->...ijkl", eye, C)
                             - np.einsum("...il,...kj->...ijkl", F, F)
                             - np.einsum("...ik,jl->...ijkl", B, eye))
            I2e = I2[..., None, None, None, None]
            d2I2 = (J ** (-4.0 / 3.0))[..., None, None, None, None] * (
                d2I2raw - 4.0 / 3.0 * (_outer(H, Fit) + _outer(Fit, H)) + 16.0 / 9.0 * I2e * FiFi + 4.0 / 3.0 * I2e * T)
            A = A + self.c01 * d2I2
        if volumetric:
            Je = J[..., None, None, None, None]
            A = A + self.kappa * ((2.0 * Je - 1.0) * Je * FiFi - Je * (Je - 1.0) * T)
        return A

    def cauchy(self, F) -> np.ndarray:
        """Cauchy (true) stress σ = P Fᵀ / J, (..., 3, 3), units of the moduli."""
        F = np.asarray(F, dtype=np.float64)
        return self.first_piola(F) @ np.swapaxes(F, -1, -2) / np.linalg.det(F)[..., None, None]

    # -- JSON ------------------------------------------------------------------------------------
    def to_json(self) -> dict:
        """The case format's ``material`` object (see :func:`material_from_json`)."""
        out = {} if self.model == "neo-hookean" else {"model": self.model}
        out.update({name: getattr(self, name) for name in self.constants})
        if self.bulk_modulus is not None:
            out["bulk_modulus"] = self.bulk_modulus
        if self.bulk_to_shear is not None:
            out["bulk_to_shear"] = self.bulk_to_shear
        return out


@dataclass(frozen=True)
class NeoHookean(_Rubber):
    """Neo-Hookean rubber: W = μ/2 (Ī₁ − 3) + κ/2 (J − 1)².

    Parameters
    ----------
    shear_modulus : float
        μ > 0, MPa or relative (default 1).
    bulk_modulus, bulk_to_shear : float, optional
        κ directly, or κ / μ; at most one (default ``bulk_to_shear`` 1000).

    Examples
    --------
    >>> m = NeoHookean(0.5, bulk_to_shear=2000)
    >>> m.shear_modulus, m.kappa
    (0.5, 1000.0)
    >>> NeoHookean(-1.0)
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: material.shear_modulus: must be > 0, got -1
    """

    shear_modulus: float = 1.0

    model: ClassVar[str] = "neo-hookean"
    constants: ClassVar[tuple[str, ...]] = ("shear_modulus",)

    def _check(self) -> None:
        if not self.shear_modulus > 0:
            raise CaseError("material.shear_modulus", f"must be > 0, got {self.shear_modulus:g}")

    @property
    def coefficients(self) -> tuple[float, ...]:
        return (0.5 * self.shear_modulus,)


@dataclass(frozen=True)
class MooneyRivlin(_Rubber):
    """Mooney–Rivlin rubber: W = c₁₀ (Ī₁ − 3) + c₀₁ (Ī₂ − 3) + κ/2 (J − 1)².

    Parameters
    ----------
    c10, c01 : float
        MPa or relative; c₁₀ > 0 and μ₀ = 2 (c₁₀ + c₀₁) > 0. A negative c₀₁
        is accepted but makes the rubber unstable at large equibiaxial
        stretch (see :func:`~sectiondeform.materials.homogeneous.unstable_modes`).
    bulk_modulus, bulk_to_shear : float, optional
        κ directly, or κ / μ₀; at most one (default ``bulk_to_shear`` 1000).

    Examples
    --------
    >>> MooneyRivlin(0.2, 0.05).shear_modulus
    0.5
    """

    c10: float = 0.5
    c01: float = 0.0

    model: ClassVar[str] = "mooney-rivlin"
    constants: ClassVar[tuple[str, ...]] = ("c10", "c01")

    def _check(self) -> None:
        if not self.c10 > 0:
            raise CaseError("material.c10", f"must be > 0, got {self.c10:g}")
        if not self.c10 + self.c01 > 0:
            raise CaseError("material.c01", f"the initial shear modulus 2 (c10 + c01) must be > 0, got {self.shear_modulus:g}")

    @property
    def coefficients(self) -> tuple[float, ...]:
        return (self.c10,)


@dataclass(frozen=True)
class Yeoh(_Rubber):
    """Yeoh rubber: W = c₁₀ (Ī₁ − 3) + c₂₀ (Ī₁ − 3)² + c₃₀ (Ī₁ − 3)³ + κ/2 (J − 1)².

    Parameters
    ----------
    c10, c20, c30 : float
        MPa or relative; c₁₀ > 0 (μ₀ = 2 c₁₀). A negative c₂₀ (the usual
        initial softening) or c₃₀ may make the rubber unstable at large
        stretch (see :func:`~sectiondeform.materials.homogeneous.unstable_modes`).
    bulk_modulus, bulk_to_shear : float, optional
        κ directly, or κ / μ₀; at most one (default ``bulk_to_shear`` 1000).

    Examples
    --------
    >>> Yeoh(0.2, -0.001, 0.00005).shear_modulus
    0.4
    """

    c10: float = 0.5
    c20: float = 0.0
    c30: float = 0.0

    model: ClassVar[str] = "yeoh"
    constants: ClassVar[tuple[str, ...]] = ("c10", "c20", "c30")

    def _check(self) -> None:
        if not self.c10 > 0:
            raise CaseError("material.c10", f"must be > 0, got {self.c10:g}")

    @property
    def coefficients(self) -> tuple[float, ...]:
        return (self.c10, self.c20, self.c30)


Material = NeoHookean | MooneyRivlin | Yeoh
MATERIAL_MODELS: dict[str, type] = {"neo-hookean": NeoHookean, "mooney-rivlin": MooneyRivlin, "yeoh": Yeoh}


def material_from_json(obj, field: str = "material", default_bulk_to_shear: float | None = None) -> Material:
    """Read the case format's ``material`` object (format version 2).

    ``{"shear_modulus": μ, "bulk_to_shear": k}`` is a neo-Hookean rubber
    (both optional: μ = 1, k = ``default_bulk_to_shear``, else 1000).
    ``{"model": "mooney-rivlin", "c10": …, "c01": …}`` and
    ``{"model": "yeoh", "c10": …, "c20": …, "c30": …}`` name themselves, with
    ``bulk_modulus`` (MPa) or ``bulk_to_shear`` (at most one). A neo-Hookean
    object may also say ``"model": "neo-hookean"`` and give ``bulk_modulus``.

    Parameters
    ----------
    obj : dict
        The parsed JSON object.
    field : str
        Where it sits in the case (``"bodies[1].material"``), for messages.
    default_bulk_to_shear : float, optional
        The case's ``options.bulk_to_shear``, used when the object gives
        neither ``bulk_modulus`` nor ``bulk_to_shear``.

    Returns
    -------
    NeoHookean or MooneyRivlin or Yeoh

    Raises
    ------
    CaseError
        One line naming the field: unknown model or key, missing constant,
        a value that is not a finite number, a modulus not > 0.

    Examples
    --------
    >>> material_from_json({"model": "yeoh", "c10": 0.3, "c20": -0.01, "c30": 0.001, "bulk_modulus": 2000})
    Yeoh(bulk_modulus=2000.0, bulk_to_shear=None, c10=0.3, c20=-0.01, c30=0.001)
    >>> material_from_json({"model": "mooney-rivlin", "c10": -1, "c01": 0.2}, "bodies[1].material")
    Traceback (most recent call last):
    ...
    sectiondeform.errors.CaseError: bodies[1].material.c10: must be > 0, got -1
    """
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected an object such as {{\"shear_modulus\": 1.0}}, got {type(obj).__name__}")
    name = obj.get("model", "neo-hookean")
    if name not in MATERIAL_MODELS:
        near = difflib.get_close_matches(str(name), list(MATERIAL_MODELS), n=1)
        hint = f"did you mean {near[0]}?" if near else f"use one of {', '.join(MATERIAL_MODELS)}"
        raise CaseError(f"{field}.model", f"unknown material model {name!r}; {hint}")
    cls = MATERIAL_MODELS[name]
    known = ("model", *cls.constants, "bulk_modulus", "bulk_to_shear")
    for key in obj:
        if key not in known:
            near = difflib.get_close_matches(str(key), known, n=1)
            hint = f"did you mean {near[0]}?" if near else f"use one of {', '.join(known)}"
            raise CaseError(f"{field}.{key}", f"unknown key for a {name} material; {hint}")
    values = {}
    for key in cls.constants:
        if key in obj:
            values[key] = number(obj[key], f"{field}.{key}", low=-MODULUS_LIMIT, high=MODULUS_LIMIT)
        elif cls is not NeoHookean:
            raise CaseError(f"{field}.{key}", f"missing; a {name} material needs {', '.join(cls.constants)}")
    for key in ("bulk_modulus", "bulk_to_shear"):
        if key in obj:
            values[key] = number(obj[key], f"{field}.{key}")
    if "bulk_modulus" in values and "bulk_to_shear" in values:
        raise CaseError(f"{field}.bulk_modulus", "give bulk_modulus or bulk_to_shear, not both")
    if "bulk_modulus" not in values and "bulk_to_shear" not in values and default_bulk_to_shear is not None:
        values["bulk_to_shear"] = default_bulk_to_shear
    try:
        return cls(**values)
    except CaseError as exc:
        where = exc.field.replace("material", field, 1) if exc.field.startswith("material") else field
        raise CaseError(where, exc.problem) from None


def material_to_json(material: Material) -> dict:
    """The ``material`` object of ``material`` (inverse of :func:`material_from_json`)."""
    return material.to_json()


# -- kinematics -------------------------------------------------------------------------------------

def _outer(a, b):
    return np.einsum("...ij,...kl->...ijkl", a, b)


def _kinematics(F) -> dict:
    F = np.asarray(F, dtype=np.float64)
    if F.shape[-2:] != (3, 3):
        raise ValueError(f"F must have shape (..., 3, 3), got {F.shape}")
    J = np.linalg.det(F)
    if not np.all(J > 0):
        raise MeshError(f"det F must be > 0 at every point (an inverted element); smallest {float(np.min(J)):.3g}")
    Fit = np.swapaxes(np.linalg.inv(F), -1, -2)
    C = np.swapaxes(F, -1, -2) @ F
    I1 = np.trace(C, axis1=-2, axis2=-1)
    I2 = 0.5 * (I1**2 - np.einsum("...ij,...ji->...", C, C))
    Jm23 = J ** (-2.0 / 3.0)
    Jm43 = Jm23 * Jm23
    dI1 = Jm23[..., None, None] * (2.0 * F - (2.0 / 3.0) * I1[..., None, None] * Fit)
    dI2 = Jm43[..., None, None] * (2.0 * (I1[..., None, None] * F - F @ C) - (4.0 / 3.0) * I2[..., None, None] * Fit)
    return {"F": F, "J": J, "Fit": Fit, "I1": I1, "I2": I2, "I1bar": Jm23 * I1, "I2bar": Jm43 * I2,
            "dI1": dI1, "dI2": dI2}
