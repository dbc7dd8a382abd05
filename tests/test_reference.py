"""The finite-element reference: invariants of the physics, convergence, errors.

Small meshes throughout (a few hundred to a few thousand triangles); the full
refinement study is ``benchmarks/validation.py``.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import sectiondeform as sd

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.materials import NeoHookean  # noqa: E402
from sectiondeform.reference import solve_reference  # noqa: E402
from sectiondeform.reference.mesh import triangulate  # noqa: E402
from sectiondeform.reference.solver import MixedProblem, neo_hookean  # noqa: E402

from conftest import CASES_DIR, box_case, rigid  # noqa: E402

BLOCK = [[40.0, 0.0], [40.0, 8.0], [30.0, 10.0], [10.0, 10.0], [0.0, 8.0], [0.0, 0.0]]


def block(target=None, ratio=1.0, **options):
    """A 40 x 10 block with chamfered top corners (T ~ 9.5)."""
    return sd.case_from_dict(box_case(40.0, 10.0, target=target, ratio=ratio, upper=BLOCK, **options))


def arc_target(width=40.0, sag=6.0):
    """An arc through (0, 0) and (width, 0) bulging down by ``sag``: a concave support."""
    radius = (width**2 / 4 + sag**2) / (2 * sag)
    half = np.degrees(np.arcsin(width / 2 / radius))
    return {"arc": {"center": [width / 2, radius - sag], "radius": radius,
                    "start_deg": -90 - half, "end_deg": -90 + half}}


# --- mesh ------------------------------------------------------------------------


def test_mesh_keeps_the_upper_points_and_the_lower_fractions(shared_case):
    sec = sd.build_section(shared_case)
    mesh = triangulate(shared_case, 0.2)
    np.testing.assert_array_equal(mesh.points[mesh.upper_nodes[0]], sec.upper)
    assert np.all(np.diff(mesh.lower_fractions) > 0)
    assert mesh.lower_fractions[0] == 0.0 and mesh.lower_fractions[-1] == 1.0
    np.testing.assert_allclose(shared_case.lower.at_fractions(mesh.lower_fractions), mesh.points[mesh.lower_nodes],
                               atol=1e-9 * sec.size)
    sag = np.abs(mesh.body_area(0) - sec.area)  # support nodes lie on the curve, not on the section's chords
    assert sag <= 1e-3 * sec.area
    assert np.all(mesh.body == 0)
    assert mesh.min_angle_deg >= 28.0
    p = mesh.points[mesh.triangles]
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    assert np.all(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] > 0)  # counter-clockwise


# --- material and assembly ---------------------------------------------------------


def test_stress_and_tangent_are_the_derivatives():
    rng = np.random.default_rng(1)
    H, p, lz, kappa = 0.3 * rng.standard_normal((2, 2, 4)), rng.standard_normal(4), 1.25, 200.0
    out = neo_hookean(H, lz, p, 1.0, kappa)
    eps = 1e-6
    for k in range(2):
        for m in range(2):
            e = np.zeros((2, 2, 1))
            e[k, m] = eps
            plus, minus = neo_hookean(H + e, lz, p, 1.0, kappa), neo_hookean(H - e, lz, p, 1.0, kappa)
            np.testing.assert_allclose((plus["P"] - minus["P"]) / (2 * eps), out["A"][:, :, k, m], atol=1e-7)
            np.testing.assert_allclose((plus["psi_mixed"] - minus["psi_mixed"]) / (2 * eps), out["P"][k, m], atol=1e-7)


def test_tangent_matrix_is_the_residual_derivative():
    sec = sd.build_section(block())
    pr = MixedProblem(triangulate(block(), 0.5), [NeoHookean(1.0, bulk_to_shear=100.0)])
    rng = np.random.default_rng(2)
    x = np.concatenate((0.02 * sec.thickness * rng.standard_normal(pr.n_u), 0.1 * rng.standard_normal(pr.n_p)))
    K = pr.tangent(pr.material(x, 1.2))
    dx = rng.standard_normal(len(x))
    eps = 1e-6
    fd = (pr.residual(x + eps * dx, 1.2) - pr.residual(x - eps * dx, 1.2)) / (2 * eps)
    np.testing.assert_allclose(K @ dx, fd, atol=1e-6 * np.abs(fd).max())
    assert abs(K - K.T).max() < 1e-10 * abs(K).max()


# --- physics -----------------------------------------------------------------------


def test_identity_target_with_ratio_one_does_not_move():
    case = block()
    ref = solve_reference(case, mesh_size=0.4)
    sec = sd.build_section(case)
    np.testing.assert_allclose(ref.bodies[0].upper, sec.upper, atol=1e-12 * sec.size)
    assert abs(ref.strain_energy) <= 1e-12 * sec.area
    assert ref.bodies[0].area_final == pytest.approx(sec.area, rel=1e-12)


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(angle=st.floats(-180.0, 180.0), dx=st.floats(-50.0, 50.0), dy=st.floats(-50.0, 50.0))
def test_rigid_motion_of_the_target_gives_zero_strain_energy(angle, dx, dy):
    lower = np.array([[0.0, 0.0], [40.0, 0.0]])
    case = block(target={"polyline": rigid(lower, angle, (dx, dy)).tolist()})
    sec = sd.build_section(case)
    ref = solve_reference(case, mesh_size=0.5)
    assert abs(ref.strain_energy) <= 1e-12 * sec.area
    np.testing.assert_allclose(ref.bodies[0].upper, rigid(sec.upper, angle, (dx, dy)), atol=1e-9 * sec.thickness)
    np.testing.assert_allclose(ref.pressure, 0.0, atol=1e-9)


def test_area_follows_the_ratio_within_the_compressibility():
    """|A/(r A0) - 1| is the volume the finite bulk modulus lets go: it scales like μ/κ."""
    errors = {}
    for k in (100.0, 1000.0):
        ref = solve_reference(block(arc_target(), ratio=0.8), mesh_size=0.3, bulk_to_shear=k)
        # The area error is exactly the mean volume change (J = λz det F2D) ...
        assert ref.bodies[0].relative_error == pytest.approx(ref.bodies[0].volume_change, rel=1e-6, abs=1e-12)
        # ... which is of the order of the pressures over κ.
        assert abs(ref.bodies[0].relative_error) <= ref.bodies[0].max_volume_change
        assert abs(ref.bodies[0].relative_error) < 5.0 / k
        errors[k] = ref.bodies[0].relative_error
    assert 5.0 < errors[100.0] / errors[1000.0] < 20.0


def test_refinement_converges_on_a_block():
    """Upper points against a 0.05 T solution: error falls faster than h, and is < 0.5 % of T at 0.1 T."""
    case = block(arc_target(), ratio=0.8)
    T = sd.build_section(case).thickness
    fine = solve_reference(case, mesh_size=0.05).bodies[0].upper
    hs = np.array([0.4, 0.2, 0.1])
    err = np.array([np.linalg.norm(solve_reference(case, mesh_size=h).bodies[0].upper - fine, axis=1).max() for h in hs])
    rate = np.polyfit(np.log(hs), np.log(err), 1)[0]
    assert rate > 1.0
    assert err[-1] < 0.005 * T


def test_paper_example_is_converged_at_the_default_mesh():
    """The two finest meshes of a small study on the paper example agree to < 0.5 % of T."""
    case = sd.load_case(CASES_DIR / "paper-example.json")
    T = sd.build_section(case).thickness
    coarse = solve_reference(case, mesh_size=0.2)
    fine = solve_reference(case)  # the default, 0.1 T
    assert np.linalg.norm(coarse.bodies[0].upper - fine.bodies[0].upper, axis=1).max() < 0.005 * T
    assert fine.jacobian_min > 0 and fine.steps >= 1
    assert abs(fine.bodies[0].relative_error) < 1e-3


def test_target_argument_and_progress():
    case = block(arc_target(), ratio=0.9)
    sec = sd.build_section(case)
    lines = []
    a = solve_reference(case, mesh_size=0.5)


    class Moved:  # the case's target turned by 30 degrees and moved: the solution follows rigidly
        def at_fractions(self, s):
            return rigid(case.target.at_fractions(s), 30.0, (5.0, -2.0))

    b = solve_reference(case, Moved(), mesh_size=0.5, progress=lines.append)
    np.testing.assert_allclose(rigid(a.bodies[0].upper, 30.0, (5.0, -2.0)), b.bodies[0].upper, atol=1e-7 * sec.thickness)
    assert lines and lines[-1].startswith("reference: load 100.0%")
    assert b.mesh.kind == "triangle6" and b.mesh.cells.shape[1] == 6
    assert b.initial_mesh.points.shape == b.mesh.points.shape


# --- errors --------------------------------------------------------------------------


def test_bad_arguments_are_case_errors():
    case = block()
    with pytest.raises(sd.CaseError, match="bulk_to_shear"):
        solve_reference(case, bulk_to_shear=10.0)
    with pytest.raises(sd.CaseError, match="mesh_size"):
        solve_reference(case, mesh_size=0.0)
    with pytest.raises(sd.CaseError, match="target"):
        solve_reference(case, target=3.0)


def test_folded_target_raises_a_convergence_error():
    # The support folds back onto itself at its middle: the base would have to close flat.
    target = {"polyline": [[0.0, 0.0], [20.0, 0.0], [0.0, 0.01]]}
    with pytest.raises(sd.ConvergenceError, match="did not converge"):
        solve_reference(block(target), mesh_size=0.5)


def test_missing_extra_names_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "triangle", None)
    with pytest.raises(sd.MissingExtraError, match=r"sectiondeform\[fem\]"):
        solve_reference(block())
