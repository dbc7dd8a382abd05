"""What every deformation model provides: one map from the initial section to the deformed one.

A model works in two stages, so the interactive use (one section, many
targets) redoes only the second:

1. ``Model.prepare(stack, options)`` -> :class:`Prepared`: everything that
   depends on the bodies alone (their meshes, the location of the upper
   points in them, factorisations), from the bodies' sections as they rest
   on each other (:class:`~sectiondeform.stack.Stack`); ``options`` is the
   model's own frozen :class:`ModelOptions` subclass, declared as
   ``Model.options_type``;
2. ``Prepared.place(target, laws, start=None)`` -> :class:`Placed`: per
   body the deformed mesh on the target and the images of its upper
   points, meeting its law. A prepared object is never changed by ``place``: a
   model that can start from an earlier solution takes it as ``start`` (a
   :attr:`Placement.state`), so the same arguments give the same answer,
   bit for bit, and one prepared object may serve several threads.

Quality and info figures are frozen dataclasses (:class:`MeshQuality`,
:class:`FinalQuality`, :class:`Info` subclasses); ``to_json`` gives the keys
of the result format, leaving out figures a model does not have.

The lower nodes resting on the support always go to the target at their
arc-length fractions, so the deformed lower curve is the target itself; a
model decides where the upper points go.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, ClassVar

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from ..stack import Stack

__all__ = [
    "MeshData", "Placement", "Placed", "Prepared", "Model", "ModelOptions", "Figures", "MeshQuality",
    "FinalQuality", "Info",
]


def _plain(value):
    """A JSON-ready copy of a figure (tuples as lists, numpy scalars as Python numbers)."""
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


@dataclass(frozen=True)
class Figures:
    """Base of the frozen records of figures; :meth:`to_json` leaves out the ones that are None."""

    def to_json(self) -> dict:
        """The figures as a JSON object, keys as the field names."""
        return {f.name: _plain(getattr(self, f.name)) for f in fields(self) if getattr(self, f.name) is not None}


@dataclass(frozen=True)
class ModelOptions(Figures):
    """Base of a model's options: a frozen dataclass whose fields are the ``options`` keys it reads.

    A subclass gives every field a default and checks its values in
    ``__post_init__`` with :func:`~sectiondeform.checks.positive`.
    """

    @classmethod
    def keys(cls) -> tuple[str, ...]:
        """The option keys this model reads."""
        return tuple(f.name for f in fields(cls))

    def to_json(self) -> dict:
        """The options that differ from their defaults."""
        return {f.name: getattr(self, f.name) for f in fields(self) if getattr(self, f.name) != f.default}


@dataclass(frozen=True)
class MeshQuality(Figures):
    """Figures of a prepared (initial) mesh.

    Attributes
    ----------
    elements : int
    element_size : float
        Units.
    jacobian_min, jacobian_max : float, optional
        Smallest and largest corner Jacobian (layered quad mesh), units².
    layers, columns : int, optional
        Shape of a structured layered mesh.
    virtual_columns : tuple of int, optional
        Columns added beyond A and B (paper model).
    nodes, unknowns : int, optional
        Node and free unknown counts (finite-element mesh).
    through_thickness : float, optional
        Elements across the mean thickness asked for.
    jacobian_ratio_min : float, optional
        Smallest ratio of det J inside an element to its largest (P2 mesh).
    """

    elements: int
    element_size: float
    jacobian_min: float | None = None
    jacobian_max: float | None = None
    layers: int | None = None
    columns: int | None = None
    virtual_columns: tuple[int, int] | None = None
    nodes: int | None = None
    unknowns: int | None = None
    through_thickness: float | None = None
    jacobian_ratio_min: float | None = None

    def describe(self) -> str:
        """One line on the mesh, for a summary."""
        if self.layers is not None:
            text = f"{self.layers} layers x {self.columns} elements"
        else:
            text = f"{self.elements} elements"
        return text + f", size {self.element_size:.4g}"


@dataclass(frozen=True)
class FinalQuality(Figures):
    """Figures of a placed (final) mesh; the result writes them with the prefix ``final_``.

    Attributes
    ----------
    jacobian_min, jacobian_max : float, optional
        Corner Jacobian range of a layered quad mesh, units².
    area_stretch_min, area_stretch_max : float, optional
        Range of det F of a finite-element solution.
    """

    jacobian_min: float | None = None
    jacobian_max: float | None = None
    area_stretch_min: float | None = None
    area_stretch_max: float | None = None


@dataclass(frozen=True)
class Info(Figures):
    """Base of a model's figures on one placement (a subclass per model)."""


@dataclass(frozen=True, eq=False)
class MeshData:
    """A mesh as arrays, for output and plotting.

    Attributes
    ----------
    points : (N, 2) float64 ndarray
        Node coordinates, units.
    cells : (M, k) int64 ndarray
        Node indices of each element, counter-clockwise corners first.
    kind : str
        ``"quad"`` (k = 4), ``"triangle"`` (k = 3) or ``"triangle6"``
        (k = 6, corners then mid-edge nodes), as meshio names them.
    shape : tuple of int, optional
        ``(layers, columns)`` for a structured layered mesh.
    """

    points: np.ndarray
    cells: np.ndarray
    kind: str = "quad"
    shape: tuple | None = None

    def to_json(self) -> dict:
        """``{"kind", "points", "cells"[, "layers", "columns"]}`` with plain lists."""
        out = {"kind": self.kind, "points": self.points.tolist(), "cells": self.cells.tolist()}
        if self.shape is not None:
            out["layers"], out["columns"] = int(self.shape[0]), int(self.shape[1])
        return out


@dataclass(frozen=True, eq=False)
class Placement:
    """What a model gives back for one target.

    Attributes
    ----------
    upper : (m, 2) float64 ndarray
        Image of each upper characteristic point, B' first, A' last.
    final_mesh : MeshData
        The deformed (or rebuilt) mesh on the target.
    quality : FinalQuality
        Figures of the final mesh.
    info : Info
        Model-specific figures (height scale, Newton iterations, area
        correction...).
    warnings : tuple of str
        Anything the user must know about this result.
    state : object, optional
        The model's solved state, to pass back as ``start`` of a later
        placement (a warm start); None for a model without one.
    holes : tuple of (k_h, 2) float64 ndarray
        Image of each hole's points (the section's, in order).
    target : float, optional
        The law's quantity the placement meets when the model decides it
        (the area a growth leaves for the axial stretch the model solved),
        units²; None: the law's own target.
    """

    upper: np.ndarray
    final_mesh: MeshData
    quality: FinalQuality = FinalQuality()
    info: Info = Info()
    warnings: tuple = ()
    state: object = None
    holes: tuple = ()
    target: float | None = None


@dataclass(frozen=True, eq=False)
class Placed:
    """One placement of a whole problem: per body its deformed curves and :class:`Placement`.

    Attributes
    ----------
    lowers : list of (n_b, 2) float64 ndarray
        Each body's deformed lower nodes (its section's), units.
    images : list of (m_b, 2) float64 ndarray
        Each body's deformed upper points (its section's, with the nodes of
        the bodies resting on it), B' to A', units.
    placements : list of Placement
    state : object, optional
        The model's solved state of the whole problem, for a warm start.
    """

    lowers: list
    images: list
    placements: list
    state: object = None


class Prepared(ABC):
    """A problem made ready for deformation by one model.

    Attributes
    ----------
    bodies : tuple
        Per body, an object with its ``initial_mesh`` (:class:`MeshData`)
        and ``quality`` (:class:`MeshQuality`).
    """

    bodies: tuple

    @abstractmethod
    def place(self, target, laws: tuple, start=None, travels=None) -> Placed:
        """Deform onto ``target`` (a :class:`~sectiondeform.stack.Target`) under ``laws`` (one per body).

        ``start`` is the :attr:`Placed.state` of an earlier placement to
        start from (a model without a solver ignores it); ``travels``, the
        rigid parts' travels if not the problem's (a model that takes rigid
        parts). Never changes the prepared object: the same arguments give
        the same answer.
        """

    def preview(self, target, laws: tuple, start=None, travels=None) -> Placed:
        """A fast placement for dragging the target or a rigid part, meeting the laws; by default :meth:`place`.

        A model whose full placement is slow (the hyperelastic one) answers
        with a linearised step about ``start`` and says so in its info.
        """
        return self.place(target, laws, start, travels)


class Model(ABC):
    """A deformation model: a name, its options type and a ``prepare`` step."""

    name: ClassVar[str] = ""
    options_type: ClassVar[type[ModelOptions]] = ModelOptions

    @abstractmethod
    def prepare(self, stack: Stack, options: ModelOptions) -> Prepared:
        """Build what depends on the bodies alone (meshes, point locations, factorisations)."""
