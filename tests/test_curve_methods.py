"""Curve behaviour as methods: reversed, transformed, ends, joining; property tests over every kind."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, event, given, settings
from hypothesis import strategies as st

from sectiondeform.curves import (
    Arc,
    BSpline,
    Chain,
    Curve,
    Polyline,
    polygon_area,
    zigzag_fraction,
)

FR = np.linspace(0.0, 1.0, 41)
coord = st.floats(-100.0, 100.0, allow_nan=False, allow_infinity=False)
point = st.tuples(coord, coord)


def _spread(points) -> bool:
    p = np.asarray(points, dtype=float)
    return bool(np.all(np.hypot(*np.diff(p, axis=0).T) > 1e-3))


polylines = st.lists(point, min_size=2, max_size=8).filter(_spread).map(lambda p: Polyline(np.array(p)))
arcs = st.builds(
    lambda c, r, a0, sweep: Arc(np.array(c), r, a0, a0 + sweep),
    point, st.floats(0.1, 50.0), st.floats(-360.0, 360.0),
    st.floats(5.0, 355.0).flatmap(lambda s: st.sampled_from((s, -s))),
)
bsplines = st.integers(1, 3).flatmap(
    lambda k: st.lists(point, min_size=k + 1, max_size=k + 5).filter(_spread).map(lambda p: BSpline(k, np.array(p)))
)
simple = st.one_of(polylines, arcs, bsplines)


def _chain(parts):
    # Each piece moved to start where the one before ends.
    out = [parts[0]]
    for c in parts[1:]:
        out.append(c.transformed(np.eye(2), out[-1].ends[1] - c.ends[0]))
    return Chain(tuple(out))


curves = st.one_of(simple, st.lists(simple, min_size=2, max_size=3).map(_chain))
angles = st.floats(-math.pi, math.pi)


def rotation(theta: float, mirror: bool = False) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    m = np.array([[c, -s], [s, c]])
    return m @ np.diag([1.0, -1.0]) if mirror else m


def closed_area(curve: Curve) -> float:
    """Signed area enclosed by the curve and the chord from its end back to its start (Green's theorem)."""
    a, b = curve.ends
    return curve.green() + 0.5 * float(b[0] * a[1] - a[0] * b[1])


@settings(max_examples=150, deadline=None)
@given(curves)
def test_reversed_twice_is_the_curve(curve):
    event(curve.kind)
    back = curve.reversed().reversed()
    assert type(back) is type(curve)
    assert np.allclose(back.at_fractions(FR), curve.at_fractions(FR), atol=1e-9 * (1 + curve.length))
    assert all(np.array_equal(x, y) for x, y in zip(back.ends, curve.ends))


@settings(max_examples=150, deadline=None)
@given(curves)
def test_reversed_swaps_the_ends_and_runs_backwards(curve):
    event(curve.kind)
    rev = curve.reversed()
    (a, b), (ra, rb) = curve.ends, rev.ends
    assert np.array_equal(ra, b) and np.array_equal(rb, a)
    assert rev.length == pytest.approx(curve.length, rel=1e-9)
    tol = 1e-7 * (1 + curve.length)
    assert np.allclose(rev.at_fractions(FR), curve.at_fractions(1.0 - FR), atol=tol)
    assert closed_area(rev) == pytest.approx(-closed_area(curve), abs=tol * (1 + curve.length))


@settings(max_examples=150, deadline=None)
@given(curves, angles, point, st.booleans())
def test_rigid_motion_keeps_length_and_area(curve, theta, offset, mirror):
    event(curve.kind)
    m = rotation(theta, mirror)
    moved = curve.transformed(m, offset)
    assert type(moved) is type(curve)  # a rigid motion is a similarity: every kind stays itself
    scale = 1 + curve.length + float(np.abs(curve.at_fractions(FR)).max())
    assert moved.length == pytest.approx(curve.length, rel=1e-9, abs=1e-9)
    sign = -1.0 if mirror else 1.0
    assert closed_area(moved) == pytest.approx(sign * closed_area(curve), abs=1e-7 * scale**2)
    expected = curve.at_fractions(FR) @ m.T + np.asarray(offset)
    assert np.allclose(moved.at_fractions(FR), expected, atol=1e-7 * scale)
    assert np.allclose(np.vstack(moved.ends), np.vstack(curve.ends) @ m.T + np.asarray(offset), atol=1e-9 * scale)


@settings(max_examples=100, deadline=None)
@given(curves, st.floats(0.01, 100.0))
def test_scaling_multiplies_length_and_area(curve, k):
    event(curve.kind)
    big = curve.scaled(k)
    assert big.length == pytest.approx(k * curve.length, rel=1e-9)
    scale = 1 + float(np.abs(curve.at_fractions(FR)).max())
    assert closed_area(big) == pytest.approx(k * k * closed_area(curve), abs=1e-7 * (k * scale) ** 2)


@settings(max_examples=60, deadline=None)
@given(arcs, st.floats(1.2, 3.0))
def test_arc_under_a_stretch_is_a_polyline_near_the_ellipse(arc, stretch):
    m = np.diag([stretch, 1.0])
    image = arc.transformed(m, tol=1e-3)
    assert isinstance(image, Polyline)
    # Every point of the image lies on the stretched circle: ((x - cx) / s)^2 + (y - cy)^2 = r^2.
    c = arc.center @ m.T
    v = image.vertices - c
    radius = np.hypot(v[:, 0] / stretch, v[:, 1])
    assert np.allclose(radius, arc.radius, rtol=1e-9)
    # and the chords stay within the asked chordal error of the ellipse.
    mids = 0.5 * (image.vertices[1:] + image.vertices[:-1]) - c
    assume(len(mids) > 0)
    inside = arc.radius - np.hypot(mids[:, 0] / stretch, mids[:, 1])
    assert inside.max() <= 1e-3 + 1e-9


def test_ends_are_the_stored_points():
    b = BSpline(3, np.array([[0, 0], [1, 2], [3, 2], [4, 0.5]]))
    assert np.array_equal(b.ends[0], [0, 0]) and np.array_equal(b.ends[1], [4, 0.5])
    assert np.allclose(b.ends[1], b.end)
    a = Arc(np.array([1.0, 1.0]), 2.0, 0.0, 90.0)
    assert np.allclose(a.ends[0], [3, 1]) and np.allclose(a.ends[1], [1, 3])


def test_joining_and_moving_ends():
    p, q = Polyline([[0, 0], [1, 0]]), Polyline([[1, 0], [1, 1]])
    assert p.joined(q).vertices.tolist() == [[0, 0], [1, 0], [1, 1]]
    arc = Arc(np.zeros(2), 1.0, 0.0, 90.0)
    assert p.joined(arc) is None and arc.joined(p) is None
    assert arc.with_end_moved(True, [5, 5]) is None  # an arc cannot move an end alone
    moved = BSpline(2, np.array([[0, 0], [1, 1], [2, 0]])).with_end_moved(True, [2, 0.5])
    assert np.array_equal(moved.ends[1], [2, 0.5]) and np.array_equal(moved.ends[0], [0, 0])
    chain = Chain((p, q))
    assert np.array_equal(chain.with_end_moved(False, [-1, 0]).ends[0], [-1, 0])
    assert chain.point_count == 4 and chain.parts() == (p, q)


def test_a_new_curve_kind_is_one_class(tmp_path):
    """A kind the package does not know, defined by its own class alone, is written and read back by the drawings."""
    pytest.importorskip("ezdxf")
    pytest.importorskip("svgelements")
    from dataclasses import dataclass

    from sectiondeform.io import read_case, write_case
    from sectiondeform.laws import AreaRatio
    from sectiondeform.problem import Problem

    @dataclass(frozen=True, eq=False)
    class Parabola(Curve):
        """y = x^2 / 10 for x in [x0, x1] (parametrised by x: enough for this test)."""

        x0: float
        x1: float
        kind = "parabola"

        def at_fractions(self, s):
            x = self.x0 + np.clip(np.asarray(s, dtype=float), 0, 1) * (self.x1 - self.x0)
            return np.column_stack((x, x * x / 10))

        def discretise(self, tol):
            s = np.linspace(0.0, 1.0, 201)
            return self.at_fractions(s), s

        @property
        def length(self):
            p = self.discretise(0)[0]
            return float(np.hypot(*np.diff(p, axis=0).T).sum())

        def reversed(self):
            return Polyline(self.discretise(0)[0][::-1])

        def transformed(self, matrix, offset=(0.0, 0.0), tol=1e-3):
            return Polyline(self.discretise(0)[0]).transformed(matrix, offset, tol)

        def green(self):
            return Polyline(self.discretise(0)[0]).green()

        def to_json(self):
            return Polyline(self.discretise(0)[0]).to_json()

    lower = Parabola(-5.0, 5.0)
    upper = Polyline([[5.0, 2.5], [0.0, 6.0], [-5.0, 2.5]])
    case = Problem.single(lower, upper, Polyline([[-6.0, 0.0], [6.0, 0.0]]), AreaRatio(0.9), name="p")
    for ext in (".svg", ".dxf"):
        write_case(tmp_path / f"p{ext}", case)
        back = read_case(tmp_path / f"p{ext}")
        assert np.allclose(back.lower.ends[0], lower.ends[0], atol=1e-9)
        assert np.allclose(back.lower.ends[1], lower.ends[1], atol=1e-9)
        x, y = back.lower.at_fractions(FR).T  # every point on the parabola, within the chords' sag
        assert np.abs(y - x * x / 10).max() < 1e-3
        assert back.lower.length == pytest.approx(lower.length, rel=1e-6)


def test_polygon_area_and_zigzag():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert polygon_area(square) == 1.0 and polygon_area(square[::-1]) == -1.0
    rng = np.random.default_rng(1)
    x = np.linspace(0, 10, 400)
    noisy = np.column_stack((x, 0.01 * rng.standard_normal(400)))
    smooth = np.column_stack((x, np.sin(x / 3)))
    assert zigzag_fraction(noisy) > 0.4 and zigzag_fraction(smooth) < 0.02
