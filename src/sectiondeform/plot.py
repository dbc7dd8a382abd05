"""Figures in the spirit of the paper's Figure 11 (matplotlib, extra ``[plot]``), for one body or several.

Four panels: (1) each body with its lower and upper curves, (2) the
initial meshes, (3) the final meshes on the target (and on the deformed
foundations), (4) the deformed bodies over the initial ones, with the
areas written on them. One body is drawn in the paper's colours, several
in one colour each; a revolution axis is drawn where it lies near. A
body's holes are drawn as what they are, the inside of the body: outlined,
never filled (:func:`body_path`), before and after.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from .errors import require
from .io import check_figure_path
from .models.base import MeshData
from .result import RESULT_V1

__all__ = ["save_figure", "write_figure", "draw_result", "draw_mesh", "new_figure", "body_colours", "body_path",
           "PAPER_COLOURS"]

def new_figure(**kw):
    """A matplotlib figure of its own (not pyplot's), so the user's backend is left alone.

    Keywords go to :class:`matplotlib.figure.Figure` (``figsize``, ``layout``...).
    """
    require("matplotlib", "plot", "drawing a figure")
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(**kw)
    FigureCanvasAgg(fig)
    return fig


def draw_mesh(ax, mesh: MeshData, **style) -> None:
    """Draw a mesh's element edges on a matplotlib axes."""
    from matplotlib.collections import PolyCollection

    corners = {"quad": 4, "quad8": 4, "triangle": 3, "triangle6": 3}.get(mesh.kind, mesh.cells.shape[1])
    polys = mesh.points[mesh.cells[:, :corners]]
    kw = {"facecolors": "none", "edgecolors": "0.55", "linewidths": 0.4}
    kw.update(style)
    ax.add_collection(PolyCollection(polys, **kw))


def _closed(points: np.ndarray) -> np.ndarray:
    return np.vstack((points, points[:1]))


def body_path(contour: np.ndarray, holes=()):
    """A body as a matplotlib path: its contour, and its holes run the other way, so a fill leaves them empty.

    Parameters
    ----------
    contour : (N, 2) float64 ndarray
        The body's contour, closed (the first point not repeated), units.
    holes : sequence of (k, 2) float64 ndarray
        Its holes, the same way.

    Returns
    -------
    matplotlib.path.Path
        One closed subpath per ring: a fill (nonzero winding, as
        :class:`~matplotlib.patches.PathPatch` draws) covers the body less
        its holes; a clip path clips to it.
    """
    from matplotlib.path import Path

    from .section import polygon_area

    sign = np.sign(polygon_area(np.asarray(contour)))
    rings = [np.asarray(contour)] + [np.asarray(h) if np.sign(polygon_area(np.asarray(h))) != sign else np.asarray(h)[::-1]
                                     for h in holes]
    codes = np.concatenate([[Path.MOVETO] + [Path.LINETO] * (len(r) - 1) + [Path.CLOSEPOLY] for r in rings])
    return Path(np.concatenate([_closed(r) for r in rings]), codes.astype(Path.code_type))


def _fill(ax, contour: np.ndarray, holes, **style) -> None:
    """Fill a body less its holes (:func:`body_path`)."""
    from matplotlib.patches import PathPatch

    ax.add_patch(PathPatch(body_path(contour, holes), **{"edgecolor": "none", **style}))


def _outline(ax, contour: np.ndarray, holes, **style) -> None:
    """Draw a body's contour and its holes' outlines."""
    for ring in (contour, *holes):
        ax.plot(*_closed(np.asarray(ring)).T, **style)


PAPER_COLOURS = {"lower": "tab:blue", "upper": "tab:red", "target": "tab:green", "outline": "k", "initial_mesh": "0.55",
                 "mesh": "tab:green",
                 "deformed": "tab:orange"}
"""The colours of the paper's one body (``section-result/1``), by role, as in its Figure 11."""


def body_colours(result) -> list[dict]:
    """The colour of each role (:data:`PAPER_COLOURS`' keys) for each body of ``result``.

    The one body of a ``section-result/1`` result is drawn in the paper's
    colours (:data:`PAPER_COLOURS`); otherwise each body in a colour of its
    own (``C0``, ``C1``...) for every role.
    """
    if result.dialect == RESULT_V1:
        return [PAPER_COLOURS]
    return [dict.fromkeys(PAPER_COLOURS, f"C{i % 10}") for i in range(len(result.bodies))]


def _named(result, body) -> str:
    """``"name: "`` before a body's legend entries; empty for the one body of a ``section-result/1`` result."""
    return "" if result.dialect == RESULT_V1 else f"{body.name}: "


def _deformed_label(result, body) -> str:
    """Legend of a deformed body: its area, or its volume of revolution, and (named bodies) the law's error."""
    u = result.units
    named = _named(result, body)
    text = f"{named}deformed {body.area_final:.1f} {u}²"
    if body.volume_final is not None:
        text += f", volume {body.volume_final:.5g} {u}³"
    if named:
        text += f" ({body.measure} error {body.relative_error:+.1e})"
    return text


def _target_title(result) -> str:
    """The last panel's legend title: the bodies' total target (area, or volume) and the worst relative error."""
    u = result.units
    areas = all(b.measure == "area" for b in result.bodies)
    total = sum(b.target for b in result.bodies)
    unit = f"{u}²" if areas else f"{u}³ (volume)" if all(b.measure == "volume" for b in result.bodies) else None
    target = f"target {total:.1f} {unit}, " if unit is not None else ""
    return f"{target}error {result.relative_error:+.1e}"


def _suptitle(result) -> str:
    """The figure's title: each body's law ratio (its final over initial area, or volume), up to four bodies."""
    if len(result.bodies) > 4:
        return f"{result.name}: {len(result.bodies)} bodies"
    ratios = ", ".join(f"{_named(result, b)}{b.measure} ratio {b.target / _initial(b):.4g}" for b in result.bodies)
    return f"{result.name}: {ratios}"


def _initial(body) -> float:
    return body.area_initial if body.measure == "area" else body.volume_initial


def _curve_labels(result, body) -> tuple:
    """Legend of the first panel's lower, upper and deformed lower curves: the paper's, or one entry per named body."""
    if result.dialect == RESULT_V1:
        return "lower curve (BC)", "upper curve", "deformed BC (target)"
    return f"{body.name} (dashed: deformed lower curve)", None, None


def _draw_axis(axes, axis, points: np.ndarray, u: str) -> str:
    """Draw the revolution axis (dash-dot, every panel) if near ``points`` (N, 2); else return a line naming it."""
    p0, p1 = np.asarray(axis, dtype=np.float64)
    along = (p1 - p0) / np.hypot(*(p1 - p0))
    normal = np.array([-along[1], along[0]])
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, size = (lo + hi) / 2, float(np.hypot(*(hi - lo)))
    dist = float(np.dot(centre - p0, normal))
    if abs(dist) <= 0.75 * size:
        for ax in axes:
            ax.axline(p0, p1, color="k", ls="-.", lw=0.8, label="axis of revolution")
            ax.update_datalim([centre - dist * normal])
        return ""
    pts = ", ".join(f"({x:.4g}, {y:.4g})" for x, y in (p0, p1))
    return f"\nrevolution axis through {pts}, {abs(dist):.4g} {u} from the bodies' centre (not drawn)"


def _mesh_shape(result) -> str:
    """`` (the initial mesh described)`` for the paper's one body; each named body's element count otherwise."""
    if result.dialect != RESULT_V1:
        return " (" + ", ".join(f"{b.name} {len(b.initial_mesh.cells)}" for b in result.bodies) + " elements)"
    quality = result.bodies[0].quality
    return f" ({quality.initial.describe()})" if quality is not None else ""


def draw_result(result, fig=None):
    """Draw the four panels of a :class:`~sectiondeform.result.Result`, one colour per body; returns the figure.

    (1) each body's lower and upper curves and its deformed lower curve (on
    the target or on its deformed foundations), (2) the initial meshes,
    (3) the final meshes, (4) the deformed bodies over the initial ones with
    their areas (and volumes of revolution). A revolution axis is drawn
    (dash-dot) where it lies near the bodies; farther away, the title names
    it. One body is drawn in the paper's colours (:func:`body_colours`).
    """
    if fig is None:
        fig = new_figure(figsize=(11, 8), layout="constrained")
    axes = fig.subplots(2, 2, sharex=True, sharey=True).ravel()
    u = result.units
    bodies = result.bodies
    for body in bodies:  # every initial body first, so none hides a deformed one
        _fill(axes[3], body.initial_contour, body.initial_holes, facecolor="0.85")
    area0 = sum(b.area_initial for b in bodies)
    axes[3].fill([], [], color="0.85", label=f"initial  {area0:.1f} {u}²")
    for body, c in zip(bodies, body_colours(result)):
        labels = _curve_labels(result, body)
        axes[0].plot(*body.initial_lower.T, color=c["lower"], lw=2, label=labels[0])
        axes[0].plot(*body.initial_upper.T, color=c["upper"], lw=1.5, label=labels[1])
        axes[0].plot(*body.initial_upper.T, ".", color=c["upper"], ms=2)
        axes[0].plot(*body.lower.T, "--", color=c["target"], lw=1.2, label=labels[2])
        for hole in body.initial_holes:
            axes[0].plot(*_closed(hole).T, color=c["upper"], lw=1.5)
        draw_mesh(axes[1], body.initial_mesh, edgecolors=c["initial_mesh"])
        _outline(axes[1], body.initial_contour, body.initial_holes, color=c["outline"], lw=1.2)
        draw_mesh(axes[2], body.final_mesh, edgecolors=c["mesh"])
        axes[2].plot(*body.lower.T, color=c["target"], lw=2)
        _fill(axes[3], body.contour, body.holes, facecolor=c["deformed"], alpha=0.6, label=_deformed_label(result, body))
        _outline(axes[3], body.contour, body.holes, color=c["deformed"], lw=1.2)
    draw_rigid(axes[2:], result)
    note = ""
    if result.axis is not None:
        points = np.concatenate([np.concatenate((b.initial_contour, b.contour)) for b in bodies])
        note = _draw_axis(axes, result.axis, points, u)
    axes[0].set_title("1  section: lower and upper curves")
    axes[0].legend(loc="best", fontsize=8)
    axes[1].set_title(f"2  initial mesh{_mesh_shape(result)}")
    axes[2].set_title(f"3  final mesh on the deformed BC ({result.model} model)")
    axes[3].set_title("4  deformed section over the initial one")
    # Below the panel: over it, the legend covered the bodies (the fills leave it no empty corner).
    axes[3].legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), fontsize=8, title=_target_title(result),
                   title_fontsize=8)
    for ax in axes:
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.grid(True, lw=0.3, alpha=0.5)
    fig.suptitle(_suptitle(result) + note)
    return fig


def draw_rigid(axes, result) -> None:
    """Each rigid part where it ends (grey, hatched) and the contact pressure along the contact (coloured points)."""
    if not result.rigid:
        return
    top = max(part.pressure_max for part in result.rigid) or 1.0
    for part in result.rigid:
        ring = _closed(part.outline)
        for ax in axes:
            ax.fill(*ring.T, facecolor="0.6", edgecolor="0.3", hatch="//", alpha=0.5, lw=0.8)
        p = part.pressure
        if len(p):
            axes[-1].scatter(p[:, 0], p[:, 1], c=p[:, 2], cmap="inferno", vmin=0.0, vmax=top, s=10, zorder=5,
                             label=f"{part.name}: pressure max {part.pressure_max:.3g}, contact {part.length:.3g} {result.units}")


def draw_load_deflection(result, fig=None):
    """The load–deflection curve of a result with rigid parts: the size of each part's force against the load fraction."""
    if fig is None:
        fig = new_figure(figsize=(6, 4), layout="constrained")
    ax = fig.subplots()
    travel = np.array([s.travel for s in result.history])
    sizes = {name: np.hypot(*np.array([s.forces[name] for s in result.history]).T)
             for name in [part.name for part in result.rigid] + ["support"]}
    support = sizes.pop("support")
    for name, size in sizes.items():
        ax.plot(travel, size, "o-", ms=3, zorder=2, label=name)
    # The support dashed over open marks: a part alone carries the same force, and its curve would hide the part's.
    atol = 1e-9 * float(support.max(initial=0.0))
    same = any(np.allclose(support, size, rtol=1e-4, atol=atol) for size in sizes.values())
    ax.plot(travel, support, "o--", ms=6, mfc="none", zorder=3,
            label="support (the same size as the part's)" if same else "support")
    from .result import contact_units

    force = contact_units(result.units, result.axis is not None)["force"]
    ax.set_xlabel("fraction of the travel")
    ax.set_ylabel(f"size of the force ({force}{', the whole ring' if result.axis is not None else ''})")
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(fontsize=8)
    ax.set_title(f"{result.name}: load–deflection")
    return fig


def write_figure(fig, path) -> Path:
    """Write a matplotlib figure to ``path`` (.png, .svg or .pdf) atomically, then close it.

    Raises
    ------
    CaseError
        If the extension is not one of .png, .svg, .pdf or the folder does not exist.
    """
    from .io.json import atomic_write

    path = check_figure_path(path)
    try:
        atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=130, format=path.suffix[1:].lower()))
    finally:
        if fig.canvas.manager is not None:  # a pyplot figure of the caller's: pyplot forgets it
            sys.modules["matplotlib.pyplot"].close(fig)
    return path


def save_figure(result, path) -> Path:
    """Draw a result (:func:`draw_result`) and write it to ``path`` (.png, .svg or .pdf), atomically.

    Raises
    ------
    CaseError
        If the extension is not one of .png, .svg, .pdf or the folder does not exist.
    MissingExtraError
        If matplotlib is not installed (``pip install 'sectiondeform[plot]'``).
    """
    check_figure_path(path)
    return write_figure(draw_result(result), path)
