"""Drawing pieces joined into curves, through the public functions' inputs and outputs."""

import numpy as np
import pytest
import shapely

from sectiondeform.curves import Polyline
from sectiondeform.io.chaining import one_chain
from sectiondeform.io.pieces import Piece


def _ring_pieces(n, seed):
    t = np.linspace(0, 2 * np.pi, n + 1)
    ring = np.column_stack((3 + 2 * np.cos(t), 2 * np.sin(t)))
    ring[-1] = ring[0]
    rng = np.random.default_rng(seed)
    pieces = []
    for i in rng.permutation(n):
        a, b = ring[i], ring[i + 1]
        if rng.random() < 0.5:
            a, b = b, a
        pieces.append(Piece(Polyline(np.array([a, b])), frozenset({"0"}), f"LINE #{i}"))
    return ring, pieces


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_shuffled_reversed_segments_chain_into_the_ring(seed):
    ring, pieces = _ring_pieces(60, seed)
    path, _ = one_chain(pieces, "layer 0", 1e-9, closed=True)
    v = path.curve.vertices
    assert path.closed and len(v) == 61 and np.allclose(v[0], v[-1])
    # the same polygon as the ring, whatever the start and direction
    assert shapely.Polygon(v).equals_exact(shapely.Polygon(ring), 0) or shapely.Polygon(v).symmetric_difference(
        shapely.Polygon(ring)).area < 1e-12


def test_reverse_and_transform_keep_the_shape():
    c = Polyline(np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 4.0]]))
    r = c.reversed()
    s = np.linspace(0, 1, 11)
    np.testing.assert_allclose(r.at_fractions(s), c.at_fractions(1 - s), atol=1e-12)
    a = np.radians(30)
    m = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    moved = c.transformed(m, (5.0, -1.0))
    np.testing.assert_allclose(moved.at_fractions(s), c.at_fractions(s) @ m.T + [5.0, -1.0], atol=1e-12)
    assert moved.length == pytest.approx(c.length)
