"""Figures of a deformed assembly, one colour per body (matplotlib, extra ``[plot]``).

Three panels: (1) the initial assembly with every body's initial mesh,
(2) the final meshes on the deformed foundations, (3) the deformed bodies
over the initial ones, with each body's area and relative error.
"""

from __future__ import annotations

import numpy as np

from .assembly_result import AssemblyResult
from .plot import draw_mesh, new_figure

__all__ = ["draw_assembly"]


def _closed(points: np.ndarray) -> np.ndarray:
    return np.vstack((points, points[:1]))


def draw_assembly(result: AssemblyResult, fig=None):
    """Draw the three panels of an :class:`~sectiondeform.assembly_result.AssemblyResult`; returns the figure."""
    if fig is None:
        fig = new_figure(figsize=(11, 10), layout="constrained")
    axes = fig.subplots(3, 1, sharex=True, sharey=True)
    colours = [f"C{i % 10}" for i in range(len(result.bodies))]
    u = result.units
    for body in result.bodies:  # every initial body first, so none hides a deformed one
        axes[2].fill(*body.initial_contour.T, color="0.85")
    for body, c in zip(result.bodies, colours):
        draw_mesh(axes[0], body.initial_mesh, edgecolors=c, linewidths=0.3)
        axes[0].plot(*_closed(body.initial_contour).T, color=c, lw=1.2, label=body.name)
        draw_mesh(axes[1], body.final_mesh, edgecolors=c, linewidths=0.3)
        axes[1].plot(*_closed(body.contour).T, color=c, lw=1.2)
        axes[2].fill(*body.contour.T, color=c, alpha=0.6,
                     label=f"{body.name}: {body.area_final:.4g} {u}² (error {body.relative_error:+.1e})")
        axes[2].plot(*_closed(body.contour).T, color=c, lw=1.0)
    axes[0].set_title("1  initial assembly and meshes")
    axes[0].legend(loc="best", fontsize=8)
    axes[1].set_title(f"2  final meshes on the deformed foundations ({result.model} model)")
    axes[2].set_title("3  deformed bodies over the initial ones")
    axes[2].legend(loc="best", fontsize=8)
    for ax in axes:
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.grid(True, lw=0.3, alpha=0.5)
    fig.suptitle(f"{result.name}: {len(result.bodies)} bodies")
    return fig
