"""One mesh of several bodies: shared nodes on shared pieces, each body covered exactly, per-body sizes."""

from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.errors import MeshError
from sectiondeform.fem.elements import geometry
from sectiondeform.fem.union_mesh import body_pressure_cells, union_mesh


def _box(x0, y0, x1, y1, n_bottom):
    """A rectangle, counter-clockwise, with ``n_bottom`` equal segments along its bottom and top."""
    xs = np.linspace(x0, x1, n_bottom + 1)
    bottom = np.column_stack((xs, np.full_like(xs, y0)))
    top = np.column_stack((xs[::-1], np.full_like(xs, y1)))
    return np.concatenate((bottom, top))


@settings(max_examples=25, deadline=None)
@given(
    width=st.floats(5.0, 60.0),
    low=st.floats(1.0, 6.0),
    high=st.floats(1.0, 12.0),
    n=st.integers(1, 12),
    through=st.floats(1.0, 3.0),
)
def test_two_stacked_boxes_share_the_nodes_of_their_interface(width, low, high, n, through):
    lower = _box(0.0, 0.0, width, low, n)
    upper = _box(0.0, low, width, low + high, n)
    sizes = np.array([low, high]) / through
    fixed = [np.array([0, n]), np.array([0, n])]
    mesh = union_mesh([lower, upper], fixed, sizes, 1e-9 * width)
    g = geometry(mesh.nodes, mesh.cells)
    assert g.detj_ratio.min() > 0
    # Each body is covered by its own cells: their areas add up to its rectangle's.
    for b, area in enumerate((width * low, width * high)):
        assert g.weight[mesh.body == b].sum() == pytest.approx(area, rel=1e-9)
    # The nodes of both bodies' cells on the interface are the same nodes, spaced by the finer size.
    on = [np.unique(mesh.cells[mesh.body == b])[np.abs(mesh.nodes[np.unique(mesh.cells[mesh.body == b]), 1] - low) <= 1e-9 * width]
          for b in (0, 1)]
    assert np.array_equal(on[0], on[1])
    xs = np.sort(mesh.nodes[on[0], 0])
    assert xs[0] == pytest.approx(0.0, abs=1e-9 * width) and xs[-1] == pytest.approx(width, rel=1e-12)
    assert np.diff(xs).max() <= 1.01 * sizes.min() + 1e-9
    # Every contour point (graph vertex) is found again from the undeformed nodes.
    assert np.abs(mesh.vertex_weights @ mesh.nodes - mesh.points).max() <= 1e-9 * width
    # The two rings meet in the interface's vertices only.
    assert len(np.intersect1d(mesh.rings[0], mesh.rings[1])) == n + 1
    _check_pressure_cells(mesh)


def _check_pressure_cells(mesh):
    """One pressure unknown per (corner node, body): continuous within a body, split at the nodes bodies share."""
    corner, pc = mesh.cells[:, :3], mesh.pressure_cells
    pairs = np.unique(np.column_stack((corner.ravel(), np.repeat(mesh.body, 3), pc.ravel())), axis=0)
    assert len(np.unique(pairs[:, :2], axis=0)) == len(pairs)  # a node of a body has one unknown: continuous in the body
    assert len(np.unique(pairs[:, 2])) == len(pairs) == mesh.n_pressures  # distinct across bodies, all used
    assert pairs[:, 2].min() == 0 and pairs[:, 2].max() == mesh.n_pressures - 1
    shared = np.intersect1d(*(np.unique(corner[mesh.body == b]) for b in (0, 1)))
    assert mesh.n_pressures == mesh.n_vertices + len(shared)
    lone = mesh.body[:, None] == 0  # the lower body's unknowns are its own nodes
    assert np.array_equal(pc[np.broadcast_to(lone, pc.shape)], corner[np.broadcast_to(lone, pc.shape)])


def test_one_bodys_pressure_unknowns_are_its_corner_nodes():
    mesh = union_mesh([_box(0.0, 0.0, 5.0, 2.0, 3)], [np.array([0, 3])], 0.7, 1e-9)
    assert np.array_equal(mesh.pressure_cells, mesh.cells[:, :3]) and mesh.n_pressures == mesh.n_vertices
    pc, count = body_pressure_cells(mesh.cells, mesh.body, mesh.n_vertices)
    assert np.array_equal(pc, mesh.cells[:, :3]) and count == mesh.n_vertices


@settings(max_examples=20, deadline=None)
@given(
    # the upper body's corners at the lower one's ends, or clearly inside: an edge a few contact tolerances
    # long (a = 1e-10: 3e-9 mm) is no narrower body but a sliver, refused with a MeshError
    a=st.one_of(st.just(0.0), st.floats(0.01, 0.45)),
    b=st.one_of(st.just(1.0), st.floats(0.55, 0.99)),
    low=st.floats(1.0, 6.0),
    high=st.floats(1.0, 12.0),
    through=st.floats(1.0, 3.0),
)
def test_a_narrower_body_on_part_of_another(a, b, low, high, through):
    # The upper body rests on the piece [a, b] of the lower one's top (30 mm wide); the lower ring
    # carries the upper one's corners as points of its top, as an assembly's preparation gives it.
    width = 30.0
    xa, xb = a * width, b * width
    top = [[width, low], [xb, low], [xa, low], [0.0, low]]
    lower = np.array([[0.0, 0.0], [width, 0.0]] + top)
    upper = np.array([[xa, low], [xb, low], [xb, low + high], [xa, low + high]])
    keep = np.concatenate(([True], np.hypot(*np.diff(lower, axis=0).T) > 1e-9))  # a = 0 or b = 1: one corner
    lower = lower[keep]
    mesh = union_mesh([lower, upper], [np.array([0, 1]), np.array([0, 1])], np.array([low, high]) / through, 1e-9)
    g = geometry(mesh.nodes, mesh.cells)
    assert g.detj_ratio.min() > 0
    for body, area in enumerate((width * low, (xb - xa) * high)):
        assert g.weight[mesh.body == body].sum() == pytest.approx(area, rel=1e-9)
    shared = np.intersect1d(np.unique(mesh.cells[mesh.body == 0]), np.unique(mesh.cells[mesh.body == 1]))
    assert np.allclose(mesh.nodes[shared, 1], low, atol=1e-9)
    assert mesh.nodes[shared, 0].min() == pytest.approx(xa, abs=1e-9) and mesh.nodes[shared, 0].max() == pytest.approx(xb, abs=1e-9)
    assert np.abs(mesh.vertex_weights @ mesh.nodes - mesh.points).max() <= 1e-9 * width


def test_a_non_positive_size_is_refused_with_one_line():
    box = _box(0.0, 0.0, 1.0, 1.0, 1)
    with pytest.raises(MeshError, match=r"^mesh: the element sizes \[1\.0, 0\.0\] are not positive finite lengths"):
        union_mesh([box, box + [0.0, 1.0]], [np.array([0, 1])] * 2, [1.0, 0.0], 1e-9)


def test_contours_touching_without_sharing_a_point_are_one_line_not_a_hang():
    """A T-junction: the upper body's contour point (1, 1) lies on the lower body's edge, which lacks it.

    No split makes the triangulation hold both pieces; the conforming loop halved the missing segments
    and re-ran Delaunay on twice the points per pass, for minutes. It now stops when the missing
    segments stop falling, and names the point in the way.
    """
    import time

    low = np.array([[0, 0], [2, 0], [2, 1], [0, 1]], float)
    top = np.array([[0, 1], [1, 1], [2, 1], [2, 2], [0, 2]], float)
    t0 = time.process_time()
    with pytest.raises(MeshError, match=r"^mesh: the mesh \(h = 0\.1\) cannot follow the contour segment .* the "
                                        r"contour point \([0-9.]+, 1\) of another piece lies on it"):
        union_mesh([low, top], [np.array([0, 1]), np.array([0, 2])], 0.1, 1e-9)
    assert time.process_time() - t0 < 2.0


def test_the_conforming_loop_checks_the_vertex_bound_before_each_delaunay(monkeypatch):
    """Whatever the splitting does, no Delaunay call gets more points than MAX_FE_VERTICES."""
    from scipy.spatial import Delaunay

    from sectiondeform.fem import union_mesh as module
    from sectiondeform.limits import MAX_FE_VERTICES

    sizes = []

    def counting(points, *args, **kwargs):
        sizes.append(len(points))
        return Delaunay(points, *args, **kwargs)

    monkeypatch.setattr(module, "Delaunay", counting)
    monkeypatch.setattr(module, "STALL_ITERATIONS", 10**6)  # only the vertex bound stops the T-junction now
    low = np.array([[0, 0], [2, 0], [2, 1], [0, 1]], float)
    top = np.array([[0, 1], [1, 1], [2, 1], [2, 2], [0, 2]], float)
    with pytest.raises(MeshError, match=r"^mesh: \d+ mesh vertices \(h = 0\.1, splitting .*\) needed, more than "
                                        r"the bound 3000"):
        module.union_mesh([low, top], [np.array([0, 1]), np.array([0, 2])], 0.1, 1e-9)
    assert sizes and max(sizes) <= MAX_FE_VERTICES


@settings(max_examples=15, deadline=None)
@given(
    width=st.floats(4.0, 30.0),
    height=st.floats(1.0, 6.0),
    start=st.floats(0.0, 0.8),
    ratio=st.sampled_from([2, 4]),
    through=st.floats(2.0, 6.0),
)
def test_a_fine_zone_halves_the_size_near_it_and_leaves_the_rest(width, height, start, ratio, through):
    """A box refined along a piece of its top: its edges there are the body's size over ``ratio``, far away the body's."""
    box = _box(0.0, 0.0, width, height, 1)
    h = height / through
    zone = shapely.LineString([(start * width, height), ((start + 0.2) * width, height)])
    plain = union_mesh([box], [np.array([0, 1])], h, 1e-9 * width)
    mesh = union_mesh([box], [np.array([0, 1])], h, 1e-9 * width, fine=[zone], fine_ratio=ratio)
    g = geometry(mesh.nodes, mesh.cells)
    assert g.detj_ratio.min() > 0.5 and g.weight.sum() == pytest.approx(width * height, rel=1e-9)
    assert np.abs(mesh.vertex_weights @ mesh.nodes - mesh.points).max() <= 1e-9 * width
    corner = mesh.cells[:, :3]
    edges = np.unique(np.sort(np.concatenate((corner[:, [0, 1]], corner[:, [1, 2]], corner[:, [2, 0]])), axis=1), axis=0)
    length = np.hypot(*(mesh.nodes[edges[:, 1]] - mesh.nodes[edges[:, 0]]).T)
    mid = shapely.points(0.5 * (mesh.nodes[edges[:, 0]] + mesh.nodes[edges[:, 1]]))
    d = shapely.distance(zone, mid)
    on_top = np.abs(mesh.nodes[edges, 1] - height).max(axis=1) <= 1e-9 * width
    # Along the zone the top's edges are the fine size (within the arc-length rounding of a chain's steps): every
    # top edge that touches the zone (a zone shorter than one fine edge holds no edge's midpoint).
    segments = shapely.linestrings(np.stack((mesh.nodes[edges[:, 0]], mesh.nodes[edges[:, 1]]), axis=1))
    along = on_top & (shapely.distance(zone, segments) <= 1e-9 * width)
    assert along.any() and length[along].max() <= 1.3 * h / ratio
    # The cells: the fine size on the zone, the body's from a size off it on (the grading's last halving).
    far = d > h * (2.0 - 2.0 / ratio) / 0.5 + 2.0 * h
    assert np.all(mesh.cell_size <= h) and mesh.cell_size.min() == pytest.approx(h / ratio)
    if far.any():
        assert length[far].max() <= 1.7 * h and np.median(length[far]) >= 0.7 * h
    assert len(mesh.nodes) > len(plain.nodes)
    # No zone, or a ratio of one, is the plain mesh to the bit.
    for same in (union_mesh([box], [np.array([0, 1])], h, 1e-9 * width, fine=[None]),
                 union_mesh([box], [np.array([0, 1])], h, 1e-9 * width, fine=[zone], fine_ratio=1)):
        assert np.array_equal(same.nodes, plain.nodes) and np.array_equal(same.cells, plain.cells)


def _sliver_points(eps):
    """A straight contour piece A-M-W (M off the line AW by ``eps``) over an interior point Q."""
    return np.array([[0.0, 0.0], [1.0, eps], [2.0, 0.0], [1.0, -1.0]])  # A, M, W, Q


@pytest.mark.parametrize("eps", [1e-13, -1e-13, 0.0])
def test_a_sliver_outside_the_body_along_its_contour_is_dropped(eps):
    from sectiondeform.fem.union_mesh import _edge_keys, _mend_slivers, _signed_areas

    pts = _sliver_points(eps)
    tri = np.array([[0, 1, 3], [1, 2, 3], [0, 2, 1]])  # the last: A, W, M, no height, its long edge AW shared with none
    seg = set(_edge_keys(np.array([[0, 1], [1, 2]]), 4).tolist())
    out, body = _mend_slivers(pts, tri.copy(), np.zeros(3, np.int64), seg)
    assert sorted(map(sorted, out.tolist())) == [[0, 1, 3], [1, 2, 3]] and len(body) == 2
    assert abs(_signed_areas(pts, out)).sum() == pytest.approx(1.0 + eps, abs=1e-15)


@pytest.mark.parametrize("eps", [1e-13, -1e-13, 0.0])
def test_a_sliver_sharing_its_long_edge_with_its_body_is_flipped_into_two_proper_triangles(eps):
    from sectiondeform.fem.union_mesh import SLIVER, _edge_keys, _mend_slivers, _signed_areas

    pts = _sliver_points(eps)
    tri = np.array([[0, 3, 2], [0, 2, 1]])  # A Q W below the line, and the sliver A W M on it
    seg = set(_edge_keys(np.array([[0, 1], [1, 2]]), 4).tolist())
    out, _ = _mend_slivers(pts, tri.copy(), np.zeros(2, np.int64), seg)
    assert sorted(map(sorted, out.tolist())) == [[0, 1, 3], [1, 2, 3]]
    areas = _signed_areas(pts, out)
    assert (areas > SLIVER).all() and areas.sum() == pytest.approx(1.0 + eps, abs=1e-15)


def test_a_thin_section_far_from_the_origin_meshes_without_slivers():
    """The fuzzing's thin section (0.3 mm by 17 mm, 3.8e6 mm from the origin): Delaunay's slivers along its straight
    top, on the points' hull, once left a triangle of no height (a divide-by-zero, then a refusal of a valid mesh).
    """
    import sectiondeform as sd
    from sectiondeform.deform import Deformer
    from sectiondeform.fem.union_mesh import SLIVER

    path = Path(__file__).parent / "data" / "fuzz-found" / "warning-fem-elements-sliver-on-the-hull-1380.json"
    with pytest.raises(sd.SectionDeformError) as info:  # its solve is past the work bound; the mesh is what is checked
        Deformer(sd.load_case(path), "hyperelastic").deform()
    assert "Newton stopped at its bound" in str(info.value)
    mesh = Deformer(sd.load_case(path), "hyperelastic").prepared.mesh
    corners = mesh.nodes[mesh.cells[:, :3]] - mesh.nodes[0]
    edges = corners[:, [1, 2, 0]] - corners
    longest2 = (edges * edges).sum(axis=2).max(axis=1)
    a, b = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    area = 0.5 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    assert (area > 0.5 * SLIVER * longest2).all()
