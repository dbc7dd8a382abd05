"""The finite-element reference on bodies of revolution: hoop stretch, radius weighting, volumetric growth.

Checks against closed forms: a free homothety about the axis with growth v = g³
is stress free; a thick incompressible ring bonded inside and expanded radially
keeps, far from its free ends, r² − a² = v (R² − A²) (every annular strip keeps
area × radius); and every strip of elements keeps its Pappus volume, computed
here from the deformed quadratic triangles alone, ever better as the mesh is
refined.
"""

from __future__ import annotations

import numpy as np
import pytest

import sectiondeform as sd

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from skfem.quadrature import get_quadrature  # noqa: E402
from skfem.refdom import RefTri  # noqa: E402

from sectiondeform.laws import VolumeRatio  # noqa: E402
from sectiondeform.materials import NeoHookean  # noqa: E402
from sectiondeform.problem import Revolution  # noqa: E402
from sectiondeform.reference import solve_reference  # noqa: E402
from sectiondeform.reference.mesh import triangulate  # noqa: E402
from sectiondeform.reference.revolution import axis_from_points, polygon_first_moment  # noqa: E402
from sectiondeform.reference.solver import MixedProblem  # noqa: E402

AXIS = [[0.0, 0.0], [1.0, 0.0]]  # the x axis: the radius is y
A, T, GROW = 10.0, 4.0, 12.0  # inner radius, wall thickness, inner radius after expansion


def ring(length=16 * T, inner=A, outer=A + T, a=GROW):
    """Annular rectangle section: x along the axis, y the radius; bonded inside, expanded to radius ``a``."""
    top = [[x, outer] for x in np.linspace(length, 0.0, 13)]
    return sd.case_from_dict({
        "format": "section-case/1", "name": "ring",
        "lower": {"polyline": [[0.0, inner], [length, inner]]},
        "upper": {"polyline": [[length, inner]] + top + [[0.0, inner]]},
        "target": {"polyline": [[0.0, a], [length, a]]},
        "law": {"area_ratio": 1.0},
    })


def revolve(case, v, axis=AXIS):
    """The one body of ``case`` as a body of revolution about ``axis`` under the volume law ``v``."""
    return case.replace(law=VolumeRatio(v), revolution=Revolution(tuple(map(tuple, axis))), dialect="section-case/2")


def p2_volumes(initial, deformed, cells, radius):
    """Volume (per radian) ∫ r dA of each deformed quadratic triangle, from its six nodes only."""
    corners = initial[cells[:, :3]]
    mids = initial[cells[:, 3:]]
    # Order the mid-edge nodes as edges (0, 1), (1, 2), (2, 0) by their initial position.
    edges = 0.5 * (corners + np.roll(corners, -1, axis=1))
    match = np.argmin(np.linalg.norm(mids[:, None, :, :] - edges[:, :, None, :], axis=-1), axis=2)
    mid_nodes = np.take_along_axis(cells[:, 3:], match, axis=1)
    x = np.concatenate((deformed[cells[:, :3]], deformed[mid_nodes]), axis=1)  # (M, 6, 2)
    X, w = get_quadrature(RefTri, 4)
    xi, eta = X
    l0, l1, l2 = 1.0 - xi - eta, xi, eta
    N = np.stack((l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), 4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0))
    dxi = np.stack((-(4 * l0 - 1), 4 * l1 - 1, 0 * xi, 4 * (l0 - l1), 4 * l2, -4 * l2))
    deta = np.stack((-(4 * l0 - 1), 0 * xi, 4 * l2 - 1, -4 * l1, 4 * l1, 4 * (l0 - l2)))
    pos = np.einsum("kq,mkd->mqd", N, x)
    jx, je = np.einsum("kq,mkd->mqd", dxi, x), np.einsum("kq,mkd->mqd", deta, x)
    det = jx[..., 0] * je[..., 1] - jx[..., 1] * je[..., 0]
    return np.sum(radius(pos) * det * w, axis=1)


# --- exact solutions ---------------------------------------------------------------------


@pytest.mark.parametrize("g", [0.9, 1.1])
def test_free_growth_about_the_axis_is_stress_free(g):
    """Target = lower scaled by g from a point of the axis, growth v = g³: F = g I, no stress, every node at g X."""
    case = sd.case_from_dict({
        "format": "section-case/1",
        "lower": {"polyline": [[0.0, 5.0], [8.0, 6.0]]},
        "upper": {"polyline": [[8.0, 6.0], [7.0, 9.0], [2.0, 10.0], [0.0, 5.0]]},
        "target": {"polyline": [[0.0, 5.0 * g], [8.0 * g, 6.0 * g]]},
        "law": {"area_ratio": 1.0},
    })
    ref = solve_reference(revolve(case, g**3), mesh_size=0.4)
    np.testing.assert_allclose(ref.mesh.points, g * ref.initial_mesh.points, atol=1e-9)
    assert abs(ref.strain_energy) < 1e-12 * ref.bodies[0].volume_initial
    np.testing.assert_allclose(ref.cauchy, 0.0, atol=1e-9)
    assert ref.bodies[0].volume_final == pytest.approx(g**3 * ref.bodies[0].volume_initial, rel=1e-12)
    assert ref.bodies[0].area_target is None and ref.summary()["bodies"][0]["stretch_z"] is None


def test_translation_along_the_axis_is_stress_free():
    case = ring(length=2 * T, a=A)
    moved = {"polyline": [[3.0, A], [3.0 + 2 * T, A]]}
    ref = solve_reference(revolve(case, 1.0), sd.curve_from_json(moved), mesh_size=0.4)
    np.testing.assert_allclose(ref.mesh.points, ref.initial_mesh.points + [3.0, 0.0], atol=1e-9)
    assert abs(ref.strain_energy) < 1e-10


@pytest.mark.parametrize("v", [1.0, 0.9])
def test_thick_ring_keeps_area_times_radius_of_every_annular_strip(v):
    """Far from the free ends: r² − a² = v (R² − A²), and no axial motion (to 0.1 % of the wall)."""
    length = 16 * T
    ref = solve_reference(revolve(ring(length), v), mesh_size=0.8, bulk_to_shear=1e5)
    P0, P1 = ref.initial_mesh.points, ref.mesh.points
    mid = np.abs(P0[:, 0] - length / 2) <= T
    assert mid.sum() > 10
    exact = np.sqrt(GROW**2 + v * (P0[mid, 1] ** 2 - A**2))
    assert np.abs(P1[mid, 1] - exact).max() < 1e-3 * T
    assert np.abs(P1[mid, 0] - P0[mid, 0]).max() < 1e-3 * T
    # The whole body meets its law up to the finite bulk modulus.
    assert ref.bodies[0].relative_error == pytest.approx(ref.bodies[0].volume_change, rel=1e-6, abs=1e-14)
    assert abs(ref.bodies[0].relative_error) < 1e-4


def test_strips_of_elements_keep_their_volume_better_as_the_mesh_is_refined():
    """Each band of triangles (by initial radius) keeps v × its Pappus volume; the worst error falls with h."""
    v = 0.9
    ax = axis_from_points(AXIS, np.array([[0.0, A], [1.0, A + T]]))
    worst = []
    for h in (0.8, 0.4, 0.2):
        ref = solve_reference(revolve(ring(4 * T), v), mesh_size=h, bulk_to_shear=1e5)
        cells = ref.initial_mesh.cells
        before = p2_volumes(ref.initial_mesh.points, ref.initial_mesh.points, cells, ax.radius)
        after = p2_volumes(ref.initial_mesh.points, ref.mesh.points, cells, ax.radius)
        # The deformed mesh's volume, from the geometry alone, is the solver's.
        assert 2 * np.pi * after.sum() == pytest.approx(ref.bodies[0].volume_final, rel=1e-10)
        assert before.sum() == pytest.approx(polygon_first_moment([[0, A], [4 * T, A], [4 * T, A + T], [0, A + T]], ax), rel=1e-12)
        r_mid = ref.initial_mesh.points[cells[:, :3]].mean(axis=1)[:, 1]
        band = np.minimum(((r_mid - A) / T * 4).astype(int), 3)
        ratio = np.bincount(band, after) / np.bincount(band, before)
        worst.append(np.abs(ratio / v - 1.0).max())
    assert worst[-1] < 2e-3
    assert worst[0] > worst[1] > worst[2]


# --- the discrete problem ------------------------------------------------------------------


def test_tangent_is_the_residual_derivative_for_a_grown_body_of_revolution():
    from sectiondeform.materials import MooneyRivlin

    case = revolve(ring(2 * T), 0.85)
    sec = sd.build_section(case)
    mesh = triangulate(case, 0.6 * T / sec.mesh_scale)
    pr = MixedProblem(mesh, [MooneyRivlin(0.3, 0.1, bulk_to_shear=200.0)], axis=axis_from_points(AXIS, sec.contour))
    rng = np.random.default_rng(3)
    x = np.concatenate((0.004 * T * rng.standard_normal(pr.n_u), 0.1 * rng.standard_normal(pr.n_p)))
    K = pr.tangent(pr.material(x, 0.85))
    dx = rng.standard_normal(len(x))
    eps = 1e-6
    fd = (pr.residual(x + eps * dx, 0.85) - pr.residual(x - eps * dx, 0.85)) / (2 * eps)
    np.testing.assert_allclose(K @ dx, fd, atol=1e-6 * np.abs(fd).max())
    assert abs(K - K.T).max() < 1e-10 * abs(K).max()
    # The residual is the energy's gradient.
    e = (pr.energy(x + eps * dx, 0.85) - pr.energy(x - eps * dx, 0.85)) / (2 * eps)
    assert e == pytest.approx(pr.residual(x, 0.85) @ dx, rel=1e-6)


def test_a_body_of_revolution_takes_its_axis_law_and_material():
    case = revolve(ring(2 * T), 0.95).replace(material='{"model": "yeoh", "c10": 0.4, "c20": 0.01, "c30": 0.0}')
    ref = solve_reference(case, mesh_size=0.5)
    body = ref.bodies[0]
    assert ref.revolution and body.load == 0.95 and body.material.model == "yeoh" and body.measure == "volume"
    assert abs(body.relative_error) < 1e-3
    assert ref.summary()["revolution"]["axis"][0] == [0.0, 0.0]


# --- refusals ------------------------------------------------------------------------------


def test_refusals_name_the_field():
    case = ring(2 * T)
    with pytest.raises(sd.GeometryError, match="the revolution axis crosses it"):  # refused by the problem itself
        solve_reference(revolve(case, 1.0, [[0.0, 11.0], [1.0, 11.0]]))
    with pytest.raises(sd.CaseError, match="coincide"):
        solve_reference(revolve(case, 1.0, [[0.0, 0.0], [0.0, 0.0]]))
    area_law = case.replace(revolution=Revolution(tuple(map(tuple, AXIS))), dialect="section-case/2")
    with pytest.raises(sd.CaseError, match=r"bodies\[0\]\.law\.area_ratio: a body of revolution needs a volume law"):
        solve_reference(area_law)
    with pytest.raises(sd.CaseError, match=r"law\.volume_ratio: must be between"):
        solve_reference(revolve(case, 1000.0))
    with pytest.raises(sd.CaseError, match=r"material\.bulk_to_shear"):
        solve_reference(revolve(case, 1.0), material=NeoHookean(1.0, bulk_to_shear=50.0))


def test_p2_moments_of_an_affinely_moved_mesh_are_its_polygon_moment():
    from sectiondeform.reference.revolution import p2_first_moments

    ref = solve_reference(revolve(ring(2 * T), 1.0), mesh_size=0.5)
    M = np.array([[1.1, 0.3], [-0.2, 0.9]])
    moved = ref.initial_mesh.points @ M.T + [1.0, 20.0]
    ax = axis_from_points(AXIS, moved)
    contour = np.array([[0, A], [2 * T, A], [2 * T, A + T], [0, A + T]]) @ M.T + [1.0, 20.0]
    total = p2_first_moments(ref.initial_mesh.points, moved, ref.initial_mesh.cells, ax).sum()
    assert total == pytest.approx(polygon_first_moment(contour, ax), rel=1e-12)


def test_the_ring_study_figures():
    from sectiondeform.reference.ring import ring_case, ring_figures

    ref = solve_reference(ring_case(0.9), mesh_size=0.8)
    f = ring_figures(ref, 0.9)
    assert f["analytic"] < 1e-4 and f["strips"] < 2e-4


def tread_on_crown():
    """The public example's tread alone, laid on the drum and shaped to the crown arc (one body of revolution)."""
    import json

    from conftest import CASES_DIR

    data = json.loads((CASES_DIR / "v2" / "tread-on-drum.json").read_text())
    tread = data["bodies"][1]

    def down(c):  # the tread rests at y = 3 on the undertread: lay it on y = 0
        if "polyline" in c:
            return {"polyline": [[x, y - 3.0] for x, y in c["polyline"]]}
        if "arc" in c:
            return {"arc": {**c["arc"], "center": [c["arc"]["center"][0], c["arc"]["center"][1] - 3.0]}}
        return {"chain": [down(p) for p in c["chain"]]}

    arc = data["target"]["arc"]
    a0, a1 = arc["start_deg"], arc["end_deg"]
    crown = {"arc": {"center": arc["center"], "radius": arc["radius"],  # the support's stretch of x from 10 to 140
                     "start_deg": a0 + 10 / 150 * (a1 - a0), "end_deg": a0 + 140 / 150 * (a1 - a0)}}
    case = sd.case_from_dict({"format": "section-case/1", "name": "tread-on-crown", "lower": down(tread["lower"]),
                              "upper": down(tread["upper"]), "target": crown, "law": {"area_ratio": 1.0}})
    return case, tread["law"]["volume_ratio"], data["revolution"]["axis"]


def test_a_tread_shaped_off_its_axis_keeps_area_times_centroid_radius():
    """Pappus on the deformed polygon: A1 r1 = v A0 r0, the area falling as the centroid moves out (to 1e-3)."""
    case, v, axis = tread_on_crown()
    ref = solve_reference(revolve(case, v, axis), mesh_size=0.4)
    ax = ref.axis
    assert abs(ref.bodies[0].relative_error) < 5e-4
    centre = np.asarray(case.target.to_json()["arc"]["center"])
    lower = ref.mesh.points[ref.mesh_data.lower_nodes]
    np.testing.assert_allclose(np.hypot(*(lower - centre).T), 200.0, rtol=1e-9)

    before = sd.build_section(case).contour
    after = np.concatenate((lower, ref.bodies[0].upper[1:-1]))
    m0, m1 = polygon_first_moment(before, ax), polygon_first_moment(after, ax)
    assert abs(m1 / m0 / v - 1.0) < 1e-3
    a0, a1 = abs(_area(before)), abs(_area(after))
    r0, r1 = m0 / a0, m1 / a1
    assert r1 > r0 + 20.0  # moved about 25 mm out
    assert a1 / a0 == pytest.approx(v * r0 / r1, rel=1e-3)


def _area(poly):
    x, y = np.asarray(poly).T
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
