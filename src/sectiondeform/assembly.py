"""An assembly of bonded bodies on one support (``section-case/2``): reading and checking.

:func:`assembly_from_dict` checks a parsed ``section-case/2`` object field
by field, as :func:`~sectiondeform.case.case_from_dict` does for version 1
(unknown keys are errors naming the nearest known key), then checks how the
bodies rest on each other (:func:`layout`):

- every point of a body's lower curve lies on its foundation, the support
  or other bodies' upper curves, within ``options.contact_tolerance``
  (default :data:`CONTACT_FRACTION` of the assembly's bounding-box
  diagonal); otherwise the error gives the gap and its place;
- bodies' interiors do not overlap (the error gives the overlap area);
- no body rests on itself through others (the error names the cycle);
- a piece shared by two bodies is in exactly one body's lower curve (a
  piece in both upper curves, or in both lower curves, is refused);
- names are unique;
- with ``revolution``, the axis crosses no body and every body lies on the
  same side of it (:func:`check_axis`); a ``volume_ratio`` law is only
  valid with ``revolution``, and is bound to its axis.

Every message is one line naming the bodies (``bodies[1] 'cover'``) and
where. The curves are compared through fine polylines (within a quarter of
the contact tolerance) sampled densely, so curved pieces that coincide are
recognised as shared.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import shapely

from .case import Case, Options, _is_user_key, options_from_json, unknown_key
from .checks import number
from .curves import Curve, curve_from_json
from .errors import CaseError, GeometryError
from .laws import Law, law_from_json
from .pappus import signed_distance

__all__ = [
    "Assembly", "Body", "Revolution", "Layout", "assembly_from_dict", "assembly_to_dict", "layout", "check_axis",
    "ASSEMBLY_FORMAT", "ASSEMBLY_KEYS", "BODY_KEYS", "MATERIAL_KEYS", "CONTACT_FRACTION",
]

ASSEMBLY_FORMAT = "section-case/2"
ASSEMBLY_KEYS = ("format", "name", "units", "support", "target", "revolution", "bodies", "options", "note")
BODY_KEYS = ("name", "lower", "upper", "law", "material", "note")
MATERIAL_KEYS = ("model", "shear_modulus", "bulk_to_shear", "bulk_modulus", "c10", "c01", "c20", "c30")
MATERIAL_MODELS = ("neo-hookean", "mooney-rivlin", "yeoh")
CONTACT_FRACTION = 1e-6
"""Default contact tolerance, as a fraction of the assembly's bounding-box diagonal."""
SAMPLES = 1024
"""Points sampled evenly along every curve for the resting and sharing checks (besides its vertices)."""


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


def revolution_from_json(obj, field: str = "revolution") -> Revolution:
    """Check a ``revolution`` object: ``{"axis": [[x, y], [x, y]]}`` with two distinct points."""
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected an object {{\"axis\": [[x, y], [x, y]]}}, got {obj!r}")
    for key in obj:
        if key != "axis":
            raise unknown_key(field, key, ("axis",))
    axis = obj.get("axis")
    if not isinstance(axis, list) or len(axis) != 2 or not all(isinstance(p, list) and len(p) == 2 for p in axis):
        raise CaseError(f"{field}.axis", f"expected two points [[x, y], [x, y]], got {axis!r}")
    pts = tuple(tuple(number(v, f"{field}.axis[{i}]") for v in p) for i, p in enumerate(axis))
    if pts[0] == pts[1]:
        raise CaseError(f"{field}.axis", "the two points coincide; give two distinct points of the axis")
    return Revolution(pts)


def material_from_json(obj, field: str) -> str:
    """Check a body's ``material`` object; its canonical JSON text (the paper model ignores it)."""
    if obj is None:
        return "{}"
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected an object such as {{\"shear_modulus\": 1.0}}, got {obj!r}")
    for key, value in obj.items():
        if key not in MATERIAL_KEYS:
            raise unknown_key(field, key, MATERIAL_KEYS)
        if key == "model":
            if value not in MATERIAL_MODELS:
                raise CaseError(f"{field}.model", f"unknown rubber model {value!r}; use one of {', '.join(MATERIAL_MODELS)}")
        elif key in ("shear_modulus", "bulk_to_shear", "bulk_modulus", "c10"):
            number(value, f"{field}.{key}", low=0.0, strict_low=True)
        else:
            number(value, f"{field}.{key}")
    return json.dumps(obj, sort_keys=True)


@dataclass(frozen=True, eq=False)
class Body:
    """One deformable body of an assembly.

    Attributes
    ----------
    name : str
        Unique within the assembly.
    lower : Curve
        From the body's A to its B, lying on its foundation.
    upper : Curve
        From B back to A.
    law : Law
    material : str
        The ``material`` object as canonical JSON (:attr:`material_data`);
        ``"{}"`` for none.
    """

    name: str
    lower: Curve
    upper: Curve
    law: Law
    material: str = "{}"

    @property
    def material_data(self) -> dict:
        """The ``material`` object (a new dict each time)."""
        return json.loads(self.material)

    def to_json(self) -> dict:
        """The body's object of the case format."""
        out = {"name": self.name, "lower": self.lower.to_json(), "upper": self.upper.to_json(), "law": self.law.to_json()}
        if self.material != "{}":
            out["material"] = self.material_data
        return out


@dataclass(frozen=True, eq=False)
class Assembly:
    """Several bonded bodies on one support: a ``section-case/2`` case, checked.

    Building one runs :func:`layout`: an assembly that exists is one whose
    bodies rest on the support or on each other as the format says.

    Attributes
    ----------
    support : Curve
        The curve the assembly rests on, A to B.
    target : Curve
        Where the support goes, A' to B'.
    bodies : tuple of Body
    name, units : str
    options : Options
    revolution : Revolution or None
    """

    support: Curve
    target: Curve
    bodies: tuple
    name: str = "assembly"
    units: str = "mm"
    options: Options = Options()
    revolution: Revolution | None = None

    def __post_init__(self):
        if not isinstance(self.options, Options):
            object.__setattr__(self, "options", options_from_json(self.options))
        object.__setattr__(self, "bodies", tuple(self.bodies))
        if not self.bodies:
            raise CaseError("bodies", "an assembly needs at least one body")
        seen: dict[str, int] = {}
        for i, body in enumerate(self.bodies):
            if body.name in seen:
                raise CaseError(f"bodies[{i}].name", f"{body.name!r} is also the name of bodies[{seen[body.name]}]; give every body its own name")
            seen[body.name] = i
        object.__setattr__(self, "bodies", tuple(self._bound(i, b) for i, b in enumerate(self.bodies)))
        object.__setattr__(self, "layout", layout(self))
        if self.revolution is not None:
            check_axis(self)

    def _bound(self, i: int, body: Body) -> Body:
        """``body`` with a law of bodies of revolution bound to the axis; refused without one."""
        law = body.law
        if not law.needs_axis:
            return body
        if self.revolution is None:
            raise CaseError(f"bodies[{i}].law.{law.key}", "only valid for a body of revolution; give the case a "
                            "revolution axis or use area_ratio")
        if law.axis == self.revolution.axis:
            return body
        return dataclasses.replace(body, law=law.about(self.revolution.axis))

    @property
    def model(self) -> str:
        """Name of the deformation model the case asks for."""
        return self.options.model

    @cached_property
    def size(self) -> float:
        """Bounding-box diagonal of the support and every body, units."""
        return _size(self.support, self.bodies)

    def label(self, i: int) -> str:
        """``bodies[i] 'name'``, for messages."""
        return f"bodies[{i}] {self.bodies[i].name!r}"

    def body_case(self, i: int, upper: Curve | None = None) -> Case:
        """Body ``i`` as a version-1 case (its lower, its upper or ``upper``, its law, the options).

        The target is the assembly's target where the body's lower curve is
        the support itself (so a one-body assembly is its version-1 case),
        else the body's own lower curve; it only guides the sampling of the
        lower curve (:func:`~sectiondeform.section.build_section`).
        """
        body = self.bodies[i]
        on_support = body.lower.to_json() == self.support.to_json()
        return Case(lower=body.lower, upper=upper or body.upper, target=self.target if on_support else body.lower,
                    law=body.law, name=f"{self.name}/{body.name}", units=self.units, options=self.options)

    def replace(self, **changes) -> Assembly:
        """The assembly with ``changes`` (fields of :class:`Assembly`); ``options`` may be a dict."""
        import dataclasses

        return dataclasses.replace(self, **changes)

    def __eq__(self, other):
        if not isinstance(other, Assembly):
            return NotImplemented
        return json.dumps(assembly_to_dict(self), sort_keys=True) == json.dumps(assembly_to_dict(other), sort_keys=True)

    def __hash__(self):
        return hash(json.dumps(assembly_to_dict(self), sort_keys=True))


def _size(support: Curve, bodies) -> float:
    pts = [support.at_fractions(np.linspace(0.0, 1.0, 65))]
    for b in bodies:
        pts += [b.lower.at_fractions(np.linspace(0.0, 1.0, 65)), b.upper.at_fractions(np.linspace(0.0, 1.0, 65))]
    return float(np.hypot(*np.ptp(np.concatenate(pts), axis=0)))


@dataclass(frozen=True, eq=False)
class Layout:
    """How the bodies of an assembly rest on each other.

    Attributes
    ----------
    order : tuple of int
        Body indices from the support up: every body after its foundations.
    foundations : tuple of tuple of int
        Per body, the bodies its lower curve rests on (sorted).
    on_support : tuple of bool
        Per body, whether part of its lower curve rests on the support.
    tolerance : float
        Contact tolerance, units.
    """

    order: tuple
    foundations: tuple
    on_support: tuple
    tolerance: float
    fine: dict = field(default_factory=dict, repr=False)

    def resting_on(self, j: int) -> tuple:
        """Indices of the bodies that rest on body ``j``."""
        return tuple(i for i, f in enumerate(self.foundations) if j in f)


def _fine(curve: Curve, tol: float) -> np.ndarray:
    """A polyline within ``tol`` of ``curve``, ``(k, 2)``."""
    pts, _ = curve.discretise(tol)
    return pts


def _samples(curve: Curve, fine: np.ndarray) -> np.ndarray:
    """Points of ``curve``: its fine polyline's vertices and :data:`SAMPLES` evenly spaced, in order."""
    s = np.linspace(0.0, 1.0, SAMPLES + 1)
    pts = curve.at_fractions(s)
    line = shapely.LineString(fine)
    d = np.concatenate((shapely.line_locate_point(line, shapely.points(fine)), shapely.line_locate_point(line, shapely.points(pts))))
    allp = np.concatenate((fine, pts))
    return allp[np.argsort(d, kind="stable")]


def _distance(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """Distance of each point to a polyline, ``(n,)``."""
    return shapely.distance(shapely.points(points), shapely.LineString(polyline))


def _shared_length(points: np.ndarray, polyline: np.ndarray, tol: float) -> tuple[float, np.ndarray | None]:
    """Length of the run of ``points`` lying within ``tol`` of ``polyline``, and a point of it.

    Consecutive points both within ``tol`` (and their midpoint) count: two
    curves that only touch at a point share no length.
    """
    near = _distance(points, polyline) <= tol
    mids = 0.5 * (points[1:] + points[:-1])
    both = near[1:] & near[:-1]
    if both.any():
        both[both] &= _distance(mids[both], polyline) <= tol
    if not both.any():
        return 0.0, None
    steps = np.hypot(*(points[1:] - points[:-1]).T)
    return float(steps[both].sum()), mids[np.argmax(both)]


def _where(p) -> str:
    return str(np.round(np.asarray(p, dtype=float), 6).tolist())


def layout(assembly: Assembly) -> Layout:
    """Check how the bodies rest on the support and on each other; the resting order.

    Raises
    ------
    GeometryError
        One line naming the bodies and the place: a lower curve resting on
        nothing (with the gap), a piece shared by two upper curves or by two
        lower curves, overlapping interiors (with the area), a cycle.
    """
    bodies = assembly.bodies
    label = assembly.label
    size = _size(assembly.support, bodies)
    tol = assembly.options.contact_tolerance
    if tol is None:
        tol = CONTACT_FRACTION * size
    fine_tol = 0.25 * tol
    support = _fine(assembly.support, fine_tol)
    lowers = [_fine(b.lower, fine_tol) for b in bodies]
    uppers = [_fine(b.upper, fine_tol) for b in bodies]
    low_pts = [_samples(b.lower, f) for b, f in zip(bodies, lowers)]
    up_pts = [_samples(b.upper, f) for b, f in zip(bodies, uppers)]
    n = len(bodies)

    for i in range(n):
        for j in range(i + 1, n):
            length, where = _shared_length(up_pts[i], uppers[j], tol)
            if length > 0:
                raise GeometryError(
                    f"{label(i)} and {label(j)}: their upper curves share a piece of length {length:.6g} near {_where(where)}; "
                    "a shared piece belongs to the lower curve of the body that rests on the other"
                )
            length, where = _shared_length(low_pts[i], lowers[j], tol)
            if length > 0:
                raise GeometryError(
                    f"{label(i)} and {label(j)}: their lower curves share a piece of length {length:.6g} near {_where(where)}; "
                    "a shared piece belongs to the lower curve of exactly one of them"
                )

    foundations, on_support = [], []
    for i in range(n):
        found = []
        gaps = [("the support", _distance(low_pts[i], support))]
        for j in range(n):
            if j == i:
                continue
            gaps.append((label(j), _distance(low_pts[i], uppers[j])))
            length, _ = _shared_length(low_pts[i], uppers[j], tol)
            if length > 0:
                found.append(j)
        d = np.min([g for _, g in gaps], axis=0)
        if (d > tol).any():
            k = int(np.argmax(d))
            nearest = min(gaps, key=lambda g: g[1][k])[0]
            raise GeometryError(
                f"{label(i)}: its lower curve rests on nothing near {_where(low_pts[i][k])}: gap {d[k]:.6g} to {nearest} "
                f"(contact tolerance {tol:.3g}); put every point of a lower curve on the support or on another body's upper curve"
            )
        support_length, _ = _shared_length(low_pts[i], support, tol)
        foundations.append(tuple(found))
        on_support.append(support_length > 0)

    polygons = []
    for i in range(n):
        ring = np.concatenate((lowers[i], uppers[i][1:-1]))
        poly = shapely.Polygon(ring)
        polygons.append(poly if poly.is_valid else shapely.make_valid(poly))
    for i in range(n):
        for j in range(i + 1, n):
            overlap = shapely.intersection(polygons[i], polygons[j])
            allowed = tol * min(polygons[i].length, polygons[j].length)
            if overlap.area > allowed:
                c = shapely.get_coordinates(overlap.representative_point())[0]
                raise GeometryError(
                    f"{label(i)} and {label(j)}: their interiors overlap (area {overlap.area:.6g} near {_where(c)}); "
                    "bodies may share pieces of their outlines, not their insides"
                )

    order = _resting_order(foundations, label)
    return Layout(order=order, foundations=tuple(foundations), on_support=tuple(on_support), tolerance=float(tol),
                  fine={"support": support, "uppers": tuple(uppers)})


def check_axis(assembly: Assembly) -> None:
    """Check that the axis of revolution crosses no body and that all bodies lie on one side of it.

    A body may touch the axis (a solid of revolution's section), not cross
    it; points within the contact tolerance of the axis count as on it.

    Raises
    ------
    GeometryError
        One line naming the body: crossed by the axis (with a point on each
        side), or lying on the other side from the first body.
    """
    axis = assembly.revolution.axis
    tol = assembly.layout.tolerance
    side0, first = 0.0, None
    for i, body in enumerate(assembly.bodies):
        pts = np.concatenate((_fine(body.lower, 0.25 * tol), _fine(body.upper, 0.25 * tol)))
        d = signed_distance(pts, axis)
        lo, hi = int(np.argmin(d)), int(np.argmax(d))
        if d[lo] < -tol and d[hi] > tol:
            raise GeometryError(
                f"{assembly.label(i)}: the revolution axis crosses it (points {_where(pts[lo])} and {_where(pts[hi])} "
                "lie on either side); a section of revolution lies on one side of its axis: move the axis or the body"
            )
        side = d[hi] if d[hi] > tol else d[lo]
        if first is None:
            side0, first = side, i
        elif side * side0 < 0:
            raise GeometryError(
                f"{assembly.label(i)}: it lies on the other side of the revolution axis from {assembly.label(first)}; "
                "all bodies of a section of revolution lie on one side of the axis"
            )


def _resting_order(foundations, label) -> tuple:
    """Bodies from the support up (Kahn); a cycle is refused naming its bodies."""
    n = len(foundations)
    waiting = {i: set(f) for i, f in enumerate(foundations)}
    order: list[int] = []
    while waiting:
        ready = sorted(i for i, f in waiting.items() if not f)
        if not ready:
            i = min(waiting)
            path = [i]
            while True:  # walk down the foundations until a body comes back
                i = min(waiting[i])
                if i in path:
                    path = path[path.index(i):] + [i]
                    break
                path.append(i)
            chain = " on ".join(label(k) for k in path)
            raise GeometryError(f"{chain}: these bodies rest on each other in a cycle; a body cannot rest, directly or through others, on itself")
        for i in ready:
            order.append(i)
            del waiting[i]
        for f in waiting.values():
            f.difference_update(ready)
    assert len(order) == n
    return tuple(order)


def assembly_from_dict(data) -> Assembly:
    """Check a parsed ``section-case/2`` object and build an :class:`Assembly`.

    Raises
    ------
    CaseError
        Naming the first field at fault (a ``volume_ratio`` law without
        ``revolution`` among them).
    GeometryError
        If the bodies do not rest on each other as the format says
        (:func:`layout`), or the axis of revolution crosses a body (:func:`check_axis`).

    Examples
    --------
    >>> a = assembly_from_dict({"format": "section-case/2",
    ...     "support": {"polyline": [[0, 0], [2, 0]]}, "target": {"polyline": [[0, 0], [2, 0]]},
    ...     "bodies": [{"name": "base", "lower": {"polyline": [[0, 0], [2, 0]]},
    ...                 "upper": {"polyline": [[2, 0], [2, 1], [0, 1], [0, 0]]}, "law": {"area_ratio": 0.9}},
    ...                {"name": "top", "lower": {"polyline": [[0, 1], [2, 1]]},
    ...                 "upper": {"polyline": [[2, 1], [1, 2], [0, 1]]}, "law": {"area_ratio": 1.0}}]})
    >>> a.layout.order, a.layout.foundations
    ((0, 1), ((), (0,)))
    """
    if not isinstance(data, dict):
        raise CaseError("case", f"expected a JSON object, got {type(data).__name__}")
    fmt = data.get("format")
    if fmt != ASSEMBLY_FORMAT:
        raise CaseError("format", f"expected {ASSEMBLY_FORMAT!r}, got {fmt!r}")
    for key in data:
        if not isinstance(key, str) or not (key in ASSEMBLY_KEYS or _is_user_key(key)):
            raise unknown_key("", key, ASSEMBLY_KEYS)
    for key in ("support", "target", "bodies"):
        if key not in data:
            raise CaseError(key, "missing; an assembly needs support, target and bodies")
    for key in ("name", "units"):
        if key in data and not isinstance(data[key], str):
            raise CaseError(key, f"expected a string, got {data[key]!r}")
    options = options_from_json(data.get("options"))
    revolution = None
    if "revolution" in data:
        revolution = revolution_from_json(data["revolution"])
    raw = data["bodies"]
    if not isinstance(raw, list) or not raw:
        raise CaseError("bodies", f"expected a non-empty list of bodies, got {raw!r}")
    axis = revolution.axis if revolution is not None else None
    bodies = [_body_from_json(b, f"bodies[{i}]", axis) for i, b in enumerate(raw)]
    return Assembly(
        support=curve_from_json(data["support"], "support"),
        target=curve_from_json(data["target"], "target"),
        bodies=tuple(bodies),
        name=data.get("name", "assembly"),
        units=data.get("units", "mm"),
        options=options,
        revolution=revolution,
    )


def _body_from_json(obj, field: str, axis=None) -> Body:
    if not isinstance(obj, dict):
        raise CaseError(field, f"expected a body object, got {type(obj).__name__}")
    for key in obj:
        if not isinstance(key, str) or not (key in BODY_KEYS or _is_user_key(key)):
            raise unknown_key(field, key, BODY_KEYS)
    for key in ("name", "lower", "upper", "law"):
        if key not in obj:
            raise CaseError(f"{field}.{key}", "missing; a body needs name, lower, upper and law")
    name = obj["name"]
    if not isinstance(name, str) or not name:
        raise CaseError(f"{field}.name", f"expected a non-empty string, got {name!r}")
    return Body(
        name=name,
        lower=curve_from_json(obj["lower"], f"{field}.lower"),
        upper=curve_from_json(obj["upper"], f"{field}.upper"),
        law=law_from_json(obj["law"], f"{field}.law", axis),
        material=material_from_json(obj.get("material"), f"{field}.material"),
    )


def assembly_to_dict(assembly: Assembly) -> dict:
    """The ``section-case/2`` object of an :class:`Assembly`."""
    out = {
        "format": ASSEMBLY_FORMAT,
        "name": assembly.name,
        "units": assembly.units,
        "support": assembly.support.to_json(),
        "target": assembly.target.to_json(),
    }
    if assembly.revolution is not None:
        out["revolution"] = assembly.revolution.to_json()
    out["bodies"] = [b.to_json() for b in assembly.bodies]
    options = assembly.options.to_json()
    if options:
        out["options"] = options
    return out
