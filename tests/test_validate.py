"""``validate``: the fast model against the reference body by body, plane and of revolution, both report dialects."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import shapely

import sectiondeform as sd

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.io.case import case_from_dict  # noqa: E402
from sectiondeform.reference.validation import validate  # noqa: E402

from conftest import CASES_DIR  # noqa: E402

TREAD = CASES_DIR / "v2" / "tread-alone-on-drum.json"
COVER = CASES_DIR / "v2" / "cover-alone-on-arc.json"
MESH = 0.4  # coarse reference: these tests check the comparison, not the reference's convergence
LOWER = {"polyline": [[0.0, 0.0], [20.0, 0.0]]}
UPPER = {"polyline": [[20.0, 0.0], [20.0, 5.0], [10.0, 6.0], [0.0, 5.0], [0.0, 0.0]]}
TARGET = {"polyline": [[0.0, 0.0], [10.0, -1.5], [20.0, 0.0]]}  # a kink of 2 changes the pad's aspect 4.4-fold: refused by the paper model


def shapely_hausdorff(a: np.ndarray, b: np.ndarray) -> float:
    """Hausdorff distance of two polylines, shapely's, densified to 1/1000 of each segment."""
    return float(shapely.hausdorff_distance(shapely.LineString(a), shapely.LineString(b), densify=1e-3))


def pappus_volume(contour: np.ndarray, axis_y: float) -> float:
    """2π × area × centroid distance from the horizontal axis y = axis_y."""
    poly = shapely.Polygon(contour)
    return 2.0 * math.pi * poly.area * (poly.centroid.y - axis_y)


def one_body(material=None):
    body = {"name": "pad", "lower": LOWER, "upper": UPPER, "law": {"area_ratio": 0.9}}
    if material is not None:
        body["material"] = material
    return case_from_dict({"format": "section-case/2", "support": LOWER, "target": TARGET, "bodies": [body]})


@pytest.fixture(scope="module")
def tread():
    return validate(sd.load_case(TREAD), mesh_size=MESH, fast_runs=1)


def test_a_version_one_case_and_its_version_two_twin_give_the_same_figures_and_each_its_report():
    v1 = case_from_dict({"format": "section-case/1", "lower": LOWER, "upper": UPPER, "target": TARGET,
                         "law": {"area_ratio": 0.9}})
    a = validate(v1, mesh_size=0.4, fast_runs=1)
    b = validate(one_body(), mesh_size=0.4, fast_runs=1)
    np.testing.assert_allclose(b.reference.bodies[0].upper, a.reference.bodies[0].upper, atol=1e-10)
    np.testing.assert_allclose(b.fast.upper, a.fast.upper, atol=1e-12)
    # the version-1 report keeps its keys; the version-2 one lists the bodies
    r1, r2 = a.to_json(), b.to_json()
    assert {"thickness", "height", "hausdorff_over_height", "area", "shape", "pointwise_distance"} <= set(r1)
    assert {"area_final", "area_relative_error", "area_polygon", "solver", "upper"} <= set(r1["reference"])
    assert r1["reference"]["solver"]["bulk_to_shear"] == 1000.0 and "bodies" not in r1["reference"]["solver"]
    assert r1["shape"]["hausdorff"] == pytest.approx(r2["bodies"][0]["hausdorff"], rel=1e-9)
    assert [x["name"] for x in r2["bodies"]] == ["pad"]
    c = validate(one_body({"model": "yeoh", "c10": 0.3, "c20": 0.05, "c30": 0.01}), mesh_size=0.4, fast_runs=1)
    assert c.reference.solution.bodies[0].material.model == "yeoh"
    assert c.to_json()["reference"]["model"].startswith("finite elements: yeoh, generalised plane strain")
    moved = np.abs(c.reference.bodies[0].upper - a.reference.bodies[0].upper).max()
    assert moved > 1e-6  # the stiffening rubber moves the free surface


def test_several_bodies_are_compared_body_by_body_and_a_body_s_bad_material_is_named():
    top = {"name": "cap", "lower": {"polyline": [[0.0, 5.0], [10.0, 6.0], [20.0, 5.0]]},
           "upper": {"polyline": [[20.0, 5.0], [20.0, 8.0], [0.0, 8.0], [0.0, 5.0]]}, "law": {"area_ratio": 0.95}}
    data = {"format": "section-case/2", "support": LOWER, "target": TARGET,
            "bodies": [{"name": "pad", "lower": LOWER, "upper": UPPER, "law": {"area_ratio": 0.9}}, top]}
    v = validate(case_from_dict(data), model="hyperelastic", mesh_size=0.8, fast_runs=1)
    assert [b.name for b in v.bodies] == ["pad", "cap"]
    top["material"] = {"shear_modulus": 1.0, "bulk_to_shear": 50}
    with pytest.raises(sd.CaseError, match=r"^bodies\[1\]\.material\.bulk_to_shear: the reference is a nearly") as err:
        validate(case_from_dict(data), model="hyperelastic", mesh_size=0.8, fast_runs=1)
    assert "\n" not in str(err.value)


def test_revolution_distances_match_an_independent_computation(tread):
    v, bv = tread, tread.bodies[0]
    fast, ref = v.fast.bodies[0].upper, v.reference.bodies[0].upper
    assert v.revolution and v.model == "paper"
    np.testing.assert_array_equal(fast, sd.Deformer(sd.load_case(TREAD), model="paper").deform().bodies[0].upper)
    length = shapely.LineString(ref).length
    assert bv.shape.hausdorff == pytest.approx(shapely_hausdorff(fast, ref), abs=1e-3 * length)
    assert bv.shape.max_pointwise == pytest.approx(np.hypot(*(fast - ref).T).max(), rel=1e-12)
    assert bv.shape.max_pointwise >= bv.shape.hausdorff > 0  # two different models, one pairing of points
    # Over the height (12 mm: the tread's base to its crown) and over the mean thickness (area / base).
    assert v.height == pytest.approx(12.0, rel=1e-6)
    # The area is the curves' exact one, which the initial polygon's chords miss by at most 2e-5 of it.
    assert bv.thickness == pytest.approx(v.fast.area_initial / 130.0, rel=1e-9)
    assert v.fast.area_initial == pytest.approx(shapely.Polygon(v.fast.initial_contour).area, rel=2e-5)


def test_revolution_volumes_are_pappus_and_the_law(tread):
    f, r, bv = tread.fast.bodies[0], tread.reference.bodies[0], tread.bodies[0]
    v0 = pappus_volume(f.initial_contour, -250.0)
    assert bv.measure == "volume"
    # The law holds against the curves' exact volume, which the initial polygon's misses by at most 2e-5 of it.
    assert f.volume_initial == pytest.approx(v0, rel=2e-5)
    assert f.volume_target == pytest.approx(0.98 * f.volume_initial, rel=1e-12)
    assert pappus_volume(f.contour, -250.0) == pytest.approx(f.volume_target, rel=1e-9)  # the fast model meets its law
    assert r.volume_initial == pytest.approx(v0, rel=1e-9)  # the reference meshes the same polygon
    assert abs(bv.fast_error) < 1e-9
    assert abs(bv.reference_error) < 2e-3  # the reference gives up volume only to its finite bulk modulus
    assert bv.reference_error == pytest.approx(r.volume_change, rel=1e-6, abs=1e-9)


def test_revolution_report_is_plain_json_with_volumes(tread):
    report = json.loads(json.dumps(tread.to_json(), allow_nan=False))
    assert report["revolution"]["axis"] == [[0.0, -250.0], [1.0, -250.0]]
    body = report["bodies"][0]
    assert body["measure"] == "volume" and body["target"] == pytest.approx(tread.fast.bodies[0].volume_target)
    assert abs(body["fast"]["relative_error"]) < 1e-9
    lines = tread.lines()
    assert "bodies of revolution" in lines[0] and any(line.lstrip().startswith("volume reference") for line in lines)


def test_a_plane_one_body_case_with_both_models():
    case = sd.load_case(COVER)
    for model in ("paper", "hyperelastic"):
        v = validate(case, model=model, mesh_size=MESH, fast_runs=1)
        f, ref = v.fast.bodies[0], v.reference.bodies[0]
        assert v.model == model and not v.revolution
        length = shapely.LineString(ref.upper).length
        assert v.bodies[0].shape.hausdorff == pytest.approx(shapely_hausdorff(f.upper, ref.upper), abs=1e-3 * length)
        # The law holds against the curves' exact area, which the initial polygon's misses by at most 2e-5 of it.
        assert f.area_initial == pytest.approx(shapely.Polygon(f.initial_contour).area, rel=2e-5)
        target = 0.9 * f.area_initial
        assert f.area_target == pytest.approx(target, rel=1e-12)
        assert shapely.Polygon(f.contour).area == pytest.approx(target, rel=1e-9)
        assert abs(v.bodies[0].reference_error) < 2e-3


def test_refusals_are_one_line_naming_the_field():
    with pytest.raises(sd.CaseError, match=r"^mesh_size: must be a finite number > 0"):
        validate(sd.load_case(TREAD), mesh_size=0.0, fast_runs=1)
    with pytest.raises(sd.CaseError, match=r"^options.bulk_to_shear: the reference is a nearly incompressible"):
        validate(one_body(), bulk_to_shear=50.0, fast_runs=1)
