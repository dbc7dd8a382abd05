"""Coulomb friction between the bodies and rigid parts (hyperelastic model): the law in slip, and friction 0 is frictionless."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.fem.neohooke import Pattern
from sectiondeform.io.case import case_from_dict

W, H = 10.0, 4.0


def _block(friction: float, travel=(3.0, -0.4)) -> dict:
    """A block (W x H, bonded on its base) under a plate that presses it by 0.4 while sliding 3 along it."""
    dx, dy = travel
    plate = [[-20 + dx, H + dy], [30 + dx, H + dy], [30 + dx, H + 2 + dy], [-20 + dx, H + 2 + dy], [-20 + dx, H + dy]]
    return {"format": "section-case/2", "name": "block", "units": "mm",
            "support": {"polyline": [[0, 0], [W, 0]]}, "target": {"polyline": [[0, 0], [W, 0]]},
            "bodies": [{"name": "block", "lower": {"polyline": [[0, 0], [W, 0]]},
                        "upper": {"polyline": [[W, 0], [W, H], [0, H], [0, 0]]},
                        "law": {"area_ratio": 1.0}, "material": {"shear_modulus": 1.0}}],
            "rigid": [{"name": "plate", "contour": {"polyline": plate}, "travel": list(travel), "friction": friction}],
            "options": {"model": "hyperelastic"}}


@pytest.fixture(scope="module")
def slid():
    return sd.Deformer(case_from_dict(_block(0.3))).deform()


def test_sliding_plate_drags_with_mu_times_the_normal_force(slid):
    # The contact slips the same way as the plate: the tangential force is mu times the normal one, at every load
    # step, but for a point or two at the edge of the contact that has just touched (within 3 %).
    steps = [s for s in slid.history if 0.0 < s.travel < 1.0]
    assert len(steps) >= 4
    ratios = []
    for s in steps:
        fx, fy = s.forces["plate"]
        assert fy > 0 and fx < 0  # pressed down and dragged along +x: the block pulls the plate back
        ratios.append(-fx / fy)
    assert max(ratios) <= 0.3 * (1 + 1e-12) and min(ratios) > 0.97 * 0.3
    assert np.mean(np.abs(np.array(ratios) - 0.3) < 1e-8) >= 0.75
    # The end state after the augmented-Lagrangian updates presses without sliding: at most mu.
    fx, fy = slid.rigid[0].force
    assert 0.29 < -fx / fy <= 0.3 + 1e-12


def test_friction_zero_is_frictionless_exactly():
    r = sd.Deformer(case_from_dict(_block(0.0))).deform()
    # A frictionless flat plate pushes along its normal only, whatever the sliding.
    assert r.rigid[0].force[0] == 0.0 and r.rigid[0].force[1] > 0
    for s in r.history:
        assert s.forces["plate"][0] == 0.0


def test_friction_raises_the_press_force_and_the_forces_balance(slid):
    # Friction holds the top back, so pressing needs more force than without it.
    free = sd.Deformer(case_from_dict(_block(0.0))).deform()
    assert slid.rigid[0].force[1] > free.rigid[0].force[1]
    np.testing.assert_allclose(np.add(slid.rigid[0].force, slid.support_force), 0.0, atol=1e-2 * slid.rigid[0].force[1])


BUMPER = Path(__file__).parent / "data" / "cases" / "v2" / "bumper-under-plate.json"


def _bumper(friction: float, slide: float) -> dict:
    case = json.loads(BUMPER.read_text())
    case["rigid"][0]["friction"] = friction
    case["rigid"][0]["travel"] = [slide, -1.2]
    return case


@pytest.mark.parametrize("friction, slide", [(0.3, 0.5), (0.1, 1.5), (1.0, 1.5)])
def test_a_plate_sliding_over_a_round_bumper_converges_within_coulombs_cone(friction, slide):
    """The switch between stick and slip made Newton cycle on a point at the edge of the contact (each refused)."""
    r = sd.Deformer(case_from_dict(_bumper(friction, slide))).deform()
    fx, fy = r.rigid[0].force
    assert fy > 0 and fx < 0  # pressed down, dragged back by the bumper
    assert -fx / fy <= friction * (1 + 1e-9)
    np.testing.assert_allclose(np.add(r.rigid[0].force, r.support_force), 0.0, atol=1e-2 * fy)


def test_the_bumper_slides_fully_under_low_friction():
    # Slid 1.5 mm under mu = 0.1 every point in contact slips: the drag is mu times the press.
    fx, fy = sd.Deformer(case_from_dict(_bumper(0.1, 1.5))).deform().rigid[0].force
    assert abs(-fx / fy - 0.1) < 2e-3


@pytest.mark.parametrize("friction", [0.0, 0.3])
def test_the_contact_tangent_is_the_derivative_of_the_residual(friction):
    """Normal and friction stiffness alike, the coupling of neighbouring edges through a node's pressure included."""
    d = sd.Deformer(case_from_dict(_block(friction)))
    prepared = d.prepared
    physics = prepared.contact.physics(prepared.physics)
    physics.t = 0.5
    z = prepared.reference.z.copy()
    n = prepared.physics.n_nodes
    x = z[: 2 * n].reshape(-1, 2)
    physics.commit(x)  # anchored where they are, then pressed into the plate and slid a little
    top = x[:, 1] > H - 1.0
    moved = x.copy()
    moved[top, 1] += 0.25 * (x[top, 1] - (H - 1.0))
    moved[top, 0] += 0.02
    z[: 2 * n] = moved.ravel()
    f = physics.fields(z, 1.0)
    touching = physics.evaluate(moved)[0][0]
    assert len(touching) > 10  # in contact, some sticking and some sliding
    pattern = Pattern(prepared.physics.edofs, len(z), np.array([], dtype=np.int64), coupling=prepared.boundary.pair_dofs)
    k = pattern.matrix_ff(physics.element_matrices(f), physics.coupling_matrices(f))
    rng = np.random.default_rng(0)
    for _ in range(3):
        v = np.zeros_like(z)
        v[: 2 * n] = rng.normal(size=2 * n) * np.repeat(top, 2)
        h = 1e-7
        fd = (physics.residual(physics.fields(z + h * v, 1.0)) - physics.residual(physics.fields(z - h * v, 1.0))) / (2 * h)
        assert np.linalg.norm(fd - k @ v) < 1e-6 * np.linalg.norm(fd)
