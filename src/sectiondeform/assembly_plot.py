"""Figures of a deformed assembly, one colour per body (matplotlib, extra ``[plot]``).

Three panels: (1) the initial assembly with every body's initial mesh,
(2) the final meshes on the deformed foundations, (3) the deformed bodies
over the initial ones, with each body's area and relative error (its
volume of revolution and the volume law's error for an assembly of
revolution). The revolution axis is drawn (dash-dot) where it lies near the
bodies; farther away, the title names it and its distance.
"""

from __future__ import annotations

import numpy as np

from .assembly_result import AssemblyResult
from .plot import draw_mesh, new_figure

__all__ = ["draw_assembly"]


def _closed(points: np.ndarray) -> np.ndarray:
    return np.vstack((points, points[:1]))


def _label(body, u: str) -> str:
    """Legend of a deformed body: its area, or its volume, and the law's relative error."""
    if body.volume_final is not None:
        return (f"{body.name}: {body.volume_final:.5g} {u}³, area {body.area_final:.4g} {u}² "
                f"({body.measure} error {body.relative_error:+.1e})")
    return f"{body.name}: {body.area_final:.4g} {u}² (error {body.relative_error:+.1e})"


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
                     label=_label(body, u))
        axes[2].plot(*_closed(body.contour).T, color=c, lw=1.0)
    note = ""
    if result.axis is not None:
        points = np.concatenate([np.concatenate((b.initial_contour, b.contour)) for b in result.bodies])
        note = _draw_axis(axes, result.axis, points, u)
    axes[0].set_title("1  initial assembly and meshes")
    axes[0].legend(loc="best", fontsize=8)
    axes[1].set_title(f"2  final meshes on the deformed foundations ({result.model} model)")
    axes[2].set_title("3  deformed bodies over the initial ones")
    axes[2].legend(loc="best", fontsize=8)
    for ax in axes:
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.grid(True, lw=0.3, alpha=0.5)
    fig.suptitle(f"{result.name}: {len(result.bodies)} bodies{note}")
    return fig
