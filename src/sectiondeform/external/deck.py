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
* ``*NODE FILE`` U and ``*EL FILE`` S (CalculiX's ``.frd``, Abaqus's ``.fil``).

The default element, CPE6, does not lock for nearly incompressible rubber
in CalculiX 2.20, which has no hybrid elements. The deck is designed for
several bodies (one set, section and material each) and for bodies of
revolution (CAX elements); the case format of version 1 has one plane body,
so only that is built today.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..case import Case
from ..errors import CaseError
from ..section import build_section
from .mesh import FeMesh, element_areas, fe_mesh

__all__ = [
    "DEFAULT_ELEMENT",
    "DEFAULT_MESH_SIZE",
    "ELEMENTS",
    "Body",
    "Deck",
    "ElementType",
    "build_deck",
    "case_option",
    "check_case_format",
    "deck_text",
]

DEFAULT_MESH_SIZE = 0.1
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
DEFAULT_ELEMENT = "CPE6"


@dataclass(frozen=True)
class Body:
    """One deformable body of the deck: its elements and neo-Hookean material.

    Attributes
    ----------
    name : str
        Element set and material name (letters, digits, underscores).
    elements : (k,) int64 ndarray
        Rows of the mesh's cells that belong to it.
    shear_modulus : float
        μ, in the case's stress unit (relative by default).
    bulk_to_shear : float
        κ / μ.
    """

    name: str
    elements: np.ndarray
    shear_modulus: float
    bulk_to_shear: float

    @property
    def c10(self) -> float:
        """Abaqus neo-Hooke C10 = μ / 2."""
        return 0.5 * self.shear_modulus

    @property
    def d1(self) -> float:
        """Abaqus neo-Hooke D1 = 2 / κ."""
        return 2.0 / (self.bulk_to_shear * self.shear_modulus)


@dataclass(frozen=True, eq=False)
class Deck:
    """Everything a deck says.

    Attributes
    ----------
    name : str
    units : str
    mesh : FeMesh
    element : ElementType
    bodies : tuple of Body
    support_displacement : (n_l, 2) float64 ndarray
        Displacement of each of ``mesh.lower_nodes``, units.
    unexpressed : tuple of str
        What the case asks for that the deck cannot say (one sentence each).
    area_initial : float
        Mesh area, units².
    area_target : float
        The case's law applied to it, units².
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


def case_option(case, key: str, default):
    """One option of a case, whether ``case.options`` is a dict or a dataclass; ``default`` when unset."""
    options = getattr(case, "options", None)
    if options is None:
        return default
    value = options.get(key) if isinstance(options, dict) else getattr(options, key, None)
    return default if value is None else value


def check_case_format(data: dict) -> None:
    """Refuse, in one line, the case kinds the deck writer cannot build yet.

    Raises
    ------
    CaseError
        For a ``section-case/2`` file (several bodies, bodies of revolution).
    """
    if isinstance(data, dict) and data.get("format") not in (None, "section-case/1"):
        what = "a body of revolution" if "revolution" in data else "several bodies"
        raise CaseError("format", f"{data.get('format')!r} ({what}) is not supported by the solver decks yet; "
                        "give a section-case/1 case (one plane body)")


def _element(name: str) -> ElementType:
    key = str(name).upper()
    if key not in ELEMENTS:
        raise CaseError("--element", f"unknown element {name!r}; use one of {', '.join(ELEMENTS)}")
    el = ELEMENTS[key]
    if el.axisymmetric:
        raise CaseError("--element", f"{el.name} is axisymmetric but the case has no revolution axis; "
                        f"use {el.name.replace('CAX', 'CPE')}")
    return el


def build_deck(case: Case, element: str = DEFAULT_ELEMENT, mesh_size: float = DEFAULT_MESH_SIZE,
               shear_modulus: float = 1.0) -> Deck:
    """The deck of a (version-1, plane) case.

    Parameters
    ----------
    case : Case
    element : str
        Abaqus element name (see :data:`ELEMENTS`); plane strain for a plane case.
    mesh_size : float
        Triangle size as a fraction of the section's mesh scale (mean thickness).
    shear_modulus : float
        μ; the shape does not depend on it.

    Returns
    -------
    Deck

    Raises
    ------
    CaseError
        For an unknown or axisymmetric element, a mesh size not > 0, a
        bulk-to-shear ratio not > 0.
    """
    el = _element(element)
    if isinstance(mesh_size, bool) or not isinstance(mesh_size, (int, float)) or not math.isfinite(mesh_size) \
            or mesh_size <= 0:
        raise CaseError("--mesh-size", f"must be a finite number > 0, got {mesh_size!r}")
    k = float(case_option(case, "bulk_to_shear", DEFAULT_BULK_TO_SHEAR))
    section = build_section(case)
    mesh = fe_mesh(section, case.lower, mesh_size * section.mesh_scale, el.family, el.nodes)
    support = np.asarray(case.target.at_fractions(mesh.lower_fractions), dtype=np.float64)
    displacement = support - mesh.points[mesh.lower_nodes]
    area0 = float(element_areas(mesh.points, mesh.cells, mesh.corners).sum())
    area_target = float(case.law.target_area(area0))
    unexpressed = []
    ratio = area_target / area0
    if abs(ratio - 1.0) > 1e-12:
        unexpressed.append(
            f"the law asks for area ratio {ratio:.6g}: generalised plane strain with an out-of-plane stretch "
            f"1/r = {1.0 / ratio:.6g} has no element in CalculiX; this deck is plain plane strain (area kept up to "
            "compressibility), so its shape is that of area ratio 1"
        )
    if el.hybrid:
        unexpressed.append(f"{el.name} is a hybrid element: Abaqus runs it, CalculiX 2.20 does not (use CPE6 or CPE8R)")
    body = Body("BODY", np.arange(len(mesh.cells), dtype=np.int64), float(shear_modulus), k)
    return Deck(name=case.name, units=case.units, mesh=mesh, element=el, bodies=(body,),
                support_displacement=displacement, unexpressed=tuple(unexpressed), area_initial=area0,
                area_target=area_target)


def _rows(first: int, table: np.ndarray, fmt: str) -> list[str]:
    return [f"{first + i}, " + ", ".join(fmt.format(v) for v in row) for i, row in enumerate(table)]


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
    out = [
        "*HEADING",
        f"{deck.name}: section deformed onto its target (units {deck.units}), written by sectiondeform",
        f"** {len(m.points)} nodes, {len(m.cells)} {el.name} elements, {n_l} support nodes moved onto the target.",
        "** Support rule: the node at arc-length fraction s of the lower curve goes to the target at fraction s.",
        "** Material: neo-Hookean, C10 = mu/2, D1 = 2/kappa.",
    ]
    if deck.unexpressed:
        out.append("** NOT EXPRESSED BY THIS DECK:")
        out += [f"**   - {line}" for line in deck.unexpressed]
    out += ["*NODE, NSET=ALL_NODES"]
    out += _rows(1, m.points, "{:.15g}")
    for body in deck.bodies:
        out.append(f"*ELEMENT, TYPE={el.name}, ELSET={body.name}")
        out += _rows(int(body.elements[0]) + 1 if len(body.elements) else 1, m.cells[body.elements] + 1, "{:d}")
    out.append("*NSET, NSET=SUPPORT")
    out += _id_lines(m.lower_nodes + 1)
    out.append("*NSET, NSET=UPPER")
    out += _id_lines(np.unique(m.upper_nodes) + 1)
    for body in deck.bodies:
        out += [
            f"*SOLID SECTION, ELSET={body.name}, MATERIAL=RUBBER_{body.name}",
            "1.0",
            f"*MATERIAL, NAME=RUBBER_{body.name}",
            "*HYPERELASTIC, NEO HOOKE",
            f"{body.c10:.15g}, {body.d1:.15g}",
        ]
    out += [
        "*STEP, NLGEOM, INC=1000",
        "*STATIC",
        f"{INITIAL_INCREMENT:g}, 1.0, {MIN_INCREMENT:g}, {MAX_INCREMENT:g}",
        "*BOUNDARY",
    ]
    nodes = m.lower_nodes + 1
    u = deck.support_displacement
    for node, (ux, uy) in zip(nodes.tolist(), u.tolist()):
        out.append(f"{node}, 1, 1, {ux:.15g}")
        out.append(f"{node}, 2, 2, {uy:.15g}")
    out += ["*NODE FILE, FREQUENCY=1000", "U", "*EL FILE, FREQUENCY=1000", "S", "*END STEP"]
    return "\n".join(out) + "\n"
