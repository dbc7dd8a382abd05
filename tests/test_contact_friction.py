"""Coulomb friction between the bodies and rigid parts (hyperelastic model): the law in slip, and friction 0 is frictionless."""

from __future__ import annotations

import numpy as np
import pytest

import sectiondeform as sd
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
    # Every contact point slips the same way: the tangential force is mu times the normal one, at every load step.
    steps = [s for s in slid.history if 0.0 < s.travel < 1.0]
    assert len(steps) >= 4
    for s in steps:
        fx, fy = s.forces["plate"]
        assert fy > 0 and fx < 0  # pressed down and dragged along +x: the block pulls the plate back
        assert abs(-fx / fy - 0.3) < 1e-8
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
