"""Bodies of revolution through the command line: volumes in section-result/2, the figure, hand-derived shapes.

The values are derived without the library's Pappus module: volumes from
shapely's area and centroid, and the annular sector that a rectangle becomes
when its flat support is bent onto an arc, from the closed forms of the
sector's area and centroid (solved with a bracketing root finder).
"""

import json
import math

import matplotlib
import numpy as np
import pytest
import shapely
from scipy.optimize import brentq

from sectiondeform.cli import main
from sectiondeform.deform import deform
from sectiondeform.io.case import case_from_dict
from sectiondeform.plot import draw_result

from conftest import CASES_DIR

matplotlib.use("Agg")

DRUM = CASES_DIR / "v2" / "tread-on-drum.json"


def volume_by_geos(contour, axis_y: float) -> float:
    """2 pi x area x centroid distance from the horizontal axis y = axis_y (shapely)."""
    poly = shapely.Polygon(contour)
    return 2 * math.pi * poly.area * abs(poly.centroid.y - axis_y)


def test_the_tread_on_drum_runs_through_the_cli_with_volumes_and_figure(tmp_path, capsys):
    out, fig = tmp_path / "r.json", tmp_path / "r.png"
    assert main(["deform", str(DRUM), "-o", str(out), "--plot", str(fig)]) == 0
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    data = json.loads(out.read_text())
    assert data["format"] == "section-result/2"
    assert data["revolution"] == {"axis": [[0.0, -250.0], [1.0, -250.0]]}
    ratios = {"undertread": 1.0, "tread": 0.98}
    case = json.loads(DRUM.read_text())
    for body, spec in zip(data["bodies"], case["bodies"]):
        vol = body["volume"]
        assert set(vol) == {"initial", "target", "final", "relative_error"}
        assert vol["target"] == pytest.approx(ratios[spec["name"]] * vol["initial"], rel=1e-14)
        assert abs(vol["final"] - vol["target"]) <= 1e-9 * vol["target"]
        assert vol["final"] == pytest.approx(volume_by_geos(body["contour"], -250.0), rel=1e-12)
        assert abs(vol["relative_error"]) <= 1e-9
        assert body["area"]["final"] == pytest.approx(shapely.Polygon(body["contour"]).area, rel=1e-12)
    # the undertread, a 150 x 3 rectangle at radius 250 to 253: initial volume by hand
    under = data["bodies"][0]["volume"]["initial"]
    assert under == pytest.approx(2 * math.pi * 150 * 3 * (250 + 1.5), rel=1e-12)
    printed = capsys.readouterr().out
    assert "undertread" in printed and "volume" in printed and "mm³" in printed


# -- a rectangle bent onto an arc becomes an annular sector -----------------------

W, H, R = 20.0, 2.0, 40.0  # rectangle W x H resting on the line y = R; the axis is y = 0
RHO = 30.0  # radius of the target arc, its centre below, its top at y = R + 3
ALPHA = W / (2 * RHO)  # half-angle of the arc of length W
CENTRE = (W / 2, R + 3.0 - RHO)
TOP_POINTS = 201


def bent_case(ratio: float, name: str = "bent") -> dict:
    """A one-body ``section-case/2`` of revolution, its lower curve the support (a version-1 style case)."""
    deg = math.degrees(ALPHA)
    lower = [[0.0, R], [W, R]]
    top = [[x, R + H] for x in np.linspace(W, 0.0, TOP_POINTS)]  # many points: the top follows the arc
    upper = [[W, R], *top, [0.0, R]]
    return {
        "format": "section-case/2", "name": name, "units": "mm",
        "support": {"polyline": lower},
        "target": {"arc": {"center": list(CENTRE), "radius": RHO, "start_deg": 90 + deg, "end_deg": 90 - deg}},
        "revolution": {"axis": [[0.0, 0.0], [1.0, 0.0]]},
        "bodies": [{"name": "strip", "lower": {"polyline": lower}, "upper": {"polyline": upper},
                    "law": {"volume_ratio": ratio}}],
        "options": {"chordal_error": 1e-4},
    }


def sector_outer_radius(ratio: float) -> float:
    """Outer radius b of the annular sector (inner radius RHO, half-angle ALPHA) of volume ratio x the rectangle's.

    Area alpha (b^2 - a^2); centroid at (2 sin alpha / 3 alpha) (b^3 - a^3) / (b^2 - a^2)
    above the centre; Pappus: V = 2 pi [alpha (b^2 - a^2) y_c + 2/3 sin alpha (b^3 - a^3)].
    """
    a, yc = RHO, CENTRE[1]
    v0 = 2 * math.pi * W * H * (R + H / 2)

    def excess(b):
        return 2 * math.pi * (ALPHA * (b * b - a * a) * yc + 2 / 3 * math.sin(ALPHA) * (b**3 - a**3)) - ratio * v0

    return brentq(excess, a, a + 10 * H, xtol=1e-14)


@pytest.mark.parametrize("ratio", [1.0, 0.9, 1.15])
def test_a_rectangle_bent_onto_an_arc_becomes_the_hand_derived_annular_sector(ratio, tmp_path):
    path, out = tmp_path / "bent.json", tmp_path / "r.json"
    path.write_text(json.dumps(bent_case(ratio)))
    assert main(["deform", str(path), "-o", str(out)]) == 0
    data = json.loads(out.read_text())
    body = data["bodies"][0]
    v0 = 2 * math.pi * W * H * (R + H / 2)
    assert body["volume"]["initial"] == pytest.approx(v0, rel=1e-12)
    assert volume_by_geos(body["contour"], 0.0) == pytest.approx(ratio * v0, rel=1e-9)
    # the images of the top edge's points lie on the circle of the sector's outer radius, up to the
    # polygon standing for the target arc: its chords s = sqrt(8 rho e) = 0.15 mm (chordal error e = 1e-4)
    # turn the two end columns by s / 2 rho from the radii, which moves the top by about
    # H^2 s / (2 rho W) = 5e-4 mm (measured 4e-4 to 5.5e-4, shrinking as sqrt(e)); bound 2e-3 H = 4e-3 mm
    top = np.asarray(body["upper"][1:-1])
    assert len(top) == TOP_POINTS
    b = sector_outer_radius(ratio)
    assert np.max(np.abs(np.hypot(*(top - CENTRE).T) - b)) <= 2e-3 * H


def test_the_axis_is_drawn_when_it_is_near_the_bodies_and_named_when_far():
    near = bent_case(1.0)
    near["revolution"] = {"axis": [[0.0, R - 8.0], [1.0, R - 8.0]]}  # 8 mm below the support
    fig = draw_result(deform(case_from_dict(near)))
    for ax in fig.axes:
        lines = [ln for ln in ax.get_lines() if ln.get_label() == "axis of revolution"]
        assert len(lines) == 1
        lo, hi = ax.get_ylim()
        assert lo < R - 8.0 < hi  # the view reaches the axis
    far = draw_result(deform(case_from_dict(bent_case(1.0))))  # axis 40 mm away, size ~20
    assert not any(ln.get_label() == "axis of revolution" for ax in far.axes for ln in ax.get_lines())
    assert "revolution axis through (0, 0), (1, 0)" in far.get_suptitle()
    label = far.axes[3].get_legend().get_texts()[1].get_text()  # after the initial bodies' entry
    assert "mm³" in label and "volume error" in label


def test_a_plane_assembly_has_no_revolution_key_nor_volume():
    case = bent_case(1.0)
    del case["revolution"]
    case["bodies"][0]["law"] = {"area_ratio": 0.9}
    data = deform(case_from_dict(case)).to_json(meshes=False)
    assert "revolution" not in data and "volume" not in data["bodies"][0]
