"""The result of a deformation, one :class:`BodyResult` per body, and its JSON form.

A result is written in the dialect of its problem: ``section-result/1`` for
the paper's one body on its own lower curve (the body's figures at the top
level), ``section-result/2`` otherwise (a list of bodies). The figures of a
one-body result are also read at the top level in Python
(``result.area_final``, ``result.contour``...); a result of several bodies
refuses them in one line, naming ``result.bodies[i]``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .errors import CaseError
from .models.base import FinalQuality, Info, MeshData, MeshQuality
from .problem import RESULT_V1, RESULT_V2

__all__ = ["Result", "BodyResult", "ResultQuality", "RESULT_V1", "RESULT_V2", "contact_units"]



@dataclass(frozen=True)
class ResultQuality:
    """The figures of both meshes of a body's result.

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
class BodyResult:
    """One deformed body.

    Attributes
    ----------
    name : str
    lower : (n, 2) float64 ndarray
        Deformed lower nodes, on the target or the deformed foundations, A' to B'.
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
        The model's figures (height scale, Newton iterations...), a type per model.
    volume_initial, volume_final : float, optional
        Volumes of revolution (Pappus), units³, for a body of revolution.
    volume_target : float, optional
        Units³, for a body whose law sets its volume.
    holes, initial_holes : tuple of (k_h, 2) float64 ndarray
        Each hole's points after and before deformation (closed, the first
        point not repeated); the areas and volumes above are the body's,
        its holes taken out.
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
    holes: tuple = ()
    initial_holes: tuple = ()

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
        """The body's object of the result format, with the project's extra keys.

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
        }
        if self.holes:
            out["holes"] = [h.tolist() for h in self.holes]
        out |= {
            "area": _measure(self.area_initial, self.area_target, self.area_final),
        }
        if self.volume_initial is not None:
            out["volume"] = _measure(self.volume_initial, self.volume_target, self.volume_final)
        out["quality"] = self.quality.to_json() if self.quality is not None else {}
        out["info"] = self.info.to_json()
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


def _one(name: str):
    """A property reading ``name`` of the one body of a one-body result."""

    def get(self):
        return getattr(self.only(name), name)

    get.__doc__ = f"The one body's ``{name}`` (:class:`BodyResult`); refused for several bodies."
    return property(get)


@dataclass(frozen=True, eq=False)
class Result:
    """A deformed problem: one :class:`BodyResult` per body, in the case's order.

    Attributes
    ----------
    name, units, model : str
    bodies : tuple of BodyResult
    timings : dict
        Seconds spent in ``prepare`` and ``place``.
    warnings : tuple of str
    axis : ((float, float), (float, float)) or None
        The revolution axis of bodies of revolution (two of its points,
        units); None for extruded sections.
    dialect : str
        ``"section-result/1"`` for the paper's one body, else ``"section-result/2"``.
    state : object, optional
        The model's solved state of the whole problem, for
        ``Deformer.deform(..., start=result)``; not written to JSON.
    rigid : tuple of PartContact
        Each rigid part's force and contact (:class:`~sectiondeform.fem.contact.PartContact`), for a problem with rigid parts.
    support_force : (float, float) or None
        The force the bodies exert on the support, for a problem with rigid parts.
    history : tuple of HistoryStep
        The forces at each load step, start to end (a load–deflection curve).
    """

    name: str
    units: str
    model: str
    bodies: tuple
    timings: dict = field(default_factory=dict)
    warnings: tuple = ()
    axis: tuple | None = None
    dialect: str = RESULT_V2
    state: object = field(default=None, repr=False)
    rigid: tuple = ()
    support_force: tuple | None = None
    history: tuple = ()

    def body(self, name: str) -> BodyResult:
        """The result of the body called ``name``."""
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def only(self, what: str = "body") -> BodyResult:
        """The one body of a one-body result.

        Raises
        ------
        CaseError
            For a result of several bodies, naming ``result.bodies[i]``.
        """
        if len(self.bodies) != 1:
            raise CaseError(what, f"the result has {len(self.bodies)} bodies; read result.bodies[i].{what}")
        return self.bodies[0]

    lower = _one("lower")
    upper = _one("upper")
    contour = _one("contour")
    initial_lower = _one("initial_lower")
    initial_upper = _one("initial_upper")
    initial_contour = _one("initial_contour")
    area_initial = _one("area_initial")
    area_target = _one("area_target")
    area_final = _one("area_final")
    initial_mesh = _one("initial_mesh")
    final_mesh = _one("final_mesh")
    quality = _one("quality")
    info = _one("info")

    @property
    def relative_error(self) -> float:
        """(final - target) / target of the law's quantity, the largest in magnitude over the bodies."""
        return max((b.relative_error for b in self.bodies), key=abs)

    def to_json(self, meshes: bool = True, fields: bool = False) -> dict:
        """The result object in its dialect, with the project's extra keys (model, timings, warnings, meshes).

        Bodies of revolution also carry the case's ``revolution`` object
        (``{"axis": [[x, y], [x, y]]}``), so the volumes can be checked
        without the case.

        Parameters
        ----------
        meshes : bool
            Include each body's meshes under ``"meshes"``.
        fields : bool
            Include each body's per-element fields under ``"fields"``
            (geometric for the paper model; with the hoop stretch for bodies
            of revolution; the hyperelastic model's with each body's von
            Mises stress and pressure, in the unit of its material's moduli).
        """
        mechanics = [None] * len(self.bodies)
        if fields:
            from .strain_fields import result_mechanics

            mechanics = result_mechanics(self)
        bodies = [b.to_json(meshes, fields, self.model, self.axis, m) for b, m in zip(self.bodies, mechanics)]
        out = {"format": self.dialect, "name": self.name, "units": self.units}
        if self.dialect == RESULT_V1:
            body = bodies[0]
            del body["name"]
            info = body.pop("info")
            quality = body.pop("quality")
            rest = {k: body.pop(k) for k in ("meshes", "fields") if k in body}
            out.update(body)
            out.update({"model": self.model, "quality": quality, "info": info, "timings": self.timings,
                        "warnings": list(self.warnings), **rest})
            return out
        out.update({"bodies": bodies, "model": self.model, "timings": self.timings, "warnings": list(self.warnings)})
        if self.axis is not None:
            out["revolution"] = {"axis": [list(map(float, p)) for p in self.axis]}
        if self.rigid:
            out["support"] = {"force": [float(v) for v in self.support_force]}
            out["rigid"] = [part.to_json() for part in self.rigid]
            out["history"] = [step.to_json() for step in self.history]
        return out


def contact_units(units: str, revolution: bool) -> dict:
    """The units of a result's contact figures, for labels: ``{"length", "pressure", "force"}``.

    The case format's convention: moduli in MPa, lengths in the case's
    ``units``; a part's force per unit length of a plane section (N/mm with
    mm), the whole ring's for a body of revolution (N with mm). Other
    lengths give the same products written out (``MPa·m`` per ...).
    """
    u = units or "units"
    if u == "mm":
        force = "N" if revolution else "N/mm"
    else:
        force = f"MPa·{u}²" if revolution else f"MPa·{u}"
    return {"length": u, "pressure": "MPa", "force": force}
