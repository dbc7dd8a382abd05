"""A solve that finds no equilibrium names the physical state it stopped in, not the mesh, when that state shows one."""

from __future__ import annotations

import pickle
import re
import threading

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import sectiondeform as sd
from sectiondeform.errors import ConvergenceError
from sectiondeform.fem.diagnosis import LEAST_STRETCH, least_stretch, physical_reason

LABELS = ["bodies[0] 'a'", "bodies[1] 'b'"]
SQUARE = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
REST = np.tile(np.eye(2), (1, 3, 1, 1))  # one cell, three points, undeformed
ONE = dict(centres=np.array([[0.5, 0.5]]), body=np.zeros(1, np.int64))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(-3.0, 3.0), min_size=4, max_size=4))
def test_the_least_stretch_is_the_smaller_singular_value(entries):
    F = np.array(entries).reshape(2, 2)
    assert least_stretch(F) == pytest.approx(np.linalg.svd(F, compute_uv=False).min(), abs=1e-6)


def test_an_undeformed_state_shows_no_reason():
    assert physical_reason(SQUARE, [np.arange(4)], F=REST, labels=LABELS, **ONE) is None


def test_a_body_crossing_itself_is_named_with_the_place():
    bow = SQUARE[[0, 2, 1, 3]]  # the outline's two sides crossed at the centre
    reason = physical_reason(bow, [np.arange(4)], F=REST, labels=LABELS, **ONE)
    assert reason.startswith("bodies[0] 'a' folds onto itself near [0.5, 0.5]")


def test_two_bodies_pressing_into_each_other_are_named_but_bonded_neighbours_are_not():
    contour = np.concatenate((SQUARE, SQUARE + [1.0, 0.0], SQUARE + [0.5, 0.5]))
    rings = [np.arange(4), np.arange(4, 8)]  # side by side: sharing an edge is no overlap
    F = np.tile(np.eye(2), (2, 3, 1, 1))
    kw = dict(centres=np.zeros((2, 2)), body=np.arange(2), F=F, labels=LABELS)
    assert physical_reason(contour, rings, **kw) is None
    reason = physical_reason(contour, [np.arange(4), np.arange(8, 12)], **kw)
    assert reason.startswith("bodies[0] 'a' and bodies[1] 'b' press into each other near") and "area 0.25" in reason


def test_a_body_reaching_across_the_axis_is_named():
    reason = physical_reason(SQUARE, [np.arange(4)], F=REST, labels=LABELS, radius=SQUARE[:, 1] - 0.5, **ONE)
    assert reason == "bodies[0] 'a' reaches across the axis near [0, 0]"


def test_a_crushed_rubber_is_named_below_the_bound_only():
    squeeze = np.array([[1.0 / LEAST_STRETCH, 0.0], [0.0, 0.99 * LEAST_STRETCH]])
    reason = physical_reason(SQUARE, [np.arange(4)], F=np.tile(squeeze, (1, 3, 1, 1)), labels=LABELS, **ONE)
    assert reason == "bodies[0] 'a' is crushed near [0.5, 0.5] (compressed to 30 % of its length there)"
    mild = np.diag([1.0 / LEAST_STRETCH, 1.01 * LEAST_STRETCH])
    assert physical_reason(SQUARE, [np.arange(4)], F=np.tile(mild, (1, 3, 1, 1)), labels=LABELS, **ONE) is None


def test_the_error_crosses_processes_without_its_state():
    """The page's solver processes send errors back pickled; the state (a SuperLU factorisation) cannot go."""
    exc = pickle.loads(pickle.dumps(ConvergenceError("stopped", "advice", threading.Lock())))
    assert str(exc) == "stopped; advice" and exc.state is None


# -- through the model: generated cases the fuzzing found refused with "refine the mesh" ----------------------

def _block_squeezed_by_a_plate() -> dict:
    """A rubber block of revolution (5 x 2 mm) squeezed 30 % by a plate with friction: its corner is crushed."""
    return {"format": "section-case/2", "name": "block", "units": "mm",
            "revolution": {"axis": [[0.0, -10.0], [1.0, -10.0]]},
            "support": {"polyline": [[0.0, 0.0], [5.0, 0.0]]}, "target": {"polyline": [[0.0, 0.0], [5.0, 0.0]]},
            "bodies": [{"name": "b0", "lower": {"polyline": [[0.0, 0.0], [5.0, 0.0]]},
                        "upper": {"polyline": [[5.0, 0.0], [5.0, 2.0], [0.0, 2.0], [0.0, 0.0]]},
                        "law": {"volume_ratio": 1.0}, "material": {"shear_modulus": 100.0}}],
            "rigid": [{"name": "plate", "contour": {"polyline": [[-5.0, 1.4], [10.0, 1.4], [10.0, 12.0], [-5.0, 12.0],
                                                                  [-5.0, 1.4]]},
                       "travel": [0.0, -0.6], "friction": 0.3}],
            "options": {"model": "hyperelastic"}}


def _layer_on_a_layer_under_a_plate() -> dict:
    """A narrower soft layer bonded on a wider one, both growing, pressed by a plate: it bulges into the one below."""
    return {"format": "section-case/2", "name": "layers", "units": "mm",
            "support": {"polyline": [[0.0, 0.0], [0.5, 0.0]]}, "target": {"polyline": [[0.0, 0.0], [0.5, 0.0]]},
            "bodies": [{"name": "b0", "lower": {"polyline": [[0.0, 0.0], [0.5, 0.0]]},
                        "upper": {"polyline": [[0.5, 0.0], [0.5, 0.05], [0.0, 0.05], [0.0, 0.0]]},
                        "law": {"area_ratio": 1.1}},
                       {"name": "b1", "lower": {"polyline": [[0.05, 0.05], [0.45, 0.05]]},
                        "upper": {"polyline": [[0.45, 0.05], [0.45, 0.1], [0.05, 0.1], [0.05, 0.05]]},
                        "law": {"area_ratio": 1.1}, "material": {"shear_modulus": 0.1}}],
            "rigid": [{"name": "plate", "contour": {"polyline": [[-0.5, 0.09], [1.0, 0.09], [1.0, 1.1], [-0.5, 1.1],
                                                                  [-0.5, 0.09]]},
                       "travel": [0.0, -0.01], "friction": 0.0}],
            "options": {"model": "hyperelastic", "chordal_error": 0.001}}


@pytest.mark.parametrize("case, named", [
    # a corner under the plate's edge or at the support's end (which first depends on the mesh under the plate)
    (_block_squeezed_by_a_plate, r"bodies\[0\] 'b0' is crushed near \[-?\d+\.\d*, -?\d+\.\d*\] \(compressed to \d+ % "),
    # the soft layer's side bulges over the one below and folds (which comes first depends on the load steps)
    (_layer_on_a_layer_under_a_plate, r"(bodies\[0\] 'b0' and bodies\[1\] 'b1' press into each other|"
                                      r"bodies\[1\] 'b1' folds onto itself) near "),
], ids=["crushed", "into-each-other"])
def test_a_loading_that_cannot_go_on_names_the_physical_state_not_the_mesh(case, named):
    with pytest.raises(ConvergenceError, match=r"^rigid\[0\] 'plate': the loading cannot go on at load step") as info:
        sd.deform(sd.case_from_dict(case()))
    message = str(info.value)
    assert "\n" not in message
    assert "at the last equilibrium reached, " in message
    assert re.search(named, message), message
    assert "mesh" not in message and message.endswith("a milder target or law, or a shorter travel")
