"""Joining the pieces of a drawing: any order and direction gives back the one curve they came from."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import event, given, settings
from hypothesis import strategies as st

from sectiondeform.curves import Arc, Polyline
from sectiondeform.errors import CaseError
from sectiondeform.io.chaining import one_chain
from sectiondeform.io.pieces import Piece, merge_runs, pin_ends


def _walk(n: int, seed: int) -> np.ndarray:
    """A random non-self-touching polyline of n + 1 vertices: x strictly increasing."""
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(0.5, 2.0, n + 1))
    return np.column_stack((x, rng.uniform(-3.0, 3.0, n + 1)))


@settings(max_examples=80, deadline=None)
@given(st.integers(2, 30), st.integers(0, 2**32 - 1), st.data())
def test_shuffled_and_flipped_pieces_chain_back_to_the_polyline(n, seed, data):
    v = _walk(n, seed)
    segments = [Polyline(v[i : i + 2]) for i in range(n)]
    order = data.draw(st.permutations(range(n)))
    flips = data.draw(st.lists(st.booleans(), min_size=n, max_size=n))
    event(f"{sum(flips)} of {n} flipped" if n < 4 else "n >= 4")
    pieces = [Piece(segments[i].reversed() if f else segments[i], frozenset({"L"}), f"line {i}")
              for i, f in zip(order, flips)]
    curve = one_chain(pieces, "layer L", 1e-9, closed=False)[0].curve
    got = curve.characteristic_points(1e-3)
    if np.array_equal(got[0], v[-1]):
        got = got[::-1]
    assert np.array_equal(got, v)


def test_a_branch_and_separate_chains_are_errors_naming_where():
    legs = [Polyline([[0, 0], [1, 0]]), Polyline([[1, 0], [2, 0]]), Polyline([[1, 0], [1, 1]])]
    with pytest.raises(CaseError, match=r"branch at \(1, 0\): 3 pieces meet"):
        one_chain([Piece(c, frozenset(), f"p{i}") for i, c in enumerate(legs)], "layer X", 1e-9)
    apart = [Polyline([[0, 0], [1, 0]]), Polyline([[1.5, 0], [2, 0]])]
    with pytest.raises(CaseError, match=r"nearest gap is 0\.5 .* option snap at 0\.505"):
        one_chain([Piece(c, frozenset(), f"p{i}") for i, c in enumerate(apart)], "layer X", 1e-9)


def test_merge_runs_and_pin_ends():
    p, q = Polyline([[0, 0], [1, 0]]), Polyline([[1, 0], [2, 1]])
    arc = Arc(np.array([2.0, 0.0]), 1.0, 90.0, 0.0)
    merged = merge_runs([p, q, arc, Polyline([[3, 0], [4, 0]])])
    assert [c.kind for c in merged] == ["polyline", "arc", "polyline"]
    assert merged[0].vertices.tolist() == [[0, 0], [1, 0], [2, 1]]
    pinned = pin_ends(arc, [2.0, 1.0 + 1e-3], [3.0, 0.0], scale=1.0)  # an arc cannot move: a bridge
    assert pinned.kind == "chain" and np.array_equal(pinned.ends[0], [2.0, 1.001])
    assert np.array_equal(pin_ends(p, [0, 1e-6], [1, 0]).ends[0], [0, 1e-6])
