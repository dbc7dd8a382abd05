"""The meshes of a result through meshio: VTU, VTK, Gmsh MSH, XDMF, Abaqus INP.

:func:`write_result` writes a result's *final* mesh; :func:`write_mesh`
writes its final or its initial mesh. Numbering is kept: node i of the
file is row i of the result's ``points`` (1-based formats such as Gmsh and
Abaqus number it i + 1), element j is row j of ``cells``, corners
counter-clockwise as in :class:`~sectiondeform.models.base.MeshData`.
Points are written with z = 0.

Where the two meshes have the same nodes (the layered paper model), VTU,
VTK and MSH files carry point data: the final mesh has ``initial`` (the
initial coordinates) and ``displacement`` (final - initial), the initial
mesh ``final`` and ``displacement``; every file has the cell data
``element`` (0-based element number). Any other point or cell data (one row
per node or element, any number of components) is passed through
:func:`to_meshio`; ``write_mesh(..., fields=True)`` adds the per-element
strain or geometric fields as cell data (:mod:`sectiondeform.strain_fields`):
for the hyperelastic model also ``von_mises_stress`` and ``pressure``
(−tr σ / 3, positive in compression), in units of the shear modulus for a
one-body section, in the unit of each body's material for an assembly.
Abaqus INP carries the mesh only.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..errors import CaseError, require
from .json import atomic_write

__all__ = ["write_mesh", "write_result", "to_meshio", "FORMATS"]

FORMATS = {".vtu": "vtu", ".vtk": "vtk", ".msh": "gmsh", ".xdmf": "xdmf", ".inp": "abaqus"}


def writer_options(fmt: str) -> dict:
    """Write options for meshio by format: binary VTK and Gmsh; XDMF with its data inline (one file, no HDF5 beside it)."""
    return {"gmsh": {"binary": True}, "vtk": {"binary": True}, "xdmf": {"data_format": "XML"}}.get(fmt, {})


def _xyz(points: np.ndarray) -> np.ndarray:
    return np.column_stack((points, np.zeros(len(points))))


def to_meshio(result, which: str = "final", data: bool = True, point_data: dict | None = None,
              cell_data: dict | None = None):
    """One mesh of a result as a :class:`meshio.Mesh`.

    Parameters
    ----------
    result : Result
    which : str
        ``"final"`` or ``"initial"``.
    data : bool
        Attach the point and cell data described in the module docstring.
    point_data, cell_data : dict of str to ndarray, optional
        More data to attach: arrays ``(N, ...)`` per node, ``(M, ...)`` per element.

    Raises
    ------
    CaseError
        For extra data whose row count is not the mesh's node or element count.

    Returns
    -------
    meshio.Mesh
        Points ``(N, 3)`` float64 (z = 0), one cell block in element order.
    """
    meshio = require("meshio", "cad", "writing meshes")
    if which not in ("final", "initial"):
        raise CaseError("mesh", f"unknown mesh {which!r}; use final or initial")
    mesh, other = (result.final_mesh, result.initial_mesh) if which == "final" else (result.initial_mesh, result.final_mesh)
    point_data_in, cell_data_in = point_data, cell_data
    point_data, cell_data = {}, {}
    if data:
        cell_data["element"] = [np.arange(len(mesh.cells), dtype=np.int64)]
        if other.points.shape == mesh.points.shape:
            point_data["initial" if which == "final" else "final"] = _xyz(other.points)
            point_data["displacement"] = _xyz(result.final_mesh.points - result.initial_mesh.points)
    for name, values in (point_data_in or {}).items():
        point_data[name] = _rows(values, len(mesh.points), name, "node")
    for name, values in (cell_data_in or {}).items():
        cell_data[name] = [_rows(values, len(mesh.cells), name, "element")]
    return meshio.Mesh(_xyz(mesh.points), [(mesh.kind, np.asarray(mesh.cells, dtype=np.int64))],
                       point_data=point_data, cell_data=cell_data)


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


def write_mesh(path, result, which: str = "final", fields: bool = False) -> None:
    """Write one mesh of a result, format by extension, atomically.

    Parameters
    ----------
    path : str or Path
        ``.vtu``, ``.vtk``, ``.msh`` (Gmsh 4.1, binary: meshio 5.3 cannot re-read the data of ASCII files), ``.xdmf``
        (XDMF 3, data inline) or ``.inp`` (Abaqus).
    result : Result
    which : str
        ``"final"`` or ``"initial"``.
    fields : bool
        Add the per-element fields as cell data
        (:func:`~sectiondeform.strain_fields.result_fields`: the hyperelastic
        model's strains, von Mises stress and pressure, the paper model's
        geometric fields and its mesh's strains prefixed ``geometric_``;
        none in Abaqus files; for an assembly, each body's, in its block). Gmsh files
        take 1, 3 or 9 components per field, XDMF files 1, 3, 6 or 9: the
        others are split into ``name_0``, ``name_1``, ...

    Raises
    ------
    CaseError
        For an unknown extension.
    """
    from ..assembly_result import AssemblyResult

    if isinstance(result, AssemblyResult):  # one mesh of every body, tagged (sectiondeform.io.assembly)
        from .assembly import write_mesh as write_assembly_mesh

        cells = None
        if fields and FORMATS.get(Path(path).suffix.lower()) not in (None, "abaqus"):
            cells = assembly_cell_data(result, fmt=FORMATS[Path(path).suffix.lower()])
        return write_assembly_mesh(path, result, which, cell_data=cells)
    meshio = require("meshio", "cad", "writing meshes")
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in FORMATS:
        raise CaseError(str(path), f"unknown mesh format {ext!r}; use one of {', '.join(FORMATS)}")
    fmt = FORMATS[ext]
    cells = None
    if fields and fmt != "abaqus":
        from ..strain_fields import result_fields, result_mechanics

        lz = getattr(result.info, "out_of_plane_stretch", 1.0)
        cells = result_fields(result.initial_mesh, result.final_mesh, result.model, lz,
                              mechanics=result_mechanics(result)[0])[1]
        cells = split_components(cells, fmt)
    mesh = to_meshio(result, which, data=fmt != "abaqus", cell_data=cells)
    kwargs = writer_options(fmt)
    if fmt == "gmsh":
        tags = np.zeros(len(mesh.cells[0].data), dtype=np.int32)
        mesh.cell_data["gmsh:physical"] = [tags + 1]
        mesh.cell_data["gmsh:geometrical"] = [tags + 1]
    def write(tmp):
        meshio.write(str(tmp), mesh, file_format=fmt, **kwargs)
        if fmt == "abaqus":  # meshio names quads CAX4P (axisymmetric pore pressure): plane strain instead
            _teach_meshio_plane_strain()
            tmp.write_text(re.sub(r"(?i)type\s*=\s*CAX4P\b", "type=CPE4", tmp.read_text()))

    atomic_write(path, write)


def assembly_cell_data(result, fmt: str = "vtu") -> dict:
    """Each body's per-element fields of an assembly result, as cell data: name to one array per body.

    The fields of :func:`~sectiondeform.strain_fields.result_fields` with each
    body's mechanics (the hyperelastic model's von Mises stress and pressure
    in the unit of the body's material); a field some body lacks is left out.
    ``fmt``: the meshio format written, whose field widths apply (:func:`split_components`).
    """
    from ..strain_fields import result_fields, result_mechanics

    per_body = []
    for body, mechanics in zip(result.bodies, result_mechanics(result)):
        lz = getattr(body.info, "out_of_plane_stretch", 1.0)
        values = result_fields(body.initial_mesh, body.final_mesh, result.model, lz, result.axis, mechanics)[1]
        per_body.append(split_components(values, fmt))
    names = [k for k in per_body[0] if all(k in v for v in per_body)] if per_body else []
    return {k: [v[k] for v in per_body] for k in names}


def write_result(path, result, fields: bool = False) -> None:
    """Write the final mesh of a result (see :func:`write_mesh`), with its per-element fields if asked."""
    write_mesh(path, result, "final", fields=fields)
