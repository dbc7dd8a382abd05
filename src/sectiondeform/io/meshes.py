"""The meshes of a result through meshio: VTU, VTK, Gmsh MSH, XDMF, Abaqus INP.

:func:`write_result` writes a result's *final* mesh; :func:`write_mesh`
writes its final or its initial mesh: one cell block per body, the bodies'
nodes one after the other in the case's order (a node on a piece two
bodies share is written once per body). Numbering is kept: within a body's
block, node i is row i of its mesh's ``points`` (1-based formats such as
Gmsh and Abaqus number from 1), element j row j of its ``cells``, corners
counter-clockwise as in :class:`~sectiondeform.models.base.MeshData`.
Points are written with z = 0.

Where every body's two meshes have the same nodes (the layered paper
model), VTU, VTK and MSH files carry point data: the final mesh has
``initial`` (the initial coordinates) and ``displacement`` (final -
initial), the initial mesh ``final`` and ``displacement``; every file has
the cell data ``element`` (the element's number in its body's mesh).
``write_mesh(..., fields=True)`` adds each body's per-element strain or
geometric fields as cell data (:mod:`sectiondeform.strain_fields`): for the
hyperelastic model also ``von_mises_stress`` and ``pressure`` (−tr σ / 3,
positive in compression), in units of the shear modulus for the paper's
one body, in the unit of each body's material otherwise, per element as
cell data and recovered at the nodes as point data of the same names
(:func:`body_point_data`). A result with rigid parts also has the point
data ``contact_pressure`` on the final mesh: the pressure at the bodies'
boundary nodes in contact, 0 elsewhere (:func:`contact_point_data`).
Abaqus INP carries the mesh only.

The bodies of a ``section-result/2`` result are tagged: cell data
``body`` = the body's tag (its index in the case's ``bodies`` plus 1),
field data ``{name: [tag, 2]}``, which Gmsh files keep as named physical
groups (``gmsh:physical`` = the tag; VTU and VTK files keep no field data:
tag t is ``bodies[t - 1]`` of the case and of the result JSON); Abaqus
files get one element set per body, named after it. A ``section-result/1``
result (the paper's one body) is written untagged, physical group 1.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..errors import CaseError, require
from ..result import RESULT_V1
from .files import atomic_write

__all__ = ["write_mesh", "write_result", "to_meshio", "split_components", "body_point_data", "contact_point_data",
           "FORMATS"]

FORMATS = {".vtu": "vtu", ".vtk": "vtk", ".msh": "gmsh", ".xdmf": "xdmf", ".inp": "abaqus"}


def writer_options(fmt: str) -> dict:
    """Write options for meshio by format.

    Binary VTK and Gmsh; XDMF with its data inline (one file, no HDF5 beside
    it); Abaqus reals with 13 significant digits, at most 20 characters,
    since CalculiX reads only the first 20 characters of a field
    (:mod:`sectiondeform.external.inp_number`; meshio's default, 17 digits,
    takes 22 or 23).
    """
    return {"gmsh": {"binary": True}, "vtk": {"binary": True}, "xdmf": {"data_format": "XML"},
            "abaqus": {"float_fmt": ".12e"}}.get(fmt, {})


def _xyz(points: np.ndarray) -> np.ndarray:
    return np.column_stack((points, np.zeros(len(points))))


def _tagged(result) -> bool:
    """Whether the file tags its bodies: every result but the paper's one body (``section-result/1``)."""
    return result.dialect != RESULT_V1


def to_meshio(result, which: str = "final", data: bool = True, point_data: dict | None = None,
              cell_data: dict | None = None):
    """One mesh of every body of a result as one :class:`meshio.Mesh`.

    Parameters
    ----------
    result : Result
    which : str
        ``"final"`` or ``"initial"``.
    data : bool
        Attach the point, cell and field data described in the module docstring.
    point_data : dict of str to ndarray, optional
        More data, ``(N, ...)``: one row per node of the file (the bodies' nodes in order).
    cell_data : dict of str to ndarray or list, optional
        More data: ``(M, ...)``, one row per element of the file (the
        bodies' elements in order), or a list of one such array per body.

    Raises
    ------
    CaseError
        For an unknown mesh, or extra data whose row count is not the node or element count.

    Returns
    -------
    meshio.Mesh
        Points ``(N, 3)`` float64 (z = 0), one cell block per body in element order.
    """
    meshio = require("meshio", "cad", "writing meshes")
    if which not in ("final", "initial"):
        raise CaseError("mesh", f"unknown mesh {which!r}; use final or initial")
    meshes = [(b.final_mesh, b.initial_mesh) if which == "final" else (b.initial_mesh, b.final_mesh) for b in result.bodies]
    offsets = np.cumsum([0] + [len(m.points) for m, _ in meshes])
    blocks = [(m.kind, np.asarray(m.cells, dtype=np.int64) + o) for (m, _), o in zip(meshes, offsets)]
    points = np.concatenate([m.points for m, _ in meshes])
    counts = [len(m.cells) for m, _ in meshes]
    out_points, out_cells, field_data = {}, {}, {}
    if data:
        out_cells["element"] = [np.arange(n, dtype=np.int64) for n in counts]
        if all(m.points.shape == other.points.shape for m, other in meshes):
            twin = np.concatenate([other.points for _, other in meshes])
            out_points["initial" if which == "final" else "final"] = _xyz(twin)
            out_points["displacement"] = _xyz(points - twin if which == "final" else twin - points)
        if _tagged(result):
            out_cells["body"] = [np.full(n, i + 1, dtype=np.int64) for i, n in enumerate(counts)]
            field_data = {b.name: np.array([i + 1, 2], dtype=np.int64) for i, b in enumerate(result.bodies)}
    for name, values in (point_data or {}).items():
        out_points[name] = _rows(values, len(points), name, "node")
    for name, values in (cell_data or {}).items():
        if isinstance(values, (list, tuple)):
            out_cells[name] = [_rows(v, n, name, "element") for v, n in zip(values, counts)]
        else:
            out_cells[name] = np.split(_rows(values, sum(counts), name, "element"), np.cumsum(counts)[:-1])
    return meshio.Mesh(_xyz(points), blocks, point_data=out_points, cell_data=out_cells, field_data=field_data)


def _rows(values, count: int, name: str, what: str) -> np.ndarray:
    """``values`` as an array with one row per node or element, checked."""
    arr = np.asarray(values)
    if arr.ndim == 0 or len(arr) != count:
        raise CaseError(name, f"expected one row per {what} ({count}), got shape {arr.shape}")
    return arr


#: Number of components a data field may have, by format; other fields are split.
FIELD_WIDTHS = {"gmsh": (1, 3, 9), "xdmf": (1, 3, 6, 9)}


def split_components(data: dict, fmt: str) -> dict:
    """Fields a format cannot carry whole, split into ``name_0``, ``name_1``, ...

    Gmsh data fields have 1, 3 or 9 components, XDMF attributes 1, 3, 6 or 9
    (scalar, vector, symmetric or full tensor); other formats take any.
    """
    widths = FIELD_WIDTHS.get(fmt)
    out = {}
    for name, values in data.items():
        values = np.asarray(values)
        if widths is None or values.ndim == 1 or values.shape[1] in widths:
            out[name] = values
        else:
            out.update({f"{name}_{i}": values[:, i] for i in range(values.shape[1])})
    return out


def _teach_meshio_plane_strain() -> None:
    """Let meshio's Abaqus reader read back the plane-strain quads written here (it knows CPS4, not CPE4)."""
    from meshio.abaqus import _abaqus

    for name in ("CPE4", "CPE4R", "CPE4H"):
        _abaqus.abaqus_to_meshio_type.setdefault(name, "quad")


def _one_block_per_type(mesh, meshio):
    """The mesh with the blocks of one cell type joined (cell data joined alike; ``body`` still tags each cell).

    XDMF writes blocks of several types as one *Mixed* topology, which
    meshio 5.3 cannot read back for quadratic triangles: bodies that share
    one element type are written as one block instead.
    """
    types = [c.type for c in mesh.cells]
    if len(set(types)) != 1 or len(types) == 1:
        return mesh
    cells = [(types[0], np.concatenate([c.data for c in mesh.cells]))]
    data = {name: [np.concatenate(blocks)] for name, blocks in mesh.cell_data.items()}
    return meshio.Mesh(mesh.points, cells, point_data=mesh.point_data, cell_data=data)


def _for_format(mesh, result, which: str, fmt: str, meshio):
    """The mesh with what ``fmt`` needs: Gmsh physical groups, one XDMF block per type, Abaqus element sets."""
    tags = [np.full(len(c.data), i + 1, dtype=np.int32) for i, c in enumerate(mesh.cells)]
    if fmt == "xdmf":
        return _one_block_per_type(mesh, meshio)
    if fmt == "gmsh":
        mesh.cell_data["gmsh:physical"] = tags
        mesh.cell_data["gmsh:geometrical"] = [t.copy() for t in tags]
        if _tagged(result):
            counts = [len((b.final_mesh if which == "final" else b.initial_mesh).points) for b in result.bodies]
            mesh.point_data["gmsh:dim_tags"] = np.column_stack((np.full(sum(counts), 2),
                                                                np.repeat(np.arange(1, len(counts) + 1), counts)))
    if fmt == "abaqus" and _tagged(result):
        sets = {re.sub(r"[^A-Za-z0-9_]", "_", b.name): [np.arange(len(c.data)) if k == i else np.array([], dtype=np.int64)
                                                          for k, c in enumerate(mesh.cells)]
                for i, b in enumerate(result.bodies)}
        return meshio.Mesh(mesh.points, mesh.cells, cell_sets=sets)
    return mesh


def write_mesh(path, result, which: str = "final", fields: bool = False) -> None:
    """Write one mesh of every body of a result, format by extension, atomically.

    Parameters
    ----------
    path : str or Path
        ``.vtu``, ``.vtk``, ``.msh`` (Gmsh 4.1, binary: meshio 5.3 cannot re-read the data of ASCII files), ``.xdmf``
        (XDMF 3, data inline) or ``.inp`` (Abaqus).
    result : Result
    which : str
        ``"final"`` or ``"initial"``.
    fields : bool
        Add each body's per-element fields as cell data, in its block
        (:func:`body_cell_data`), and the hyperelastic model's nodal
        stresses as point data (:func:`body_point_data`); none in Abaqus files. Gmsh files take 1,
        3 or 9 components per field, XDMF files 1, 3, 6 or 9: the others are
        split into ``name_0``, ``name_1``, ...

    Raises
    ------
    CaseError
        For an unknown extension.
    """
    meshio = require("meshio", "cad", "writing meshes")
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in FORMATS:
        raise CaseError(str(path), f"unknown mesh format {ext!r}; use one of {', '.join(FORMATS)}")
    fmt = FORMATS[ext]
    cells = body_cell_data(result, fmt) if fields and fmt != "abaqus" else None
    points = body_point_data(result) if fields and fmt != "abaqus" else None
    if result.rigid and which == "final" and fmt != "abaqus":  # rigid parts: the contact pressure on the boundary
        points = {**(points or {}), "contact_pressure": contact_point_data(result)}
    mesh = _for_format(to_meshio(result, which, data=fmt != "abaqus", point_data=points, cell_data=cells),
                       result, which, fmt, meshio)

    def write(tmp):
        meshio.write(str(tmp), mesh, file_format=fmt, **writer_options(fmt))
        if fmt == "abaqus":  # meshio names quads CAX4P (axisymmetric pore pressure): plane strain instead
            _teach_meshio_plane_strain()
            tmp.write_text(re.sub(r"(?i)type\s*=\s*CAX4P\b", "type=CPE4", tmp.read_text()))

    atomic_write(path, write)


def body_cell_data(result, fmt: str = "vtu") -> dict:
    """Each body's per-element fields, as cell data: name to one array per body.

    The fields of :func:`~sectiondeform.strain_fields.result_fields` with each
    body's mechanics (the hyperelastic model's von Mises stress and pressure,
    relative to the shear modulus for the paper's one body, else in the unit
    of the body's material); a field some body lacks is left out. ``fmt``:
    the meshio format written, whose field widths apply (:func:`split_components`).
    """
    from ..strain_fields import result_fields, result_mechanics

    per_body = []
    for body, mechanics in zip(result.bodies, result_mechanics(result)):
        lz = getattr(body.info, "out_of_plane_stretch", 1.0)
        values = result_fields(body.initial_mesh, body.final_mesh, result.model, lz, result.axis, mechanics)[1]
        per_body.append(split_components(values, fmt))
    names = [k for k in per_body[0] if all(k in v for v in per_body)] if per_body else []
    return {k: [v[k] for v in per_body] for k in names}


def body_point_data(result) -> dict:
    """The hyperelastic model's stresses recovered at the nodes, as point data: name to ``(N,)``, the bodies' nodes in order.

    ``von_mises_stress`` and ``pressure`` of
    :func:`~sectiondeform.strain_fields.nodal_stresses`, each body's own
    (a node of a shared piece is written once per body, with its body's
    value: the pressure jumps there); a field some body lacks is left out.
    Empty for the paper model.
    """
    from ..strain_fields import result_mechanics

    nodal = [m.nodal if m is not None else {} for m in result_mechanics(result)]
    names = [k for k in nodal[0] if all(k in n for n in nodal)] if nodal else []
    return {k: np.concatenate([n[k] for n in nodal]) for k in names}


def contact_point_data(result) -> np.ndarray:
    """The contact pressure at the bodies' final boundary nodes, ``(N,)``, the bodies' nodes in order; 0 off contact.

    A boundary node (of an edge of one element) is in contact with a part
    when it lies on the part's outline (within twice the penetration left,
    or 10⁻⁴ of the body's size), and takes the pressure of the nearest
    point where the part's pressure is known (the corners of its edges,
    :attr:`~sectiondeform.fem.contact.PartContact.pressure`). Units of the moduli.
    """
    import shapely
    from scipy.spatial import cKDTree

    out = []
    parts = [(np.asarray(p.pressure, dtype=np.float64).reshape(-1, 3), shapely.LinearRing(p.outline),
              2.0 * p.penetration_max) for p in result.rigid if len(p.pressure) and p.outline is not None]
    for body in result.bodies:
        mesh = body.final_mesh
        values = np.zeros(len(mesh.points))
        corners = 3 if mesh.kind.startswith("triangle") else 4
        cells = np.asarray(mesh.cells)
        c = cells[:, :corners]
        edges = np.sort(np.stack((c, np.roll(c, -1, axis=1)), axis=2).reshape(-1, 2), axis=1)
        _, inverse, counts = np.unique(edges, axis=0, return_inverse=True, return_counts=True)
        free = counts[inverse.ravel()] == 1
        on = np.zeros(len(mesh.points), bool)
        on[edges[free].ravel()] = True
        if cells.shape[1] == 2 * corners:  # mid-edge nodes of the free edges
            on[cells[:, corners:].reshape(-1)[free]] = True
        nodes = np.flatnonzero(on)
        xy = np.asarray(mesh.points)[nodes]
        for q, ring, pen in parts:
            tol = max(pen, 1e-4 * np.sqrt(abs(body.area_final)))
            near = shapely.distance(shapely.points(xy), ring) <= tol
            _, j = cKDTree(q[:, :2]).query(xy[near])
            values[nodes[near]] = np.maximum(values[nodes[near]], q[j, 2])
        out.append(values)
    return np.concatenate(out)


def write_result(path, result, fields: bool = False) -> None:
    """Write the final mesh of a result (see :func:`write_mesh`), with its per-element fields if asked."""
    write_mesh(path, result, "final", fields=fields)
