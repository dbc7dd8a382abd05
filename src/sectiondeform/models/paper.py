"""The paper's model: a geometric final mesh on the target (paper §3.4-3.6).

Prepare (once per section): grow the layered initial mesh from the lower
curve (:func:`~sectiondeform.layers.grow_mesh`), locate the upper points in
it, and write every node as an offset ``(a, b)`` in the frame (tangent,
normal) of its column's base node.

Place (once per target): build the empty final mesh with the same layers
and columns on the target nodes, each node at ``T_j + k (a t'_j + b n'_j)``
in the target's frame, and put the upper points at their local coordinates.
The nodes and so the placed points are affine in the height scale ``k``; the
area of the deformed section (target + placed upper curve, shoelace) is
therefore a quadratic in ``k``, and its first moment about an axis of
revolution (the volume law, Pappus) a cubic, both solved in closed form
(:func:`scale_roots`; the law asks for its own polynomial,
:meth:`~sectiondeform.laws.Law.coefficients`): the law holds to rounding
error. Of several positive roots, the one nearest the expected scale that
leaves no inverted element is taken. With the target equal to the lower curve and ratio 1, ``k``
is 1 and every point comes back; a rigid motion of the target moves the
section rigidly.

Where the target bends so sharply that the straight frame lines would cross
(an inverted element), or converge so fast that no height scale reaches the
law's area, the target's normal field is smoothed, with growing weight,
before giving up with :class:`~sectiondeform.errors.MeshError` (or
:class:`~sectiondeform.errors.LawError`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..applicability import (
    applicability_warnings,
    aspect_change,
    bend_change,
    edges,
    extent_refusal,
    extent_warnings,
    overhang,
    stretch_range,
    uniform_height_scale,
)
from ..curves import polygon_area
from ..errors import CaseError, GeometryError, LawError, MeshError, SectionDeformError
from ..laws import Law, law_roots
from ..layers import (
    SMOOTHING_WEIGHTS,
    Smoother,
    corner_jacobians,
    extend_base,
    grow_mesh,
    node_frames,
    plan_extension,
)
from ..locate import Location, locate, locate_some
from ..section import Section
from ..stack import Stack, Target, renamed
from .base import FinalQuality, Info, MeshData, MeshQuality, Model, ModelOptions, Placed, Placement, Prepared

# Weights tried, in turn, on the target's normal field; the largest ones
# make it nearly linear along the target (fine meshes need them: the
# smoothing length grows as the fourth root of the weight, in nodes).
TARGET_SMOOTHING = (0.0,) + SMOOTHING_WEIGHTS + (5e6, 5e7, 5e8, 5e9, 5e10)

__all__ = ["PaperModel", "PaperPrepared", "PaperSection", "PaperOptions", "PaperInfo", "MODEL", "scale_roots"]

DENSE_MAP_MAX = 2**21  # entries of each (upper points x columns) placement matrix kept dense


def scale_roots(coefficients, wanted: float, guess: float) -> list[float]:
    """The positive real ``k`` where a polynomial of degree <= 3 takes the value ``wanted``, nearest ``guess`` first.

    A law's quantity of the placed section is a polynomial in the height
    scale ``k`` (:meth:`~sectiondeform.laws.Law.coefficients`): a quadratic
    for the area, a cubic for a volume of revolution
    (:func:`~sectiondeform.laws.law_roots`).

    ``coefficients`` and ``wanted`` are those of
    :func:`~sectiondeform.laws.law_roots`; ``guess`` is the expected ``k``.
    Returns the positive roots, nearest ``guess`` first (empty when none).

    Examples
    --------
    >>> scale_roots([0.0, 0.0, 0.0, 1.0], 8.0, 1.0)  # k³ = 8
    [2.0]
    >>> [round(k, 12) for k in scale_roots([0.0, 3.0, -1.0], 2.0, 1.2)]  # 3k - k² = 2: k = 1 or 2
    [1.0, 2.0]
    """
    return sorted((r for r in law_roots(coefficients, wanted) if r > 0), key=lambda r: abs(r - guess))


def _column_matrix(weights: np.ndarray, columns: np.ndarray, n: int) -> np.ndarray:
    """``(p, n)`` matrix whose row p sums ``weights[p]`` ``(p, 4)`` into the ``columns[p]`` of its corners."""
    out = np.zeros((len(weights), n))
    np.add.at(out, (np.arange(len(weights))[:, None], columns), weights)
    return out


def _hole_location(mesh, section: Section, upper: Location) -> Location:
    """``upper`` followed by the location of every hole's points (each one located, else refused), 8 weights a row."""
    if not section.holes:
        return upper
    pts = np.concatenate(section.holes)
    loc = locate(mesh.points, mesh.quads, pts)
    nodes = np.concatenate((loc.nodes, loc.nodes), axis=1)
    weights = np.concatenate((loc.weights, np.zeros_like(loc.weights)), axis=1)
    return Location(np.concatenate((upper.elements, loc.elements)), np.concatenate((upper.local, loc.local)),
                    np.concatenate((upper.nodes, nodes)), np.concatenate((upper.weights, weights)))


def _upper_location(mesh, section: Section) -> Location:
    """Where every upper point sits in the layered mesh, as bilinear weights of mesh nodes.

    The mesh is grown to cover the characteristic points; a point put between
    two of them (:func:`~sectiondeform.section.densified`) that the mesh
    does not reach (a top spanning a hollow of the lower curve, above the
    layers that the corners need) is placed on the chord between the nearest
    points located on either side: its weights are theirs, in proportion.
    The rows have 8 weights (4 zero for a located point).
    """
    upper = np.asarray(section.upper)
    ch = section.characteristic_index
    found_loc, found = locate_some(mesh.points, mesh.quads, upper)
    if not found[ch].all():  # a characteristic point the mesh misses: the refusal names it
        locate(mesh.points, mesh.quads, upper[ch])
    p = len(upper)
    nodes = np.zeros((p, 8), dtype=np.int64)
    weights = np.zeros((p, 8))
    elements = np.full(p, -1, dtype=np.int64)
    local = np.zeros((p, 2))
    nodes[found, :4] = nodes[found, 4:] = found_loc.nodes
    weights[found, :4] = found_loc.weights
    elements[found], local[found] = found_loc.elements, found_loc.local
    missing = np.flatnonzero(~found)
    if missing.size:
        idx = np.flatnonzero(found)
        before = idx[np.searchsorted(idx, missing) - 1]
        after = idx[np.searchsorted(idx, missing)]
        cum = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(upper, axis=0).T))))
        t = ((cum[missing] - cum[before]) / (cum[after] - cum[before]))[:, None]
        nodes[missing, :4], nodes[missing, 4:] = nodes[before, :4], nodes[after, :4]
        weights[missing, :4], weights[missing, 4:] = (1.0 - t) * weights[before, :4], t * weights[after, :4]
    return Location(elements, local, nodes, weights)


def _frames_from_normals(normals: np.ndarray, orientation: int) -> tuple[np.ndarray, np.ndarray]:
    n = normals / np.hypot(normals[:, 0], normals[:, 1])[:, None]
    t = orientation * np.column_stack((n[:, 1], -n[:, 0]))
    return t, n


class PaperSection:
    """One body's section ready for the paper's model: initial mesh, locations, frame offsets."""

    def __init__(self, section: Section):
        self.section = section
        self._lower_polyline_length = float(np.hypot(*np.diff(section.lower, axis=0).T).sum())
        size = section.size
        h = section.element_size
        characteristic = np.concatenate((section.upper[section.characteristic_index], *section.holes))
        self.extension = plan_extension(section.lower, section.orientation, characteristic, h)
        base = extend_base(section.lower, *self.extension)
        mesh = grow_mesh(base, h, section.orientation, characteristic, tol=1e-9 * size)
        self.mesh = mesh
        self.quads = mesh.quads
        self.location = _hole_location(mesh, section, _upper_location(mesh, section))
        self._hole_slices = np.cumsum([len(section.upper)] + [len(h) for h in section.holes])
        nodes = mesh.nodes
        t0, n0 = node_frames(nodes[0], section.orientation)
        rel = nodes - nodes[0][None]
        self.a = np.einsum("ijd,jd->ij", rel, t0)
        self.b = np.einsum("ijd,jd->ij", rel, n0)
        self._a3, self._b3 = self.a[..., None], self.b[..., None]
        n = nodes.shape[1]
        self.columns = self.location.nodes % n
        # The upper points are linear in the target's nodes and frames:
        # fixed_up = W T, moving_up = A t + B n, with (m, n) matrices of the
        # bilinear weights (times the nodes' frame offsets) summed by column.
        w, corners = self.location.weights, self.location.nodes
        self._weights = (w, w * self.a.ravel()[corners], w * self.b.ravel()[corners])
        dense = len(w) * n <= DENSE_MAP_MAX
        self._maps = tuple(_column_matrix(c, self.columns, n) for c in self._weights) if dense else None
        self._smoother = Smoother(n, end_weight=1.0)
        jac = mesh.jacobians()
        self.initial_mesh = MeshData(mesh.points, mesh.quads, "quad", (mesh.n_layers, mesh.n_columns))
        self.quality = MeshQuality(
            elements=int(len(mesh.quads)),
            element_size=float(section.element_size),
            jacobian_min=float(jac.min()),
            jacobian_max=float(jac.max()),
            layers=int(mesh.n_layers),
            columns=int(mesh.n_columns),
            virtual_columns=(len(self.extension[0]), len(self.extension[1])),
        )
        self.height = section.height
        self.overhang = overhang(section.lower, section.upper)
        self.edges = edges(self.mesh.nodes)  # the initial elements' edge lengths, for the extent figures

    def extended_target(self, target_nodes: np.ndarray) -> np.ndarray:
        """The target nodes with the virtual base nodes beyond A' and B', ``(n + p + q, 2)``.

        Virtual nodes prolong the target along its end tangents, at the
        initial distances times the target's stretch (its length over the
        lower curve's).
        """
        before, after = self.extension
        if not len(before) and not len(after):
            return target_nodes
        stretch = np.hypot(*np.diff(target_nodes, axis=0).T).sum() / self._lower_polyline_length
        return extend_base(target_nodes, before * stretch, after * stretch)

    def _nodes(self, target_nodes: np.ndarray, t: np.ndarray, n: np.ndarray, k: float) -> np.ndarray:
        """Final node coordinates ``T_j + k (a t_j + b n_j)``, ``(L + 1, n, 2)``."""
        return target_nodes + k * (self._a3 * t + self._b3 * n)

    def _map(self, i: int, x: np.ndarray) -> np.ndarray:
        """Map ``i`` (0: W, 1: A, 2: B) applied to per-column values ``x`` ``(n, 2)``: ``(m, 2)``."""
        if self._maps is not None:
            return self._maps[i] @ x
        return np.einsum("pk,pkd->pd", self._weights[i], x[self.columns])

    def _moving_up(self, t: np.ndarray, n: np.ndarray) -> np.ndarray:
        """Upper points' offsets from the target for a unit height scale, ``(m, 2)``."""
        return self._map(1, t) + self._map(2, n)

    def place(self, target_nodes: np.ndarray, law: Law, initial: float) -> Placement:
        """Build the final mesh on ``target_nodes`` ((n, 2), units) and solve the law's height scale.

        ``initial`` is the law's quantity of the body's curves, signed
        (:meth:`~sectiondeform.stack.Stack.initial_quantity`): the placed
        contour meets ``law.target(initial)``.
        """
        sec = self.section
        wanted = law.target(initial)
        real = target_nodes
        target_nodes = self.extended_target(real)
        t, n = node_frames(target_nodes, sec.orientation)
        steps = real[1:] - real[:-1]
        lengths = np.hypot(steps[:, 0], steps[:, 1]).sum()
        guess = wanted / initial * sec.lower_length / lengths
        fixed_all = self._map(0, target_nodes)
        fixed_up, *fixed_holes = np.split(fixed_all, self._hole_slices)[:-1] if sec.holes else (fixed_all,)
        fixed = np.concatenate((real, fixed_up[1:-1]))
        zeros = np.zeros_like(real)
        smoothing = 0.0
        law_error, jac = None, None
        for lam in TARGET_SMOOTHING:
            if lam:
                t, n = _frames_from_normals(self._smoother(n, lam), sec.orientation)
            moving_all = self._moving_up(t, n)
            moving_up, *moving_holes = np.split(moving_all, self._hole_slices)[:-1] if sec.holes else (moving_all,)
            moving = np.concatenate((zeros, moving_up[1:-1]))
            coefficients = law.coefficients(fixed, moving)
            for hf, hm in zip(fixed_holes, moving_holes):  # oriented against the contour: their quantity comes off
                coefficients = coefficients + law.coefficients(hf, hm)
            roots = scale_roots(coefficients, wanted, guess)
            if not roots:  # converging normals cap the reachable quantity: smooth them more
                law_error = LawError(
                    f"law: no height scale gives the {law.measure} {abs(wanted):.6g}; the target cannot carry "
                    f"this section under this law (check the target's direction and the {law.key})"
                )
                continue
            for k in roots:  # the nearest root that leaves no inverted element
                nodes = self._nodes(target_nodes, t, n, k)
                jac = corner_jacobians(nodes[..., 0], nodes[..., 1], sec.orientation)
                jac_min = float(np.minimum(np.minimum(jac[0], jac[1]), np.minimum(jac[2], jac[3])).min())
                if jac_min > 0:
                    break
            if jac_min > 0:
                smoothing = lam
                break
        else:
            if jac is None:
                raise law_error
            e = int(np.argmin(np.minimum.reduce(jac).ravel()))
            cols = self.mesh.n_columns
            raise MeshError(
                f"target: the final mesh has an inverted element (layer {e // cols}, column {e % cols}) "
                "even with its normals smoothed; the target bends too sharply for this section's thickness "
                '(the hyperelastic model, option model at hyperelastic, follows the material instead of the normals)'
            )
        upper = fixed_up + k * moving_up
        upper[0], upper[-1] = real[-1], real[0]
        holes = tuple(hf + k * hm for hf, hm in zip(fixed_holes, moving_holes))
        final = MeshData(nodes.reshape(-1, 2), self.quads, "quad", self.initial_mesh.shape)
        jac_max = float(np.maximum(np.maximum(jac[0], jac[1]), np.maximum(jac[2], jac[3])).max())
        final_area = polygon_area(np.concatenate((real, upper[1:-1])))
        info = PaperInfo(
            height_scale=float(k),
            uniform_height_scale=uniform_height_scale(sec.lower_length, lengths, abs(initial / sec.area),
                                                      abs(wanted / final_area)),
            normal_smoothing=float(smoothing),
            bend_change=bend_change(sec.lower, real, self.height),
            overhang=self.overhang / self.height,
            stretch_min=(stretch := stretch_range(self.edges, final_edges := edges(nodes)))[0],
            stretch_max=stretch[1],
            aspect_change=aspect_change(self.edges, final_edges),
        )
        refusal = extent_refusal(info.height_scale, info.aspect_change)
        if refusal:
            raise MeshError(refusal)
        warnings = self.warnings(info)
        if law.growth is not None and law.measure == "area":
            warnings.append(f"law: the growth {law.growth:g} of an extruded body is met geometrically: the paper model scales "
                            f"the section's area by {law.growth:g}^(2/3), a free body's growth; a bonded body's follows its "
                            'mechanics (option model at hyperelastic)')
        return Placement(
            upper=upper,
            final_mesh=final,
            quality=FinalQuality(jacobian_min=jac_min, jacobian_max=jac_max),
            info=info,
            warnings=tuple(warnings),
            holes=holes,
        )

    def warnings(self, info: PaperInfo) -> list[str]:
        """The applicability and extent warnings of one placement (:mod:`sectiondeform.applicability`)."""
        return applicability_warnings(self.height, self.overhang, info.bend_change, self.quality.virtual_columns) + \
            extent_warnings(info.height_scale, (info.stretch_min, info.stretch_max), info.aspect_change,
                            info.uniform_height_scale)


@dataclass(frozen=True)
class PaperOptions(ModelOptions):
    """The paper model reads no options of its own (the common ones shape its mesh)."""


@dataclass(frozen=True)
class PaperInfo(Info):
    """Figures of one paper placement.

    Attributes
    ----------
    height_scale : float
        The scale ``k`` of the nodes' offsets that meets the law.
    uniform_height_scale : float
        The height scale a uniform map following the support would give
        (:func:`~sectiondeform.applicability.uniform_height_scale`): the
        motion's share of ``k``.
    normal_smoothing : float
        Weight of the smoothing applied to the target's normals (0: none).
    bend_change : float, optional
        Largest change of the support's turning over a stretch as long as
        the section's height, radians (:func:`~sectiondeform.applicability.bend_change`).
    overhang : float, optional
        Reach of the upper curve beyond the lower curve's ends, over the
        section's height (:func:`~sectiondeform.applicability.overhang`).
    stretch_min, stretch_max : float, optional
        Range of final over initial element edge length along the layers.
    aspect_change : float, optional
        Largest change of an element's aspect ratio, either way.
    """

    height_scale: float
    uniform_height_scale: float = 1.0
    normal_smoothing: float = 0.0
    bend_change: float | None = None
    overhang: float | None = None
    stretch_min: float | None = None
    stretch_max: float | None = None
    aspect_change: float | None = None


class PaperPrepared(Prepared):
    """Every body of a problem ready for the paper's model, placed from the support up.

    Each body's lower nodes go where their sources send them (the target at
    their support fractions; a foundation's image of the point they rest
    on), then the body's own placement meets its own law. A point of a
    shared piece therefore has one image, the same for both bodies, bit for
    bit.
    """

    def __init__(self, stack: Stack):
        self.stack = stack
        problem = stack.problem
        bodies = [None] * len(stack.bodies)
        for b in stack.layout.order:
            try:
                bodies[b] = PaperSection(stack.bodies[b].section)
            except SectionDeformError as exc:
                raise renamed(exc, problem.label(b)) from None
        self.bodies = tuple(bodies)

    def place(self, target: Target, laws: tuple, start=None, travels=None) -> Placed:
        """Place every body from the support up (``start`` is ignored: the placement is closed-form; the model takes no
        rigid parts, so ``travels`` is None).
        """
        stack = self.stack
        n = len(self.bodies)
        lowers, images, placements = [None] * n, [None] * n, [None] * n
        for b in stack.layout.order:
            fixed = stack.fixed_parts[b]
            nodes = np.empty((len(stack.bodies[b].source), 2))
            nodes[fixed["support_nodes"]] = target.nodes[fixed["support_index"]]
            for j, on, where in fixed["on_foundations"]:
                nodes[on] = images[j][where]
            try:
                with np.errstate(all="ignore"):
                    placement = self.bodies[b].place(nodes, laws[b], stack.initial_quantity(b, laws[b]))
            except (MeshError, LawError, GeometryError) as exc:
                raise renamed(exc, stack.problem.label(b)) from exc
            lowers[b], images[b], placements[b] = nodes, placement.upper, placement
        return Placed(lowers, images, placements)


class PaperModel(Model):
    """The paper's geometric method."""

    name = "paper"
    options_type = PaperOptions

    def prepare(self, stack: Stack, options: PaperOptions | None = None) -> PaperPrepared:
        if stack.problem.rigid:
            raise CaseError("rigid", 'the paper model has no mechanics for rigid parts in contact; use option model at hyperelastic')
        return PaperPrepared(stack)


MODEL = PaperModel()
