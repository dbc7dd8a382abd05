"""The finite-element reference of an assembly of bonded bodies, and ``validate`` on assemblies."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

import sectiondeform as sd

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.compare import hausdorff_distance  # noqa: E402
from sectiondeform.io.case import case_from_dict  # noqa: E402
from sectiondeform.reference import solve_reference  # noqa: E402
from sectiondeform.reference.mesh import triangulate  # noqa: E402
from sectiondeform.reference.validation import draw_validation, validate  # noqa: E402

from conftest import CASES_DIR  # noqa: E402

STRIP = CASES_DIR / "v2" / "two-layer-strip.json"
W, H0, H1 = 20.0, 2.0, 3.0  # width, lower and upper layer thicknesses, mm
SUPPORT = {"polyline": [[0.0, 0.0], [W, 0.0]]}
# An arc of the support's length (20 mm), sagging 2 mm: a real bend of both layers.
ARC_R = 26.0
ARC_HALF = W / (2 * ARC_R)
ARC = {"arc": {"center": [W / 2, ARC_R - 2.0 - ARC_R * (1 - math.cos(ARC_HALF))],
               "radius": ARC_R, "start_deg": -90 - math.degrees(ARC_HALF), "end_deg": -90 + math.degrees(ARC_HALF)}}
MESH = 0.4  # coarse: a few hundred triangles per body


def box(y0: float, y1: float) -> dict:
    """Lower and upper curves of the rectangle [0, W] x [y0, y1] (upper points every 2 mm along its top)."""
    top = [[x, y1] for x in np.linspace(W, 0.0, 11)]
    return {"lower": {"polyline": [[0.0, y0], [W, y0]]},
            "upper": {"polyline": [[W, y0], [W, 0.5 * (y0 + y1)], *top, [0.0, 0.5 * (y0 + y1)], [0.0, y0]]}}


def stack(laws=(0.9, 0.9), materials=(None, None), target=ARC, revolution=None, support=SUPPORT):
    bodies = []
    for name, (y0, y1), law, mat in zip(("low", "top"), ((0.0, H0), (H0, H0 + H1)), laws, materials):
        body = {"name": name, **box(y0, y1), "law": law if isinstance(law, dict) else {"area_ratio": law}}
        if mat is not None:
            body["material"] = mat
        bodies.append(body)
    if support is not SUPPORT:
        bodies[0]["lower"] = support
    data = {"format": "section-case/2", "support": support, "target": target, "bodies": bodies}
    if revolution is not None:
        data["revolution"] = {"axis": revolution}
    return case_from_dict(data)


def union_case(law=0.9, target=ARC):
    """The two layers as one body: the same outline, the interface's ends kept as upper points."""
    top = [[x, H0 + H1] for x in np.linspace(W, 0.0, 11)]
    upper = [[W, 0.0], [W, H0 / 2], [W, H0], [W, H0 + H1 / 2], *top, [0.0, H0 + H1 / 2], [0.0, H0], [0.0, H0 / 2], [0.0, 0.0]]
    return sd.case_from_dict({"format": "section-case/1", "lower": SUPPORT, "upper": {"polyline": upper},
                              "target": target, "law": {"area_ratio": law}})


@pytest.fixture(scope="module")
def stacked():
    return solve_reference(stack(), mesh_size=MESH)


def test_shared_nodes_are_shared_and_the_interface_is_interior():
    a = stack()
    m = triangulate(a, MESH)
    # no two vertices in one place: nothing to open a gap
    assert len(cKDTree(m.points).query_pairs(1e-9 * a.size)) == 0
    # every body is covered exactly by its own triangles
    assert [m.body_area(b) for b in (0, 1)] == pytest.approx([W * H0, W * H1], rel=1e-12)
    # the upper body's A and B are the lower body's top corners: one vertex each
    sec_top = sd.build_section(a.body_case(1))
    ends = m.contour_nodes[1][[0, len(sec_top.lower) - 1]]
    np.testing.assert_array_equal(ends, m.upper_nodes[0][[-3, 2]])
    # each edge on the interface y = H0 has one triangle of each body; edges with one triangle are the outline only
    t = m.triangles
    edges = np.sort(np.concatenate((t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]])), axis=1)
    owner = np.tile(m.body, 3)
    keys, inverse, counts = np.unique(edges, axis=0, return_inverse=True, return_counts=True)
    p = m.points
    on_interface = (np.abs(p[keys[:, 0], 1] - H0) < 1e-12) & (np.abs(p[keys[:, 1], 1] - H0) < 1e-12)
    assert on_interface.sum() >= W / (MESH * H0)  # split to the finer body's size
    assert (counts[on_interface] == 2).all()
    for k in np.flatnonzero(on_interface)[:50]:
        assert sorted(owner[inverse.ravel() == k].tolist()) == [0, 1]
    boundary = keys[counts == 1]
    mid = 0.5 * (p[boundary[:, 0]] + p[boundary[:, 1]])
    outline = (np.abs(mid[:, 0]) < 1e-12) | (np.abs(mid[:, 0] - W) < 1e-12) | (np.abs(mid[:, 1]) < 1e-12) \
        | (np.abs(mid[:, 1] - H0 - H1) < 1e-12)
    assert outline.all()
    # the prescribed nodes are the support's, by their fraction along it
    np.testing.assert_allclose(p[m.lower_nodes, 1], 0.0, atol=0)
    np.testing.assert_allclose(m.lower_fractions, p[m.lower_nodes, 0] / W, atol=1e-12)


def test_two_equal_layers_reproduce_the_one_body_reference_of_their_union(stacked):
    one = solve_reference(union_case(), mesh_size=MESH)
    fine = solve_reference(union_case(), mesh_size=MESH / 2)
    # the union's upper points: the lower layer's sides, then the upper layer's upper curve
    low, top = stacked.bodies[0].upper, stacked.bodies[1].upper
    mine = np.concatenate((low[:2], top, low[-2:]))
    gap = np.hypot(*(mine - one.bodies[0].upper).T).max()
    # the discretisation error of the one-body reference at this size: how far it moves when the mesh is halved
    discretisation = np.hypot(*(one.bodies[0].upper - fine.bodies[0].upper).T).max()
    assert discretisation < 0.01 * (H0 + H1)
    # the two meshes differ (the interface is a line of nodes in one), so each is within its discretisation
    # error of the exact solution and the two within twice that (measured: 0.0067 mm against 0.0049 mm)
    assert gap < 2.0 * discretisation
    assert hausdorff_distance(mine, one.bodies[0].upper) <= gap + 1e-12
    # and both layers' areas add up to the union's
    total = sum(b.area_final for b in stacked.bodies)
    assert total == pytest.approx(one.bodies[0].area_final, rel=1e-5)


def test_each_body_meets_its_own_law_up_to_compressibility():
    # the laws differ by body (0.95 under 0.9): each body's area is r x its own
    a = stack(laws=(0.95, 0.85), materials=({"shear_modulus": 3.0}, {"shear_modulus": 1.0}))
    stiff = solve_reference(a, mesh_size=MESH, bulk_to_shear=1000.0)
    stiffer = solve_reference(a, mesh_size=MESH, bulk_to_shear=10000.0)
    for b, c in zip(stiff.bodies, stiffer.bodies):
        assert b.load == pytest.approx(1.0 / {"low": 0.95, "top": 0.85}[b.name])
        # in generalised plane strain the area error is exactly the mean elastic volume change
        assert b.relative_error == pytest.approx(b.volume_change, rel=1e-9, abs=1e-15)
        # measured: 3.9e-5 (lower) and 1.4e-4 (upper) at bulk/shear 1000, and it falls as 1 / (bulk/shear):
        # each body has its own pressure, so its own volume constraint
        assert abs(b.relative_error) < 1e-3
        assert abs(c.relative_error) == pytest.approx(abs(b.relative_error) / 10, rel=0.1)


@pytest.mark.parametrize("revolution", [None, [[0.0, -30.0], [1.0, -30.0]]])
def test_identity_and_rigid_motion_move_the_assembly_rigidly(revolution):
    laws = ({"area_ratio": 1.0}, {"area_ratio": 1.0}) if revolution is None else ({"volume_ratio": 1.0},) * 2
    mats = ({"shear_modulus": 5.0}, {"model": "mooney-rivlin", "c10": 0.3, "c01": 0.1})
    a = stack(laws=laws, materials=mats, target=SUPPORT, revolution=revolution)
    ref = solve_reference(a, mesh_size=0.8)
    sections = [sd.build_section(a.body_case(b)) for b in range(2)]
    for b, sec in zip(ref.bodies, sections):
        np.testing.assert_allclose(b.upper, sec.upper, atol=1e-9 * a.size)
    np.testing.assert_allclose(ref.mesh.points, ref.initial_mesh.points, atol=1e-9 * a.size)
    if revolution is not None:
        return  # moving a body of revolution off its axis stretches its hoops: no rigid motion there
    angle, shift = math.radians(25.0), np.array([7.0, -3.0])
    rot = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    moved = {"polyline": (np.array(SUPPORT["polyline"]) @ rot.T + shift).tolist()}
    ref = solve_reference(stack(laws=laws, materials=mats, target=moved), mesh_size=0.8)
    for b, sec in zip(ref.bodies, sections):
        np.testing.assert_allclose(b.upper, sec.upper @ rot.T + shift, atol=1e-9 * a.size)
    np.testing.assert_allclose(ref.mesh.points, ref.initial_mesh.points @ rot.T + shift, atol=1e-9 * a.size)


def test_a_stiffer_lower_layer_holds_the_shrinking_upper_layer_wider():
    # the upper layer shrinks (r = 0.85), the lower one not (r = 1), the support stays: the interface is pulled
    # inwards by the upper layer, and the stiffer the lower layer the less it gives way
    def interface_corner(mu_low):
        a = stack(laws=(1.0, 0.85), materials=({"shear_modulus": mu_low}, {"shear_modulus": 1.0}), target=SUPPORT)
        ref = solve_reference(a, mesh_size=MESH)
        corner = ref.bodies[0].upper[2]  # the lower layer's top right corner, (W, H0), shared with the top layer
        top_corner = ref.bodies[1].upper[0]  # the top layer's own lower right corner: the same point
        np.testing.assert_array_equal(corner, top_corner)
        return corner[0] - W

    soft, even, stiff = interface_corner(0.2), interface_corner(1.0), interface_corner(20.0)
    assert soft < even < stiff < 0.0  # always pulled in, less and less
    assert abs(stiff) < 0.2 * abs(soft)


def test_validate_compares_every_body(tmp_path):
    case = sd.load_case(STRIP)
    v = validate(case, model="hyperelastic", mesh_size=0.4, fast_runs=1)
    text = "\n".join(v.lines())
    assert "body 'backing'" in text and "body 'cover'" in text
    report = v.to_json()
    assert [b["name"] for b in report["bodies"]] == ["backing", "cover"]
    for b, body in zip(report["bodies"], case.bodies):
        # each body's figures are its own: the distance between its two upper curves, its own law
        upper_f, upper_r = np.array(b["fast"]["upper"]), np.array(b["reference"]["upper"])
        assert b["max_pointwise"] == pytest.approx(np.hypot(*(upper_f - upper_r).T).max(), rel=1e-12)
        assert b["hausdorff"] <= b["max_pointwise"] + 1e-12
        assert b["hausdorff_over_thickness"] == pytest.approx(b["hausdorff"] / b["thickness"])
        assert abs(b["fast"]["relative_error"]) < 1e-9  # the fast models meet the laws exactly
        assert abs(b["reference"]["relative_error"]) < 1e-3  # up to the bulk modulus (measured 1e-4, 2.4e-4)
        assert b["reference"]["load"] == pytest.approx(1.0 / body.law.ratio)
        # the hyperelastic model solves the same mechanics on a coarse mesh: within 2 % of the body's thickness
        assert b["hausdorff_over_thickness"] < 0.02
    json.dumps(report)
    pytest.importorskip("matplotlib")
    assert len(draw_validation(v).axes) >= 1


def test_validate_bodies_of_revolution_gives_volumes_per_body():
    a = stack(laws=({"volume_ratio": 1.0}, {"volume_ratio": 0.97}), target=ARC, revolution=[[0.0, -40.0], [1.0, -40.0]])
    v = validate(a, model="paper", mesh_size=0.8, fast_runs=1)
    assert v.revolution and v.to_json()["revolution"]["axis"] == [[0.0, -40.0], [1.0, -40.0]]
    for b in v.bodies:
        assert b.measure == "volume"
        assert abs(b.fast_error) < 1e-8 and abs(b.reference_error) < 1e-3
    assert v.height == pytest.approx(H0 + H1)
    assert [line.split()[1] for line in v.lines() if line.startswith("  body")] == ["'low'", "'top'"]
