"""Every real of a deck reaches CalculiX as written: CalculiX reads only the first 20 characters of a field."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sectiondeform.external.deck import build_deck, deck_text
from sectiondeform.external.inp_number import FIELD_WIDTH, inp_real
from sectiondeform.external.material_cards import hyperelastic_card
from sectiondeform.io.case import case_from_dict, load_case
from sectiondeform.laws import AreaRatio
from sectiondeform.materials.models import MooneyRivlin, NeoHookean, Yeoh

sys.path.insert(0, str(Path(__file__).parent))
from test_fe_assembly_decks import parse  # noqa: E402

DATA = Path(__file__).parent / "data" / "cases"


def as_calculix_reads(field: str) -> float:
    """A data field as CalculiX 2.20 reads a real: ``read(textpart(k)(1:20), '(f20.0)')``."""
    return float(field.strip()[:FIELD_WIDTH])


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_a_real_fits_the_field_and_keeps_13_digits(value):
    text = inp_real(value)
    assert len(text) <= FIELD_WIDTH
    assert as_calculix_reads(text) == float(text)
    assert math.isclose(float(text), value, rel_tol=5e-13, abs_tol=0.0)


def test_nan_and_infinity_are_refused():
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(ValueError, match="finite"):
            inp_real(bad)


def _v2(name: str):
    return build_deck(case_from_dict(json.loads((DATA / "v2" / f"{name}.json").read_text())), mesh_size=0.3)


def _v1(name: str):
    return build_deck(load_case(DATA / f"{name}.json").replace(law=AreaRatio(1.0)), mesh_size=0.1)


@pytest.mark.parametrize("make, name", [(_v2, "two-layer-strip"), (_v2, "tread-on-drum"), (_v1, "grooved-tread"),
                                        (_v1, "thick-block-s-curve")])
def test_nodes_and_support_motion_reach_calculix_as_the_deck_means_them(make, name):
    deck = make(name)
    blocks = parse(deck_text(deck))
    points, u = deck.placed_points, deck.support_displacement
    if deck.axis is not None:
        points, u = deck.axis.to_rz(points), deck.axis.to_rz(u + np.asarray(deck.axis.origin))
    rows = blocks["*NODE, NSET=ALL_NODES"]
    read = np.array([[as_calculix_reads(v) for v in row[1:]] for row in rows])
    assert [int(row[0]) for row in rows] == list(range(1, len(points) + 1))
    scale = np.abs(points).max()
    assert np.abs(read - points).max() <= 1e-12 * scale
    bc = blocks["*BOUNDARY"]
    read_u = np.array([as_calculix_reads(row[3]) for row in bc]).reshape(-1, 2)
    assert [int(row[0]) for row in bc[::2]] == (deck.mesh.lower_nodes + 1).tolist()
    assert np.abs(read_u - u).max() <= 1e-12 * max(np.abs(u).max(), scale)


@pytest.mark.parametrize("material, meant", [
    (NeoHookean(3.0, bulk_to_shear=10_000.0), [1.5, 2.0 / 30_000.0]),
    (MooneyRivlin(0.4, 0.0123456789012345, bulk_to_shear=7000.0), [0.4, 0.0123456789012345, 2.0 / (7000.0 * 0.8246913578024690)]),
    (Yeoh(0.5, -1.23456789012345e-05, 3.3333333333333e-07, bulk_modulus=33_333.0),
     [0.5, -1.23456789012345e-05, 3.3333333333333e-07, 2.0 / 33_333.0, 0.0, 0.0]),
])
def test_material_constants_reach_calculix_as_meant(material, meant):
    values = [as_calculix_reads(v) for v in hyperelastic_card(material)[1].split(",")]
    assert np.allclose(values, meant, rtol=1e-12, atol=0.0)
