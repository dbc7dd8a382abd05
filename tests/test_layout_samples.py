"""The layout check's samples of a curve come in the curve's own order.

The samples (a fine polyline's vertices and evenly spaced points) are merged
by their fractions of the curve. The oracle is independent of those
fractions: each sample's distance along the fine polyline, found by
projecting it onto the polyline (shapely's ``line_locate_point``, what the
check used before), must not decrease, and every sample lies on the curve.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.curves import Arc, BSpline, Chain, Polyline
from sectiondeform.layout import SAMPLES, _samples

coordinate = st.floats(-100, 100, allow_nan=False)


@st.composite
def polylines(draw):
    """A polyline that goes on in x (no piece comes back near another: the projection is then the order)."""
    n = draw(st.integers(2, 12))
    steps = draw(st.lists(st.floats(0.5, 20), min_size=n - 1, max_size=n - 1))
    ys = draw(st.lists(st.floats(-5, 5), min_size=n, max_size=n))
    x0, y0 = draw(coordinate), draw(coordinate)
    x = x0 + np.concatenate(([0.0], np.cumsum(steps)))
    return Polyline(np.column_stack((x, y0 + np.asarray(ys))))


@st.composite
def arcs(draw):
    radius = draw(st.floats(1, 500))
    start = draw(st.floats(-180, 180))
    sweep = draw(st.floats(5, 300)) * draw(st.sampled_from([-1, 1]))
    return Arc(center=(draw(coordinate), draw(coordinate)), radius=radius, start_deg=start, end_deg=start + sweep)


@st.composite
def splines(draw):
    n = draw(st.integers(4, 9))
    ys = draw(st.lists(st.floats(-5, 5), min_size=n, max_size=n))
    points = np.column_stack((np.linspace(0.0, 10.0 * n, n), ys))
    degree = 3
    knots = np.concatenate(([0.0] * degree, np.linspace(0.0, 1.0, n - degree + 1), [1.0] * degree))
    return BSpline(degree=degree, control_points=points, knots=knots)


@st.composite
def chains(draw):
    first = draw(polylines())
    end = first.vertices[-1]
    radius = draw(st.floats(2, 50))
    arc = Arc(center=(end[0], end[1] + radius), radius=radius, start_deg=-90.0, end_deg=-30.0)
    return Chain((first, arc))


@settings(max_examples=60, deadline=None)
@given(st.one_of(polylines(), arcs(), splines(), chains()), st.floats(1e-4, 1.0))
def test_the_samples_follow_the_curve_in_order(curve, tol):
    fine, fractions = curve.discretise(tol)
    samples = _samples(curve, fine, fractions)
    assert samples.shape == (len(fine) + SAMPLES + 1, 2)
    line = shapely.LineString(fine)
    along = shapely.line_locate_point(line, shapely.points(samples))
    slack = 1e-9 * curve.length + 2.0 * tol  # a sample between two vertices projects within the chordal error
    assert np.all(np.diff(along) >= -slack)
    assert along[0] <= slack and along[-1] >= line.length - slack
    assert np.allclose(samples[0], curve.at_fractions(np.array([0.0]))[0])
    assert np.allclose(samples[-1], curve.at_fractions(np.array([1.0]))[0])


def test_a_closing_arc_keeps_its_order():
    """A circle nearly closed: its last points lie next to its first, where a projection could not tell them apart."""
    curve = Arc(center=(0.0, 0.0), radius=10.0, start_deg=0.0, end_deg=359.0)
    fine, fractions = curve.discretise(1e-3)
    samples = _samples(curve, fine, fractions)
    angles = np.unwrap(np.arctan2(samples[:, 1], samples[:, 0]))
    assert np.all(np.diff(angles) >= -1e-12) and math.isclose(angles[-1], math.radians(359.0), rel_tol=1e-12)
