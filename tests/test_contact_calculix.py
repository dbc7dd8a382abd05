"""Decks with rigid parts (contact) and their CalculiX runs (ccx: skipped without it, failing when SECTIONDEFORM_REQUIRE_CCX=1)."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.external.contact_deck import free_faces
from sectiondeform.external.contact_read import read_dat_forces
from sectiondeform.external.deck import build_deck, deck_text
from sectiondeform.external.inp_number import FIELD_WIDTH
from sectiondeform.external.solve import solve_calculix
from sectiondeform.io.case import case_from_dict

from conftest import CASES_DIR

BUMPER = CASES_DIR / "v2" / "bumper-under-plate.json"
SLEEVE = CASES_DIR / "v2" / "sleeve-on-shaft.json"
ORING = CASES_DIR / "v2" / "o-ring-squeeze-20.json"
ORING_K100 = CASES_DIR / "v2" / "o-ring-squeeze-20-k100.json"


def _cards(text: str) -> list[str]:
    return [line.split(",")[0].strip().upper() for line in text.splitlines() if line.startswith("*") and not line.startswith("**")]


def _data_reals(text: str) -> list[str]:
    """Every real of the deck's data lines (not keyword or comment lines)."""
    out = []
    for line in text.splitlines():
        if line.startswith("*"):
            continue
        out += [f.strip() for f in line.split(",") if re.fullmatch(r"\s*[-+]?[0-9.]+([eE][-+]?[0-9]+)?\s*", f)]
    return out


@pytest.mark.parametrize("path, element, rigid_element", [(BUMPER, "CPE6", "CPE3"), (SLEEVE, "CAX6", "CAX3"), (ORING_K100, "CPE6", "CPE3"),
                                                         (ORING, "CPE6", "CPE3")])
def test_contact_deck_has_the_cards_and_20_character_reals(path, element, rigid_element):
    problem = sd.load_case(path)
    deck = build_deck(problem, mesh_size=0.3)
    text = deck_text(deck)
    cards = _cards(text)
    for card in ("*SURFACE", "*RIGID BODY", "*SURFACE INTERACTION", "*SURFACE BEHAVIOR", "*CONTACT PAIR", "*STEP",
                 "*STATIC", "*BOUNDARY", "*NODE PRINT", "*CONTACT FILE", "*END STEP"):
        assert card in cards, card
    assert cards.count("*CONTACT PAIR") == cards.count("*RIGID BODY") == len(problem.rigid)
    assert f"TYPE={element}" in text and f"TYPE={rigid_element}" in text
    assert "PRESSURE-OVERCLOSURE=LINEAR" in text and "TYPE=SURFACE TO SURFACE" in text
    assert re.search(r"^\*STEP, NLGEOM, INC=\d+$", text, re.M)
    assert all(len(v) <= FIELD_WIDTH for v in _data_reals(text))
    # Each rigid part's reference node moves by its travel (in (r, z) for a body of revolution), its rotations held.
    for part in deck.rigid:
        ref = re.search(r"REF NODE=(\d+), ROT NODE=(\d+)", text.split(f"*RIGID BODY, NSET={part.name}_NODES")[1])
        ux, uy = part.travel if deck.axis is None else deck.axis.to_rz(part.travel[None] + deck.axis.origin)[0]
        step = text.split("*STEP")[1]
        assert float(re.search(rf"^{ref.group(1)}, 1, 1, (\S+)$", step, re.M).group(1)) == pytest.approx(ux, abs=1e-12)
        assert float(re.search(rf"^{ref.group(1)}, 2, 2, (\S+)$", step, re.M).group(1)) == pytest.approx(uy, abs=1e-12)
        assert re.search(rf"^{ref.group(2)}, 1, 3, 0.0$", step, re.M)


def test_hard_contact_and_friction_cards():
    d = case_from_dict({**_bumper(), "rigid": [{**_bumper()["rigid"][0], "friction": 0.4}]})
    text = deck_text(build_deck(d, mesh_size=0.3, contact_penalty="hard"))
    assert "PRESSURE-OVERCLOSURE=HARD" in text
    assert re.search(r"^\*FRICTION\n0.4, ", text, re.M)


def test_contact_penalty_is_checked_in_one_line(tmp_path):
    from sectiondeform.cli import main

    out = tmp_path / "deck.inp"
    assert main(["export-fe", str(BUMPER), "-o", str(out), "--contact-penalty", "-3"]) == 2
    assert not out.exists()


def test_free_faces_leave_out_the_support_and_shared_edges():
    # Two triangles sharing the edge 1-2 on a support 0-1: the free faces are the other three.
    cells = np.array([[0, 1, 2], [1, 3, 2]])
    assert free_faces(cells, 3, np.array([0, 1])).tolist() == [[0, 2], [1, 0], [1, 1]]
    assert free_faces(cells, 3, np.array([], dtype=int)).tolist() == [[0, 0], [0, 2], [1, 0], [1, 1]]


def test_dat_forces_are_read_per_set_and_time():
    text = ("\n total force (fx,fy,fz) for set R_PLATE_NODES and time  0.5000000E+00\n\n"
            "       -1.0E-02  2.5E+00  0.0E+00\n\n"
            " total force (fx,fy,fz) for set R_PLATE_NODES and time  0.1000000E+01\n\n"
            "        0.0E+00  5.0E+00  0.0E+00\n")
    assert read_dat_forces(text) == {"R_PLATE_NODES": [(0.5, (-0.01, 2.5, 0.0)), (1.0, (0.0, 5.0, 0.0))]}


def _bumper() -> dict:
    return json.loads(BUMPER.read_text())


def test_bumper_force_from_calculix_within_3_percent_of_the_model(ccx):
    problem = sd.load_case(BUMPER)
    model = sd.Deformer(problem).deform()
    cx = solve_calculix(problem, mesh_size=0.25)
    (plate,) = cx.rigid
    # The plate is pushed up, the support down, by the same force; CalculiX's within 3 % of the model's.
    assert plate.force[1] > 0 and abs(plate.force[0]) < 1e-6 * plate.force[1]
    np.testing.assert_allclose(np.add(plate.force, cx.support_force), 0.0, atol=1e-6 * plate.force[1])
    assert abs(plate.force[1] / model.rigid[0].force[1] - 1.0) < 0.03
    # The load-deflection curve: zero at the start, rising to the end's force.
    f = [s.forces["plate"][1] for s in cx.history]
    assert f[0] == 0.0 and f[-1] == plate.force[1] and np.all(np.diff(f) >= -1e-9 * f[-1])
    assert cx.to_json()["rigid"][0]["name"] == "plate"
