"""Rigid parts in files and figures: DXF/SVG layers RIGID-<name> (cases and results), the contact pressure in meshes, --plot-history."""

from __future__ import annotations

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.cli import main
from sectiondeform.curves import polygon_area
from sectiondeform.io import read_case, read_drawing, write_case, write_result

from conftest import CASES_DIR

BUMPER = CASES_DIR / "v2" / "bumper-under-plate.json"
SLEEVE = CASES_DIR / "v2" / "sleeve-on-shaft.json"
ORING = CASES_DIR / "v2" / "o-ring-squeeze-20.json"


@pytest.fixture(scope="module")
def bumper():
    return sd.Deformer(sd.load_case(BUMPER)).deform()


@pytest.mark.parametrize("path", [BUMPER, SLEEVE, ORING])
@pytest.mark.parametrize("ext", ["dxf", "svg"])
def test_rigid_parts_go_through_drawings(path, ext, tmp_path):
    case = sd.load_case(path)
    out = tmp_path / f"case.{ext}"
    write_case(out, case)
    tags = {t for p in read_drawing(out).pieces for t in p.tags}
    assert {f"RIGID-{r.name}".upper() for r in case.rigid} <= tags
    back = read_case(out)
    assert [(r.name, r.travel, r.friction) for r in back.rigid] == [(r.name, r.travel, r.friction) for r in case.rigid]
    for a, b in zip(case.rigid, back.rigid):
        pa, pb = (polygon_area(r.contour.discretise(1e-9)[0]) for r in (a, b))
        assert abs(abs(pb) / abs(pa) - 1.0) < 1e-9


@pytest.mark.parametrize("ext", ["dxf", "svg"])
def test_result_drawing_has_the_parts_at_their_end(bumper, ext, tmp_path):
    out = tmp_path / f"result.{ext}"
    write_result(out, bumper)
    pieces = [p for p in read_drawing(out).pieces if "RIGID-PLATE" in p.tags]
    assert pieces
    pts = np.concatenate([p.curve.discretise(1e-6)[0] for p in pieces if p.curve is not None])
    # The plate ends with its lower face at y = 6.8 (its contour in the case).
    assert abs(pts[:, 1].min() - 6.8) < 1e-9 and abs(pts[:, 1].max() - 10.0) < 1e-9


def test_meshes_carry_the_contact_pressure_on_the_boundary(bumper, tmp_path):
    meshio = pytest.importorskip("meshio")
    out = tmp_path / "final.vtu"
    write_result(out, bumper)
    m = meshio.read(out)
    p = m.point_data["contact_pressure"]
    plate = bumper.rigid[0]
    on = p > 0
    assert on.sum() >= 3
    # Only nodes on the plate's face (within the documented tolerance) are pressed, with pressures of the contact's
    # range; all others carry 0.
    tol = max(2 * plate.penetration_max, 1e-4 * np.sqrt(bumper.bodies[0].area_final))
    assert np.all(np.abs(m.points[on, 1] - 6.8) <= tol * (1 + 1e-9))
    assert p.max() <= plate.pressure_max * (1 + 1e-12) and p.min() == 0.0
    assert np.all(np.abs(m.points[on, 0]) <= plate.length / 2 + bumper.bodies[0].quality.initial.element_size)


def test_deform_draws_the_load_deflection_curve(tmp_path):
    fig = tmp_path / "history.png"
    assert main(["deform", str(BUMPER), "-o", str(tmp_path / "r.json"), "--plot-history", str(fig)]) == 0
    assert fig.stat().st_size > 1000
    # A case without rigid parts has no such curve: one line, exit 2, nothing written.
    plain = CASES_DIR / "v2" / "two-layer-strip.json"
    if plain.exists():
        assert main(["deform", str(plain), "-o", str(tmp_path / "p.json"), "--plot-history", str(tmp_path / "h.png")]) == 2
        assert not (tmp_path / "p.json").exists() and not (tmp_path / "h.png").exists()
