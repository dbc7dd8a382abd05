"""Decks of section-case/2 cases: one element set, section and material per body, bonded nodes, the axis frame."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pytest

from sectiondeform.cli import main
from sectiondeform.errors import CaseError
from sectiondeform.external.axis import axis_frame, reverse_orientation
from sectiondeform.external.deck import build_deck, deck_text
from sectiondeform.external.mesh import element_areas
from sectiondeform.external.solve import revolved_volumes
from sectiondeform.io.case import case_from_dict

CASES = Path(__file__).parent / "data" / "cases" / "v2"
STRIP = CASES / "two-layer-strip.json"
DRUM = CASES / "tread-on-drum.json"


def parse(text: str) -> dict:
    """Keyword line -> data rows (lists of stripped strings); comments skipped."""
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


def small_strip() -> dict:
    """The shared two-layer strip shortened to 20 mm, for small meshes."""
    data = json.loads(STRIP.read_text())
    data["support"] = {"polyline": [[0.0, 0.0], [20.0, 0.0]]}
    data["target"] = {"arc": {"center": [10.0, -39.0], "radius": 40.0, "start_deg": 104.3, "end_deg": 75.7}}
    backing, cover = data["bodies"]
    backing["lower"] = {"polyline": [[0.0, 0.0], [20.0, 0.0]]}
    backing["upper"] = {"polyline": [[20.0, 0.0], [20.0, 4.0], [10.0, 4.0], [0.0, 4.0], [0.0, 0.0]]}
    cover["lower"] = {"polyline": [[0.0, 4.0], [20.0, 4.0]]}
    cover["upper"] = {"polyline": [[20.0, 4.0], [20.0, 10.0], [0.0, 10.0], [0.0, 4.0]]}
    return data


def deck_of(data: dict, **kw):
    deck = build_deck(case_from_dict(data), **kw)
    return deck, parse(deck_text(deck))


def test_one_element_set_section_and_material_per_body():
    deck, blocks = deck_of(json.loads(STRIP.read_text()), mesh_size=0.6)
    placed = np.array([[float(v) for v in r[1:3]] for r in blocks["*NODE, NSET=ALL_NODES"]])
    nodes = (placed - deck.translation) @ deck.rotation  # back to the case's coordinates
    sets = {}
    for name in ("BACKING", "COVER"):
        rows = blocks[f"*ELEMENT, TYPE=CPE6, ELSET={name}"]
        sets[name] = np.array([[int(v) for v in r[1:]] for r in rows]) - 1
        assert f"*SOLID SECTION, ELSET={name}, MATERIAL=RUBBER_{name}" in blocks
        assert f"*MATERIAL, NAME=RUBBER_{name}" in blocks
    # Each set covers its body exactly: the backing 100 x 4, the cover the rest, counter-clockwise.
    back = element_areas(nodes, sets["BACKING"], 3)
    assert back.min() > 0 and back.sum() == pytest.approx(400.0, rel=1e-9)
    assert np.all(nodes[sets["BACKING"]][..., 1] <= 4.0 + 1e-9)
    assert np.all(nodes[sets["COVER"]][..., 1] >= 4.0 - 1e-9)
    # Materials from each body's shear modulus (3 and 1), kappa = 1000 mu: C10 = mu/2, D1 = 2/kappa.
    cards = blocks["*HYPERELASTIC, NEO HOOKE"]
    assert np.allclose([[float(v) for v in c] for c in cards], [[1.5, 2 / 3000], [0.5, 2 / 1000]], rtol=1e-12)
    # Element numbers are unique across the sets.
    ids = [int(r[0]) for k, rows in blocks.items() if k.startswith("*ELEMENT") for r in rows]
    assert sorted(ids) == list(range(1, len(ids) + 1))


def test_bonded_bodies_share_their_nodes_on_the_shared_piece():
    deck, blocks = deck_of(json.loads(STRIP.read_text()), mesh_size=0.6)
    placed = np.array([[float(v) for v in r[1:3]] for r in blocks["*NODE, NSET=ALL_NODES"]])
    nodes = (placed - deck.translation) @ deck.rotation
    used = {}
    for name in ("BACKING", "COVER"):
        rows = blocks[f"*ELEMENT, TYPE=CPE6, ELSET={name}"]
        used[name] = {int(v) - 1 for r in rows for v in r[1:]}
    shared = used["BACKING"] & used["COVER"]
    on_line = {int(k) for k in np.flatnonzero(np.abs(nodes[:, 1] - 4.0) < 1e-9)}
    assert shared == on_line  # every node of y = 4 belongs to both bodies, and no other node does
    assert len(np.unique(np.round(nodes, 9), axis=0)) == len(nodes)  # no doubled nodes (no crack)
    # Edges on y = 4: each one is an edge of a backing element and of a cover element.
    def edges(name):
        cells = np.array([[int(v) - 1 for v in r[1:4]] for r in blocks[f"*ELEMENT, TYPE=CPE6, ELSET={name}"]])
        e = np.sort(np.concatenate([cells[:, [0, 1]], cells[:, [1, 2]], cells[:, [2, 0]]]), axis=1)
        return {tuple(x) for x in e if abs(nodes[x[0], 1] - 4) < 1e-9 and abs(nodes[x[1], 1] - 4) < 1e-9}
    assert edges("BACKING") == edges("COVER") and len(edges("COVER")) > 10


def test_support_nodes_go_onto_the_target_and_laws_are_said():
    data = json.loads(STRIP.read_text())
    deck, blocks = deck_of(data, mesh_size=0.6)
    fe = case_from_dict(data)
    x0 = deck.mesh.points[deck.mesh.lower_nodes]
    assert np.allclose(x0[:, 1], 0.0) and np.allclose(deck.mesh.lower_fractions, x0[:, 0] / 100.0)
    on_target = fe.target.at_fractions(x0[:, 0] / 100.0)
    assert np.allclose(deck.placed_points[deck.mesh.lower_nodes] + deck.support_displacement, on_target, atol=1e-12)
    head = deck_text(deck).split("*NODE")[0]
    assert "NOT EXPRESSED" in head and "area ratio 0.95" in head and "area ratio 0.9" in head


@pytest.mark.parametrize("material, card, values", [
    ({"model": "mooney-rivlin", "c10": 0.4, "c01": 0.1, "bulk_modulus": 500.0}, "*HYPERELASTIC, MOONEY-RIVLIN",
     [0.4, 0.1, 2 / 500]),
    ({"model": "yeoh", "c10": 0.5, "c20": -0.01, "c30": 0.002, "bulk_to_shear": 2000.0}, "*HYPERELASTIC, YEOH",
     [0.5, -0.01, 0.002, 2 / 2000, 0, 0]),
    ({"shear_modulus": 2.0}, "*HYPERELASTIC, NEO HOOKE", [1.0, 2 / 2000]),
])
def test_material_models_become_their_hyperelastic_cards(material, card, values):
    data = small_strip()
    data["bodies"][1]["material"] = material
    _, blocks = deck_of(data, mesh_size=1.0)
    assert [float(v) for v in blocks[card][-1]] == pytest.approx(values)


def test_axis_frame_maps_the_axis_to_r_zero_and_back():
    frame = axis_frame(((0.0, -250.0), (1.0, -250.0)), np.array([[0.0, 0.0], [150.0, 15.0]]))
    on_axis = np.array([[-3.0, -250.0], [0.0, -250.0], [77.0, -250.0]])
    rz = frame.to_rz(on_axis)
    assert np.allclose(rz[:, 0], 0.0) and np.allclose(rz[:, 1], on_axis[:, 0])
    pts = np.random.default_rng(0).uniform(-10, 10, (20, 2)) + [0.0, -200.0]
    assert np.allclose(frame.from_rz(frame.to_rz(pts)), pts)
    assert np.allclose(frame.to_rz(pts)[:, 0], pts[:, 1] + 250.0)  # r = distance from the axis
    # A slanted axis: r is the distance from the line, z the position along it.
    slanted = axis_frame(((0.0, 0.0), (3.0, 4.0)), np.array([[-4.0, 3.0]]))
    assert np.allclose(slanted.to_rz(np.array([[-4.0, 3.0], [3.0, 4.0]])), [[5.0, 0.0], [0.0, 5.0]])
    with pytest.raises(CaseError, match="both sides"):
        axis_frame(((0.0, 0.0), (1.0, 0.0)), np.array([[0.0, 1.0], [0.0, -1.0]]))


def test_revolution_deck_is_written_in_r_z_with_counter_clockwise_axisymmetric_elements():
    data = json.loads(DRUM.read_text())
    deck, blocks = deck_of(data, mesh_size=0.8)
    assert deck.element.name == "CAX6" and deck.axis is not None
    rz = np.array([[float(v) for v in r[1:3]] for r in blocks["*NODE, NSET=ALL_NODES"]])
    assert np.allclose(deck.rotation, np.eye(2)) and deck.translation[1] == 0.0  # may only slide along the axis
    assert np.allclose(rz, deck.placed_points[:, ::-1] + [250.0, 0.0])  # r = y + 250, z = x
    for name in ("UNDERTREAD", "TREAD"):
        cells = np.array([[int(v) - 1 for v in r[1:]] for r in blocks[f"*ELEMENT, TYPE=CAX6, ELSET={name}"]])
        assert element_areas(rz, cells, 3).min() > 0  # counter-clockwise in (r, z)
    # Support displacements in (u_r, u_z): the support nodes go onto the target, mapped to (r, z).
    fe = case_from_dict(data)
    u = {}
    for node, dof, _, value in blocks["*BOUNDARY"]:
        u.setdefault(int(node) - 1, [0.0, 0.0])[int(dof) - 1] = float(value)
    nodes = np.array(sorted(u))
    final = rz[nodes] + np.array([u[k] for k in nodes])
    frac = dict(zip(deck.mesh.lower_nodes.tolist(), deck.mesh.lower_fractions.tolist()))
    target = fe.target.at_fractions(np.array([frac[k] for k in nodes]))
    assert np.allclose(final, target[:, ::-1] + [250.0, 0.0], atol=1e-9)
    head = deck_text(deck).split("*NODE")[0]
    assert "r = (X - [0.0, -250.0])" in head and "volume ratio 0.98" in head
    with pytest.raises(CaseError, match="body of revolution"):
        build_deck(fe, "CPE6")


def test_reverse_orientation_flips_the_sign_of_every_area():
    deck, _ = deck_of(small_strip(), mesh_size=1.0)
    m = deck.mesh
    flipped = reverse_orientation(m.cells, m.kind)
    assert np.allclose(element_areas(m.points, flipped, 3), -element_areas(m.points, m.cells, 3))


def test_revolved_volume_of_a_ring_is_pappus():
    # A rectangle r in [2, 3], z in [0, 1] meshed by the deck's mesher: volume = 2 pi * area * centroid radius.
    data = {"format": "section-case/2", "name": "ring", "support": {"polyline": [[2.0, 0.0], [3.0, 0.0]]},
            "target": {"polyline": [[2.0, 0.0], [3.0, 0.0]]}, "revolution": {"axis": [[0.0, 0.0], [0.0, 1.0]]},
            "bodies": [{"name": "ring", "lower": {"polyline": [[2.0, 0.0], [3.0, 0.0]]},
                        "upper": {"polyline": [[3.0, 0.0], [3.0, 1.0], [2.0, 1.0], [2.0, 0.0]]},
                        "law": {"volume_ratio": 1.0}}]}
    deck, _ = deck_of(data, mesh_size=0.5)
    rz = deck.axis.to_rz(deck.mesh.points)
    v = revolved_volumes(rz, deck.mesh.cells, deck.mesh.corners) * (-1 if deck.axis.mirrored else 1)
    assert v.min() > 0 and v.sum() == pytest.approx(2 * np.pi * 1.0 * 2.5, rel=1e-12)


def test_export_fe_cli_writes_v2_decks_and_refuses_area_ratio(tmp_path, capsys):
    path = tmp_path / "strip.json"
    path.write_text(json.dumps(small_strip()))
    out = tmp_path / "deck.inp"
    assert main(["export-fe", str(path), "-o", str(out), "--mesh-size", "1"]) == 0
    captured = capsys.readouterr()
    assert "ELSET=COVER" in out.read_text() and len(captured.err.strip().splitlines()) == 2
    assert main(["export-fe", str(path), "-o", str(tmp_path / "x.inp"), "--area-ratio", "1"]) == 2
    assert "--area-ratio" in capsys.readouterr().err and not (tmp_path / "x.inp").exists()
    # Without an axis a volume ratio is the growth of an extruded body: an in-plane *EXPANSION, the extrusion held
    # at a free body's stretch (no generalised plane strain element in CalculiX), written and warned in one line.
    grown = copy.deepcopy(small_strip())
    grown["bodies"][0]["law"] = {"volume_ratio": 1.2}
    path.write_text(json.dumps(grown))
    assert main(["export-fe", str(path), "-o", str(out)]) == 0
    (growth,) = [line for line in capsys.readouterr().err.splitlines() if "'backing'" in line]
    assert "grows by volume ratio 1.2: this plane-strain deck" in growth and "area ratio" not in growth
    text = out.read_text()
    assert "law volume ratio 1.2" in text and "*EXPANSION, TYPE=ORTHO" in text
