"""Holes and growth in the finite-element reference, ``validate`` and the CalculiX decks.

CalculiX tests need ccx: skipped without it, failing when SECTIONDEFORM_REQUIRE_CCX=1.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.cli import main
from sectiondeform.io.case import case_from_dict

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.reference import solve_reference  # noqa: E402
from sectiondeform.reference.mesh import triangulate  # noqa: E402

DATA = Path(__file__).parent / "data" / "cases" / "v2"
HOLLOW = DATA / "hollow-on-arc.json"
TUBE = DATA / "grown-tube.json"
R = 1.1
G = R ** (1.0 / 3.0)


def _circle(cx, cy, r, n=16):
    """A hole: a regular n-gon (few points, so coarse meshes stay coarse)."""
    t = np.linspace(0.0, 2.0 * np.pi, n + 1)
    return {"polyline": np.column_stack((cx + r * np.cos(t), cy + r * np.sin(t))).tolist()}


def _block(target, law, holes=(), width=4.0, height=2.0):
    """A plane block [0, width] x [0, height] on the x axis, its holes, its law."""
    body = {"name": "b", "lower": {"polyline": [[0, 0], [width, 0]]},
            "upper": {"polyline": [[width, 0], [width, height], [0, height], [0, 0]]}, "law": law}
    if holes:
        body["holes"] = list(holes)
    return case_from_dict({"format": "section-case/2", "support": {"polyline": [[0, 0], [width, 0]]},
                           "target": {"polyline": target}, "bodies": [body]})


def _inside(points, hole):
    import shapely

    return shapely.contains_xy(shapely.Polygon(hole), points[:, 0], points[:, 1])


# --- the reference ------------------------------------------------------------------------------------------


def test_the_reference_of_a_free_grown_hollow_block_is_the_closed_form():
    """Support grown with the body: every length x r^(1/3), the extrusion's too, the hole's points included."""
    problem = _block([[0, 0], [4 * G, 0]], {"volume_ratio": R}, [_circle(2.0, 1.0, 0.5)])
    ref = solve_reference(problem, mesh_size=0.4)
    body = ref.bodies[0]
    assert np.abs(body.upper - G * body.initial_upper).max() < 1e-9
    assert np.abs(body.holes[0] - G * body.initial_holes[0]).max() < 1e-9
    assert body.load == pytest.approx(G, rel=1e-9)  # the axial stretch, freed: the growth's cube root
    assert body.growth == R
    assert body.area_final == pytest.approx(G * G * body.area_initial, rel=1e-9)
    assert abs(body.relative_error) < 1e-9


def test_the_reference_of_a_free_grown_tube_of_revolution_is_the_closed_form():
    ref = solve_reference(sd.load_case(TUBE), mesh_size=0.5)
    body = ref.bodies[0]
    assert np.abs(body.upper - G * body.initial_upper).max() < 1e-9 * 16.0
    assert body.volume_final == pytest.approx(R * body.volume_initial, rel=1e-9)


def test_a_bonded_grown_block_frees_its_extrusion_like_the_hyperelastic_model():
    """On a support that does not grow the axial stretch is no longer r^(1/3); the axial force vanishes."""
    problem = _block([[0, 0], [4, 0]], {"volume_ratio": R}, [_circle(2.0, 1.0, 0.5)])
    ref = solve_reference(problem, mesh_size=0.3)
    body = ref.bodies[0]
    assert abs(body.load - G) > 1e-3
    assert abs(body.relative_error) < 1e-4  # the area is the volume grown over the axial stretch
    fast = sd.Deformer(problem, model="hyperelastic").deform().bodies[0]
    assert fast.info.out_of_plane_stretch == pytest.approx(body.load, rel=1e-3)
    assert np.abs(fast.upper - body.upper).max() < 0.01 * 2.0
    assert np.abs(fast.holes[0] - body.holes[0]).max() < 0.01 * 2.0


def test_the_reference_mesh_follows_the_holes():
    problem = sd.load_case(HOLLOW)
    mesh = triangulate(problem, 0.4)
    hole = mesh.points[mesh.hole_nodes[0][0]]
    assert np.array_equal(hole, np.asarray(mesh.sections[0].holes[0]))  # the hole's points are nodes
    centres = mesh.points[mesh.triangles].mean(axis=1)
    assert not _inside(centres, hole).any()
    assert mesh.body_area(0) == pytest.approx(mesh.sections[0].area, rel=1e-9)  # contour less the hole


def test_a_hole_of_radius_going_to_zero_gives_the_solid_body_in_the_reference():
    """A tiny hole's shape is the solid body's up to the mesh's error: that gap shrinks as the mesh is refined."""
    target, law = [[0, 0], [2, 0.4], [4, 0]], {"area_ratio": 0.95}
    tiny = []
    for mesh_size in (0.2, 0.1):
        solid = solve_reference(_block(target, law), mesh_size=mesh_size).bodies[0]
        gaps = []
        for radius in (0.2, 0.01):
            body = solve_reference(_block(target, law, [_circle(2.0, 1.0, radius)]), mesh_size=mesh_size).bodies[0]
            assert body.area_initial == pytest.approx(solid.area_initial - 8.0 * radius**2 * np.sin(np.pi / 8.0), rel=1e-9)  # the 16-gon
            gaps.append(np.abs(body.upper - solid.upper).max())
        assert gaps[1] < gaps[0] / 2.5
        tiny.append(gaps[1])
    assert tiny[1] < tiny[0] / 2  # not the hole's effect: the mesh's error, converging
    assert tiny[1] < 2.5e-4 * 2.0


# --- validate -------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("model", ("paper", "hyperelastic"))
def test_validate_compares_the_holes_of_the_public_hollow_profile(model, tmp_path):
    out = tmp_path / "report.json"
    assert main(["validate", str(HOLLOW), "--model", model, "--mesh-size", "0.4", "-q", "-o", str(out)]) == 0
    body = json.loads(out.read_text())["bodies"][0]
    assert len(body["holes"]) == 1
    hole = body["holes"][0]
    assert len(hole["fast"]) == len(hole["reference"]) > 100
    assert abs(body["reference"]["relative_error"]) < 1e-3  # the law counts the hole
    if model == "hyperelastic":
        assert body["hausdorff_over_height"] < 0.01 and hole["hausdorff_over_height"] < 0.01


def _two_hollow_bodies(revolution: bool) -> dict:
    """A backing 4 x 1 and a cover 4 x 2 on it with a hole; about the axis y = -2 when ``revolution``."""
    case = {"format": "section-case/2", "support": {"polyline": [[0, 0], [4, 0]]},
            "target": {"polyline": [[0, 0], [2, 0.3], [4, 0]]},
            "bodies": [{"name": "backing", "lower": {"polyline": [[0, 0], [4, 0]]},
                        "upper": {"polyline": [[4, 0], [4, 1], [0, 1], [0, 0]]}, "law": {"area_ratio": 1.0},
                        "holes": [_circle(1.0, 0.5, 0.25)]},
                       {"name": "cover", "lower": {"polyline": [[0, 1], [4, 1]]},
                        "upper": {"polyline": [[4, 1], [4, 3], [0, 3], [0, 1]]}, "law": {"volume_ratio": R},
                        "holes": [_circle(2.0, 2.0, 0.5)], "material": {"shear_modulus": 0.5}}]}
    if revolution:
        case["revolution"] = {"axis": [[0, -2], [1, -2]]}
        case["bodies"][0]["law"] = {"volume_ratio": 1.0}
    return case


@pytest.mark.parametrize("revolution", (False, True))
def test_validate_several_hollow_bodies_one_growing_plane_and_of_revolution(revolution, tmp_path):
    path = tmp_path / "case.json"
    path.write_text(json.dumps(_two_hollow_bodies(revolution)))
    out = tmp_path / "report.json"
    assert main(["validate", str(path), "--model", "hyperelastic", "--mesh-size", "0.3", "-q", "-o", str(out)]) == 0
    report = json.loads(out.read_text())
    for body in report["bodies"]:
        assert len(body["holes"]) == 1
        assert body["hausdorff_over_height"] < 0.01 and body["holes"][0]["hausdorff_over_height"] < 0.01
        assert abs(body["reference"]["relative_error"]) < 1e-3
    cover = report["reference"]["solver"]["bodies"][1]
    if revolution:
        assert cover["volume_ratio"] == R
    else:
        assert cover["growth"] == R and abs(cover["stretch_z"] - G) < 0.05


# --- decks and CalculiX -------------------------------------------------------------------------------------


def test_the_deck_of_a_hollow_profile_has_no_element_in_the_hole(tmp_path):
    from sectiondeform.external.deck import build_deck, deck_text

    problem = sd.load_case(HOLLOW)
    deck = build_deck(problem, mesh_size=0.4)
    m = deck.mesh
    hole = np.asarray(sd.build_section(problem).holes[0])
    assert not _inside(m.points[m.cells].mean(axis=1), hole).any()
    assert np.array_equal(m.points[m.hole_nodes], hole)  # the hole's points are nodes, free: not on the support
    assert not np.isin(m.hole_nodes, m.lower_nodes).any()
    assert deck.area_initial == pytest.approx(sd.build_section(problem).area, rel=1e-9)
    text = deck_text(deck)
    assert "*NSET, NSET=HOLES" in text and "*EXPANSION" not in text


def test_a_growth_deck_carries_an_expansion_of_the_cube_root_and_a_temperature_step():
    from sectiondeform.external.deck import build_deck, deck_text

    plane = build_deck(_block([[0, 0], [4, 0]], {"volume_ratio": R}), mesh_size=1.0)
    text = deck_text(plane)
    alpha = float(text.split("*EXPANSION, TYPE=ORTHO, ZERO=0.\n")[1].split(",")[0])
    assert alpha == pytest.approx(G - 1.0, rel=1e-12)
    assert "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nALL_NODES, 0." in text and "*TEMPERATURE\nALL_NODES, 1." in text
    assert len(plane.unexpressed) == 1 and "plane-strain deck" in plane.unexpressed[0]
    tube = build_deck(sd.load_case(TUBE), mesh_size=1.0)
    assert "*EXPANSION, ZERO=0.\n" in deck_text(tube) and not tube.unexpressed


def test_calculix_reads_the_hollow_deck_and_its_hole_deforms_inside_the_body(ccx):
    import shapely

    from sectiondeform.external.solve import solve_calculix

    problem = _block([[0, 0], [2, 0.3], [4, 0]], {"area_ratio": 1.0}, [_circle(2.0, 1.0, 0.5)])
    body = solve_calculix(problem, mesh_size=0.5).bodies[0]
    assert len(body.holes) == 1 and body.holes[0].shape == body.initial_holes[0].shape
    assert body.area_initial == pytest.approx(8.0 - 8.0 * 0.25 * np.sin(np.pi / 8.0), rel=1e-9)  # the 16-gon out
    assert abs(body.area_final / body.area_initial - 1) < 2e-3  # nearly incompressible, the hole counted
    final = body.final_mesh
    centres = final.points[final.cells[:, :3]].mean(axis=1)
    assert not _inside(centres, body.holes[0]).any()  # the deformed hole is still empty
    assert shapely.Polygon(body.holes[0]).area == pytest.approx(8.0 * 0.25 * np.sin(np.pi / 8.0), rel=0.05)


@pytest.mark.parametrize("revolution", (False, True))
def test_calculix_grows_a_free_body_by_the_cube_root(ccx, revolution):
    from sectiondeform.external.solve import solve_calculix

    if revolution:
        problem = sd.load_case(TUBE)
    else:
        problem = _block([[0, 0], [4 * G, 0]], {"volume_ratio": R}, [_circle(2.0, 1.0, 0.5)])
    body = solve_calculix(problem, mesh_size=1.0).bodies[0]
    size = float(np.ptp(body.initial_upper, axis=0).max())
    assert np.abs(body.upper - G * body.initial_upper).max() < 1e-5 * size
    for hole, hole0 in zip(body.holes, body.initial_holes):
        assert np.abs(hole - G * hole0).max() < 1e-5 * size
