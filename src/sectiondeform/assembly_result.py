"""The result of deforming an assembly (``section-result/2``) and its JSON form."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .models.base import Info, MeshData
from .result import ResultQuality

__all__ = ["AssemblyResult", "BodyResult", "ASSEMBLY_RESULT_FORMAT"]

ASSEMBLY_RESULT_FORMAT = "section-result/2"


@dataclass(frozen=True, eq=False)
class BodyResult:
    """One deformed body of an assembly.

    Attributes
    ----------
    name : str
    lower : (n, 2) float64 ndarray
        Deformed lower nodes, on the deformed foundations, A' to B'.
    upper : (m, 2) float64 ndarray
        Image of each characteristic point of the case's upper curve, in order.
    contour : (k, 2) float64 ndarray
        The closed deformed body, lower then upper, also through every point
        where another body's lower curve rests on it (shared ends once).
    initial_lower, initial_upper, initial_contour : ndarray
        The same points before deformation.
    area_initial, area_final : float
        Units².
    area_target : float or None
        Units², for a body whose law sets its area; None otherwise.
    initial_mesh, final_mesh : MeshData
    quality : ResultQuality
    info : Info
    volume_initial, volume_final : float, optional
        Volumes of revolution (Pappus), units³, for an assembly of revolution.
    volume_target : float, optional
        Units³, for a body whose law sets its volume.
    """

    name: str
    lower: np.ndarray
    upper: np.ndarray
    contour: np.ndarray
    initial_lower: np.ndarray
    initial_upper: np.ndarray
    initial_contour: np.ndarray
    area_initial: float
    area_target: float | None
    area_final: float
    initial_mesh: MeshData
    final_mesh: MeshData
    quality: ResultQuality | None = None
    info: Info = Info()
    volume_initial: float | None = None
    volume_target: float | None = None
    volume_final: float | None = None

    @property
    def measure(self) -> str:
        """The quantity the body's law sets: ``"area"`` or ``"volume"``."""
        return "area" if self.area_target is not None else "volume"

    @property
    def target(self) -> float:
        """Target of the law's quantity (units² or units³)."""
        return self.area_target if self.area_target is not None else self.volume_target

    @property
    def final(self) -> float:
        """Final value of the law's quantity (units² or units³)."""
        return self.area_final if self.area_target is not None else self.volume_final

    @property
    def relative_error(self) -> float:
        """(final - target) / target of the law's quantity."""
        return (self.final - self.target) / self.target

    def to_json(self, meshes: bool = True, fields: bool = False, model: str = "paper", axis=None,
                mechanics=None) -> dict:
        """The body's object of ``section-result/2``, with the project's extra keys.

        ``fields``: add the per-element fields of the ``model``'s meshes
        (:func:`~sectiondeform.strain_fields.result_fields`; with the
        revolution ``axis``, the hoop stretch out of the plane; with the
        body's ``mechanics``, its von Mises stress and pressure in the unit
        of its material).
        """
        out = {
            "name": self.name,
            "lower": self.lower.tolist(),
            "upper": self.upper.tolist(),
            "contour": self.contour.tolist(),
            "area": _measure(self.area_initial, self.area_target, self.area_final),
            "quality": self.quality.to_json() if self.quality is not None else {},
            "info": self.info.to_json(),
        }
        if self.volume_initial is not None:
            out["volume"] = _measure(self.volume_initial, self.volume_target, self.volume_final)
            out["quality"], out["info"] = out.pop("quality"), out.pop("info")  # keep the format's keys first
        if meshes:
            out["meshes"] = {"initial": self.initial_mesh.to_json(), "final": self.final_mesh.to_json()}
        if fields:
            from .strain_fields import fields_json, result_fields

            kind, values = result_fields(self.initial_mesh, self.final_mesh, model,
                                         getattr(self.info, "out_of_plane_stretch", 1.0), axis, mechanics)
            out["fields"] = fields_json(kind, values, mechanics)
        return out


def _measure(initial, target, final) -> dict:
    """``{"initial", "target", "final", "relative_error"}``, without the last two when there is no target."""
    if target is None:
        return {"initial": initial, "final": final}
    return {"initial": initial, "target": target, "final": final, "relative_error": (final - target) / target}


@dataclass(frozen=True, eq=False)
class AssemblyResult:
    """A deformed assembly: one :class:`BodyResult` per body, in the case's order.

    Attributes
    ----------
    name, units, model : str
    bodies : tuple of BodyResult
    timings : dict
        Seconds spent in ``prepare`` and ``place``.
    warnings : tuple of str
    axis : ((float, float), (float, float)) or None
        The revolution axis of an assembly of revolution (two of its points,
        units); None for extruded sections.
    state : object, optional
        The hyperelastic model's solved state of the whole assembly, for
        ``AssemblyDeformer.deform(..., start=result)``; not written to JSON.
    """

    name: str
    units: str
    model: str
    bodies: tuple
    timings: dict = field(default_factory=dict)
    warnings: tuple = ()
    axis: tuple | None = None
    state: object = field(default=None, repr=False)

    def body(self, name: str) -> BodyResult:
        """The result of the body called ``name``."""
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def to_json(self, meshes: bool = True, fields: bool = False) -> dict:
        """The ``section-result/2`` object, with the project's extra keys (model, timings, warnings, meshes).

        An assembly of revolution also carries the case's ``revolution``
        object (``{"axis": [[x, y], [x, y]]}``), so the result's volumes can be
        checked without the case.

        Parameters
        ----------
        meshes : bool
            Include each body's meshes under ``"meshes"``.
        fields : bool
            Include each body's per-element fields under ``"fields"`` (geometric
            for the paper model; with the hoop stretch for bodies of revolution;
            the hyperelastic model's with each body's von Mises stress and
            pressure, in the unit of its material's moduli).
        """
        mechanics = [None] * len(self.bodies)
        if fields:
            from .strain_fields import result_mechanics

            mechanics = result_mechanics(self)
        out = {
            "format": ASSEMBLY_RESULT_FORMAT,
            "name": self.name,
            "units": self.units,
            "bodies": [b.to_json(meshes, fields, self.model, self.axis, m) for b, m in zip(self.bodies, mechanics)],
            "model": self.model,
            "timings": self.timings,
            "warnings": list(self.warnings),
        }
        if self.axis is not None:
            out["revolution"] = {"axis": [list(map(float, p)) for p in self.axis]}
        return out
