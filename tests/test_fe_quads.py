"""Quadrilateral decks (CPE8R) run in CalculiX, and their meshes draw (skipped without ccx, failing in CI)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.compare import compare_curves

DATA = Path(__file__).parent / "data" / "fe"


@pytest.fixture(scope="module")
def solutions(ccx):
    from sectiondeform.external.solve import solve_calculix

    case = sd.load_case(DATA / "square.json")
    return case, solve_calculix(case, element="CPE8R", mesh_size=0.5), solve_calculix(case, element="CPE6", mesh_size=0.5)


def test_a_cpe8r_deck_runs_and_agrees_with_cpe6(solutions):
    case, quads, triangles = solutions
    mesh = quads.final_mesh
    assert quads.info.element_type == "CPE8R" and mesh.kind == "quad8" and mesh.cells.shape[1] == 8
    T = quads.area_initial / case.lower.length
    # nearly incompressible (kappa = 1000 mu): the area is kept to the compressibility
    assert abs(quads.area_final / quads.area_initial - 1.0) < 2e-3
    # the support went onto the target
    on_target = case.target.at_fractions(sd.build_section(case).fractions)
    assert np.allclose(quads.lower, on_target, atol=1e-4 * T)
    # two element families, two meshes, one physics: the same upper curve to a small fraction of the thickness
    assert compare_curves(quads.upper, triangles.upper, scale=T).hausdorff_relative < 0.01


def test_a_quad8_mesh_is_drawn_by_its_corners(solutions):
    pytest.importorskip("matplotlib")
    from matplotlib.collections import PolyCollection

    from sectiondeform.plot import draw_mesh, new_figure

    _, quads, _ = solutions
    fig = new_figure()
    ax = fig.subplots()
    draw_mesh(ax, quads.final_mesh)
    (polys,) = [c for c in ax.collections if isinstance(c, PolyCollection)]
    paths = polys.get_paths()
    assert len(paths) == len(quads.final_mesh.cells)
    first = paths[0].vertices
    corners = quads.final_mesh.points[quads.final_mesh.cells[0, :4]]
    assert len(first) <= 5 and np.allclose(first[:4], corners)  # the four corners (closed), not the mid-side nodes
