"""``validate`` on version-2 cases of one body: a body of revolution through the assembly path, a plane one.

The distances are checked against an independent computation (shapely's
Hausdorff distance of the two upper polylines, densified; the volume of
revolution by Pappus on shapely's polygon); what is refused exits 2 with one
line and writes nothing.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
import shapely

import sectiondeform as sd

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.assembly_deform import deform_assembly  # noqa: E402
from sectiondeform.cli import main  # noqa: E402
from sectiondeform.reference.validation import validate_case  # noqa: E402

from conftest import CASES_DIR  # noqa: E402

TREAD = CASES_DIR / "v2" / "tread-alone-on-drum.json"
COVER = CASES_DIR / "v2" / "cover-alone-on-arc.json"
STRIP = CASES_DIR / "v2" / "two-layer-strip.json"
MESH = 0.4  # coarse reference: these tests check the comparison, not the reference's convergence


def shapely_hausdorff(a: np.ndarray, b: np.ndarray) -> float:
    """Hausdorff distance of two polylines, shapely's, densified to 1/1000 of each segment."""
    return float(shapely.hausdorff_distance(shapely.LineString(a), shapely.LineString(b), densify=1e-3))


def pappus_volume(contour: np.ndarray, axis_y: float) -> float:
    """2π × area × centroid distance from the horizontal axis y = axis_y."""
    poly = shapely.Polygon(contour)
    return 2.0 * math.pi * poly.area * (poly.centroid.y - axis_y)


@pytest.fixture(scope="module")
def tread():
    return validate_case(sd.load_case(TREAD), mesh_size=MESH, fast_runs=1)


def test_the_one_body_revolution_case_is_a_body_of_revolution_on_its_support():
    a = sd.load_case(TREAD)
    assert len(a.bodies) == 1 and a.revolution is not None
    assert a.bodies[0].lower.to_json() == a.support.to_json()
    assert a.bodies[0].law.key == "volume_ratio"


def test_revolution_distances_match_an_independent_computation(tread):
    v = tread
    assert v.revolution and v.model == "paper" and v.assembly is not None
    # The fast body is the assembly path's, the reference the one-body solve's, point for point.
    np.testing.assert_array_equal(v.fast.upper, deform_assembly(sd.load_case(TREAD), model="paper").bodies[0].upper)
    assert v.fast.upper.shape == v.reference.upper.shape
    length = shapely.LineString(v.reference.upper).length
    assert v.shape.hausdorff == pytest.approx(shapely_hausdorff(v.fast.upper, v.reference.upper), abs=1e-3 * length)
    d = [shapely.Point(p).distance(shapely.Point(q)) for p, q in zip(v.fast.upper, v.reference.upper)]
    assert v.shape.max_pointwise == pytest.approx(max(d), rel=1e-12)
    assert v.shape.max_pointwise >= v.shape.hausdorff > 0  # two different models, one pairing of points
    # Over the height (12 mm: the tread's base to its crown) and over the mean thickness (area / base).
    poly = shapely.Polygon(v.fast.initial_contour)
    assert v.height == pytest.approx(12.0, rel=1e-9)
    assert v.thickness == pytest.approx(poly.area / 130.0, rel=1e-9)
    report = v.to_json()
    assert report["hausdorff_over_height"] == pytest.approx(v.shape.hausdorff / 12.0, rel=1e-12)


def test_revolution_volumes_are_pappus_and_the_law(tread):
    v = tread
    axis_y = -250.0
    f, r = v.fast, v.reference
    v0 = pappus_volume(f.initial_contour, axis_y)
    assert f.volume_initial == pytest.approx(v0, rel=1e-12)
    assert f.volume_target == pytest.approx(0.98 * v0, rel=1e-12)
    assert pappus_volume(f.contour, axis_y) == pytest.approx(f.volume_target, rel=1e-9)  # the fast model meets its law
    assert r.volume_initial == pytest.approx(v0, rel=1e-9)  # the reference meshes the same polygon
    fast_err, ref_err = v.volume_relative_errors
    assert abs(fast_err) < 1e-9
    assert abs(ref_err) < 2e-3  # the reference gives up volume only to its finite bulk modulus
    assert ref_err == pytest.approx(r.volume_change, rel=1e-6, abs=1e-9)


def test_revolution_report_is_plain_json_with_volumes_and_no_area_target(tread):
    report = json.loads(json.dumps(tread.to_json(), allow_nan=False))
    assert report["area"]["target"] is None
    assert report["fast"]["area_relative_error"] is None and report["reference"]["area_relative_error"] is None
    assert report["revolution"]["axis"] == [[0.0, -250.0], [1.0, -250.0]]
    assert report["volume"]["target"] == pytest.approx(tread.fast.volume_target)
    assert abs(report["fast"]["volume_relative_error"]) < 1e-9
    lines = tread.lines()
    assert "body of revolution" in lines[0] and any(line.lstrip().startswith("volume reference") for line in lines)


def test_validate_cli_on_the_revolution_case_writes_the_report(tmp_path, capsys):
    out = tmp_path / "report.json"
    assert main(["validate", str(TREAD), "--mesh-size", str(MESH), "-q", "-o", str(out)]) == 0
    report = json.loads(out.read_text())
    upper_fast = np.array(report["fast"]["upper"])
    upper_ref = np.array(report["reference"]["upper"])
    length = shapely.LineString(upper_ref).length
    assert report["shape"]["hausdorff"] == pytest.approx(shapely_hausdorff(upper_fast, upper_ref), abs=1e-3 * length)
    assert report["shape"]["max_pointwise"] == pytest.approx(np.hypot(*(upper_fast - upper_ref).T).max(), rel=1e-12)
    assert "of the mean thickness" in capsys.readouterr().out


def test_the_hyperelastic_model_of_revolution_is_near_the_axisymmetric_reference(tmp_path, capsys):
    # the same axisymmetric mechanics, coarse against fine: far nearer than the paper model's geometry
    paper, hyper = tmp_path / "paper.json", tmp_path / "hyper.json"
    for model, out in (("paper", paper), ("hyperelastic", hyper)):
        assert main(["validate", str(TREAD), "--model", model, "--mesh-size", "0.2", "-q", "-o", str(out)]) == 0
    p, h = (json.loads(f.read_text())["shape"] for f in (paper, hyper))
    assert h["hausdorff_relative"] < 0.01 and h["hausdorff_relative"] < p["hausdorff_relative"] / 5


@pytest.mark.parametrize(
    ("path", "model", "extra", "message"),
    [
        (STRIP, "paper", ["--bulk-to-shear", "50"], r"^options.bulk_to_shear: the reference is a nearly incompressible"),
        (TREAD, "hyperelastic", ["--mesh-size", "0"], r"^mesh_size: must be a finite number > 0"),
    ],
)
def test_what_is_refused_exits_2_in_one_line_and_writes_nothing(tmp_path, capsys, path, model, extra, message):
    out, fig = tmp_path / "report.json", tmp_path / "fig.png"
    code = main(["validate", str(path), "--model", model, "--mesh-size", str(MESH), "-q", "-o", str(out),
                 "--plot", str(fig), *extra])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1
    assert re.search(message, err.split("error: ", 1)[1])
    assert not out.exists() and not fig.exists()


def test_a_plane_one_body_case_goes_through_the_assembly_path_with_both_models():
    case = sd.load_case(COVER)
    assert case.revolution is None and case.bodies[0].lower.to_json() == case.support.to_json()
    for model in ("paper", "hyperelastic"):
        v = validate_case(case, model=model, mesh_size=MESH, fast_runs=1)
        assert v.model == model and v.assembly is not None and not v.revolution
        length = shapely.LineString(v.reference.upper).length
        assert v.shape.hausdorff == pytest.approx(shapely_hausdorff(v.fast.upper, v.reference.upper), abs=1e-3 * length)
        target = 0.9 * shapely.Polygon(v.fast.initial_contour).area
        assert v.fast.area_target == pytest.approx(target, rel=1e-12)
        assert shapely.Polygon(v.fast.contour).area == pytest.approx(target, rel=1e-9)
        assert abs(v.to_json()["reference"]["area_relative_error"]) < 2e-3


def test_calculix_is_refused_for_a_version_two_case_before_any_work(tmp_path, capsys):
    out = tmp_path / "report.json"
    assert main(["validate", str(COVER), "--reference", "calculix", "-q", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--reference: CalculiX validates version-1 cases only" in err
    assert not out.exists()
