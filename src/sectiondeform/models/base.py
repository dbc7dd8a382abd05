"""What every deformation model provides: one map from the initial section to the deformed one.

A model works in two stages, so the interactive use (one section, many
targets) redoes only the second:

1. ``Model.prepare(section, options)`` -> :class:`Prepared`: everything that
   depends on the section alone (its mesh, the location of the upper
   points in it, factorisations);
2. ``Prepared.place(target_nodes, law)`` -> :class:`Placement`: the deformed
   mesh on the target and the images of the upper points, meeting the law.

The lower nodes always go to ``target_nodes`` (the target at the lower
nodes' arc-length fractions), so the deformed lower curve is the target
itself; a model decides where the upper points go.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..laws import Law
from ..section import Section

__all__ = ["MeshData", "Placement", "Prepared", "Model"]


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
    quality : dict
        Figures such as ``jacobian_min``/``jacobian_max`` of the final mesh.
    info : dict
        Model-specific figures (height scale, Newton iterations, area
        correction...).
    warnings : tuple of str
        Anything the user must know about this result.
    """

    upper: np.ndarray
    final_mesh: MeshData
    quality: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)
    warnings: tuple = ()


class Prepared(ABC):
    """A section made ready for deformation by one model."""

    section: Section
    initial_mesh: MeshData
    quality: dict

    @abstractmethod
    def place(self, target_nodes: np.ndarray, law: Law) -> Placement:
        """Deform onto ``target_nodes`` ((n, 2), the target at the lower fractions) under ``law``."""

    def preview(self, target_nodes: np.ndarray, law: Law) -> Placement:
        """A fast placement for dragging the target, meeting the law; by default :meth:`place`.

        A model whose full placement is slow (the hyperelastic one) answers
        with a linearised step and says so in ``info["preview"]``.
        """
        return self.place(target_nodes, law)


class Model(ABC):
    """A deformation model: a name and a ``prepare`` step."""

    name: ClassVar[str] = ""

    @abstractmethod
    def prepare(self, section: Section, options: dict) -> Prepared:
        """Build what depends on the section alone (mesh, point locations)."""
