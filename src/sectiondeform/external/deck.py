"""Abaqus / CalculiX input decks (``.inp``) of a case.

:func:`build_deck` turns a case into a :class:`Deck` (mesh, element type,
bodies, support motion, what the solver cannot express); :func:`deck_text`
writes it in the keyword syntax both Abaqus/Standard and CalculiX read:

* ``*NODE``, ``*ELEMENT`` (one element set per body), ``*NSET`` SUPPORT
  (the lower curve's nodes) and UPPER (the upper characteristic points);
* per body a ``*SOLID SECTION`` (unit thickness: plane strain) and a
  ``*MATERIAL`` with ``*HYPERELASTIC, NEO HOOKE``: C10 = μ / 2,
  D1 = 2 / κ (the Abaqus form, U = C10 (Ī1 − 3) + (J − 1)² / D1);
* one ``*STEP, NLGEOM`` with ``*STATIC`` automatic increments and the
  support's nodes moved onto the target by ``*BOUNDARY`` (ramped over the
  step): the node at arc-length fraction s of the lower curve goes to the
  point of the target at the same fraction s, the rule of every model of
  the project;
* ``*NODE FILE`` U and ``*EL FILE`` S (CalculiX's ``.frd``, Abaqus's ``.fil``);
* growth (``{"volume_ratio": r}``: cure shrinkage, swelling) as a thermal
  expansion: per growing body an ``*EXPANSION`` with α = r^(1/3) − 1, every
  node at temperature 0 initially (``*INITIAL CONDITIONS``) and 1 at the
  end of the step (``*TEMPERATURE``, ramped with the support). The linear
  thermal strain α ΔT = r^(1/3) − 1, not ln(r) / 3: CalculiX makes the
  thermal deformation gradient (1 + α ΔT) I for a hyperelastic material
  (a free block comes back stretched by exactly 1 + α ΔT, stress free), so
  only this value gives the growth stretch r^(1/3) whatever the growth;
  ln(r) / 3 would be short by r^(1/3) − 1 − ln(r) / 3 (5e-4 at r = 1.1,
  0.17 at r = 3). A body of revolution expands isotropically (CAX: r, z and
  the hoop). An extruded body cannot be free along its length in a plane
  strain element (CalculiX has no generalised plane strain element): its
  deck expands in the plane only (``TYPE=ORTHO``, α, α, 0), which is plane
  strain about the extrusion stretched by a free body's r^(1/3) — exact for
  a free body, a bonded body's axial force left in (a warning says so).

The bodies' holes are holes of the mesh (:func:`~sectiondeform.reference.mesh.triangulate`):
no element inside, their faces free and unloaded; their nodes are the set
``HOLES``.

Every real is written in at most 20 characters (:func:`.inp_number.inp_real`):
CalculiX reads no more of a field and drops the rest without a word.

One writer for every problem: one body or several bonded ones (one
conforming mesh, shared nodes on shared pieces, one element set, section and
material per body; a ``section-case/1`` problem's set is ``BODY``), plane
(CPE elements) or of revolution (CAX elements, nodes in (r, z), see
:mod:`.axis`). The default element, CPE6, does not lock for nearly
incompressible rubber in CalculiX 2.20, which has no hybrid elements.
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass

import numpy as np

from ..errors import CaseError, MeshError
from ..materials.models import material_from_json
from ..problem import V1
from .axis import AxisFrame, axis_frame, reverse_orientation
from .contact_deck import PENALTY_FACTOR
from .inp_number import inp_real
from .material_cards import hyperelastic_card, material_summary
from .mesh import FeMesh, element_areas

__all__ = [
    "DEFAULT_AXI_ELEMENT",
    "DEFAULT_ELEMENT",
    "DEFAULT_MESH_SIZE",
    "ELEMENTS",
    "Body",
    "Deck",
    "ElementType",
    "build_deck",
    "rigid_fit",
    "deck_text",
    "default_element",
]

from . import DEFAULT_AXI_ELEMENT, DEFAULT_ELEMENT, DEFAULT_MESH_SIZE  # noqa: E402 - light defaults, read by the command line

DEFAULT_BULK_TO_SHEAR = 1000.0
INITIAL_INCREMENT = 0.05
MIN_INCREMENT = 1e-5
MAX_INCREMENT = 0.1


@dataclass(frozen=True)
class ElementType:
    """A continuum element of Abaqus / CalculiX.

    Attributes
    ----------
    name : str
        Abaqus name, e.g. ``"CPE6"``.
    family : str
        ``"triangle"`` or ``"quad"``.
    nodes : int
    axisymmetric : bool
        CAX (body of revolution) rather than CPE (plane strain).
    hybrid : bool
        Mixed displacement-pressure element (Abaqus only).
    """

    name: str
    family: str
    nodes: int
    axisymmetric: bool
    hybrid: bool

    @property
    def calculix(self) -> bool:
        """CalculiX 2.20 has this element (no hybrid elements)."""
        return not self.hybrid


def _element_table() -> dict:
    table = {}
    for prefix, axi in (("CPE", False), ("CAX", True)):
        for base, family, nodes in (("3", "triangle", 3), ("6", "triangle", 6), ("4", "quad", 4), ("4R", "quad", 4),
                                    ("8", "quad", 8), ("8R", "quad", 8)):
            for hybrid in (False, True):
                if hybrid and base == "3":
                    continue
                name = f"{prefix}{base}{'H' if hybrid else ''}"
                table[name] = ElementType(name, family, nodes, axi, hybrid)
    return table


#: Every element type the writer knows, by Abaqus name.
ELEMENTS = _element_table()


@dataclass(frozen=True, eq=False)
class Body:
    """One deformable body of the deck: its elements and its rubber.

    Attributes
    ----------
    name : str
        Element set and material name (letters, digits, underscores).
    elements : (k,) int64 ndarray
        Rows of the mesh's cells that belong to it.
    material : NeoHookean or MooneyRivlin or Yeoh
        Its rubber (:mod:`sectiondeform.materials.models`).
    law : str
        The case's law, for the comment block (``"area ratio 0.9"``).
    expansion : tuple of float
        The thermal expansion coefficients of its growth, (α,) isotropic or
        (α, α, 0) in the plane only (an extruded body); empty: no growth.
    """

    name: str
    elements: np.ndarray
    material: object
    law: str = ""
    expansion: tuple = ()

    @property
    def shear_modulus(self) -> float:
        """Initial shear modulus μ."""
        return float(self.material.shear_modulus)

    @property
    def bulk_to_shear(self) -> float:
        """κ / μ."""
        return float(self.material.kappa / self.material.shear_modulus)

    @property
    def c10(self) -> float:
        """Abaqus C10 (μ / 2 for a neo-Hookean rubber)."""
        return float(self.material.coefficients[0])

    @property
    def d1(self) -> float:
        """Abaqus D1 = 2 / κ."""
        return 2.0 / float(self.material.kappa)


@dataclass(frozen=True, eq=False)
class Deck:
    """Everything a deck says.

    Attributes
    ----------
    name : str
    units : str
    mesh : FeMesh
        In the case's (x, y) coordinates.
    element : ElementType
    bodies : tuple of Body
    support_displacement : (n_l, 2) float64 ndarray
        Displacement of each of ``mesh.lower_nodes`` beyond the rigid
        placement, units, in (x, y).
    unexpressed : tuple of str
        What the case asks for that the deck cannot say (one sentence each).
    area_initial : float
        Mesh area, units².
    area_target : float
        The sum of the bodies' area targets (a body under a volume law
        counts its initial area), units².
    axis : AxisFrame or None
        For a body of revolution: the map to the solver's (r, z), in which
        the deck writes its nodes and displacements.
    rotation : (2, 2) float64 ndarray
    translation : (2,) float64 ndarray
        The rigid placement of the stress-free body written in the deck:
        node X is written at ``rotation @ X + translation`` (see
        :func:`rigid_fit`); the identity by default (and always with rigid parts).
    rigid : tuple of RigidPart
        The rigid parts, meshed at their start (:mod:`.contact_deck`).
    contact_penalty : float or None
        The slope K of the linear pressure–overclosure law (moduli per unit length); None for hard contact.
    """

    name: str
    units: str
    mesh: FeMesh
    element: ElementType
    bodies: tuple
    support_displacement: np.ndarray
    unexpressed: tuple
    area_initial: float
    area_target: float
    axis: AxisFrame | None = None
    rotation: np.ndarray = dataclasses.field(default_factory=lambda: np.eye(2))
    translation: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(2))
    rigid: tuple = ()
    contact_penalty: float | None = None

    @property
    def placed_points(self) -> np.ndarray:
        """Node coordinates as the deck writes them (rigidly placed, in the case's plane), ``(N, 2)``."""
        return self.mesh.points @ self.rotation.T + self.translation

    @property
    def increments(self) -> tuple[float, float, float]:
        """``*STATIC`` initial, minimum and maximum increment (fractions of the step).

        The solver's first iteration moves only the support; so that the
        elements on it are not turned inside out, the first increment moves
        the support by at most a quarter of the smallest size of the elements
        on it (0.05 when that allows it); at most 0.1 of the step.
        """
        m = self.mesh
        touching = np.isin(m.cells, m.lower_nodes).any(axis=1)
        size = float(np.sqrt(2.0 * element_areas(m.points, m.cells[touching], m.corners).min()))
        motion = float(np.hypot(*self.support_displacement.T).max()) if len(self.support_displacement) else 0.0
        motion = max([motion] + [float(np.hypot(*p.travel)) for p in self.rigid])
        cap = 1.0 if motion == 0 else 0.25 * size / motion
        first, largest = min(INITIAL_INCREMENT, cap), MAX_INCREMENT
        if self.rigid:  # contact: no increment moves a part by more than half an element
            largest = min(largest, max(first, 0.5 * size / motion if motion > 0 else largest))
        return first, min(MIN_INCREMENT, 1e-3 * first), largest


def rigid_fit(points: np.ndarray, targets: np.ndarray, axis: AxisFrame | None = None):
    """The rigid motion that best takes ``points`` onto ``targets`` (least squares), ``(R, t)``.

    A rigid motion of a stress-free plane body changes nothing of its
    mechanics, so the deck places the body there first and the support
    motion left to the solver is only what deforms it. A body of revolution
    may only slide along its axis (a radial shift would stretch its hoops).

    Examples
    --------
    >>> X = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 2.0]])
    >>> R, t = rigid_fit(X, X[:, ::-1] * [-1, 1] + [3.0, 1.0])  # turned by 90 degrees, moved
    >>> (np.round(R, 12) + 0.0).tolist(), (np.round(t, 12) + 0.0).tolist()
    ([[0.0, -1.0], [1.0, 0.0]], [3.0, 1.0])
    """
    X, Y = np.asarray(points, dtype=np.float64), np.asarray(targets, dtype=np.float64)
    if axis is not None:
        e = np.asarray(axis.along)
        return np.eye(2), e * float(np.mean((Y - X) @ e))
    cx, cy = X.mean(axis=0), Y.mean(axis=0)
    u, _, vt = np.linalg.svd((X - cx).T @ (Y - cy))
    d = np.sign(np.linalg.det(vt.T @ u.T)) or 1.0
    R = vt.T @ np.diag([1.0, d]) @ u.T
    return R, cy - R @ cx


def default_element(axisymmetric: bool) -> str:
    """The element that does not lock for nearly incompressible rubber in CalculiX: CPE6, or CAX6 for revolution."""
    return DEFAULT_AXI_ELEMENT if axisymmetric else DEFAULT_ELEMENT


def _element(name: str | None, axisymmetric: bool = False) -> ElementType:
    if name is None:
        name = default_element(axisymmetric)
    key = str(name).upper()
    if key not in ELEMENTS:
        raise CaseError("--element", f"unknown element {name!r}; use one of {', '.join(ELEMENTS)}")
    el = ELEMENTS[key]
    if el.axisymmetric and not axisymmetric:
        raise CaseError("--element", f"{el.name} is axisymmetric but the case has no revolution axis; "
                        f"use {el.name.replace('CAX', 'CPE')}")
    if axisymmetric and not el.axisymmetric:
        raise CaseError("--element", f"{el.name} is plane strain but the case is a body of revolution; "
                        f"use {el.name.replace('CPE', 'CAX')}")
    return el


def _mesh_size(mesh_size) -> float:
    if isinstance(mesh_size, bool) or not isinstance(mesh_size, (int, float)) or not math.isfinite(mesh_size) \
            or mesh_size <= 0:
        raise CaseError("--mesh-size", f"must be a finite number > 0, got {mesh_size!r}")
    return float(mesh_size)


def _hybrid_note(el: ElementType) -> list[str]:
    if not el.hybrid:
        return []
    plain = el.name[:-1]
    return [f"{el.name} is a hybrid element: Abaqus runs it, CalculiX 2.20 does not (use {plain[:3]}6 or {plain[:3]}8R)"]


def _area_note(who: str, ratio: float) -> str:
    return (f"{who} asks for area ratio {ratio:.6g}: generalised plane strain with an out-of-plane stretch "
            f"1/r = {1.0 / ratio:.6g} has no element in CalculiX; this deck is plain plane strain (area kept up to "
            "compressibility), so its shape is that of area ratio 1")


def _set_name(name: str, used: set) -> str:
    """An element-set name from a body name: letters, digits and underscores, upper case, unique."""
    base = re.sub(r"[^A-Za-z0-9_]", "_", name).upper() or "BODY"
    if not base[0].isalpha():
        base = "B_" + base
    out, k = base[:70], 2
    while out in used:
        out, k = f"{base[:66]}_{k}", k + 1
    used.add(out)
    return out


def _law_text(law) -> str:
    """E.g. ``"area ratio 0.9"``."""
    return f"{law.key.replace('_', ' ')} {law.ratio:.6g}"


def growth_note(who: str, ratio: float) -> str:
    """The warning of an extruded body's growth in a plane-strain deck."""
    g = ratio ** (1.0 / 3.0)
    return (f"{who} grows by volume ratio {ratio:.6g}: this plane-strain deck expands the section in its plane by "
            f"{g:.6g} and holds the extrusion at a free body's stretch {g:.6g} (CalculiX has no generalised plane strain "
            "element): exact for a free body; a bonded body's axial force is not released, so its section may differ "
            "from the models' free extrusion")


def _expansion(law, axisymmetric: bool) -> tuple:
    """The thermal expansion coefficients that express a law's growth (empty: none): α = r^(1/3) − 1."""
    if axisymmetric:
        ratio = law.ratio if law.measure == "volume" else 1.0
        return () if abs(ratio - 1.0) <= 1e-12 else (ratio ** (1.0 / 3.0) - 1.0,)
    if law.growth is None or law.measure != "area" or abs(law.growth - 1.0) <= 1e-12:
        return ()
    alpha = law.growth ** (1.0 / 3.0) - 1.0
    return (alpha, alpha, 0.0)


def _bodies(problem, body_of: np.ndarray, areas: np.ndarray, axisymmetric: bool):
    """Each body of the deck (set, elements, rubber, law, growth), its warnings, and the sum of the targets."""
    k = dict(problem.options.model_values).get("bulk_to_shear", DEFAULT_BULK_TO_SHEAR)
    bodies, unexpressed, used, target = [], [], set(), 0.0
    for i, b in enumerate(problem.bodies):
        elements = np.flatnonzero(body_of == i).astype(np.int64)
        where = "" if problem.dialect == V1 else f"bodies[{i}]."
        material = material_from_json(b.material_data, f"{where}material", default_bulk_to_shear=k)
        name = "BODY" if problem.dialect == V1 else _set_name(b.name, used)
        law = b.law
        expansion = _expansion(law, axisymmetric)
        bodies.append(Body(name, elements, material, _law_text(law), expansion))
        area = float(areas[elements].sum())
        target += law.target_area(area) if law.measure == "area" else area
        if abs(law.ratio - 1.0) > 1e-12:
            who = problem.label(i) or "the law"
            if law.growth is None and law.measure == "area" and not axisymmetric:  # not an extruded body's growth
                unexpressed.append(_area_note(who, law.ratio))
            elif len(expansion) == 3:
                unexpressed.append(growth_note(who, law.ratio))
    return tuple(bodies), unexpressed, target


def build_deck(problem, element: str | None = None, mesh_size: float = DEFAULT_MESH_SIZE,
               contact_penalty=None) -> Deck:
    """The deck of a problem: one conforming mesh, one element set, section and material per body.

    Shared pieces are bonded (the bodies share their nodes there); the
    support's nodes go onto the target by the arc-length rule; a body of
    revolution is written in the solver's (r, z) (see :mod:`.axis`).
    Growth (a volume ratio other than 1) is a thermal expansion (see the
    module). What the solver cannot express (an area ratio other than 1 on
    a plane body) or expresses only in part (an extruded body's growth, its
    extrusion not freed) is in :attr:`Deck.unexpressed`.

    Parameters
    ----------
    problem : Problem
        One body or several, plane or of revolution.
    element : str, optional
        Abaqus element name (see :data:`ELEMENTS`): plane strain for a plane
        problem, axisymmetric for bodies of revolution; by default
        :func:`default_element`.
    mesh_size : float
        Triangle size as a fraction of each body's mesh scale (mean thickness).
    contact_penalty : float or "hard", optional
        With rigid parts: the slope K of the linear pressure–overclosure law
        (moduli per unit length), or ``"hard"``; by default
        ``PENALTY_FACTOR × 3 μ / h`` (:mod:`.contact_deck`).

    Returns
    -------
    Deck

    Raises
    ------
    CaseError
        For an unknown element or one of the wrong family, a mesh size not > 0.
    """
    from .mesh import fe_mesh

    axisymmetric = problem.revolution is not None
    el = _element(element, axisymmetric)
    mesh, body_of = fe_mesh(problem, _mesh_size(mesh_size), el.family, el.nodes)
    order = np.argsort(body_of, kind="stable")  # each body's elements in one run of numbers
    mesh = dataclasses.replace(mesh, cells=mesh.cells[order])
    mesh.cells.setflags(write=False)
    if len(mesh.lower_nodes) < 2:  # nothing to move the bodies by: a deck without loading
        raise MeshError(f"deck mesh: {len(mesh.lower_nodes)} nodes on the support, at least 2 needed to move it; "
                        "the mesher lost the support of this small section: draw it in a smaller unit (larger numbers)")
    support = np.asarray(problem.target.at_fractions(mesh.lower_fractions), dtype=np.float64)
    areas = element_areas(mesh.points, mesh.cells, mesh.corners)
    axis = axis_frame(problem.revolution.axis, mesh.points) if axisymmetric else None
    if problem.rigid:  # the parts start where the case puts them: no rigid placement first
        R, t = np.eye(2), np.zeros(2)
    else:
        R, t = rigid_fit(mesh.points[mesh.lower_nodes], support, axis)
    bodies, unexpressed, target = _bodies(problem, body_of[order], areas, axisymmetric)
    rigid, penalty = (), None
    if problem.rigid:
        from .contact_deck import rigid_parts

        size = float(np.sqrt(2.0 * np.median(areas)))
        keep = None
        if axis is not None:  # a rigid element with a node on the axis has no volume: the parts cut off it
            big = 1e3 * problem.size
            keep = axis.from_rz(np.array([[1e-3 * size, -big], [big, -big], [big, big], [1e-3 * size, big]]))
        rigid = rigid_parts(problem, size, keep)
        if contact_penalty is None:
            mu = min(b.shear_modulus for b in bodies)
            penalty = PENALTY_FACTOR * 3.0 * mu / float(np.sqrt(2.0 * areas.min()))
        elif contact_penalty != "hard":
            penalty = float(contact_penalty)
    return Deck(name=problem.name, units=problem.units, mesh=mesh, element=el, bodies=bodies,
                support_displacement=support - (mesh.points[mesh.lower_nodes] @ R.T + t),
                unexpressed=tuple(unexpressed + _hybrid_note(el)), area_initial=float(areas.sum()),
                area_target=float(target), axis=axis, rotation=R, translation=t, rigid=rigid, contact_penalty=penalty)


def _mirror_faces(faces: np.ndarray) -> np.ndarray:
    """The faces of triangles whose corners 2 and 3 were swapped: S1 (1-2) becomes S3 (1-3), S2 stays."""
    return np.column_stack((faces[:, 0], np.array([2, 1, 0])[faces[:, 1]]))


def _rows(first: int, table: np.ndarray) -> list[str]:
    return [f"{first + i}, " + ", ".join(inp_real(v) for v in row) for i, row in enumerate(table)]


def _id_lines(ids: np.ndarray, per_line: int = 16) -> list[str]:
    return [", ".join(str(int(i)) for i in ids[k:k + per_line]) for k in range(0, len(ids), per_line)]


def deck_text(deck: Deck) -> str:
    """The deck in Abaqus / CalculiX keyword syntax (nodes and elements numbered from 1).

    Returns
    -------
    str
        The whole ``.inp`` file, ending with a newline.
    """
    m, el = deck.mesh, deck.element
    n_l = len(m.lower_nodes)
    points, cells, u = deck.placed_points, m.cells, deck.support_displacement
    if deck.axis is not None:
        points = deck.axis.to_rz(points)
        u = deck.axis.to_rz(u + np.asarray(deck.axis.origin))  # the linear part of the map
        if deck.axis.mirrored:
            cells = reverse_orientation(cells, m.kind)
    out = [
        "*HEADING",
        f"{deck.name}: section deformed onto its target (units {deck.units}), written by sectiondeform",
        f"** {len(m.points)} nodes, {len(m.cells)} {el.name} elements, {n_l} support nodes moved onto the target.",
        "** Support rule: the node at arc-length fraction s of the support goes to the target at fraction s.",
    ]
    if len(deck.bodies) > 1:
        out.append("** Bodies bonded: on a shared piece of outline the bodies share their nodes.")
    if deck.axis is not None:
        out.append(f"** Body of revolution, {deck.axis.comment()}.")
    if not (np.allclose(deck.rotation, np.eye(2)) and np.allclose(deck.translation, 0.0)):
        (r11, r12), (r21, r22) = deck.rotation.tolist()
        out.append(f"** Nodes rigidly placed first (stress-free): X' = [[{r11:.12g}, {r12:.12g}], [{r21:.12g}, "
                   f"{r22:.12g}]] X + [{deck.translation[0]:.12g}, {deck.translation[1]:.12g}] (the case's X), the "
                   "rigid motion that best fits the support onto the target; *BOUNDARY gives the rest.")
    for body in deck.bodies:
        law = f", law {body.law}" if body.law else ""
        out.append(f"** Body {body.name}: {len(body.elements)} elements, {material_summary(body.material)}{law}.")
    out.append("** Material: the Abaqus forms, e.g. neo-Hookean C10 = mu/2, D1 = 2/kappa.")
    if any(body.expansion for body in deck.bodies):
        out.append("** Growth: *EXPANSION alpha = r^(1/3) - 1 with the temperature from 0 to 1 over the step (thermal "
                   "stretch 1 + alpha = r^(1/3)); an extruded body expands in its plane only (TYPE=ORTHO).")
    if deck.unexpressed:
        out.append("** NOT EXPRESSED BY THIS DECK:")
        out += [f"**   - {line}" for line in deck.unexpressed]
    out += ["*NODE, NSET=ALL_NODES"]
    out += _rows(1, points)
    for body in deck.bodies:
        out.append(f"*ELEMENT, TYPE={el.name}, ELSET={body.name}")
        out += [f"{e + 1}, " + ", ".join(str(int(v)) for v in row)
                for e, row in zip(body.elements.tolist(), cells[body.elements] + 1)]
    out.append("*NSET, NSET=SUPPORT")
    out += _id_lines(m.lower_nodes + 1)
    if len(m.upper_nodes):
        out.append("*NSET, NSET=UPPER")
        out += _id_lines(np.unique(m.upper_nodes) + 1)
    if len(m.hole_nodes):
        out.append("*NSET, NSET=HOLES")  # free faces: nothing loads them
        out += _id_lines(np.unique(m.hole_nodes) + 1)
    growing = any(body.expansion for body in deck.bodies)
    for body in deck.bodies:
        out.append(f"*SOLID SECTION, ELSET={body.name}, MATERIAL=RUBBER_{body.name}")
        if not el.axisymmetric:
            out.append("1.0")  # unit thickness: plane strain per unit length
        out += [f"*MATERIAL, NAME=RUBBER_{body.name}", *hyperelastic_card(body.material)]
        if growing:  # every material of a deck at temperature: those that do not grow expand by nothing
            kind = ", TYPE=ORTHO" if len(body.expansion) == 3 else ""
            out += [f"*EXPANSION{kind}, ZERO=0.", ", ".join(inp_real(a) for a in (body.expansion or (0.0,)))]
    if growing:
        out += ["*INITIAL CONDITIONS, TYPE=TEMPERATURE", "ALL_NODES, 0."]
    moves = []
    if deck.rigid:
        from .contact_deck import contact_cards, free_faces

        if deck.axis is not None:
            axis = deck.axis

            def to_deck(p):
                return axis.to_rz(p)

            def vec(v):
                return axis.to_rz(v + np.asarray(axis.origin))
        else:
            def to_deck(p):
                return p

            def vec(v):
                return v
        rigid = [p if deck.axis is None or not deck.axis.mirrored else
                 dataclasses.replace(p, triangles=p.triangles[:, [0, 2, 1]], faces=_mirror_faces(p.faces))
                 for p in deck.rigid]
        cards, moves = contact_cards(rigid, free_faces(cells, m.corners, m.lower_nodes), len(m.points) + 1,
                                     len(m.cells) + 1, "CAX3" if el.axisymmetric else "CPE3", to_deck, vec,
                                     deck.contact_penalty, not el.axisymmetric)
        out += cards
    out += [
        f"*STEP, NLGEOM, INC={10000 if deck.rigid else 1000}",
        "*STATIC",
        "{:.6g}, 1.0, {:.6g}, {:.6g}".format(*deck.increments),
        "*BOUNDARY",
    ]
    nodes = m.lower_nodes + 1
    for node, (ux, uy) in zip(nodes.tolist(), u.tolist()):
        out.append(f"{node}, 1, 1, {inp_real(ux)}")
        out.append(f"{node}, 2, 2, {inp_real(uy)}")
    out += moves
    if growing:  # the growth: temperature 1 at the end of the step (alpha = r^(1/3) - 1), ramped with the support
        out += ["*TEMPERATURE", "ALL_NODES, 1."]
    if deck.rigid:  # every increment (one frequency for all output in CalculiX): the load-deflection curve
        for part in deck.rigid:  # the part's nodes' reactions (the reference node's, through MPCs, are not computed)
            out += [f"*NODE PRINT, NSET={part.name}_NODES, TOTALS=ONLY, FREQUENCY=1", "RF"]
        out += ["*NODE PRINT, NSET=SUPPORT, TOTALS=ONLY", "RF", "*NODE FILE", "U", "*CONTACT FILE", "CDIS, CSTR",
                "*END STEP"]
    else:
        out += ["*NODE FILE, FREQUENCY=1000", "U", "*EL FILE, FREQUENCY=1000", "S", "*END STEP"]
    return "\n".join(out) + "\n"
