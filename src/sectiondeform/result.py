"""The result of one deformation (``section-result/1``) and its JSON form."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .models.base import FinalQuality, Info, MeshData, MeshQuality

__all__ = ["Result", "ResultQuality", "RESULT_FORMAT"]

RESULT_FORMAT = "section-result/1"


@dataclass(frozen=True)
class ResultQuality:
    """The figures of both meshes of a result.

    Attributes
    ----------
    initial : MeshQuality
        The prepared mesh.
    final : FinalQuality
        The placed mesh; written with the prefix ``final_``.
    """

    initial: MeshQuality
    final: FinalQuality = FinalQuality()

    def to_json(self) -> dict:
        """The result's ``quality`` object: the initial figures, then the final ones prefixed ``final_``."""
        out = self.initial.to_json()
        out.update({f"final_{k}": v for k, v in self.final.to_json().items()})
        return out


@dataclass(frozen=True, eq=False)
class Result:
    """A deformed section.

    Attributes
    ----------
    name, units, model : str
    lower : (n, 2) float64 ndarray
        Deformed lower curve as discretised, on the target, A' to B'.
    upper : (m, 2) float64 ndarray
        Image of each upper characteristic point, B' to A'.
    initial_lower, initial_upper : ndarray
        The same points before deformation.
    area_initial, area_target, area_final : float
        Areas in units².
    initial_mesh, final_mesh : MeshData
    quality : ResultQuality
        Mesh figures: layers, columns, element counts, Jacobian ranges.
    info : Info
        Model figures (height scale, iterations...), a type per model.
    timings : dict
        Seconds spent in ``prepare`` and ``place``.
    warnings : tuple of str
    state : object, optional
        The model's solved state, for ``Deformer.deform(..., start=result)``;
        not written to JSON.
    """

    name: str
    units: str
    model: str
    lower: np.ndarray
    upper: np.ndarray
    initial_lower: np.ndarray
    initial_upper: np.ndarray
    area_initial: float
    area_target: float
    area_final: float
    initial_mesh: MeshData
    final_mesh: MeshData
    quality: ResultQuality | None = None
    info: Info = Info()
    timings: dict = field(default_factory=dict)
    warnings: tuple = ()
    state: object = field(default=None, repr=False)

    @property
    def contour(self) -> np.ndarray:
        """Closed deformed section, lower then upper, shared ends once, ``(n + m - 2, 2)``."""
        return np.concatenate((self.lower, self.upper[1:-1]))

    @property
    def initial_contour(self) -> np.ndarray:
        """Closed initial section, ``(n + m - 2, 2)``."""
        return np.concatenate((self.initial_lower, self.initial_upper[1:-1]))

    @property
    def relative_error(self) -> float:
        """(final - target) / target."""
        return (self.area_final - self.area_target) / self.area_target

    def to_json(self, meshes: bool = True, fields: bool = False) -> dict:
        """The ``section-result/1`` object, with the project's extra keys.

        Parameters
        ----------
        meshes : bool
            Include both meshes under ``"meshes"``.
        fields : bool
            Include the per-element fields under ``"fields"``: the hyperelastic
            model's strains, von Mises stress and pressure (units of the
            shear modulus), or the paper model's geometric fields
            (:mod:`sectiondeform.strain_fields`).
        """
        out = {
            "format": RESULT_FORMAT,
            "name": self.name,
            "units": self.units,
            "lower": self.lower.tolist(),
            "upper": self.upper.tolist(),
            "contour": self.contour.tolist(),
            "area": {
                "initial": self.area_initial,
                "target": self.area_target,
                "final": self.area_final,
                "relative_error": self.relative_error,
            },
            "model": self.model,
            "quality": self.quality.to_json() if self.quality is not None else {},
            "info": self.info.to_json(),
            "timings": self.timings,
            "warnings": list(self.warnings),
        }
        if meshes:
            out["meshes"] = {"initial": self.initial_mesh.to_json(), "final": self.final_mesh.to_json()}
        if fields:
            from .strain_fields import fields_json, result_fields, result_mechanics

            lz = getattr(self.info, "out_of_plane_stretch", 1.0)
            mechanics = result_mechanics(self)[0]
            kind, values = result_fields(self.initial_mesh, self.final_mesh, self.model, lz, mechanics=mechanics)
            out["fields"] = fields_json(kind, values, mechanics)
        return out
