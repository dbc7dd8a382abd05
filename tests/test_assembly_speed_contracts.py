"""Re-deforming an assembly: the explicit warm start and the drag preview keep every contract of a deformation.

A warm start (``deform(target, start=previous)``) follows the path from the
earlier solution: it must give the same answer bit for bit for the same
arguments (no hidden state in the deformer), the cold answer to the Newton
tolerance, and every law and bond exactly. The preview is one linear step:
laws and bonds exact, the shape first-order in the change of target.
"""

import json

import numpy as np
import pytest

from sectiondeform.curves import Polyline
from sectiondeform.deform import Deformer
from sectiondeform.errors import CaseError, MeshError
from sectiondeform.io.case import case_from_dict

from conftest import CASES_DIR

STRIP = CASES_DIR / "v2" / "two-layer-strip.json"
THROUGH = 2.0  # a coarse mesh keeps these tests quick


def strip(model="hyperelastic", through=THROUGH, ratios=None):
    data = json.loads(STRIP.read_text())
    data["options"] = {**data.get("options", {}), "model": model, "elements_through_thickness": through}
    if ratios is not None:
        for body, r in zip(data["bodies"], ratios):
            body["law"] = {"area_ratio": r}
    return case_from_dict(data)


def bumped(assembly, height):
    """The case's target with a smooth bump of ``height`` (units) normal to the support's direction."""
    s = np.linspace(0.0, 1.0, 401)
    pts = assembly.target.at_fractions(s)
    return Polyline(pts + height * np.sin(np.pi * s)[:, None] * np.array([0.0, 1.0]))


def thickness(result):
    return min(abs(b.area_initial) for b in result.bodies) / 100.0  # the strip is 100 long


def same(r1, r2):
    """Every array of the two results equal, bit for bit."""
    for b1, b2 in zip(r1.bodies, r2.bodies):
        for key in ("lower", "upper", "contour"):
            if not np.array_equal(getattr(b1, key), getattr(b2, key)):
                return False
        if not np.array_equal(b1.final_mesh.points, b2.final_mesh.points):
            return False
    return True


def gap(result):
    backing, cover = result.bodies
    return np.hypot(*(cover.lower[:, None, :] - backing.contour[None, :, :]).transpose(2, 0, 1)).min(axis=1).max()


@pytest.fixture(scope="module")
def solved():
    a = strip()
    d = Deformer(a)
    return a, d, d.deform()


def test_a_warm_start_gives_the_same_answer_bit_for_bit_whatever_ran_before(solved):
    a, d, first = solved
    target = bumped(a, 0.5)
    one = d.deform(target, start=first)
    d.deform(bumped(a, -1.0))  # other work in between must not matter
    d.preview(bumped(a, 0.3), start=first)
    two = d.deform(target, start=first)
    assert same(one, two)
    assert all(b.info.warm_start for b in one.bodies)
    assert one.state is not None and one.state is not first.state


def test_a_warm_start_reaches_the_cold_answer_and_keeps_every_law_and_bond(solved):
    a, d, first = solved
    target = bumped(a, 0.5)
    warm, cold = d.deform(target, start=first), d.deform(target)
    T = thickness(first)
    for w, c in zip(warm.bodies, cold.bodies):
        assert abs(w.relative_error) <= 1e-9
        assert np.abs(w.contour - c.contour).max() <= 1e-4 * T  # both converged to the Newton tolerance
    assert gap(warm) <= 1e-9 * 100.0
    assert warm.bodies[0].info.factorisations <= cold.bodies[0].info.factorisations


def test_without_start_the_answer_depends_on_the_target_alone(solved):
    a, d, first = solved
    d.deform(bumped(a, 0.7), start=first)
    assert same(d.deform(), first)


def test_the_state_is_not_written_to_json(solved):
    assert "state" not in solved[2].to_json(meshes=False)


def test_a_preview_at_the_start_target_is_the_start_result(solved):
    a, d, first = solved
    p = d.preview(start=first)
    T = thickness(first)
    for bp, bf in zip(p.bodies, first.bodies):
        assert np.abs(bp.contour - bf.contour).max() <= 1e-12 * T
        assert bp.info.preview
    assert p.state is first.state


def test_a_preview_meets_every_law_stays_bonded_and_is_first_order(solved):
    a, d, first = solved
    T = thickness(first)
    errors = []
    for h in (0.4, 0.2):
        target = bumped(a, h)
        p = d.preview(target, start=first)
        exact = d.deform(target, start=first)
        for b in p.bodies:
            assert abs(b.relative_error) <= 1e-9
        assert gap(p) <= 1e-9 * 100.0
        moved = max(np.abs(be.contour - bf.contour).max() for be, bf in zip(exact.bodies, first.bodies))
        err = max(np.abs(bp.contour - be.contour).max() for bp, be in zip(p.bodies, exact.bodies))
        assert err < 0.2 * moved  # far better than standing still
        errors.append(err)
    assert errors[1] < 0.5 * errors[0]  # second order in the change: halving it at least halves the error
    assert errors[1] < 1e-2 * T


def test_a_cold_preview_meets_every_law():
    a = strip(ratios=[0.97, 0.95])
    p = Deformer(a).preview()
    assert all(abs(b.relative_error) <= 1e-9 and b.info.preview for b in p.bodies)
    assert p.state is None


def test_a_start_of_another_assembly_or_kind_is_refused(solved):
    a, d, first = solved
    other = Deformer(strip(through=1.0)).deform()
    with pytest.raises(CaseError, match="start"):
        d.deform(start=other)
    with pytest.raises(CaseError, match="start"):
        d.deform(start=first.bodies[0])


def test_the_paper_model_ignores_start():
    a = strip("paper")
    d = Deformer(a)
    first = d.deform()
    assert first.state is None
    assert same(d.deform(bumped(a, 0.5), start=first), d.deform(bumped(a, 0.5)))
    assert same(d.preview(bumped(a, 0.5)), d.deform(bumped(a, 0.5)))


def test_a_paper_re_deformation_depends_on_the_target_alone_whatever_ran_before():
    """What the deformer works out once and keeps (node sources, upper bookkeeping) is never changed by a call:
    the same target gives the same answer bit for bit after other targets, refused ones included.
    """
    a = strip("paper")
    d = Deformer(a)
    fresh = Deformer(a).deform(bumped(a, 0.5))
    d.deform(bumped(a, -2.0))
    result = d.deform(bumped(a, 0.5))
    for body in result.bodies:  # writing into a result must not reach the deformer
        for key in ("lower", "upper", "contour"):
            getattr(body, key)[:] = np.nan
    with pytest.raises(MeshError, match="inverted"):
        d.deform(np.array([[0.0, 0.0], [100.0, 0.0], [0.0, 0.01]]))  # folded back on itself
    assert same(d.deform(bumped(a, 0.5)), fresh)


def test_other_laws_on_the_prepared_assembly_are_met_from_a_start_under_the_old_ones(solved):
    from sectiondeform.laws import AreaRatio

    a, d, first = solved
    laws = (AreaRatio(0.9), AreaRatio(0.85))
    r = d.deform(law=laws, start=first)  # no path from the old laws: a cold solve, the same as without start
    assert same(r, d.deform(law=laws))
    assert all(abs(b.relative_error) <= 1e-9 for b in r.bodies)
    assert [b.info.out_of_plane_stretch for b in r.bodies] == pytest.approx([1 / 0.9, 1 / 0.85], rel=1e-12)
    assert not r.bodies[0].info.warm_start
    again = d.deform(bumped(a, 0.5), laws, start=r)  # and from a start under the new laws, warm
    assert again.bodies[0].info.warm_start and all(abs(b.relative_error) <= 1e-9 for b in again.bodies)
    p = d.preview(bumped(a, 0.5), laws, start=first)
    assert all(abs(b.relative_error) <= 1e-9 for b in p.bodies)
    assert same(d.deform(), first)  # the prepared deformer is untouched
