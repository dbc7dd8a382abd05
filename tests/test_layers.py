import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from sectiondeform.layers import grow_mesh, node_frames, quad_jacobians, structured_quads
from sectiondeform.locate import locate


def _covered(mesh, pts):
    loc = locate(mesh.points, mesh.quads, pts)
    return loc.elements.size == len(pts)


def test_flat_base_gives_square_elements():
    base = np.column_stack((np.linspace(0, 10, 11), np.zeros(11)))
    cover = np.array([[10, 0], [10, 3.5], [0, 3.5], [0, 0]], float)
    mesh = grow_mesh(base, 1.0, 1, cover, 1e-9)
    assert mesh.n_layers == 4 and mesh.n_columns == 10
    assert np.allclose(mesh.jacobians(), 1.0)
    assert _covered(mesh, cover)


def test_concave_base_layers_do_not_fold():
    # a V-shaped valley: normals converge above it
    x = np.linspace(-10, 10, 41)
    base = np.column_stack((x, np.abs(x)))
    cover = np.array([[10, 10], [10, 16], [-10, 16], [-10, 10]], float)
    mesh = grow_mesh(base, 0.5, 1, cover, 1e-9)
    assert mesh.jacobians().min() > 0
    assert _covered(mesh, cover)


def test_overhanging_shoulders_are_covered_by_splayed_ends():
    base = np.column_stack((np.linspace(0, 10, 11), np.zeros(11)))
    cover = np.array([[10, 0], [12, 3], [11, 6], [-1, 6], [-2.5, 3], [0, 0]], float)
    mesh = grow_mesh(base, 1.0, 1, cover, 1e-9)
    assert mesh.jacobians().min() > 0
    assert _covered(mesh, cover)
    assert mesh.nodes[-1, 0, 0] < -2 and mesh.nodes[-1, -1, 0] > 11


@settings(max_examples=25, deadline=None)
@given(
    st.floats(-0.04, 0.04),  # curvature of the base
    st.floats(0.5, 2.0),  # element height
    st.floats(2.0, 12.0),  # section height
)
def test_grown_mesh_is_valid_and_covers(curvature, h, height):
    x = np.linspace(-10, 10, 21)
    base = np.column_stack((x, curvature * x**2))
    top = np.column_stack((x[::-1], curvature * x[::-1] ** 2 + height))
    cover = np.vstack((base[-1], top, base[0]))
    mesh = grow_mesh(base, h, 1, cover, 1e-9)
    assert mesh.jacobians().min() > 0
    assert _covered(mesh, cover)


def test_structured_quads_orientation():
    pts = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], float)
    assert quad_jacobians(pts, structured_quads(1, 2, 1)).min() > 0
    mirrored = pts * [-1, 1]
    assert quad_jacobians(mirrored, structured_quads(1, 2, -1)).min() > 0


def test_node_frames_bisect_corners():
    line = np.array([[0, 0], [1, 0], [1, 1]], float)
    t, n = node_frames(line, 1)
    assert np.allclose(t[1], [np.sqrt(0.5), np.sqrt(0.5)])
    assert np.allclose(n[1], [-np.sqrt(0.5), np.sqrt(0.5)])
    assert np.allclose(np.hypot(*n.T), 1.0)


def test_far_overhang_extends_the_base():
    from sectiondeform.layers import extend_base, plan_extension

    # a mushroom: 2 wide foot, 12 wide cap
    base = np.column_stack((np.linspace(0, 2, 5), np.zeros(5)))
    cover = np.array([[2, 0], [2, 1], [7, 1.2], [7, 4], [-5, 4], [-5, 1.2], [0, 1], [0, 0]], float)
    before, after = plan_extension(base, 1, cover, 0.5)
    assert before.max() >= 5 and after.max() >= 5
    ext = extend_base(base, before, after)
    mesh = grow_mesh(ext, 0.5, 1, cover, 1e-9)
    assert mesh.jacobians().min() > 0
    assert _covered(mesh, cover)


def test_concave_corner_keeps_elements_open():
    """Layers in a right-angled corner: smoothing is raised before elements are squeezed flat."""
    base = np.concatenate((np.column_stack((np.zeros(40), np.linspace(10, 0.25, 40))),
                           np.column_stack((np.linspace(0, 30, 121), np.zeros(121)))))
    cover = np.array([[30, 0], [30, 3.5], [3.5, 3.5], [3.5, 10], [0, 10]], float)
    mesh = grow_mesh(base, 0.25, 1, cover, 1e-9)
    assert mesh.jacobians().min() > 0
    assert _covered(mesh, cover)
