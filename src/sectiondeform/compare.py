"""Distances between two deformed shapes: how far one model's answer is from another's.

Used by ``sectiondeform validate`` to measure the fast method against the
finite-element reference, and by anyone comparing two results of the same
case. Pure numpy (core install).

* :func:`hausdorff_distance`: Hausdorff distance between two polylines as
  curves (every point of each segment counts, not only the vertices);
* :func:`point_to_curve_distance`: distance of each point to a polyline;
* :func:`section_height`: the section's height above its lower curve, the
  size the distances are reported against (it means the same for a block
  on a long base and a lip seal on a short foot);
* :func:`compare_curves`: both of these and the pointwise distance between
  corresponding points, absolute and relative to a length (the section's
  height).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from .curves import as_points
from .errors import CaseError

__all__ = ["CurveComparison", "compare_curves", "hausdorff_distance", "point_to_curve_distance", "section_height"]

DENSIFY_FRACTION = 1e-3


CHUNK = 1 << 20  # point-segment pairs per block of the distance computation


def _segment_distance(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Distance of each of ``points`` (k, 2) to the polyline ``curve`` (n, 2), in blocks of points."""
    a, d = curve[:-1], np.diff(curve, axis=0)
    dd = np.einsum("jd,jd->j", d, d)
    safe = np.where(dd > 0, dd, 1.0)
    out = np.empty(len(points))
    step = max(1, CHUNK // max(1, len(a)))
    for i in range(0, len(points), step):
        q = points[i:i + step, None, :] - a[None]
        t = np.where(dd > 0, np.clip(np.einsum("kjd,jd->kj", q, d) / safe, 0.0, 1.0), 0.0)
        r = q - t[..., None] * d[None]
        out[i:i + step] = np.sqrt(np.einsum("kjd,kjd->kj", r, r).min(axis=1))
    return out


def _densify(curve: np.ndarray, step: float) -> np.ndarray:
    """The polyline's vertices and points every ``step`` or less along each segment."""
    d = np.diff(curve, axis=0)
    parts = np.maximum(1, np.ceil(np.hypot(d[:, 0], d[:, 1]) / step)).astype(np.int64)
    rank = np.repeat(np.arange(len(d)), parts)
    sub = (np.arange(parts.sum()) - np.repeat(np.cumsum(parts) - parts, parts)) / parts[rank]
    return np.concatenate((curve[:-1][rank] + d[rank] * sub[:, None], curve[-1:]))


def point_to_curve_distance(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Distance of each point to a polyline.

    Parameters
    ----------
    points : (k, 2) float64 ndarray
        Points, units.
    curve : (n, 2) float64 ndarray
        Vertices of the polyline, units, n >= 2 (repeated vertices allowed).

    Returns
    -------
    (k,) float64 ndarray
        Distances, units.

    Examples
    --------
    >>> point_to_curve_distance(np.array([[0.5, 2.0], [3.0, 0.0]]), np.array([[0.0, 0.0], [1.0, 0.0]])).tolist()
    [2.0, 2.0]
    """
    pts = as_points(points, "points", min_count=1)
    return _segment_distance(pts, as_points(curve, "curve", min_count=2))


def section_height(lower: np.ndarray, upper: np.ndarray) -> float:
    """Height of a section above its lower curve: the largest distance of an upper point from the lower polyline.

    A size that means the same for any section: the thickness of a block on
    a long base, the reach of a lip standing on a short foot (where the mean
    thickness, area over lower length, is several times the real size).

    Parameters
    ----------
    lower : (n, 2) float64 ndarray
        The lower curve's nodes, A to B, units.
    upper : (m, 2) float64 ndarray
        The upper curve's characteristic points, units.

    Returns
    -------
    float
        Units.

    Examples
    --------
    >>> section_height(np.array([[0.0, 0.0], [4.0, 0.0]]), np.array([[4.0, 0.0], [3.0, 2.0], [-3.0, 4.0], [0.0, 0.0]]))
    5.0
    """
    return float(point_to_curve_distance(upper, lower).max())


def hausdorff_distance(a: np.ndarray, b: np.ndarray, resolution: float | None = None) -> float:
    """Hausdorff distance between two polylines taken as curves.

    Each polyline is sampled every ``resolution`` along its segments and the
    samples' exact distances to the other polyline are taken, so the result
    is within ``resolution / 2`` below the exact value (shapely's own
    ``hausdorff_distance`` uses the vertices only).

    Parameters
    ----------
    a : (n, 2) float64 ndarray
    b : (m, 2) float64 ndarray
        Polyline vertices, units.
    resolution : float, optional
        Sampling step, units; by default 1e-3 of the longer polyline's length.

    Returns
    -------
    float
        Distance, units.

    Raises
    ------
    CaseError
        If a polyline has fewer than two points or non-finite values.

    Examples
    --------
    >>> a = np.array([[0.0, 0.0], [2.0, 0.0]])
    >>> b = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
    >>> hausdorff_distance(a, b)           # the apex of b, 1 above a
    1.0
    >>> round(hausdorff_distance(b, a), 12)
    1.0
    """
    a = as_points(a, "a", min_count=2)
    b = as_points(b, "b", min_count=2)
    if resolution is None:
        lengths = [float(np.hypot(*np.diff(c, axis=0).T).sum()) for c in (a, b)]
        resolution = DENSIFY_FRACTION * max(lengths)
        if resolution == 0.0:  # both curves are single points
            return float(np.hypot(*(a[0] - b[0])))
    if not resolution > 0:
        raise CaseError("resolution", f"must be > 0, got {resolution!r}")
    return float(max(_segment_distance(_densify(a, resolution), b).max(),
                     _segment_distance(_densify(b, resolution), a).max()))


@dataclass(frozen=True)
class CurveComparison:
    """Distances between a curve and a reference curve with corresponding points.

    Attributes
    ----------
    hausdorff : float
        Hausdorff distance between the two polylines, units.
    hausdorff_relative : float
        ``hausdorff / scale``.
    max_pointwise : float
        Largest distance between corresponding points, units.
    max_pointwise_relative : float
        ``max_pointwise / scale``.
    max_pointwise_index : int
        Index of the point where it is reached.
    mean_pointwise : float
        Mean distance between corresponding points, units.
    scale : float
        Length the relative figures divide by (the section's height, :func:`section_height`), units.
    """

    hausdorff: float
    hausdorff_relative: float
    max_pointwise: float
    max_pointwise_relative: float
    max_pointwise_index: int
    mean_pointwise: float
    scale: float

    def to_json(self) -> dict:
        """The figures as a plain dictionary."""
        return asdict(self)


def compare_curves(curve: np.ndarray, reference: np.ndarray, scale: float = 1.0) -> CurveComparison:
    """Compare a deformed curve with a reference one point by point and as curves.

    Parameters
    ----------
    curve, reference : (m, 2) float64 ndarray
        The same m points deformed by two models (e.g. the upper
        characteristic points, B' to A'), units.
    scale : float
        Length for the relative figures (the section's height, :func:`section_height`), units.

    Returns
    -------
    CurveComparison

    Raises
    ------
    CaseError
        If the arrays differ in shape or ``scale`` is not > 0.

    Examples
    --------
    >>> ref = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    >>> c = compare_curves(ref + [0.0, 0.1], ref, scale=2.0)
    >>> round(c.hausdorff, 12), round(c.max_pointwise_relative, 12)
    (0.1, 0.05)
    """
    a = as_points(curve, "curve", min_count=2)
    b = as_points(reference, "reference", min_count=2)
    if a.shape != b.shape:
        raise CaseError("curve", f"has {len(a)} points but the reference has {len(b)}; they must correspond one to one")
    if not (np.isfinite(scale) and scale > 0):
        raise CaseError("scale", f"must be a finite length > 0, got {scale!r}")
    d = np.hypot(*(a - b).T)
    h = hausdorff_distance(a, b)
    k = int(np.argmax(d))
    return CurveComparison(
        hausdorff=h,
        hausdorff_relative=h / scale,
        max_pointwise=float(d[k]),
        max_pointwise_relative=float(d[k]) / scale,
        max_pointwise_index=k,
        mean_pointwise=float(d.mean()),
        scale=float(scale),
    )
