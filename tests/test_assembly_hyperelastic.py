"""Assemblies with the hyperelastic model: one solve, per-body materials and laws, bonded interfaces."""

import json

import numpy as np
import pytest
import shapely

from sectiondeform.cli import main
from sectiondeform.curves import Polyline
from sectiondeform.deform import Deformer
from sectiondeform.fem.mapping import offset_to_law, rigid_fit
from sectiondeform.io.case import case_from_dict
from sectiondeform.laws import AreaRatio

from conftest import CASES_DIR, chord_offset

STRIP = CASES_DIR / "v2" / "two-layer-strip.json"
THROUGH = 2.0  # elements across the thinnest body: a coarse mesh keeps these tests quick


def strip_dict(ratios=None, moduli=None, through=THROUGH, target=None):
    data = json.loads(STRIP.read_text())
    data["options"] = {**data.get("options", {}), "model": "hyperelastic", "elements_through_thickness": through}
    for i, body in enumerate(data["bodies"]):
        if ratios is not None:
            body["law"] = {"area_ratio": ratios[i]}
        if moduli is not None:
            body["material"] = {"shear_modulus": moduli[i]}
    if target is not None:
        data["target"] = target
    return data


def solve(data):
    return Deformer(case_from_dict(data)).deform()


def rotation(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s], [s, c]])


def bonded_gap(result):
    """Largest distance from a cover lower node to the backing's deformed outline points."""
    backing, cover = result.bodies
    return np.hypot(*(cover.lower[:, None, :] - backing.contour[None, :, :]).transpose(2, 0, 1)).min(axis=1).max()


@pytest.fixture(scope="module")
def strip_result():
    data = strip_dict()
    return case_from_dict(data), solve(data)


def test_two_layer_strip_deforms_meeting_each_law_bonded_and_simple(strip_result):
    assembly, result = strip_result
    assert result.model == "hyperelastic"
    for body, case_body in zip(result.bodies, assembly.bodies):
        assert abs(body.area_final - case_body.law.ratio * body.area_initial) <= 1e-9 * body.area_target
        assert shapely.is_simple(shapely.linearrings(body.contour))
        assert len(body.upper) == len(body.initial_upper)
    assert bonded_gap(result) <= 1e-9 * assembly.size
    backing, cover = result.bodies
    # The backing's lower curve is on the target, A' and B' at its ends.
    target = assembly.target.at_fractions(np.array([0.0, 1.0]))
    assert np.allclose(backing.lower[[0, -1]], target, atol=1e-9 * assembly.size)
    # The deformed bodies do not overlap, and each body keeps its own stretch.
    overlap = shapely.Polygon(backing.contour).intersection(shapely.Polygon(cover.contour)).area
    assert overlap <= 1e-9 * shapely.Polygon(backing.contour).area
    assert [b.info.out_of_plane_stretch for b in result.bodies] == pytest.approx([1 / 0.95, 1 / 0.9])
    # Those stretches are in the physics: the solve itself nearly meets each body's own law (a backing
    # at the cover's stretch would come out some 5 % short of its area: a few hundredths of its thickness
    # to correct).
    assert all(b.info.area_correction < 0.01 for b in result.bodies)


def test_result_json_is_section_result_2_with_one_mesh_per_body(strip_result):
    _, result = strip_result
    data = result.to_json()
    assert data["format"] == "section-result/2" and data["model"] == "hyperelastic"
    for body in data["bodies"]:
        assert body["meshes"]["initial"]["kind"] == "triangle6"
        assert len(body["meshes"]["initial"]["points"]) == len(body["meshes"]["final"]["points"])


def test_shared_nodes_are_one_point_of_the_mesh(strip_result):
    assembly, _ = strip_result
    joint = Deformer(assembly).prepared
    mesh = joint.mesh
    backing_nodes = np.unique(mesh.cells[mesh.body == 0])
    cover_nodes = np.unique(mesh.cells[mesh.body == 1])
    shared = np.intersect1d(backing_nodes, cover_nodes)
    # Every shared node lies on the interface y = 4, and the interface is covered by them (100 mm long).
    assert np.allclose(mesh.nodes[shared, 1], 4.0, atol=1e-9)
    xs = np.sort(mesh.nodes[shared, 0])
    assert xs[0] == pytest.approx(0.0, abs=1e-9) and xs[-1] == pytest.approx(100.0, abs=1e-9)
    assert np.diff(xs).max() <= 2 * mesh.size


def test_each_body_is_meshed_at_its_own_thickness_over_elements_through_thickness(strip_result):
    # The 4 mm backing and the 13 mm cover: element sizes 4 / 2 and 12.8 / 2, the shared piece at the
    # finer one. Every cell of a body has edges near its own size (the mean edge over the size).
    assembly, result = strip_result
    deformer = Deformer(assembly)
    sections = deformer.stack.sections
    for body, section in zip(result.bodies, sections):
        h = section.mesh_scale / THROUGH
        assert body.quality.initial.element_size == pytest.approx(h)
        pts, cells = np.asarray(body.initial_mesh.points), np.asarray(body.initial_mesh.cells)[:, :3]
        edges = np.hypot(*(pts[cells] - pts[np.roll(cells, -1, axis=1)]).transpose(2, 0, 1))
        assert 0.6 * h <= float(np.median(edges)) <= 1.4 * h
    assert deformer.prepared.mesh.size == pytest.approx(min(s.mesh_scale for s in sections) / THROUGH)


def test_identity_and_rigid_motion_are_reproduced_per_body():
    data = strip_dict(ratios=(1.0, 1.0))
    assembly = case_from_dict(data)
    deformer = Deformer(assembly)
    same = deformer.deform(assembly.support)
    q, t = rotation(0.7), np.array([12.0, -5.0])
    support = assembly.support.at_fractions(np.linspace(0.0, 1.0, 2))
    moved = deformer.deform(Polyline(support @ q.T + t))
    size = assembly.size
    # The law holds against the curves' exact area: on the identity the upper points of a curved body move
    # out by the area its polygon's chords miss (chord_offset), the lower ones not at all; a rigid motion
    # moves that identity rigidly.
    offset = chord_offset(same) + 1e-9 * size
    for body, rigid in zip(same.bodies, moved.bodies):
        assert np.abs(body.upper - body.initial_upper).max() <= offset
        assert np.abs(body.lower - body.initial_lower).max() <= 1e-9 * size
        assert np.abs(rigid.upper - (body.upper @ q.T + t)).max() <= 1e-9 * size
        assert abs(rigid.info.area_correction - body.info.area_correction) <= 1e-9  # the identity's own correction


def _union_case(assembly, ratio):
    """The version-1 case of the union of the strip's two bodies: the backing's sides below y = 4, the cover's upper above."""
    backing, cover = assembly.bodies
    b_up = backing.upper.discretise(0.01)[0]
    right, left = b_up[b_up[:, 0] == 100.0], b_up[b_up[:, 0] == 0.0]
    return {
        "format": "section-case/1",
        "lower": assembly.support.to_json(),
        "upper": {"chain": [{"polyline": right.tolist()}, cover.upper.to_json(), {"polyline": left.tolist()}]},
        "target": assembly.target.to_json(),
        "law": {"area_ratio": ratio},
        "options": {"model": "hyperelastic", "chordal_error": 0.01},
    }


def test_equal_materials_in_two_stacked_bodies_give_the_shape_of_their_union():
    # Two bodies of one material under one law are one body: the two-body solve and the single-body model
    # of their union discretise the same problem, on different meshes of the same element size h, and
    # each then moves its upper points by its reported law correction. So their upper curves may differ
    # by those corrections plus the discretisation error, estimated from the change of the assembly's
    # result when h is halved (4/3 of it for a second-order method), and by at most 0.2 % of the height.
    ratio, through = 0.9, 2.0
    deformers = [Deformer(case_from_dict(strip_dict(ratios=(ratio, ratio), moduli=(1.0, 1.0), through=t)))
                 for t in (through, 2 * through)]
    coarse, fine = (d.deform() for d in deformers)
    assembly = deformers[0].problem
    union = _union_case(assembly, ratio)
    thickness = Deformer(case_from_dict(union)).section.mesh_scale
    h = deformers[0].prepared.mesh.size
    single = Deformer(case_from_dict({**union, "options": {**union["options"], "elements_through_thickness": thickness / h}}))
    one = single.deform()
    top = coarse.body("cover")
    # The union's upper points that are the cover's upper points (the same places before deformation).
    d = np.hypot(*(top.initial_upper[:, None, :] - one.initial_upper[None, :, :]).transpose(2, 0, 1))
    same = d.min(axis=1) <= 1e-9
    assert same.sum() >= 88  # at least the flat top, 17 mm high
    diff = np.hypot(*(one.upper[d.argmin(axis=1)[same]] - top.upper[same]).T).max()
    corrections = one.info.area_correction * single.section.thickness + sum(
        r.info.area_correction * b.section.thickness for r, b in zip(coarse.bodies, deformers[0].stack.bodies))
    discretisation = 4.0 / 3.0 * np.hypot(*(top.upper - fine.body("cover").upper).T).max()
    assert 0 < diff <= corrections + discretisation
    assert diff <= 2e-3 * 17.0


def test_shared_piece_has_one_image_in_both_bodies(strip_result):
    # On their shared piece (y = 4 before deformation) the backing's deformed upper curve and the cover's
    # deformed lower curve are one curve: each curve's points lie on the other to rounding (the cover's
    # lower points are the backing's, bit for bit; the backing's own upper points in between lie on the
    # cover's lower polyline), and the two bodies' meshes have the same nodes there, deformed alike.
    assembly, result = strip_result
    backing, cover = result.bodies
    on_b = np.abs(backing.initial_contour[:, 1] - 4.0) <= 1e-12
    on_c = np.abs(cover.initial_contour[:, 1] - 4.0) <= 1e-12
    curve_b, curve_c = (shapely.LineString(c[np.argsort(i[on, 0])]) for c, i, on in (
        (backing.contour[on_b], backing.initial_contour, on_b), (cover.contour[on_c], cover.initial_contour, on_c)))
    assert on_c.sum() > 2 and curve_c.length > 90.0
    assert shapely.distance(shapely.points(backing.contour[on_b]), curve_c).max() <= 1e-12 * assembly.size
    assert shapely.distance(shapely.points(cover.contour[on_c]), curve_b).max() <= 1e-12 * assembly.size
    assert set(map(tuple, cover.contour[on_c])) <= set(map(tuple, backing.contour[on_b]))
    mb, mc = (np.asarray(b.initial_mesh.points) for b in (backing, cover))
    nb, nc = (np.flatnonzero(np.abs(m[:, 1] - 4.0) <= 1e-12) for m in (mb, mc))
    nb, nc = nb[np.argsort(mb[nb, 0])], nc[np.argsort(mc[nc, 0])]
    assert np.array_equal(mb[nb], mc[nc])
    assert np.array_equal(np.asarray(backing.final_mesh.points)[nb], np.asarray(cover.final_mesh.points)[nc])
    # The deformed interface is curved (the target is an arc): coinciding is not a trivial property.
    assert np.ptp(backing.contour[on_b, 1]) > 1.0


def _shape_change(body):
    """Largest distance of the deformed outline from the best rigid motion of the initial one, units."""
    q, t = rigid_fit(body.initial_contour, body.contour)
    return float(np.hypot(*(body.initial_contour @ q.T + t - body.contour).T).max())


def test_a_stiff_cover_on_a_soft_backing_barely_changes_its_shape():
    # The support is stretched by 5 % along its length: the backing, bonded to it, is stretched with it
    # whatever the materials (its ends 2.5 mm off its best rigid placement). A cover of the backing's
    # material stretches along. A stiffer cover is held back, the thin soft backing shearing under it:
    # its shape change shrinks as its modulus grows, towards a rigid body. A soft cover on a stiff backing
    # is stretched more than one on a backing of its own material.
    target = {"polyline": [[0.0, 0.0], [105.0, 0.0]]}
    moduli = ((1.0, 1.0), (1.0, 100.0), (1.0, 1000.0), (100.0, 1.0))
    results = {m: solve(strip_dict(ratios=(1.0, 1.0), moduli=m, target=target)) for m in moduli}
    cover = {m: _shape_change(r.body("cover")) for m, r in results.items()}
    assert cover[1.0, 100.0] < 0.15 * cover[1.0, 1.0]
    assert cover[1.0, 1000.0] < 0.3 * cover[1.0, 100.0]
    assert cover[100.0, 1.0] > cover[1.0, 1.0]
    for r in results.values():
        assert _shape_change(r.body("backing")) == pytest.approx(2.5, rel=0.01)


def _top_waviness(result):
    """Peak-to-peak height of the cover's flat top over its middle (x in 20..80 before deformation), mm."""
    cover = result.body("cover")
    middle = (cover.initial_upper[:, 1] == 17.0) & (cover.initial_upper[:, 0] > 20) & (cover.initial_upper[:, 0] < 80)
    return float(np.ptp(cover.upper[middle, 1]))


def test_a_soft_cover_on_a_stiff_backing_follows_the_support_less_than_a_stiff_cover_on_a_soft_one():
    # A wavy target (amplitude 2 mm, wavelength 50 mm). A layer takes up the support's waves by shearing;
    # a stiff one is carried nearly as a body. A soft cover (13 mm) over a stiff backing shears under its
    # free surface, which smooths out: the top follows the support less. A stiff cover over the thin (4 mm)
    # soft backing cannot bridge the waves: that would change the backing's thickness over half a
    # wavelength, squeezing nearly incompressible rubber along it (a stiffness growing as (wavelength /
    # thickness)^3), so the cover is carried on the waves: the top follows the support more. Equal
    # moduli lie in between.
    x = np.linspace(0.0, 100.0, 201)
    wavy = {"polyline": np.column_stack((x, 2.0 * np.sin(2 * np.pi * x / 50.0))).tolist()}
    stiff_bottom = _top_waviness(solve(strip_dict(ratios=(1.0, 1.0), moduli=(20.0, 1.0), target=wavy)))
    equal = _top_waviness(solve(strip_dict(ratios=(1.0, 1.0), moduli=(1.0, 1.0), target=wavy)))
    stiff_top = _top_waviness(solve(strip_dict(ratios=(1.0, 1.0), moduli=(1.0, 20.0), target=wavy)))
    assert stiff_top > equal > stiff_bottom
    assert stiff_top > 1.2 * stiff_bottom


def test_the_area_offset_meets_the_area_moving_only_the_free_points():
    rng = np.random.default_rng(3)
    angles = np.sort(rng.uniform(0, 2 * np.pi, 20))
    ring = np.column_stack((np.cos(angles), np.sin(angles))) * rng.uniform(0.8, 1.2, (20, 1))
    movable = rng.uniform(size=20) < 0.5
    area = 0.5 * np.sum(ring[:, 0] * np.roll(ring[:, 1], -1) - np.roll(ring[:, 0], -1) * ring[:, 1])
    out, _ = offset_to_law(ring, movable, AreaRatio(0.9), 0.9 * area)
    got = 0.5 * np.sum(out[:, 0] * np.roll(out[:, 1], -1) - np.roll(out[:, 0], -1) * out[:, 1])
    assert got == pytest.approx(0.9 * area, rel=1e-12)
    assert np.array_equal(out[~movable], ring[~movable])


def test_cli_deforms_an_assembly_with_the_hyperelastic_model(tmp_path):
    out = tmp_path / "r.json"
    assert main(["deform", str(STRIP), "-o", str(out), "--model", "hyperelastic", "--no-meshes"]) == 0
    data = json.loads(out.read_text())
    assert data["format"] == "section-result/2" and data["model"] == "hyperelastic"
    assert all(abs(b["area"]["relative_error"]) <= 1e-9 for b in data["bodies"])
