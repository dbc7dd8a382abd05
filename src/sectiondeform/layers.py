"""The layered structured quad mesh grown from the lower curve (paper §3.4).

Nodes are stored as a ``(L + 1, n, 2)`` array: layer ``i`` (0 is the base)
and column ``j`` (0 at A). Element ``(i, j)`` has the nodes::

    (i+1, j) 3-----2 (i+1, j+1)
             |     |
      (i, j) 0-----1 (i, j+1)

listed counter-clockwise in :attr:`LayeredMesh.quads` whatever the section's
orientation (the two bottom nodes are swapped in the ``quads`` order of a
clockwise section, so every element of a valid mesh has a positive Jacobian).

Growth: each new layer stands on the normals of the layer below, at the
element height; the layer is then smoothed into a continuous curve by a
small quadratic optimisation (closeness to the raw layer plus a penalty on
the second differences of its nodes, a pentadiagonal solve), with the
smoothing weight raised until no element of the new strip is inverted, the
layer does not cross itself and no corner Jacobian falls below
``MIN_RELATIVE_JACOBIAN`` of the element's nominal one (height x bottom
edge; where no weight reaches that, the least weight giving a valid strip is
kept; where no weight reaches it, as nodes crowd into a concave corner,
the exact offset of the layer below is tried first, its swallowtails
trimmed by shapely and its nodes spread at the base's arc-length
fractions). On a smooth layer the penalty acts like a
fourth derivative and moves nothing measurable; at kinks and above concave
parts it rounds the layer and evens out the node spacing. The two end columns are straight
lines along the base's end normals, splayed outward where the upper curve
overhangs the ends of the lower curve (:func:`end_frames`), the splay fading
over the columns within the section's height of each end. Layers are added until every upper
point lies in the mesh.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

from .curves import cross as _cross
from .curves import zigzag_fraction
from .errors import MeshError

__all__ = [
    "LayeredMesh",
    "Smoother",
    "grow_mesh",
    "node_frames",
    "end_frames",
    "extend_base",
    "plan_extension",
    "quad_jacobians",
    "grid_jacobians",
    "corner_jacobians",
    "SMOOTHING_WEIGHTS",
]

SMOOTHING_WEIGHTS = (0.05, 0.5, 5.0, 50.0, 500.0, 5e3, 5e4, 5e5)
SPLAY_STEP_DEG = 10.0
SPLAY_MAX_DEG = 80.0
SPLAY_EXTEND_DEG = 45.0
# Smallest corner Jacobian of a new strip, relative to height x bottom edge,
# that the smoothing of a layer aims for (it takes the least smoothing that
# gives a valid strip when none reaches it): squeezed elements above
# concave corners are spread out before they can fold.
MIN_RELATIVE_JACOBIAN = 0.2
# A lower curve of at least this many points turning side at more than this fraction of them is a scan's noise.
SCAN_MIN_POINTS, SCAN_ZIGZAG = 20, 0.3


@dataclass(frozen=True, eq=False)
class LayeredMesh:
    """A structured quad mesh of ``L`` layers and ``n - 1`` columns.

    Attributes
    ----------
    nodes : (L + 1, n, 2) float64 ndarray
        Node coordinates by layer and column, units.
    orientation : int
        +1 if the section lies to the left of the base (A to B), else -1.
    """

    nodes: np.ndarray
    orientation: int = 1

    @property
    def n_layers(self) -> int:
        """Number of element layers L."""
        return self.nodes.shape[0] - 1

    @property
    def n_columns(self) -> int:
        """Number of elements per layer, n - 1."""
        return self.nodes.shape[1] - 1

    @property
    def points(self) -> np.ndarray:
        """Node coordinates flattened layer by layer, ``((L + 1) * n, 2)``."""
        return self.nodes.reshape(-1, 2)

    @cached_property
    def quads(self) -> np.ndarray:
        """Counter-clockwise node indices of each element, ``(L * (n - 1), 4)`` int64."""
        return structured_quads(self.n_layers, self.nodes.shape[1], self.orientation)

    def jacobians(self) -> np.ndarray:
        """Corner Jacobians (twice the corner triangle areas), ``(M, 4)``, units²."""
        return grid_jacobians(self.nodes, self.orientation)


def structured_quads(n_layers: int, n_nodes: int, orientation: int = 1) -> np.ndarray:
    """Quads of a structured ``n_layers`` x ``(n_nodes - 1)`` grid, ``(M, 4)`` int64.

    Examples
    --------
    >>> structured_quads(1, 3).tolist()
    [[0, 1, 4, 3], [1, 2, 5, 4]]
    >>> structured_quads(1, 2, -1).tolist()
    [[1, 0, 2, 3]]
    """
    i, j = np.meshgrid(np.arange(n_layers), np.arange(n_nodes - 1), indexing="ij")
    base = (i * n_nodes + j).ravel()
    q = np.stack((base, base + 1, base + n_nodes + 1, base + n_nodes), axis=1)
    if orientation < 0:
        q = q[:, [1, 0, 3, 2]]
    return q.astype(np.int64)


def quad_jacobians(points: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """Cross product of the two edges at each corner of each quad, ``(M, 4)``.

    All four positive means a valid (non-inverted, convex-cornered) bilinear
    element: the bilinear Jacobian is affine in each local coordinate, so it
    is positive everywhere in the element.

    Examples
    --------
    >>> pts = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    >>> quad_jacobians(pts, np.array([[0, 1, 2, 3]])).tolist()
    [[1.0, 1.0, 1.0, 1.0]]
    """
    p = points[quads]
    e_next = np.roll(p, -1, axis=1) - p
    e_prev = np.roll(p, 1, axis=1) - p
    return e_next[..., 0] * e_prev[..., 1] - e_next[..., 1] * e_prev[..., 0]


def grid_jacobians(nodes: np.ndarray, orientation: int = 1) -> np.ndarray:
    """:func:`quad_jacobians` of a layered grid, without gathering: ``(L * (n - 1), 4)``.

    Equal, value for value and in the same order, to
    ``quad_jacobians(nodes.reshape(-1, 2), structured_quads(L, n, orientation))``,
    from the grid's horizontal and vertical edges.

    Parameters
    ----------
    nodes : (L + 1, n, 2) float64 ndarray
    orientation : int

    Examples
    --------
    >>> g = np.array([[[0.0, 0.0], [1.0, 0.0]], [[0.0, 1.0], [1.0, 1.0]]])
    >>> grid_jacobians(g).tolist()
    [[1.0, 1.0, 1.0, 1.0]]
    """
    return np.stack(corner_jacobians(nodes[..., 0], nodes[..., 1], orientation), axis=-1).reshape(-1, 4)


def corner_jacobians(x: np.ndarray, y: np.ndarray, orientation: int = 1) -> tuple:
    """The four corner Jacobians of a layered grid from its coordinate grids, in element corner order.

    Parameters
    ----------
    x, y : (L + 1, n) float64 ndarray
        Node coordinates by layer and column.
    orientation : int

    Returns
    -------
    tuple of four (L, n - 1) float64 ndarray
        Corners 0 to 3 of each element, as :func:`grid_jacobians` orders them.
    """
    hx, hy = x[:, 1:] - x[:, :-1], y[:, 1:] - y[:, :-1]  # along the layers (np.diff, without its overhead)
    vx, vy = x[1:] - x[:-1], y[1:] - y[:-1]  # up the columns

    def cross(i, j):  # horizontal edge of row i (0 bottom, 1 top) x vertical edge of column j
        return hx[i : len(hx) - 1 + i] * vy[:, j : vy.shape[1] - 1 + j] - hy[i : len(hy) - 1 + i] * vx[:, j : vx.shape[1] - 1 + j]

    if orientation < 0:
        return (-cross(0, 1), -cross(0, 0), -cross(1, 0), -cross(1, 1))
    return (cross(0, 0), cross(0, 1), cross(1, 1), cross(1, 0))


def node_frames(line: np.ndarray, orientation: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit tangent and inward unit normal at each node of a polyline.

    The tangent at an interior node bisects the two adjacent segments; the
    normal is the tangent turned a quarter towards the section's side.

    Parameters
    ----------
    line : (n, 2) float64 ndarray
    orientation : int
        +1: the section lies to the left of the line's direction.

    Returns
    -------
    tangents, normals : (n, 2) float64 ndarray
    """
    seg = line[1:] - line[:-1]
    seg /= np.hypot(seg[:, 0], seg[:, 1])[:, None]
    t = np.empty_like(line)
    t[0], t[-1] = seg[0], seg[-1]
    t[1:-1] = seg[:-1] + seg[1:]
    norm = np.hypot(t[:, 0], t[:, 1])
    # A cusp (segments going back on themselves) has no bisector: keep the incoming direction.
    cusp = norm < 1e-12
    if cusp.any():
        t[cusp] = np.concatenate((seg[:1], seg))[cusp]  # node i: segment i - 1 (node 0: segment 0)
        norm[cusp] = 1.0
    t /= norm[:, None]
    n = t[:, ::-1] * np.array([-orientation, orientation])  # (-t_y, t_x), turned to the section's side
    return t, n


class Smoother:
    """Solves (W + lam K'K) Q = W G: the smoothest layer Q close to the raw layer G.

    K is the second-difference operator, W weights the two ends ``end_weight``
    times more than the interior so they stay on their prescribed lines.
    The operator of each weight is built once and kept: where the system is
    small and well conditioned (``n <= DENSE_MAX``, ``lam <= DENSE_MAX_WEIGHT``)
    the dense matrix (W + lam K'K)^-1 W, one product per call; otherwise its
    banded Cholesky factor (scipy's LAPACK, as ``solveh_banded`` uses,
    imported only then).
    """

    DENSE_MAX = 200
    DENSE_MAX_WEIGHT = 50.0

    def __init__(self, n: int, end_weight: float = 1e4):
        self.n = n
        w = np.ones(n)
        w[0] = w[-1] = end_weight
        self.w = w
        self._ops = {}

    def _bands(self, lam: float) -> np.ndarray:
        """Upper banded form of W + lam K'K, ``(3, n)``: K'K has bands (1, -4, 6, ..., 6, -4, 1)."""
        n = self.n
        ktk = np.full(n, 6.0)
        ktk[[0, -1]], ktk[[1, -2]] = 1.0, 5.0
        off1 = np.full(n - 1, -4.0)
        off1[[0, -1]] = -2.0
        ab = np.zeros((3, n))
        ab[2] = self.w + lam * ktk
        ab[1, 1:] = lam * off1
        ab[0, 2:] = lam
        return ab

    def _operator(self, lam: float) -> tuple[bool, np.ndarray]:
        """``(dense, op)`` for ``lam``, built on first use."""
        if lam not in self._ops:
            ab = self._bands(lam)
            if self.n <= self.DENSE_MAX and lam <= self.DENSE_MAX_WEIGHT:
                a = np.diag(ab[2]) + np.diag(ab[1, 1:], 1) + np.diag(ab[1, 1:], -1)
                a += np.diag(ab[0, 2:], 2) + np.diag(ab[0, 2:], -2)
                self._ops[lam] = (True, np.linalg.solve(a, np.diag(self.w)))
            else:
                from scipy.linalg import cholesky_banded

                self._ops[lam] = (False, cholesky_banded(ab, check_finite=False))
        return self._ops[lam]

    def __call__(self, g: np.ndarray, lam: float) -> np.ndarray:
        if self.n < 3 or lam == 0:
            return g
        dense, op = self._operator(lam)
        if dense:
            return op @ g
        from scipy.linalg import cho_solve_banded

        return cho_solve_banded((op, False), self.w[:, None] * g, check_finite=False)


def end_frames(base: np.ndarray, orientation: int) -> tuple[np.ndarray, np.ndarray]:
    """Directions of the two end columns and their outward perpendiculars.

    An end column leaves the base along the base's end normal where that
    normal leans outward (a convex end: the column fans out with its
    neighbours), and along the bisector of the end normal and the normal of
    the chord A-B where it leans inward (a concave end: the column converges
    only half as much as its neighbours, so they never cross it and a
    concave base leaves room for many layers).

    Returns
    -------
    dirs, outward : (2, 2) float64 ndarray
        Row 0 for A, row 1 for B; ``outward`` points away from the section.
    """
    _, n = node_frames(base, orientation)
    chord = base[-1] - base[0]
    nc = orientation * np.array([-chord[1], chord[0]]) / math.hypot(*chord)
    ends = n[[0, -1]]
    along = chord / math.hypot(*chord)
    leans_in = np.array([ends[0] @ along > 0, ends[1] @ along < 0])
    dirs = np.where(leans_in[:, None], ends + nc, ends)
    dirs /= np.hypot(dirs[:, 0], dirs[:, 1])[:, None]
    perp = orientation * np.column_stack((dirs[:, 1], -dirs[:, 0]))  # along the base, A to B
    return dirs, perp * np.array([[-1.0], [1.0]])


def extend_base(line: np.ndarray, before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """Prolong a polyline along its end tangents by virtual nodes.

    Parameters
    ----------
    line : (n, 2) float64 ndarray
        The base, A to B.
    before, after : (p,) and (q,) float64 ndarray
        Distances of the virtual nodes beyond A (listed from farthest to
        nearest) and beyond B (nearest to farthest), units.

    Returns
    -------
    (p + n + q, 2) float64 ndarray

    Examples
    --------
    >>> extend_base(np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([1.0]), np.array([0.5, 1.0])).tolist()
    [[-1.0, 0.0], [0.0, 0.0], [1.0, 0.0], [1.5, 0.0], [2.0, 0.0]]
    """
    if not len(before) and not len(after):
        return line
    ta, tb = line[1] - line[0], line[-1] - line[-2]
    ta, tb = ta / math.hypot(*ta), tb / math.hypot(*tb)
    return np.concatenate((line[0] - before[:, None] * ta, line, line[-1] + after[:, None] * tb))


def plan_extension(base: np.ndarray, orientation: int, points: np.ndarray, height: float) -> tuple[np.ndarray, np.ndarray]:
    """Virtual nodes beyond A and B for points that overhang the base too far for a splay.

    Where a point lies beyond an end column at more than
    ``SPLAY_EXTEND_DEG`` from it, the base is prolonged along its end
    tangent past the farthest such point (plus one element), in steps of
    about ``height``; the remaining overhang is left to the splay.

    Returns
    -------
    before, after : (p,), (q,) float64 ndarray
        Distances for :func:`extend_base`, units.
    """
    out = []
    for end, sign in ((0, -1.0), (-1, 1.0)):
        t = base[1] - base[0] if end == 0 else base[-1] - base[-2]
        t = sign * t / math.hypot(*t)
        n = orientation * np.array([-t[1], t[0]]) * sign
        rel = points - base[end]
        u, v = rel @ t, rel @ n
        far = (u > 0) & (np.degrees(np.arctan2(u, np.maximum(v, 0.0))) > SPLAY_EXTEND_DEG)
        if far.any():
            reach = float(u[far].max()) + height
            count = max(1, math.ceil(reach / height))
            out.append(np.linspace(reach, 0.0, count + 1)[:-1] if end == 0 else np.linspace(0.0, reach, count + 1)[1:])
        else:
            out.append(np.zeros(0))
    return out[0], out[1]


def _splay_needed(base: np.ndarray, orientation: int, points: np.ndarray) -> tuple[float, float]:
    """Outward tilt, in degrees, of the end columns at A and B so that overhanging points fit."""
    dirs, outward = end_frames(base, orientation)
    out = []
    for k, end in enumerate((0, -1)):
        rel = points - base[end]
        u = rel @ outward[k]  # distance beyond the end column
        v = rel @ dirs[k]
        over = (u > 1e-9 * (1 + np.abs(v))) & (v > 0)
        ang = np.degrees(np.arctan2(u[over], v[over])).max() + 2.0 if over.any() else 0.0
        out.append(min(ang, SPLAY_MAX_DEG))
    return out[0], out[1]


def _end_direction(dirs: np.ndarray, outward: np.ndarray, k: int, deg: float) -> np.ndarray:
    a = math.radians(deg)
    return math.cos(a) * dirs[k] + math.sin(a) * outward[k]


def _strip_quality(below: np.ndarray, new: np.ndarray, orientation: int, height: float) -> tuple[float, float]:
    """Smallest corner Jacobian of the strip of elements between two layers, and smallest relative one.

    The relative Jacobian divides each corner's by ``height`` times the
    length of the element's bottom edge: 1 for a rectangle of the nominal
    height, near 0 for an element squeezed or sheared flat.
    """
    both = np.stack((below, new))
    h, v = both[:, 1:] - both[:, :-1], new - below  # rows 0 and 1: the bottom and top edges
    left = h[..., 0] * v[:-1, 1] - h[..., 1] * v[:-1, 0]  # corners 0 (bottom row) and 3 (top row)
    right = h[..., 0] * v[1:, 1] - h[..., 1] * v[1:, 0]  # corners 1 and 2
    worst = np.minimum(left, right) if orientation > 0 else -np.maximum(left, right)
    nominal = height * np.hypot(h[0, :, 0], h[0, :, 1])
    return float(worst.min()), float((worst / nominal).min())


def _distance_to_polyline(line: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Distance of each point of ``x`` ``(m, 2)`` to the polyline ``line`` ``(n, 2)``, ``(m,)``."""
    ax, ay = line[:-1, 0], line[:-1, 1]
    dx, dy = np.diff(line[:, 0]), np.diff(line[:, 1])
    dd = dx * dx + dy * dy
    # (m, n - 1) arrays, computed in place: fresh arrays of this size cost more than the arithmetic.
    rx, ry = x[:, :1] - ax, x[:, 1:] - ay
    t, tmp = rx * dx, ry * dy
    t += tmp
    t /= np.where(dd > 0, dd, 1.0)
    np.clip(t, 0.0, 1.0, out=t)
    rx -= np.multiply(t, dx, out=tmp)  # gx
    ry -= np.multiply(t, dy, out=tmp)  # gy
    np.multiply(rx, rx, out=t)
    t += np.multiply(ry, ry, out=tmp)
    return np.sqrt(np.min(t, axis=1))


def _in_strip(below: np.ndarray, new: np.ndarray, orientation: int, x: np.ndarray, tol: float) -> np.ndarray:
    """Which points of ``x`` ``(m, 2)`` lie in the strip of elements between two layers, ``(m,)`` bool.

    The elements are convex (all corner Jacobians positive), so a point is
    in one when it is on the inner side of its four edges, within ``tol``.
    Only points in the strip's bounding box, and then only the (point,
    element) pairs whose bounding boxes meet, are tested.
    """
    inside = np.zeros(len(x), dtype=bool)
    low, high = np.minimum(below, new), np.maximum(below, new)
    lo, hi = np.minimum(low[:-1], low[1:]) - tol, np.maximum(high[1:], high[:-1]) + tol  # element boxes
    box = (x >= lo.min(axis=0)) & (x <= hi.max(axis=0))
    cand = np.flatnonzero(box[:, 0] & box[:, 1])
    if not cand.size:
        return inside
    xc = x[cand]
    x0, y0 = xc[:, :1], xc[:, 1:]
    p, e = np.nonzero((x0 >= lo[:, 0]) & (x0 <= hi[:, 0]) & (y0 >= lo[:, 1]) & (y0 <= hi[:, 1]))
    n = len(below)
    corners = np.concatenate((below, new))[e[:, None] + np.array([0, 1, n + 1, n])]  # (pairs, 4, 2)
    edges = corners[:, [1, 2, 3, 0]] - corners
    side = orientation * _cross(edges, xc[p][:, None] - corners) + tol * np.hypot(edges[..., 0], edges[..., 1])
    inside[cand[p[np.all(side >= 0, axis=1)]]] = True
    return inside


def grow_mesh(
    base: np.ndarray,
    height: float,
    orientation: int,
    cover: np.ndarray,
    tol: float,
    max_layers: int | None = None,
) -> LayeredMesh:
    """Grow layers from ``base`` until every point of ``cover`` lies in the mesh.

    Parameters
    ----------
    base : (n, 2) float64 ndarray
        Discretised lower curve, A to B, units.
    height : float
        Element height, units.
    orientation : int
        +1 if the section lies to the left of the base.
    cover : (m, 2) float64 ndarray
        Points the mesh must contain (the upper curve's characteristic points).
    tol : float
        Distance within which a point on the mesh's outline counts as inside.
    max_layers : int, optional
        Stop with an error past this many layers; by default twice the
        farthest point's distance over ``height``, plus 4.

    Returns
    -------
    LayeredMesh

    Raises
    ------
    MeshError
        If a layer cannot be smoothed free of inverted elements, or some
        point cannot be covered even with the end columns splayed to 80°.
    """
    base = np.asarray(base, dtype=np.float64)
    cover = np.asarray(cover, dtype=np.float64)
    distance = _distance_to_polyline(base, cover)
    reach = float(np.max(distance))
    if max_layers is None:
        max_layers = int(math.ceil(2.0 * reach / height)) + 4
    splay = list(_splay_needed(base, orientation, cover))
    smoother = Smoother(len(base))
    frames = end_frames(base, orientation)
    while True:
        dirs = (_end_direction(*frames, 0, splay[0]), _end_direction(*frames, 1, splay[1]))
        tilt = _splay_taper(base, splay, min(0.5 * float(np.hypot(*np.diff(base, axis=0).T).sum()), reach))
        nodes, missing = _grow(base, height, orientation, cover, distance > tol, tol, max_layers, smoother, dirs, tilt)
        if not missing.size:
            return LayeredMesh(nodes, orientation)
        # Splay the end nearest to the uncovered points further, or give up.
        near_a = np.hypot(*(cover[missing] - base[0]).T) < np.hypot(*(cover[missing] - base[-1]).T)
        grew = False
        for end, flag in ((0, near_a.any()), (1, (~near_a).any())):
            if flag and splay[end] < SPLAY_MAX_DEG:
                splay[end] = min(SPLAY_MAX_DEG, splay[end] + SPLAY_STEP_DEG)
                grew = True
        if not grew:
            k = int(missing[0])
            raise MeshError(
                f"upper point {k} at {np.round(cover[k], 6).tolist()} cannot be covered by the layered mesh "
                f"grown from the lower curve (end columns splayed to {SPLAY_MAX_DEG:g} degrees, "
                f"{max_layers} layers); it lies below the lower curve's end or behind it"
            )


def _respace(layer: np.ndarray, fractions: np.ndarray) -> np.ndarray:
    """Nodes moved along ``layer`` to the arc-length ``fractions`` (``(n,)``, those of the base)."""
    cum = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(layer, axis=0).T))))
    d = fractions * cum[-1]
    return np.column_stack((np.interp(d, cum, layer[:, 0]), np.interp(d, cum, layer[:, 1])))


def _offset_layer(below, height, orientation, start, end, fractions) -> np.ndarray:
    """The offset of ``below`` by ``height`` towards the section, swallowtails trimmed (shapely).

    The offset curve (rounded at convex corners, trimmed at concave ones)
    is joined to the layer's end nodes ``start`` and ``end`` and the nodes
    are spread along it at the base's arc-length ``fractions``.
    """
    curve = shapely.offset_curve(shapely.LineString(below), orientation * height, quad_segs=4, join_style="round")
    line = np.vstack((start, shapely.get_coordinates(curve), end))
    return _respace(line, fractions)


def _smooth_layer(below, raw, orientation, height, smoother, fractions):
    """Smoothed layers on ``raw``: the good one and the merely valid one (each None if there is none).

    The good one has the least weight whose strip keeps every corner
    Jacobian above ``MIN_RELATIVE_JACOBIAN`` of the nominal one; the valid
    one the least weight giving a strip with no inverted element. With
    ``fractions``, the smoothed nodes are first moved along the layer to the
    base's arc-length fractions.
    """
    fallback = None
    for lam in SMOOTHING_WEIGHTS:
        new = smoother(raw, lam)
        new[0], new[-1] = raw[0], raw[-1]
        if fractions is not None:
            new = _respace(new, fractions)
        jac, rel = _strip_quality(below, new, orientation, height)
        if jac > 1e-9 * height * height and shapely.LineString(new).is_simple:
            if rel >= MIN_RELATIVE_JACOBIAN:
                return new, new
            fallback = new if fallback is None else fallback
    return None, fallback


def _splay_taper(base: np.ndarray, splay: list, length: float):
    """Outward tilt of every column, radians, ``(n,)`` (positive towards B), or None without splay.

    The end columns' splay fades linearly to nothing over ``length`` (units)
    of the base from each end, so the columns fan out evenly instead of the
    splay being taken up by the few columns next to the end.
    """
    if not (splay[0] or splay[1]):
        return None
    s = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(base, axis=0).T))))
    fade_a = np.clip(1.0 - s / length, 0.0, 1.0)
    fade_b = np.clip(1.0 - (s[-1] - s) / length, 0.0, 1.0)
    return math.radians(splay[1]) * fade_b - math.radians(splay[0]) * fade_a


def _grow(base, height, orientation, cover, off_base, tol, max_layers, smoother, end_dirs, tilt=None):
    layers = [base]
    steps = np.hypot(*np.diff(base, axis=0).T)
    fractions = np.concatenate(([0.0], np.cumsum(steps))) / steps.sum()
    todo = np.flatnonzero(off_base)
    while todo.size and len(layers) <= max_layers:
        below = layers[-1]
        t, n = node_frames(below, orientation)
        if tilt is None:
            g = height * n
        else:  # splayed ends: every column leans out a little, the more the nearer the end
            g = height * (np.cos(tilt)[:, None] * n + np.sin(tilt)[:, None] * t)
        g[0], g[-1] = height * end_dirs[0], height * end_dirs[1]
        raw = below + g
        good, fallback = _smooth_layer(below, raw, orientation, height, smoother, None)
        if good is None:  # nodes crowding into a concave corner: the trimmed offset, nodes spread along it
            offset = _offset_layer(below, height, orientation, raw[0], raw[-1], fractions)
            good, fallback_offset = _smooth_layer(below, offset, orientation, height, smoother, fractions)
            fallback = fallback if fallback is not None else fallback_offset
        new = good if good is not None else fallback
        if new is None:
            if len(base) >= SCAN_MIN_POINTS and zigzag_fraction(base) > SCAN_ZIGZAG:  # a scan's noise, not a bend
                advice = (f"the lower curve is a noisy polyline ({len(base)} points, turning left and right at "
                          f"{100 * zigzag_fraction(base):.0f}% of them, as a scan does): simplify it within a small "
                          "tolerance (option simplify when reading the drawing)")
            else:
                advice = "the lower curve bends too sharply for this element size: lower options.element_size or smooth the lower curve"
            raise MeshError(
                f"layer {len(layers)} of the initial mesh folds over whatever the smoothing "
                f"(element height {height:.6g}); {advice}"
            )
        layers.append(new)
        todo = todo[~_in_strip(below, new, orientation, cover[todo], tol)]
    return np.stack(layers), todo
