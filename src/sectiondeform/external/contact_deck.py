"""The rigid parts of a deck: meshed rigid bodies, the bodies' free surface, the contact cards.

CalculiX 2.20 has no analytical rigid surface, so each rigid part is a
meshed rigid body (Abaqus reads the same cards):

* the part's outline at its **start** (``contour − travel``), discretised
  at about the rubber's element size, meshed with linear triangles
  (``CPE3``, or ``CAX3`` for a body of revolution) by Triangle, the whole
  element set made one ``*RIGID BODY`` with a reference node (``REF NODE``)
  and a rotation node (``ROT NODE``); the reference node is moved by the
  part's travel with ``*BOUNDARY`` over the step (ramped, with the support),
  its rotations held;
* the master surface: the outline's element faces (``*SURFACE, TYPE=ELEMENT``);
  the slave surface: the bodies' free boundary (element faces of one
  element only, not on the support);
* ``*SURFACE INTERACTION`` with ``*SURFACE BEHAVIOR,
  PRESSURE-OVERCLOSURE=LINEAR`` (a penalty: pressure = K × overclosure,
  K = :data:`PENALTY_FACTOR` × E / h with E = 3 μ the rubber's initial
  Young's modulus and h the smallest element size; or ``HARD``), a
  ``*FRICTION`` card from the part's ``friction`` (its stick slope
  :data:`STICK_SLOPE` × K), and ``*CONTACT PAIR, TYPE=SURFACE TO SURFACE``.

What comes back (:mod:`.solve`): the reference node's reaction force (the
force on the part, ``RF`` in the ``.frd``) and the contact pressure at the
slave nodes (``CONTACT`` block of ``*CONTACT FILE`` ``CSTR``).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from ..errors import CaseError, require
from .inp_number import inp_real

__all__ = ["PENALTY_FACTOR", "STICK_SLOPE", "RigidPart", "contact_cards", "free_faces", "rigid_parts"]

PENALTY_FACTOR = 50.0
"""The penalty slope K of the linear pressure–overclosure law, in units of the rubber's E = 3 μ over the element size."""
STICK_SLOPE = 0.1
"""The friction's stick slope (shear stress per unit of slip) in units of K."""

#: Faces (corner k to corner k + 1) of 2D elements, CalculiX's S1, S2, ...
_FACE_LABELS = ("S1", "S2", "S3", "S4")


@dataclass(frozen=True, eq=False)
class RigidPart:
    """One rigid part of a deck: its mesh at the start, its travel, its friction.

    Attributes
    ----------
    name : str
        Set name (letters, digits, underscores), ``R_<NAME>``.
    label : str
        The case's name of the part.
    points : (k, 2) float64 ndarray
        Nodes at the part's start, the case's (x, y), units.
    triangles : (t, 3) int64 ndarray
        Counter-clockwise linear triangles over ``points``.
    faces : (f, 2) int64 ndarray
        The outline's faces: triangle row and face index (0 to 2).
    travel : (2,) float64 ndarray
        The reference node's displacement over the step, the case's (x, y), units.
    friction : float
    """

    name: str
    label: str
    points: np.ndarray
    triangles: np.ndarray
    faces: np.ndarray
    travel: np.ndarray
    friction: float

    @property
    def reference(self) -> np.ndarray:
        """The reference node's place: the centroid of the outline's vertices, ``(2,)``."""
        return self.points.mean(axis=0)


def _part_name(name: str, used: set) -> str:
    base = "R_" + (re.sub(r"[^A-Za-z0-9_]", "_", name).upper() or "PART")
    out, k = base[:60], 2
    while out in used:
        out, k = f"{base[:56]}_{k}", k + 1
    used.add(out)
    return out


def _resample(ring: np.ndarray, spacing: float) -> np.ndarray:
    """A closed polygon with every edge split into pieces at most ``spacing`` long (vertices kept)."""
    nxt = np.roll(ring, -1, axis=0)
    out = []
    for a, b in zip(ring, nxt):
        k = max(1, int(np.ceil(np.hypot(*(b - a)) / spacing)))
        out.append(a + np.linspace(0.0, 1.0, k, endpoint=False)[:, None] * (b - a))
    return np.concatenate(out)


def rigid_parts(problem, spacing: float, keep=None) -> tuple:
    """The problem's rigid parts meshed at their start.

    Parameters
    ----------
    problem : Problem
    spacing : float
        Largest length of an outline face, units (about the rubber's element size).
    keep : (k, 2) float64 ndarray, optional
        A convex polygon each part's start is cut to (for a body of
        revolution: the half-plane off the axis, where CalculiX's
        axisymmetric elements have a volume).

    Returns
    -------
    tuple of RigidPart
    """
    if not problem.rigid:
        return ()
    triangle = require("triangle", "fem", "a rigid part in a solver deck")
    clip = None
    if keep is not None:
        import shapely

        clip = shapely.Polygon(keep)
    tol = 1e-6 * problem.size
    used, out = set(), []
    for i, part in enumerate(problem.rigid):
        ring = np.asarray(part.contour.discretise(tol)[0], dtype=np.float64)
        if np.allclose(ring[0], ring[-1]):
            ring = ring[:-1]
        keep = np.concatenate(([True], np.hypot(*np.diff(ring, axis=0).T) > tol))
        ring = ring[keep] - np.asarray(part.travel)
        if clip is not None:
            import shapely

            cut = shapely.Polygon(ring).intersection(clip)
            if cut.geom_type != "Polygon" or cut.is_empty:
                raise CaseError(f"rigid[{i}].contour", "its start lies across the axis of revolution in pieces; give a "
                                "part on one side of the axis")
            ring = np.asarray(cut.exterior.coords)[:-1]
        ring = _resample(ring, spacing)
        n = len(ring)
        seg = np.column_stack((np.arange(n), (np.arange(n) + 1) % n))
        tri = triangle.triangulate({"vertices": ring, "segments": seg}, "pYQ")
        pts, cells = np.asarray(tri["vertices"], dtype=np.float64), np.asarray(tri["triangles"], dtype=np.int64)
        if len(pts) != n or len(cells) == 0:
            raise CaseError(f"rigid[{i}].contour", "its outline could not be meshed for the deck; give a simple closed "
                            "contour")
        a, b, c = pts[cells[:, 0]], pts[cells[:, 1]], pts[cells[:, 2]]
        flip = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]) < 0
        cells[flip] = cells[flip][:, [0, 2, 1]]
        out.append(RigidPart(_part_name(part.name, used), part.name, pts, cells, _outline_faces(cells),
                             np.asarray(part.travel, dtype=np.float64), float(part.friction)))
    return tuple(out)


def _outline_faces(cells: np.ndarray) -> np.ndarray:
    """``(f, 2)`` (cell row, face index) of the faces of one cell only."""
    corners = cells.shape[1] if cells.shape[1] in (3, 4) else cells.shape[1] // 2
    c = cells[:, :corners]
    edges = np.stack((c, np.roll(c, -1, axis=1)), axis=2).reshape(-1, 2)
    key = np.sort(edges, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    k = np.flatnonzero(counts[inverse.ravel()] == 1)
    return np.column_stack((k // corners, k % corners)).astype(np.int64)


def free_faces(cells: np.ndarray, corners: int, fixed_nodes: np.ndarray) -> np.ndarray:
    """The faces of a mesh's free boundary: of one element only, not on the support.

    Parameters
    ----------
    cells : (M, k) int64 ndarray
        Elements as the deck writes them (corners counter-clockwise first).
    corners : int
        3 or 4.
    fixed_nodes : (d,) int64 ndarray
        The support's nodes; a face whose corners both are is not free.

    Returns
    -------
    (f, 2) int64 ndarray
        Element row and face index (0 for S1...).

    Examples
    --------
    >>> free_faces(np.array([[0, 1, 2], [1, 3, 2]]), 3, np.array([0, 1])).tolist()
    [[0, 2], [1, 0], [1, 1]]
    """
    faces = _outline_faces(np.asarray(cells)[:, :corners])
    c = np.asarray(cells)[:, :corners]
    a = c[faces[:, 0], faces[:, 1]]
    b = c[faces[:, 0], (faces[:, 1] + 1) % corners]
    on = np.isin(a, fixed_nodes) & np.isin(b, fixed_nodes)
    out = faces[~on]
    return out[np.lexsort((out[:, 1], out[:, 0]))]


def _face_lines(first_element: int, faces: np.ndarray) -> list[str]:
    return [f"{first_element + int(e)}, {_FACE_LABELS[int(k)]}" for e, k in faces]


def contact_cards(parts, slave_faces: np.ndarray, first_node: int, first_element: int, rigid_element: str,
                  points_to_deck, vector_to_deck, penalty: float | None, thickness: bool) -> tuple[list, list]:
    """The model cards (nodes, elements, surfaces, rigid bodies, interactions) and the step's ``*BOUNDARY`` lines.

    Parameters
    ----------
    parts : tuple of RigidPart
    slave_faces : (f, 2) int64 ndarray
        The bodies' free faces (element row, face index), from :func:`free_faces`.
    first_node, first_element : int
        The first free node and element numbers (1-based).
    rigid_element : str
        ``"CPE3"`` or ``"CAX3"``.
    points_to_deck, vector_to_deck : callable
        The map of points and of displacements from the case's plane to the deck's coordinates.
    penalty : float or None
        The slope K of the linear pressure–overclosure law (pressure per length); None for ``HARD``.
    thickness : bool
        Write the plane-strain thickness line (1.0) after ``*SOLID SECTION``.

    Returns
    -------
    model : list of str
    boundary : list of str
        The step's lines moving each reference node by its travel and holding its rotations.
    """
    model, boundary = [], []
    node, element = first_node, first_element
    model += ["** Contact: the bodies' free surface (slave) against each rigid part (master, a meshed rigid body).",
              "*SURFACE, NAME=BODIES_FREE, TYPE=ELEMENT", *_face_lines(1, slave_faces)]
    for part in parts:
        ids = node + np.arange(len(part.points))
        ref, rot = node + len(part.points), node + len(part.points) + 1
        elems = element + np.arange(len(part.triangles))
        model.append(f"** Rigid part {part.label!r}: {len(part.triangles)} {rigid_element} elements at its start, "
                     f"reference node {ref} moved by its travel, friction {part.friction:g}.")
        model.append(f"*NODE, NSET={part.name}_NODES")
        model += [f"{int(k)}, " + ", ".join(inp_real(v) for v in p)
                  for k, p in zip(ids, points_to_deck(part.points))]
        model.append(f"*NODE, NSET={part.name}_REF")
        model.append(f"{ref}, " + ", ".join(inp_real(v) for v in points_to_deck(part.reference[None])[0]))
        model.append(f"*NODE, NSET={part.name}_ROT")
        model.append(f"{rot}, " + ", ".join(inp_real(v) for v in points_to_deck(part.reference[None])[0]))
        model.append(f"*ELEMENT, TYPE={rigid_element}, ELSET={part.name}")
        model += [f"{int(e)}, " + ", ".join(str(int(v)) for v in row) for e, row in zip(elems, part.triangles + node)]
        model.append(f"*SOLID SECTION, ELSET={part.name}, MATERIAL=RIGID_{part.name}")
        if thickness:
            model.append("1.0")
        model += [f"*MATERIAL, NAME=RIGID_{part.name}", "*ELASTIC", "1e6, 0.3",
                  f"*RIGID BODY, NSET={part.name}_NODES, REF NODE={ref}, ROT NODE={rot}",
                  f"*SURFACE, NAME={part.name}_SURF, TYPE=ELEMENT", *_face_lines(element, part.faces),
                  f"*SURFACE INTERACTION, NAME={part.name}_INT"]
        if penalty is None:
            model.append("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD")
        else:
            model += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{inp_real(penalty)}"]
        if part.friction > 0:
            k = STICK_SLOPE * (penalty if penalty is not None else 1.0)
            model += ["*FRICTION", f"{inp_real(part.friction)}, {inp_real(k)}"]
        model += [f"*CONTACT PAIR, INTERACTION={part.name}_INT, TYPE=SURFACE TO SURFACE",
                  f"BODIES_FREE, {part.name}_SURF"]
        ux, uy = vector_to_deck(part.travel[None])[0]
        boundary += [f"{ref}, 1, 1, {inp_real(ux)}", f"{ref}, 2, 2, {inp_real(uy)}", f"{ref}, 3, 3, 0.0",
                     f"{rot}, 1, 3, 0.0"]
        node, element = rot + 1, int(elems[-1]) + 1
    return model, boundary
