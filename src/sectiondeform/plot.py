"""Figures in the spirit of the paper's Figure 11 (matplotlib, extra ``[plot]``).

Four panels: (1) the section with its lower and upper curves, (2) the
initial mesh, (3) the empty final mesh on the target, (4) the deformed
section over the initial one, with the areas written on it.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from .errors import require
from .io import check_figure_path
from .models.base import MeshData

__all__ = ["save_figure", "write_figure", "draw_result", "draw_mesh", "new_figure"]



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


def draw_result(result, fig=None):
    """Draw the four panels of a :class:`~sectiondeform.result.Result`; returns the figure."""
    if fig is None:
        fig = new_figure(figsize=(11, 8), layout="constrained")
    axes = fig.subplots(2, 2, sharex=True, sharey=True).ravel()
    u = result.units
    low0, up0, low1 = result.initial_lower, result.initial_upper, result.lower

    ax = axes[0]
    ax.plot(*low0.T, color="tab:blue", lw=2, label="lower curve (BC)")
    ax.plot(*up0.T, color="tab:red", lw=1.5, label="upper curve")
    ax.plot(*up0.T, ".", color="tab:red", ms=2)
    ax.plot(*low1.T, "--", color="tab:green", lw=1.2, label="deformed BC (target)")
    ax.set_title("1  section: lower and upper curves")
    ax.legend(loc="best", fontsize=8)

    ax = axes[1]
    draw_mesh(ax, result.initial_mesh)
    ax.plot(*_closed(result.initial_contour).T, color="k", lw=1.2)
    shape = f" ({result.quality.initial.describe()})" if result.quality is not None else ""
    ax.set_title(f"2  initial mesh{shape}")

    ax = axes[2]
    draw_mesh(ax, result.final_mesh, edgecolors="tab:green")
    ax.plot(*low1.T, color="tab:green", lw=2)
    ax.set_title(f"3  final mesh on the deformed BC ({result.model} model)")

    ax = axes[3]
    ax.fill(*result.initial_contour.T, color="0.85", label=f"initial  {result.area_initial:.1f} {u}²")
    ax.fill(*result.contour.T, color="tab:orange", alpha=0.6, label=f"deformed {result.area_final:.1f} {u}²")
    ax.plot(*_closed(result.contour).T, color="tab:orange", lw=1.2)
    ax.set_title("4  deformed section over the initial one")
    ax.legend(loc="best", fontsize=8, title=f"target {result.area_target:.1f} {u}², error {result.relative_error:+.1e}",
              title_fontsize=8)
    for ax in axes:
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.grid(True, lw=0.3, alpha=0.5)
    fig.suptitle(f"{result.name}: area ratio {result.area_target / result.area_initial:.4g}")
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
    if hasattr(result, "bodies"):  # an assembly's result
        from .assembly_plot import draw_assembly

        return write_figure(draw_assembly(result), path)
    return write_figure(draw_result(result), path)
