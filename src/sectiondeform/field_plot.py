"""A strain field drawn as a colour map on the deformed mesh (matplotlib, extra ``[plot]``).

One panel: each element of every body's final mesh
filled with the colour of one scalar field of :mod:`sectiondeform.strain_fields`,
clipped to the deformed section, its outline drawn over it, with a colour
bar naming the field and its kind. The hyperelastic model's stresses are
drawn smoothly: their values recovered at the nodes
(:func:`~sectiondeform.strain_fields.nodal_stresses`), each body's own,
interpolated over each P2 element split into four triangles (Gouraud
shading), the singular points marked with a red cross. For the paper model the field is the
geometric one of that name (``geometric_J`` for ``J``), and says so. The
stresses (``von_mises_stress``, ``pressure``: hyperelastic model only) are
labelled with their unit: × shear modulus when every body has the
model's default rubber (a relative modulus), else the unit of the bodies'
material moduli (MPa as the case gives them).
"""

from __future__ import annotations

import numpy as np

from .errors import CaseError
from .strain_fields import result_fields, result_mechanics

__all__ = ["PLOT_FIELDS", "STRESS_FIELDS", "check_plot_field", "field_values", "nodal_values", "draw_field",
           "save_field_figure", "stress_unit"]

PLOT_FIELDS = {
    "max_principal_strain": ("max_principal_strain", None, "largest principal strain λ₁ − 1"),
    "J": ("J", None, "J = det F, local volume ratio"),
    "max_principal_stretch": ("principal_stretches", 0, "largest principal stretch λ₁"),
    "min_principal_stretch": ("principal_stretches", 2, "smallest principal stretch λ₃"),
    "von_mises_stress": ("von_mises_stress", None, "von Mises stress"),
    "pressure": ("pressure", None, "pressure −tr σ / 3 (positive in compression)"),
}
STRESS_FIELDS = ("von_mises_stress", "pressure")


def check_plot_field(name: str) -> str:
    """``name`` if it is one of :data:`PLOT_FIELDS`; a one-line :class:`CaseError` otherwise."""
    if name not in PLOT_FIELDS:
        raise CaseError("--plot-field", f"unknown field {name!r}; use one of {', '.join(PLOT_FIELDS)}")
    return name


def field_values(result, name: str) -> tuple[str, list[np.ndarray]]:
    """The scalar field ``name`` per element of each body, and its kind (``mechanical`` or ``geometric``).

    Parameters
    ----------
    result : Result
    name : str
        One of :data:`PLOT_FIELDS`.

    Returns
    -------
    kind : str
    values : list of (M_b,) float64 ndarray
        One array per body, one value per element of its final mesh.

    Raises
    ------
    CaseError
        For a stress of the paper model (no material), or the pressure of a
        drag preview (its state is not a solution).
    """
    key, column, _ = PLOT_FIELDS[check_plot_field(name)]
    kind, out = "geometric", []
    for body, mech in zip(result.bodies, result_mechanics(result)):
        kind, fields = result_fields(body.initial_mesh, body.final_mesh, result.model,
                                     getattr(body.info, "out_of_plane_stretch", 1.0), result.axis, mech)
        values = fields.get(key if kind == "mechanical" else f"geometric_{key}")
        if values is None and kind == "geometric" and key in STRESS_FIELDS:
            raise CaseError("--plot-field", f"{name} is a stress and the paper model has no material; "
                            "use --model hyperelastic or a strain field")
        if values is None and key in STRESS_FIELDS:
            raise CaseError("--plot-field", f"no {name} for a drag preview (its state is not a solution); "
                            "deform to plot a stress")
        if values is None:
            raise CaseError("--plot-field", f"no {name} for this result's {body.final_mesh.kind} mesh")
        out.append(values if column is None else values[:, column])
    return kind, out


def nodal_values(result, name: str) -> list | None:
    """The stress ``name`` recovered at the nodes of each body's final mesh, or None where it is not.

    Parameters
    ----------
    result : Result
    name : str
        One of :data:`PLOT_FIELDS`; only the stresses (:data:`STRESS_FIELDS`)
        of the hyperelastic model have nodal values
        (:func:`~sectiondeform.strain_fields.nodal_stresses`).

    Returns
    -------
    list of (N_b,) float64 ndarray or None
        One array per body, one value per node of its final mesh; None for
        a strain, the paper model, or a field some body lacks.
    """
    if name not in STRESS_FIELDS:
        return None
    mechanics = result_mechanics(result)
    if any(m is None or name not in m.nodal for m in mechanics):
        return None
    return [m.nodal[name] for m in mechanics]


#: A P2 triangle as four linear ones over its six nodes (corners 0–2, mid-edge nodes 3–5).
_P2_SPLIT = np.array([[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]])


def stress_unit(result) -> str:
    """The unit of a hyperelastic result's stresses, for a label: ``× shear modulus`` (relative) or its material's."""
    mechanics = [m for m in result_mechanics(result) if m is not None]
    if mechanics and all(m.relative for m in mechanics):
        return "× shear modulus"
    return "unit of the bodies' moduli, MPa as given"


def draw_field(result, name: str, fig=None):
    """Draw the field ``name`` (one of :data:`PLOT_FIELDS`) on the deformed mesh; returns the figure."""
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import Normalize
    from matplotlib.patches import PathPatch

    from .plot import body_path, new_figure

    if fig is None:
        fig = new_figure(figsize=(11, 5), layout="constrained")
    ax = fig.subplots()
    kind, values = field_values(result, name)
    nodal = nodal_values(result, name)
    both = np.concatenate(values if nodal is None else nodal)
    norm = Normalize(float(both.min()), float(both.max()) if both.max() > both.min() else float(both.min()) + 1e-12)
    collection = None
    for b, (body, v) in enumerate(zip(result.bodies, values)):
        final, contour = body.final_mesh, body.contour
        outline = PathPatch(body_path(contour, body.holes), facecolor="none", edgecolor="k", lw=0.8)  # holes left out
        if nodal is not None:  # smooth: the nodal values, linear on the four triangles of each P2 element
            triangles = np.asarray(final.cells)[:, _P2_SPLIT].reshape(-1, 3)
            collection = ax.tripcolor(final.points[:, 0], final.points[:, 1], triangles, nodal[b], cmap="viridis",
                                      norm=norm, shading="gouraud")
        else:
            corners = {"quad": 4, "triangle": 3, "triangle6": 3}[final.kind]
            collection = PolyCollection(final.points[final.cells[:, :corners]], array=v, cmap="viridis", norm=norm,
                                        edgecolors="face", linewidths=0.2)
            ax.add_collection(collection)
        ax.add_patch(outline)
        collection.set_clip_path(outline)  # the paper model's mesh may reach beyond the body
    label = PLOT_FIELDS[name][2]
    if name in STRESS_FIELDS:
        label += f" ({stress_unit(result)})"
    label += "\n(geometric: the paper model's mesh, not a material)" if kind == "geometric" else ""
    if nodal is not None:
        label += "\n(recovered at the nodes; ✕ singular points)"
        for m in result_mechanics(result):
            for p in m.singular_points:
                ax.plot(*p.point, "x", color="tab:red", ms=6, mew=1.5, zorder=5)
    fig.colorbar(collection, ax=ax, label=label, shrink=0.8)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.set_title(f"{result.name}: {name} on the deformed mesh ({result.model} model), "
                 f"{both.min():.4g} to {both.max():.4g}{' at the nodes' if nodal is not None else ''}")
    return fig


def save_field_figure(result, name: str, path):
    """Draw :func:`draw_field` and write it to ``path`` (.png, .svg or .pdf), atomically."""
    from .plot import write_figure

    return write_figure(draw_field(result, name), path)
