"""Where the paper's model may be far from the material, and results beyond what it can mean.

The paper's layered map is exact for a rigid motion and close to the
material for a section that sits on its lower curve and a target that bends
gently against the section's height. It drifts from the material (measured
against the finite-element reference, ``docs/validation.md``) when

* the section **overhangs** its base: the upper curve reaches beyond the
  lower curve's ends, so part of it hangs on virtual columns that follow no
  material (:func:`overhang`);
* the section is **thick against the bend** of the target: the support's
  change of shape is carried undamped through the whole height
  (:func:`bend_change`, for a straight lower curve the height over the
  target's radius of curvature).

* the law **changes the heights** by more than :data:`HEIGHT_CHANGE_LIMIT`
  beyond what the body's motion itself implies: the paper model puts the
  law's whole area change into the heights (its height scale ``k``), where
  the material also spreads it sideways at free walls and grooves and out
  of plane (the grooved tread). The part of ``k`` that a uniform map keeping
  the material gives (:func:`uniform_height_scale`: the support stretched
  along its length, a body of revolution moved away from its axis) is exact,
  not a distortion, and is not counted.

And its answer means little whatever the material when the height scale
``k``, the stretch of the elements along the layers or their final aspect
ratio leave the ranges of ``docs/method.md`` (:func:`stretch_range`,
:func:`aspect_change`).

Each check gives a figure; :func:`applicability_warnings` and
:func:`extent_warnings` turn the figures beyond their documented limits into
one-line warnings with the number. Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "overhang",
    "bend_change",
    "stretch_range",
    "aspect_change",
    "uniform_height_scale",
    "applicability_warnings",
    "extent_warnings",
    "OVERHANG_LIMIT",
    "BEND_LIMIT",
    "HEIGHT_SCALE_LIMITS",
    "HEIGHT_CHANGE_LIMIT",
    "STRETCH_LIMITS",
    "ASPECT_LIMIT",
    "extent_refusal",
]

#: Overhang beyond the lower curve's ends, over the section's height, above which the paper model is flagged.
OVERHANG_LIMIT = 0.25
#: Change of the support's turning over a stretch as long as the height, radians, above which it is flagged.
BEND_LIMIT = 0.45
#: Height scale ``k`` outside this range: the section is squeezed or stretched beyond the model's meaning.
HEIGHT_SCALE_LIMITS = (0.5, 2.0)
#: Largest change of the heights, |1 - k|, that the paper model carries without a warning: it puts the
#: law's whole area change into the heights, where the material also spreads it sideways (free walls,
#: grooves) and out of plane. Calibrated in docs/reliability.md: the grooved tread (k 0.85, 13 % of its
#: height from the reference) is flagged, the paper example (k 0.95, 5 %) is not.
HEIGHT_CHANGE_LIMIT = 0.1
#: Final over initial element edge length along the layers, outside this range.
STRETCH_LIMITS = (0.5, 2.0)
#: Largest change of an element's aspect ratio (along over across the layers), either way.
ASPECT_LIMIT = 4.0

HINT = 'the paper model may be far from the material; the hyperelastic model (option model at hyperelastic) follows it'
REFUSAL_FIX = 'refused: deform with the hyperelastic model (option model at hyperelastic), which follows the material'


def overhang(lower: np.ndarray, upper: np.ndarray) -> float:
    """How far the upper curve reaches beyond the lower curve's ends, along its end tangents, units.

    At each end, the distance of the upper points past the end along the
    lower curve's tangent there, pointing out of the curve; the larger of
    the two ends (0 for a section standing within its base).

    Parameters
    ----------
    lower : (n, 2) float64 ndarray
        Lower curve nodes, A to B, units.
    upper : (m, 2) float64 ndarray
        Upper characteristic points, B to A, units.

    Returns
    -------
    float
        Units.

    Examples
    --------
    >>> low = np.array([[0.0, 0.0], [2.0, 0.0]])
    >>> overhang(low, np.array([[2.0, 0.0], [3.0, 1.0], [-0.5, 1.0], [0.0, 0.0]]))
    1.0
    """
    out = 0.0
    for end, inner in ((lower[0], lower[1]), (lower[-1], lower[-2])):
        t = end - inner
        t = t / math.hypot(*t)
        out = max(out, float(((upper - end) @ t).max()))
    return out


def bend_change(lower: np.ndarray, target: np.ndarray, height: float) -> float:
    """Largest change of the support's turning over a stretch of it as long as the section's height, radians.

    The target's segment directions minus the lower curve's (both sampled at
    the same arc-length fractions) give how much the support turns the
    section's base at each place; its largest variation between two points
    of the lower curve at most ``height`` apart (along the curve) is the
    figure. A rigid motion gives 0; a straight lower curve bent into a
    circle of radius R gives ``height / R`` (or the whole arc's angle if the
    base is shorter than the height).

    Parameters
    ----------
    lower, target : (n, 2) float64 ndarray
        The lower curve's nodes and the target at the same fractions, units.
    height : float
        The section's height, units.

    Returns
    -------
    float
        Radians.

    Examples
    --------
    >>> s = np.linspace(0.0, 1.0, 101)
    >>> low = np.column_stack((10.0 * s, 0 * s))
    >>> arc = 20.0 * np.column_stack((np.sin(s / 2), 1 - np.cos(s / 2)))  # radius 20, length 10
    >>> round(bend_change(low, arc, 2.0), 2)                               # 2 / 20
    0.1
    """
    d, e = np.diff(lower, axis=0), np.diff(target, axis=0)
    # the turning of the target against the lower curve's, segment by segment: one angle per segment
    # (atan2 of the cross and dot products), summed from the first with jumps wrapped to (-pi, pi]
    raw = np.arctan2(d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0], d[:, 0] * e[:, 0] + d[:, 1] * e[:, 1])
    step = np.diff(raw)
    step -= 2.0 * np.pi * np.round(step / (2.0 * np.pi))
    delta = raw[0] + np.concatenate(([0.0], np.cumsum(step)))
    seg = np.hypot(d[:, 0], d[:, 1])
    mid = np.cumsum(seg) - 0.5 * seg
    length = float(seg.sum())
    if height >= length or len(delta) < 2:
        return float(np.ptp(delta))
    # Resample on a grid of height / 8 and take the spread over every 9 consecutive samples.
    grid = np.arange(0.0, length + height / 8.0, height / 8.0)
    values = np.interp(grid, mid, delta)
    windows = np.lib.stride_tricks.sliding_window_view(values, min(9, len(values)))
    return float(np.ptp(windows, axis=1).max())


def edges(nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mean edge length of each element of a layered grid along the layers and across them, ``(L, n - 1)`` each.

    Parameters
    ----------
    nodes : (L + 1, n, 2) float64 ndarray
        The layered mesh's nodes, units.
    """
    d = nodes[:, 1:] - nodes[:, :-1]
    along = np.sqrt(d[..., 0] ** 2 + d[..., 1] ** 2)  # (L + 1, n - 1)
    d = nodes[1:] - nodes[:-1]
    across = np.sqrt(d[..., 0] ** 2 + d[..., 1] ** 2)  # (L, n)
    return 0.5 * (along[:-1] + along[1:]), 0.5 * (across[:, :-1] + across[:, 1:])


_edges = edges


def stretch_range(initial: np.ndarray, final: np.ndarray) -> tuple[float, float]:
    """Smallest and largest final over initial element edge length along the layers.

    Parameters
    ----------
    initial, final : (L + 1, n, 2) float64 ndarray, or tuple of ndarray
        The layered mesh's nodes before and after placement, units, or their :func:`edges`.

    Returns
    -------
    tuple of float
        Dimensionless.

    Examples
    --------
    >>> g = np.stack(np.meshgrid([0.0, 1.0, 2.0], [0.0, 1.0]), axis=-1)   # (2, 3, 2)
    >>> stretch_range(g, g * [3.0, 1.0])
    (3.0, 3.0)
    """
    a0, _ = initial if isinstance(initial, tuple) else edges(initial)
    a1, _ = final if isinstance(final, tuple) else edges(final)
    ratio = a1 / np.where(a0 > 0, a0, np.inf)
    return float(ratio.min()), float(ratio.max())


def aspect_change(initial: np.ndarray, final: np.ndarray) -> float:
    """Largest change of an element's aspect ratio (along over across the layers), either way.

    For each element, its final aspect ratio over its initial one, or the
    inverse if smaller than 1: 1 for a mesh moved rigidly or scaled
    uniformly, 4 where an element was stretched twice along the layers and
    squeezed twice across them.

    Parameters
    ----------
    initial, final : (L + 1, n, 2) float64 ndarray, or tuple of ndarray
        The layered mesh's nodes before and after placement, units, or their :func:`edges`.

    Returns
    -------
    float
        Dimensionless, >= 1.

    Examples
    --------
    >>> g = np.stack(np.meshgrid([0.0, 1.0, 2.0], [0.0, 1.0]), axis=-1)
    >>> aspect_change(g, g * [2.0, 0.5])
    4.0
    """
    a0, c0 = initial if isinstance(initial, tuple) else edges(initial)
    a1, c1 = final if isinstance(final, tuple) else edges(final)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = (a1 * c0) / (a0 * c1)
    q = q[np.isfinite(q) & (q > 0)]
    return float(np.maximum(q, 1.0 / q).max()) if len(q) else 1.0


def uniform_height_scale(lower_length: float, target_length: float, density: float, final_density: float) -> float:
    """The height scale of a uniform map that follows the support and keeps the material.

    A body whose lower curve is stretched by ``s`` (target length over lower
    length) and whose heights all scale by ``k`` keeps its law's quantity
    when ``k s rho1 / rho0 = 1``, ``rho`` being the law's quantity per unit
    area of section (1 for an area; ``2 pi`` times the centroid's distance
    from the axis for a volume of revolution, Pappus). That share of the
    paper model's ``k`` is the motion's, exact for a uniform map (a ring of
    rubber moved away from its axis thins as the closed form says), not a
    distortion; the height-change warning measures ``k`` against it.

    Parameters
    ----------
    lower_length, target_length : float
        Lengths of the body's lower polyline and of its image, units (> 0).
    density, final_density : float
        The law's quantity over the area, of the initial and the final
        section: 1 for an area law, ``2 pi`` x centroid distance (units) for
        a volume law.

    Returns
    -------
    float
        Dimensionless, > 0.

    Examples
    --------
    >>> uniform_height_scale(10.0, 12.5, 1.0, 1.0)   # a plane body stretched 1.25 along its base
    0.8
    >>> round(uniform_height_scale(30.0, 30.0, 2 * math.pi * 105.0, 2 * math.pi * 133.92), 3)  # a ring moved out
    0.784
    """
    return lower_length / (target_length * final_density / density)


def applicability_warnings(height: float, overhang_length: float, bend: float, virtual_columns: tuple[int, int]) -> list[str]:
    """Warnings that the paper model may be far from the material, one per figure beyond its limit.

    Parameters
    ----------
    height : float
        The section's height above its lower curve, units.
    overhang_length : float
        :func:`overhang`, units.
    bend : float
        :func:`bend_change`, radians.
    virtual_columns : tuple of int
        Columns the layered mesh adds beyond A and beyond B.
    """
    out = []
    ratio = overhang_length / height
    columns = sum(virtual_columns)
    if ratio > OVERHANG_LIMIT or columns:
        extra = f", {columns} virtual columns beyond its ends" if columns else ""
        out.append(
            f"applicability: the section overhangs its lower curve by {ratio:.2f} x its height "
            f"(limit {OVERHANG_LIMIT:g}{extra}); {HINT}"
        )
    if bend > BEND_LIMIT:
        out.append(
            f"applicability: the target bends the base by {bend:.2f} rad over a stretch as long as the "
            f"section's height (limit {BEND_LIMIT:g}: the section is thick for this bend); {HINT}"
        )
    return out


def extent_refusal(height_scale: float, aspect: float) -> str | None:
    """Why a placement means nothing whatever the material, or None: the height scale or an element's aspect beyond its range.

    The layered map stays a map of the section only while its layers keep
    their heights within :data:`HEIGHT_SCALE_LIMITS` and its elements their
    shape within :data:`ASPECT_LIMIT` (``docs/method.md``); beyond, the model
    itself cannot say what its answer means, so the caller refuses it
    (:class:`~sectiondeform.errors.MeshError`) rather than warn.

    Parameters
    ----------
    height_scale : float
        The paper model's ``k``.
    aspect : float
        :func:`aspect_change`.
    """
    lo, hi = HEIGHT_SCALE_LIMITS
    if not lo <= height_scale <= hi:
        why = (f"height scale k = {height_scale:.3g}, outside [{lo:g}, {hi:g}]: the layers are "
               f"{'stretched' if height_scale > hi else 'squeezed'}")
    elif aspect > ASPECT_LIMIT:
        why = f"an element's aspect ratio changes {aspect:.3g}-fold (limit {ASPECT_LIMIT:g}): the layers are distorted"
    else:
        return None
    return f"result: {why} beyond what the paper model can mean; {REFUSAL_FIX}"


def extent_warnings(height_scale: float, stretch: tuple[float, float], aspect: float,
                    uniform_scale: float = 1.0) -> list[str]:
    """Warnings for a placement near the documented limits of the layered map (``docs/method.md``).

    What is beyond them is refused (:func:`extent_refusal`); these are the
    milder figures: the heights changed by more than
    :data:`HEIGHT_CHANGE_LIMIT` beyond the uniform map's share
    (``height_scale / uniform_scale``), elements stretched along the layers
    beyond :data:`STRETCH_LIMITS`.

    Parameters
    ----------
    height_scale : float
        The paper model's ``k``.
    stretch : tuple of float
        :func:`stretch_range`.
    aspect : float
        :func:`aspect_change` (unused: its limit is a refusal).
    uniform_scale : float
        :func:`uniform_height_scale`: the share of ``k`` the body's motion
        gives a uniform map (1: a body that keeps its base's length and,
        for a body of revolution, its distance from the axis).
    """
    out = []
    change = height_scale / uniform_scale - 1.0
    if abs(change) > HEIGHT_CHANGE_LIMIT:
        motion = "" if abs(uniform_scale - 1.0) < 1e-9 else \
            f" beyond the {uniform_scale:.3g} of a uniform map that follows the support"
        out.append(
            f"result: the heights change by {100.0 * change:+.3g} %{motion} (k = {height_scale:.3g}, limit "
            f"{100.0 * HEIGHT_CHANGE_LIMIT:g} %): the paper model puts the law's whole area change into the heights; {HINT}"
        )
    lo, hi = STRETCH_LIMITS
    if stretch[0] < lo or stretch[1] > hi:
        out.append(
            f"result: elements stretched by {stretch[0]:.3g} to {stretch[1]:.3g} along the layers, "
            f"outside [{lo:g}, {hi:g}]; check the target's length against the lower curve's"
        )
    return out
