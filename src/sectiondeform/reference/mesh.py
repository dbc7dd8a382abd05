"""Quality triangulation of a section for the finite-element reference (extra ``[fem]``).

The domain is the section's contour, lower curve then upper curve, with
every boundary segment split to the mesh size ``h``:

* the lower curve is sampled at arc-length fractions: the section's own
  fractions with every step longer than ``h`` split evenly, so each lower
  node carries the fraction ``s`` at which it goes onto the target;
* the upper curve is the polyline of the section's characteristic points,
  every segment longer than ``h`` split evenly, so each characteristic point
  is a node of the mesh.

The interior is meshed by Shewchuk's Triangle (the PyPI package
``triangle``) with a minimum angle of 30 degrees and a maximum area of an
equilateral triangle of side ``h``. Triangle may split boundary segments
to reach that quality (near the corners A and B, where the fine upper
points meet the coarser lower ones); a node it adds on the lower curve gets
its fraction by linear interpolation along the segment it splits.
Triangle's licence forbids commercial use without permission, which is why
it sits in the optional extra ``[fem]`` only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import MeshError, require
from ..section import Section, polygon_area

__all__ = ["SectionMesh", "triangulate_section", "split_fractions"]

MIN_ANGLE_DEG = 30.0
LOWER, UPPER = 1, 2


@dataclass(frozen=True, eq=False)
class SectionMesh:
    """A triangulated section with its lower and upper nodes marked.

    Attributes
    ----------
    points : (N, 2) float64 ndarray
        Vertex coordinates, units.
    triangles : (M, 3) int64 ndarray
        Vertex indices of each triangle, counter-clockwise.
    lower_nodes : (n_l,) int64 ndarray
        Vertices on the lower curve, from A to B.
    lower_fractions : (n_l,) float64 ndarray
        Normalised arc length of each of ``lower_nodes`` on the lower curve.
    upper_nodes : (m,) int64 ndarray
        Vertex of each characteristic point of the upper curve, B to A
        (``upper_nodes[0]`` is B, ``upper_nodes[-1]`` is A).
    size : float
        Target element size h, units.
    """

    points: np.ndarray
    triangles: np.ndarray
    lower_nodes: np.ndarray
    lower_fractions: np.ndarray
    upper_nodes: np.ndarray
    size: float

    @property
    def area(self) -> float:
        """Total area of the triangles, units²."""
        p = self.points[self.triangles]
        d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        return float(0.5 * np.sum(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]))

    @property
    def min_angle_deg(self) -> float:
        """Smallest interior angle of any triangle, degrees."""
        p = self.points[self.triangles]
        e = np.roll(p, -1, axis=1) - p  # edge i: from corner i to corner i + 1
        a = -np.roll(e, 1, axis=1)  # at corner i: towards corner i - 1
        cosang = np.einsum("mkd,mkd->mk", e, a) / (np.linalg.norm(e, axis=2) * np.linalg.norm(a, axis=2))
        return float(np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0))).min())


def split_fractions(fractions: np.ndarray, max_step: float) -> np.ndarray:
    """Split every step of a sorted fraction array longer than ``max_step`` evenly.

    Parameters
    ----------
    fractions : (n,) float64 ndarray
        Increasing values, first 0 and last 1.
    max_step : float
        Largest step allowed, > 0.

    Returns
    -------
    (n', ) float64 ndarray
        The input values and the new ones, increasing.

    Examples
    --------
    >>> split_fractions(np.array([0.0, 0.5, 1.0]), 0.2).round(3).tolist()
    [0.0, 0.167, 0.333, 0.5, 0.667, 0.833, 1.0]
    """
    fractions = np.asarray(fractions, dtype=np.float64)
    steps = np.diff(fractions)
    parts = np.maximum(1, np.ceil(steps / max_step - 1e-9)).astype(np.int64)
    rank = np.repeat(np.arange(len(steps)), parts)
    sub = np.arange(parts.sum()) - np.repeat(np.cumsum(parts) - parts, parts)
    inner = fractions[:-1][rank] + steps[rank] * sub / parts[rank]
    return np.concatenate((inner, fractions[-1:]))


def _split_polyline(points: np.ndarray, max_step: float) -> tuple[np.ndarray, np.ndarray]:
    """Split each segment of an open polyline evenly; returns the points and the index of each input vertex."""
    seg = np.diff(points, axis=0)
    parts = np.maximum(1, np.ceil(np.hypot(seg[:, 0], seg[:, 1]) / max_step - 1e-9)).astype(np.int64)
    rank = np.repeat(np.arange(len(seg)), parts)
    sub = (np.arange(parts.sum()) - np.repeat(np.cumsum(parts) - parts, parts)) / parts[rank]
    out = np.concatenate((points[:-1][rank] + seg[rank] * sub[:, None], points[-1:]))
    where = np.concatenate(([0], np.cumsum(parts)))
    return out, where


def triangulate_section(section: Section, size: float, lower_curve=None) -> SectionMesh:
    """Triangulate a section with quality triangles of size about ``size``.

    Parameters
    ----------
    section : Section
        The discretised section (its lower fractions and upper points).
    size : float
        Element size h, units: the longest boundary segment, and the side of
        the largest interior triangle.
    lower_curve : Curve, optional
        The exact lower curve, to place the lower nodes on it; by default
        they are interpolated along ``section.lower``.

    Returns
    -------
    SectionMesh

    Raises
    ------
    MeshError
        If ``size`` is not positive or Triangle fails.
    MissingExtraError
        If the package ``triangle`` is not installed.

    Examples
    --------
    >>> import sectiondeform as sd
    >>> sec = sd.build_section(sd.load_case(sd.example_case_path()))
    >>> mesh = triangulate_section(sec, 4.0)
    >>> abs(mesh.area - sec.area) < 1e-9 * sec.area, mesh.min_angle_deg > 20
    (True, True)
    """
    tr = require("triangle", "fem", "the finite-element reference mesh")
    if not (isinstance(size, (int, float, np.floating)) and math.isfinite(size) and size > 0):
        raise MeshError(f"reference mesh: the element size must be a finite number > 0, got {size!r}")
    s = split_fractions(section.fractions, size / section.lower_length)
    if lower_curve is not None:
        lower = np.asarray(lower_curve.at_fractions(s), dtype=np.float64)
    else:
        lower = np.column_stack([np.interp(s, section.fractions, section.lower[:, k]) for k in (0, 1)])
    lower[0], lower[-1] = section.lower[0], section.lower[-1]
    upper, upper_where = _split_polyline(np.asarray(section.upper, dtype=np.float64), size)
    n_l = len(lower)
    ring = np.concatenate((lower, upper[1:-1]))
    n = len(ring)
    segments = np.column_stack((np.arange(n), (np.arange(n) + 1) % n))
    markers = np.where(np.arange(n) < n_l, LOWER, UPPER).astype(np.int32)
    seg_markers = np.where(np.arange(n) < n_l - 1, LOWER, UPPER).astype(np.int32)
    max_area = math.sqrt(3.0) / 4.0 * size * size
    try:
        out = tr.triangulate(
            {"vertices": ring, "segments": segments, "vertex_markers": markers[:, None],
             "segment_markers": seg_markers[:, None]},
            f"pq{MIN_ANGLE_DEG:g}a{max_area:.17g}Q",
        )
    except Exception as exc:  # pragma: no cover - Triangle's own failures
        raise MeshError(f"reference mesh: Triangle failed on the section ({exc})") from exc
    points = np.asarray(out["vertices"], dtype=np.float64)
    triangles = np.asarray(out["triangles"], dtype=np.int64)
    if len(points) < n or not np.array_equal(points[:n], ring):
        raise MeshError("reference mesh: Triangle moved or dropped a boundary node")  # pragma: no cover
    # Counter-clockwise triangles.
    p = points[triangles]
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    cw = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] < 0
    triangles[cw] = triangles[cw][:, ::-1]
    # Lower nodes added by Triangle: fraction from the lower segment they lie on.
    marks = np.asarray(out["vertex_markers"]).ravel()
    added = np.flatnonzero((marks == LOWER) & (np.arange(len(points)) >= n))
    lower_nodes, s_all = np.arange(n_l, dtype=np.int64), s
    if len(added):
        q = points[added]
        a, d = lower[:-1], np.diff(lower, axis=0)
        t = np.clip(np.einsum("kjd,jd->kj", q[:, None, :] - a[None], d) / np.einsum("jd,jd->j", d, d), 0.0, 1.0)
        dist = np.linalg.norm(a[None] + t[..., None] * d[None] - q[:, None, :], axis=2)
        j = np.argmin(dist, axis=1)
        s_add = s[j] + t[np.arange(len(q)), j] * (s[j + 1] - s[j])
        order = np.argsort(np.concatenate((s, s_add)), kind="stable")
        lower_nodes = np.concatenate((lower_nodes, added))[order]
        s_all = np.concatenate((s, s_add))[order]
    # Upper characteristic point k sits at index upper_where[k] of the split upper polyline,
    # which is ring index n_l - 1 + upper_where[k] (B = n_l - 1, A = 0 closes the ring).
    upper_nodes = (n_l - 1 + upper_where) % n
    mesh = SectionMesh(
        points=points,
        triangles=triangles,
        lower_nodes=lower_nodes,
        lower_fractions=s_all,
        upper_nodes=upper_nodes.astype(np.int64),
        size=float(size),
    )
    if abs(mesh.area - abs(polygon_area(ring))) > 1e-9 * section.area:
        raise MeshError("reference mesh: the triangles do not cover the section")  # pragma: no cover
    for arr in (points, triangles, lower_nodes, s_all, mesh.upper_nodes):
        arr.setflags(write=False)
    return mesh
