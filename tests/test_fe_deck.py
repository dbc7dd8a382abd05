"""Abaqus / CalculiX decks: syntax, element family, sets, and the support motion by the arc-length rule."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.cli import main
from sectiondeform.errors import CaseError
from sectiondeform.external.deck import build_deck, deck_text
from sectiondeform.external.interpolate import map_points, shape_functions
from sectiondeform.external.mesh import element_areas

DATA = Path(__file__).parent / "data" / "fe"
SQUARE = DATA / "square.json"


def parse_deck(text: str) -> dict:
    """Keyword blocks of a deck: keyword line -> list of data rows (lists of strings)."""
    blocks, key = {}, None
    for line in text.splitlines():
        if line.startswith("**"):
            continue
        if line.startswith("*"):
            key = line
            blocks.setdefault(key, [])
        elif key is not None:
            blocks[key].append([v.strip() for v in line.split(",")])
    return blocks


def target_at(s: np.ndarray) -> np.ndarray:
    """The square case's V-shaped target (0,0)-(5,-1)-(10,0) at arc-length fractions s, by hand."""
    half = np.hypot(5.0, 1.0)
    d = s * 2 * half
    first = d <= half
    t = np.where(first, d / half, (d - half) / half)
    x = np.where(first, 5.0 * t, 5.0 + 5.0 * t)
    y = np.where(first, -t, -1.0 + t)
    return np.column_stack((x, y))


@pytest.mark.parametrize("element, per_row", [("CPE6", 6), ("CPE3", 3), ("CPE4R", 4), ("CPE8R", 8), ("CPE8", 8)])
def test_deck_elements_nodes_and_sets(element, per_row):
    deck = build_deck(sd.load_case(SQUARE), element, 0.5)
    blocks = parse_deck(deck_text(deck))
    nodes = blocks["*NODE, NSET=ALL_NODES"]
    assert len(nodes) == len(deck.mesh.points)
    rows = blocks[f"*ELEMENT, TYPE={element}, ELSET=BODY"]
    assert all(len(r) == per_row + 1 for r in rows)
    ids = np.array([[int(v) for v in r[1:]] for r in rows])
    assert ids.min() == 1 and ids.max() == len(nodes)  # every node used, numbered from 1
    # Counter-clockwise elements covering the square exactly.
    areas = element_areas(deck.mesh.points, deck.mesh.cells, deck.mesh.corners)
    assert areas.min() > 0 and areas.sum() == pytest.approx(100.0, rel=1e-12)
    assert "*SOLID SECTION, ELSET=BODY, MATERIAL=RUBBER_BODY" in blocks
    assert blocks["*HYPERELASTIC, NEO HOOKE"] == [["0.5", "0.002"]]  # C10 = mu/2, D1 = 2/kappa, kappa = 1000 mu
    assert "*STEP, NLGEOM, INC=1000" in blocks


def test_support_nodes_go_to_the_target_by_arc_length():
    deck = build_deck(sd.load_case(SQUARE), "CPE6", 0.5)
    text = deck_text(deck)
    blocks = parse_deck(text)
    xy = np.array([[float(v) for v in r[1:3]] for r in blocks["*NODE, NSET=ALL_NODES"]])
    bc = blocks["*BOUNDARY"]
    u = {}
    for node, dof, _, value in bc:
        u.setdefault(int(node), [0.0, 0.0])[int(dof) - 1] = float(value)
    support = sorted(u)
    assert support == sorted(int(v) for r in blocks["*NSET, NSET=SUPPORT"] for v in r)
    placed = xy[np.array(support) - 1]
    x0 = (placed - deck.translation) @ deck.rotation  # the case's coordinates, before the rigid placement
    assert np.allclose(deck.rotation @ deck.rotation.T, np.eye(2)) and np.linalg.det(deck.rotation) > 0
    assert np.allclose(x0[:, 1], 0.0)  # the lower curve of the square is y = 0
    final = placed + np.array([u[k] for k in support])
    assert np.allclose(final, target_at(x0[:, 0] / 10.0), atol=1e-12)
    # Mid-edge nodes are there too: more support nodes than lower corners.
    assert len(support) % 2 == 1 and len(support) > 3


def test_area_ratio_other_than_one_is_said_in_the_deck_and_on_stderr(tmp_path, capsys):
    out = tmp_path / "deck.inp"
    assert main(["export-fe", str(DATA / "paper-example.json"), "-o", str(out), "--mesh-size", "0.5"]) == 0
    head = out.read_text().split("*NODE")[0]
    assert "NOT EXPRESSED" in head and "area ratio 0.8" in head
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "warning" in err[0] and "0.8" in err[0]
    assert main(["export-fe", str(DATA / "paper-example.json"), "-o", str(out), "--mesh-size", "0.5",
                 "--area-ratio", "1"]) == 0
    assert "NOT EXPRESSED" not in out.read_text()


def test_unknown_formats_and_axisymmetric_elements_on_plane_cases_are_refused_in_one_line(tmp_path, capsys):
    v3 = tmp_path / "v3.json"
    v3.write_text(json.dumps({"format": "section-case/3", "bodies": []}))
    assert main(["export-fe", str(v3), "-o", str(tmp_path / "d.inp")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "section-case/3" in err[0]
    assert not (tmp_path / "d.inp").exists()
    with pytest.raises(CaseError, match="axisymmetric"):
        build_deck(sd.load_case(SQUARE), "CAX6")
    with pytest.raises(CaseError, match="unknown element"):
        build_deck(sd.load_case(SQUARE), "C3D10")


def test_hybrid_elements_are_written_for_abaqus_with_a_note():
    deck = build_deck(sd.load_case(SQUARE), "CPE6H", 0.5)
    assert "TYPE=CPE6H" in deck_text(deck) and any("hybrid" in n for n in deck.unexpressed)


@pytest.mark.parametrize("kind, nodes", [("triangle", 3), ("triangle6", 6), ("quad", 4), ("quad8", 8)])
def test_shape_functions_reproduce_affine_maps(kind, nodes):
    deck = build_deck(sd.load_case(SQUARE), {"triangle": "CPE3", "triangle6": "CPE6", "quad": "CPE4",
                                             "quad8": "CPE8"}[kind], 0.5)
    m = deck.mesh
    rng = np.random.default_rng(1)
    A, b = np.array([[1.1, 0.3], [-0.2, 0.9]]), np.array([2.0, -1.0])
    X = rng.uniform(0.0, 10.0, (50, 2))
    mapped = map_points(m.points, m.points @ A.T + b, m.cells, m.kind, X)
    assert np.allclose(mapped, X @ A.T + b, atol=1e-10)
    n = shape_functions(kind, rng.uniform(0, 0.5, 7), rng.uniform(0, 0.5, 7))
    assert n.shape == (7, nodes) and np.allclose(n.sum(axis=1), 1.0)


def test_mesh_writer_names_quads_plane_strain(tmp_path):
    from sectiondeform.io.meshes import write_mesh

    # The paper model's quads; the square case is bent beyond what that model can mean (refused): the paper's example.
    result = sd.Deformer(sd.load_case(sd.example_case_path()), "paper").deform()
    assert result.final_mesh.kind == "quad"
    path = tmp_path / "mesh.inp"
    write_mesh(path, result)
    text = path.read_text()
    assert "CAX4P" not in text.upper()
    assert re.search(r"(?i)type\s*=\s*CPE4\b", text)


V2_CASES = Path(__file__).parent / "data" / "cases" / "v2"


def _case_path(name: str) -> Path:
    return DATA / name if (DATA / name).exists() else V2_CASES / name


def _sections(problem) -> list:
    return [sd.build_section(problem.body_case(b)) for b in range(len(problem.bodies))]


@pytest.mark.parametrize("name", ["square.json", "paper-example.json", "thick-block-s-curve.json",
                                  "two-layer-strip.json", "tread-on-drum.json"])
@pytest.mark.parametrize("mesh_size", [0.05, 0.2])
def test_the_triangle_estimate_is_a_lower_bound_of_the_mesh(name, mesh_size):
    """The bound refuses only what would really be too large: the estimate never exceeds the elements made.

    Over every body: the estimate is the sum of each body's, and the deck meshes them all.
    """
    from sectiondeform.external.mesh import check_deck_size

    case = sd.load_case(_case_path(name))
    deck = build_deck(case, "CPE3" if case.revolution is None else "CAX3", mesh_size)
    sections = _sections(case)
    estimate = check_deck_size(sections, [mesh_size * s.mesh_scale for s in sections])
    each = [check_deck_size([s], [mesh_size * s.mesh_scale]) for s in sections]
    assert estimate == pytest.approx(sum(each))
    assert 0.2 * len(deck.mesh.cells) <= estimate <= len(deck.mesh.cells)


@pytest.mark.parametrize("name", ["square.json", "two-layer-strip.json"])
def test_the_deck_size_is_checked_before_anything_is_triangulated(monkeypatch, name):
    import sectiondeform.reference.mesh as reference_mesh
    from sectiondeform.errors import MeshError

    def never(*args, **kwargs):
        raise AssertionError("triangulated before the size was checked")

    monkeypatch.setattr(reference_mesh, "triangulate", never)
    with pytest.raises(MeshError, match=r"^solver mesh: [0-9.e+]+ triangles needed, more than the bound 500000"):
        build_deck(sd.load_case(_case_path(name)), "CPE8", 1e-4)


@pytest.mark.parametrize("name", ["square.json", "two-layer-strip.json"])
def test_a_mesh_size_too_small_is_refused_up_front_with_the_number(tmp_path, capsys, name):
    """--mesh-size 0.0001 ran without end (2e8 triangles); now one line, before meshing, nothing written."""
    import time

    source = _case_path(name)
    out = tmp_path / "deck.inp"
    t0 = time.process_time()
    assert main(["export-fe", str(source), "-o", str(out), "--mesh-size", "0.0001"]) == 2
    assert time.process_time() - t0 < 5.0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and re.search(r"solver mesh: [0-9.e+]+ triangles needed, more than the bound 500000; "
                                       r"raise --mesh-size", err[0]), err
    assert not out.exists()
