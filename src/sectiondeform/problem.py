"""The problem: bodies resting on a support that moves to a target, each under its law.

A :class:`Problem` is the one problem type of the library: one body or
several bonded ones, a plane section or a section of revolution. A
``section-case/1`` file is a problem of one body whose lower curve is the
support (its :attr:`Problem.dialect` says so, and it is written back in that
form); a ``section-case/2`` file gives any number of bodies. Reading and
writing the files is :mod:`sectiondeform.io.case`; building a problem runs
its checks (:func:`~sectiondeform.layout.layout`): a problem that exists is
one whose bodies rest on the support or on each other as the format says.

>>> import sectiondeform as sd
>>> problem = sd.load_case(sd.example_case_path())
>>> len(problem.bodies), problem.dialect
(1, 'section-case/1')
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .curves import Curve
from .errors import CaseError
from .laws import Law, check_growth
from .layout import Layout, check_axis, layout, problem_size
from .options import Options, options_from_json
from .section import SectionCurves

__all__ = ["Problem", "Body", "Revolution", "Rigid", "DIALECTS", "V1", "V2", "RESULT_V1", "RESULT_V2"]

V1 = "section-case/1"
V2 = "section-case/2"
DIALECTS = (V1, V2)
RESULT_V1 = "section-result/1"
"""The result format of a ``section-case/1`` problem (the one body's figures at the top level)."""
RESULT_V2 = "section-result/2"
"""The result format of a ``section-case/2`` problem (a list of bodies)."""


@dataclass(frozen=True)
class Revolution:
    """The axis of a body of revolution: the line through two points of the section's plane.

    Attributes
    ----------
    axis : ((float, float), (float, float))
        Two distinct points, units.
    """

    axis: tuple

    def to_json(self) -> dict:
        """The ``revolution`` object."""
        return {"axis": [list(p) for p in self.axis]}


@dataclass(frozen=True, eq=False)
class Rigid:
    """A rigid part the bodies may touch but never enter (a shaft, a housing, a gland, a plate).

    Attributes
    ----------
    name : str
        Unique among the problem's rigid parts.
    contour : Curve
        The part's closed outline where it **ends up**, units (for a body of
        revolution, its half-plane section).
    travel : (float, float)
        The straight displacement by which it arrives, units: it starts at
        ``contour - travel``, where it must not overlap a body (touching is
        allowed). Support and rigid parts move together as one loading.
    friction : float
        Coulomb coefficient between the part and every body, >= 0.
    """

    name: str
    contour: Curve
    travel: tuple = (0.0, 0.0)
    friction: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "travel", tuple(float(v) for v in self.travel))
        object.__setattr__(self, "friction", float(self.friction))

    def to_json(self) -> dict:
        """The part's object of the case format."""
        return {"name": self.name, "contour": self.contour.to_json(), "travel": list(self.travel), "friction": self.friction}


def _check_rigid(i: int, part) -> None:
    """Refuse, in one line naming ``rigid[i]``, a part that is not a Rigid, unnamed, open, or with a bad travel or friction."""
    field = f"rigid[{i}]"
    if not isinstance(part, Rigid):
        raise CaseError(field, f"expected a Rigid, got {type(part).__name__}")
    if not isinstance(part.name, str) or not part.name:
        raise CaseError(f"{field}.name", f"expected a non-empty string, got {part.name!r}")
    if not isinstance(part.contour, Curve):
        raise CaseError(f"{field}.contour", f"expected a curve, got {type(part.contour).__name__}")
    a, b = part.contour.ends
    size = float(np.hypot(*np.ptp(part.contour.at_fractions(np.linspace(0.0, 1.0, 65)), axis=0)))
    if not size > 0:
        raise CaseError(f"{field}.contour", "has no extent; give the part's closed outline")
    gap = float(np.hypot(*(np.asarray(a) - np.asarray(b))))
    if gap > 1e-9 * size:
        raise CaseError(f"{field}.contour", f"is not closed: its ends are {gap:.6g} apart; end the outline where it starts")
    if len(part.travel) != 2 or not all(math.isfinite(v) for v in part.travel):
        raise CaseError(f"{field}.travel", f"expected two finite numbers [dx, dy], got {list(part.travel)!r}")
    if not (math.isfinite(part.friction) and part.friction >= 0.0):
        raise CaseError(f"{field}.friction", f"expected a Coulomb coefficient >= 0, got {part.friction!r}")


@dataclass(frozen=True, eq=False)
class Body:
    """One deformable body.

    Attributes
    ----------
    name : str
        Unique within the problem.
    lower : Curve
        From the body's A to its B, lying on its foundation (the support or
        other bodies' upper curves).
    upper : Curve
        From B back to A.
    law : Law
    material : str
        The ``material`` object as canonical JSON (:attr:`material_data`);
        ``"{}"`` for none (the model's default rubber).
    holes : tuple of Curve
        Closed curves strictly inside the contour, apart from it and from
        each other (a hollow profile); their boundaries are free. The body's
        area is its contour's less its holes' (checked in
        :func:`~sectiondeform.layout.layout`).
    """

    name: str
    lower: Curve
    upper: Curve
    law: Law
    material: str = "{}"
    holes: tuple = ()

    def __post_init__(self):
        object.__setattr__(self, "holes", tuple(self.holes))

    @property
    def material_data(self) -> dict:
        """The ``material`` object (a new dict each time)."""
        return json.loads(self.material)

    def to_json(self) -> dict:
        """The body's object of the case format."""
        out = {"name": self.name, "lower": self.lower.to_json(), "upper": self.upper.to_json()}
        if self.holes:
            out["holes"] = [h.to_json() for h in self.holes]
        out["law"] = self.law.to_json()
        if self.material != "{}":
            out["material"] = self.material_data
        return out


@dataclass(frozen=True, eq=False)
class Problem:
    """Bodies on a support that goes to a target; immutable, hashable, equal to another with the same case object.

    Attributes
    ----------
    support : Curve
        The curve the bodies rest on, A to B.
    target : Curve
        Where the support goes, A' to B'.
    bodies : tuple of Body
    name, units : str
    options : Options
        A dict is accepted and checked (:func:`~sectiondeform.options.options_from_json`).
    revolution : Revolution or None
    dialect : str
        The case format it is written in: ``"section-case/1"`` for one body
        whose lower curve is the support (the paper's own form), else
        ``"section-case/2"``.
    rigid : tuple of Rigid
        Rigid parts in contact with the bodies' free boundaries (none by default).
    layout : Layout
        How the bodies rest on each other, checked when the problem is built
        (and that no rigid part starts inside a body).
    """

    support: Curve
    target: Curve
    bodies: tuple
    name: str = "section"
    units: str = "mm"
    options: Options = Options()
    revolution: Revolution | None = None
    dialect: str = V2
    rigid: tuple = ()
    layout: Layout = dataclasses.field(init=False, repr=False, compare=False)

    def __post_init__(self):
        if not isinstance(self.options, Options):
            object.__setattr__(self, "options", options_from_json(self.options))
        object.__setattr__(self, "bodies", tuple(self.bodies))
        if not self.bodies:
            raise CaseError("bodies", "a problem needs at least one body")
        if self.dialect not in DIALECTS:
            raise CaseError("format", f"unknown case format {self.dialect!r}; use one of {', '.join(DIALECTS)}")
        if self.dialect == V1 and (len(self.bodies) != 1 or self.revolution is not None or self.bodies[0].material != "{}"
                                   or self.bodies[0].holes or self.bodies[0].law.growth is not None
                                   or self.bodies[0].lower.to_json() != self.support.to_json()):
            raise CaseError("format", "section-case/1 holds one body on its own lower curve, without revolution, material, "
                                      "holes or growth (volume_ratio); write it as section-case/2")
        seen: dict[str, int] = {}
        for i, body in enumerate(self.bodies):
            if body.name in seen:
                raise CaseError(f"bodies[{i}].name", f"{body.name!r} is also the name of bodies[{seen[body.name]}]; give every body its own name")
            seen[body.name] = i
        object.__setattr__(self, "bodies", tuple(self._bound(i, b) for i, b in enumerate(self.bodies)))
        object.__setattr__(self, "rigid", tuple(self.rigid))
        if self.rigid and self.dialect == V1:
            raise CaseError("rigid", "section-case/1 has no rigid parts; write the case as section-case/2")
        names: dict[str, int] = {}
        for i, part in enumerate(self.rigid):
            _check_rigid(i, part)
            if part.name in names:
                raise CaseError(f"rigid[{i}].name", f"{part.name!r} is also the name of rigid[{names[part.name]}]; give every part its own name")
            names[part.name] = i
        object.__setattr__(self, "layout", layout(self))
        if self.revolution is not None:
            check_axis(self)

    @classmethod
    def single(cls, lower: Curve, upper: Curve, target: Curve, law: Law, name: str = "section", units: str = "mm",
               options: Options | dict | None = None) -> Problem:
        """The paper's problem: one body whose lower curve is the support (``section-case/1``).

        Examples
        --------
        >>> from sectiondeform import AreaRatio, Polyline
        >>> p = Problem.single(Polyline([[0, 0], [2, 0]]), Polyline([[2, 0], [2, 1], [0, 1], [0, 0]]),
        ...                    Polyline([[0, 0], [2, 0]]), AreaRatio(0.9))
        >>> p.dialect, p.bodies[0].name
        ('section-case/1', 'section')
        """
        body = Body(name=name, lower=lower, upper=upper, law=law)
        return cls(support=lower, target=target, bodies=(body,), name=name, units=units,
                   options=options if options is not None else Options(), dialect=V1)

    def _bound(self, i: int, body: Body) -> Body:
        """``body`` with a law of bodies of revolution bound to the axis; without one, the growth of an extruded body."""
        law = body.law
        if not law.needs_axis:
            return body
        if self.revolution is None:  # the growth of an extruded body
            if law.axis is not None:
                body = dataclasses.replace(body, law=law.about(None))
            check_growth(body.law, f"bodies[{i}].law")
            return body
        if law.axis == self.revolution.axis:
            return body
        return dataclasses.replace(body, law=law.about(self.revolution.axis))

    @property
    def model(self) -> str:
        """Name of the deformation model the case asks for."""
        return self.options.model

    @property
    def law(self) -> Law:
        """The law of a one-body problem.

        Raises
        ------
        CaseError
            For a problem of several bodies (each has its own law).
        """
        return self._only("law").law

    @property
    def lower(self) -> Curve:
        """The lower curve of a one-body problem (see :attr:`law`)."""
        return self._only("lower").lower

    @property
    def upper(self) -> Curve:
        """The upper curve of a one-body problem (see :attr:`law`)."""
        return self._only("upper").upper

    def _only(self, what: str) -> Body:
        if len(self.bodies) != 1:
            raise CaseError(what, f"the problem has {len(self.bodies)} bodies, each with its own {what}; use problem.bodies[i].{what}")
        return self.bodies[0]

    @cached_property
    def size(self) -> float:
        """Bounding-box diagonal of the support and every body, units."""
        return problem_size(self.support, self.bodies)

    def label(self, i: int) -> str:
        """``bodies[i] 'name'`` for messages; empty for the body of a ``section-case/1`` problem."""
        return "" if self.dialect == V1 else f"bodies[{i}] {self.bodies[i].name!r}"

    def body_case(self, i: int, upper: Curve | None = None) -> SectionCurves:
        """Body ``i``'s curves as the section stage reads them (:func:`~sectiondeform.section.build_section`).

        The target is the problem's target where the body's lower curve is
        the support itself (so the lower curve is sampled for it), else the
        body's own lower curve; it only guides the sampling of the lower curve.
        """
        body = self.bodies[i]
        on_support = body.lower.to_json() == self.support.to_json()
        return SectionCurves(lower=body.lower, upper=upper or body.upper, target=self.target if on_support else body.lower,
                             options=self.options, holes=body.holes)

    def replace(self, **changes) -> Problem:
        """The problem with ``changes`` (fields of :class:`Problem`; ``law``, ``lower``, ``upper`` for one body).

        A one-body problem accepts ``law``, ``lower`` and ``upper`` (a
        ``section-case/1`` one keeps its lower curve as the support).
        """
        body_changes = {k: changes.pop(k) for k in ("law", "lower", "upper", "material", "holes") if k in changes}
        if body_changes:
            body = dataclasses.replace(self._only(next(iter(body_changes))), **body_changes)
            changes["bodies"] = (body,)
            if self.dialect == V1 and "lower" in body_changes:
                changes.setdefault("support", body.lower)
        return dataclasses.replace(self, **changes)

    def _key(self) -> str:
        key = self.__dict__.get("_json_key")
        if key is None:
            whole = [self.dialect, self.name, self.units, self.support.to_json(), self.target.to_json(),
                     [b.to_json() for b in self.bodies], self.options.to_json(),
                     self.revolution.to_json() if self.revolution is not None else None,
                     [r.to_json() for r in self.rigid]]
            key = json.dumps(whole, sort_keys=True)
            object.__setattr__(self, "_json_key", key)
        return key

    def __eq__(self, other):
        if not isinstance(other, Problem):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self):
        return hash(self._key())
