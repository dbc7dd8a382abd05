"""The project's finite-element reference with rigid parts (frictionless penalty at the boundary's Gauss points)."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.cli import main

from conftest import CASES_DIR

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.reference import solve_reference  # noqa: E402
from sectiondeform.reference.contact import ReferenceContact  # noqa: E402
from sectiondeform.reference.solver import PENETRATION, MixedProblem  # noqa: E402
from sectiondeform.reference.validation import validate  # noqa: E402

BUMPER = CASES_DIR / "v2" / "bumper-under-plate.json"
SLEEVE = CASES_DIR / "v2" / "sleeve-on-shaft.json"


@pytest.fixture(scope="module")
def bumper():
    """The bumper validated against the reference at a coarse reference mesh (0.3 of the mesh scale)."""
    return validate(sd.load_case(BUMPER), mesh_size=0.3, fast_runs=1)


@pytest.fixture(scope="module")
def sleeve():
    """The sleeve of revolution validated against the reference at 0.2 of the mesh scale."""
    return validate(sd.load_case(SLEEVE), mesh_size=0.2, fast_runs=1)


def _work(ref, part: str, travel) -> float:
    """The work the part does on the bodies over the loading, ∫ −F · d(travel), by the trapezoid rule on the history."""
    t = np.array([s.travel for s in ref.history])
    f = np.array([s.forces[part] for s in ref.history])  # the force on the part; the part pushes with −f
    along = -(f @ np.asarray(travel, dtype=np.float64))
    return float(np.sum(0.5 * (along[1:] + along[:-1]) * np.diff(t)))


@pytest.mark.parametrize("friction", [0.0, 0.3])
def test_the_reference_tangent_with_contact_is_the_derivative_of_its_residual(friction):
    problem = sd.load_case(BUMPER)
    ref = solve_reference(problem.replace(rigid=()), mesh_size=0.6)  # a mesh to hang the check on
    parts = tuple(dataclasses.replace(part, friction=friction) for part in problem.rigid)
    mixed = MixedProblem(ref.mesh_data, ref.materials)
    mixed.contact = contact = ReferenceContact(mixed, parts, tol=1e-6 * problem.size)
    contact.t = 0.5  # the plate 0.6 mm into the undeformed bumper: many points pressed
    rng = np.random.default_rng(3)
    x = np.zeros(mixed.n_u + mixed.n_p)
    x[: mixed.n_u] = 1e-3 * rng.standard_normal(mixed.n_u)
    contact.lam[:] = 0.05 * rng.random(contact.lam.shape)  # multipliers too
    trial, _, s = contact.touch(x)[0]
    assert np.count_nonzero(trial > 0) > 20
    if friction:  # anchors a little off, either way: some points stick, others slip
        contact.anchor[0] = s + rng.uniform(-0.3, 0.3, s.shape)
        _, slip, _ = contact.tangential(0, trial, s)
        assert 5 < np.count_nonzero(slip & (trial > 0)) < np.count_nonzero(trial > 0) - 5
    v = np.zeros_like(x)
    v[mixed.free] = rng.standard_normal(len(mixed.free))
    h = 1e-7
    fd = (mixed.residual(x + h * v, 1.0) - mixed.residual(x - h * v, 1.0)) / (2 * h)
    K = mixed.tangent(mixed.material(x, 1.0), x)
    np.testing.assert_allclose(K @ v, fd, atol=1e-5 * np.abs(fd).max())


def test_the_plate_and_the_support_carry_opposite_forces(bumper):
    ref = bumper.reference.solution
    (plate,) = ref.rigid
    # Plane, frictionless, one part: the plate is pushed straight up and the support down by as much.
    assert plate.force[1] > 0 and abs(plate.force[0]) < 1e-9 * plate.force[1]
    np.testing.assert_allclose(np.add(plate.force, ref.support_force), 0.0, atol=1e-7 * plate.force[1])
    for step in ref.history:
        np.testing.assert_allclose(np.add(step.forces["plate"], step.forces["support"]), 0.0,
                                   atol=1e-6 * plate.force[1])


def test_the_plate_does_the_work_the_bumper_stores(bumper):
    """Frictionless, the support still: the plate's work over its travel is the strain energy (trapezoid over 8 steps)."""
    ref = bumper.reference.solution
    travel = sd.load_case(BUMPER).rigid[0].travel
    work = _work(ref, "plate", travel)
    assert len(ref.history) >= 9 and ref.history[0].travel == 0.0 and ref.history[-1].travel == 1.0
    assert work == pytest.approx(ref.strain_energy, rel=0.01)


def test_the_penetration_left_is_below_its_bound(bumper, sleeve):
    for v in (bumper, sleeve):
        ref = v.reference.solution
        h = min(b.mesh_size for b in ref.bodies)
        assert all(0 < p.length and p.penetration_max <= PENETRATION * h for p in ref.rigid)


def test_the_hyperelastic_model_is_within_the_issue_bounds_of_the_reference_on_the_bumper(bumper):
    (c,) = bumper.contacts
    assert abs(c["force_error"]) < 0.03 and abs(c["length_error"]) < 0.05
    assert bumper.bodies[0].shape.max_pointwise / bumper.height < 0.01
    report = bumper.to_json()
    assert report["rigid"][0]["name"] == "plate" and report["reference"]["solver"]["rigid"][0]["name"] == "plate"


def test_the_sleeve_ring_force_against_the_reference(sleeve):
    ref = sleeve.reference.solution
    (shaft,) = ref.rigid
    # The axis is x: the shaft is squeezed radially (−y on the sleeve's side), no axial force without friction.
    assert shaft.force[1] < 0 and abs(shaft.force[0]) < 1e-6 * abs(shaft.force[1])
    assert abs(ref.support_force[0]) < 1e-6 * abs(shaft.force[1])
    (c,) = sleeve.contacts
    assert abs(c["force_error"]) < 0.03 and abs(c["length_error"]) < 0.05
    # The ring's work: 2π ∫ p r over the travel, as the whole ring's strain energy.
    assert _work(ref, "shaft", sd.load_case(SLEEVE).rigid[0].travel) == pytest.approx(ref.strain_energy, rel=0.01)


def test_a_plate_dragged_with_friction_pulls_mu_times_its_normal_force(tmp_path, capsys):
    """The block of the friction tests, pressed by 0.4 while the plate slides 3 along it: every pressed point slips,
    so while loading the tangential force is exactly μ times the normal one (return mapping, no rounding).
    """
    from test_contact_friction import _block

    case = tmp_path / "dragged.json"
    case.write_text(json.dumps(_block(0.3)))
    out = tmp_path / "report.json"
    assert main(["validate", str(case), "-q", "--mesh-size", "0.2", "--output", str(out)]) == 0
    report = json.loads(out.read_text())
    history = report["reference"]["solver"]["history"]
    assert len(history) >= 9
    for step in history[1:-1]:
        fx, fy = step["forces"]["plate"]
        assert fy > 0 and -fx / fy == pytest.approx(0.3, rel=1e-6)
    (plate,) = report["rigid"]
    assert plate["force_reference"][0] < 0 and -plate["force_reference"][0] <= 0.3 * (1 + 1e-9) * plate["force_reference"][1]
    # The model at its default mesh (4 elements through a 4 mm block) against it: the pressed corners converge
    # slowly (docs/validation.md); both forces within 6 %.
    assert plate["force_error"] < 0.06


def test_the_reference_mesh_is_finer_along_a_frictionless_parts_path_and_covers_the_bodies_exactly():
    """The lip seal's contour within the shaft's path (start to end, grown by two element sizes) is split
    ``CONTACT_REFINEMENT`` times finer; elsewhere at the body's size; the triangles still cover the section exactly.
    """
    import shapely

    from sectiondeform.reference import CONTACT_REFINEMENT, _contact_zone
    from sectiondeform.reference.mesh import triangulate
    from sectiondeform.section import build_section

    problem = sd.load_case(CASES_DIR / "v2" / "lip-seal-on-shaft.json")
    sections = [build_section(problem.body_case(0))]
    zone, ratio = _contact_zone(problem, sections, 0.3, CONTACT_REFINEMENT)
    assert ratio == CONTACT_REFINEMENT > 1
    plain, fine = triangulate(problem, 0.3, sections), triangulate(problem, 0.3, sections, fine=(zone, ratio))
    h = plain.sizes[0]
    for mesh in (plain, fine):
        assert mesh.body_area(0) == pytest.approx(sections[0].area, rel=1e-9)
    edges = np.sort(np.concatenate([fine.triangles[:, [0, 1]], fine.triangles[:, [1, 2]], fine.triangles[:, [2, 0]]]), axis=1)
    unique, count = np.unique(edges, axis=0, return_counts=True)
    boundary = unique[count == 1]  # the edges of one triangle: the section's outline
    a, b = fine.points[boundary[:, 0]], fine.points[boundary[:, 1]]
    length = np.hypot(*(b - a).T)
    near = shapely.intersects(zone, shapely.points(0.5 * (a + b)))
    assert near.any() and (~near).any()
    assert length[near].max() <= h / ratio * (1 + 1e-9)
    assert length[~near].max() > h / 2  # the rest keeps the body's size
    assert len(fine.triangles) > 1.2 * len(plain.triangles)
    # A part with friction keeps the uniform mesh.
    rough = dataclasses.replace(problem, rigid=tuple(dataclasses.replace(p, friction=0.3) for p in problem.rigid))
    assert _contact_zone(rough, sections, 0.3, CONTACT_REFINEMENT) is None
