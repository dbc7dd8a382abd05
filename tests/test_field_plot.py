"""The --plot-field colour map: the values drawn, their label, and the refusals before any work."""

import json

import numpy as np
import pytest

from sectiondeform.cli import main
from sectiondeform.deform import Deformer
from sectiondeform.errors import CaseError
from sectiondeform.field_plot import draw_field, field_values
from sectiondeform.io.case import case_from_dict

from conftest import CASES_DIR

LAM, RATIO = 1.25, 0.8
PNG = b"\x89PNG\r\n\x1a\n"


def stretch_case(model="paper"):
    """A 10 x 2 rectangle stretched by LAM along a flat target under the area ratio RATIO (homogeneous)."""
    return {
        "format": "section-case/1",
        "lower": {"polyline": [[0, 0], [10, 0]]},
        "upper": {"polyline": [[10, 0], [10, 2], [0, 2], [0, 0]]},
        "target": {"polyline": [[0, 0], [10 * LAM, 0]]},
        "law": {"area_ratio": RATIO},
        "options": {"model": model},
    }


def test_the_values_drawn_are_the_homogeneous_stretchs_and_say_geometric_for_the_paper_model():
    result = Deformer(case_from_dict(stretch_case())).deform()
    kind, (j,) = field_values(result, "J")
    assert kind == "geometric"
    np.testing.assert_allclose(j, RATIO, rtol=1e-12)  # area ratio r, out-of-plane stretch 1
    _, (top,) = field_values(result, "max_principal_stretch")
    np.testing.assert_allclose(top, LAM, rtol=1e-12)
    fig = draw_field(result, "min_principal_stretch")
    assert "geometric" in fig.axes[-1].get_ylabel()  # the colour bar


def test_the_hyperelastic_model_draws_mechanical_fields_with_its_out_of_plane_stretch():
    result = Deformer(case_from_dict(stretch_case("hyperelastic"))).deform()
    kind, (top,) = field_values(result, "max_principal_stretch")
    assert kind == "mechanical"
    assert np.all(top >= 1 / RATIO - 1e-12)  # lambda_z = 1/r is one of the three stretches
    assert "geometric" not in draw_field(result, "J").axes[-1].get_ylabel()
    kind, (vm,) = field_values(result, "von_mises_stress")
    assert np.all(vm > 0)  # lambda_z = 1.25 out of the plane: never a pure pressure


def test_the_paper_model_has_no_stress_to_draw():
    result = Deformer(case_from_dict(stretch_case())).deform()
    with pytest.raises(CaseError, match=r"^--plot-field: von_mises_stress is a stress and the paper model has no material"):
        field_values(result, "von_mises_stress")


def test_the_cli_draws_the_field_of_an_assembly_of_revolution(tmp_path):
    out, fig = tmp_path / "r.json", tmp_path / "j.png"
    drum = CASES_DIR / "v2" / "tread-on-drum.json"
    assert main(["deform", str(drum), "-o", str(out), "--plot", str(fig), "--plot-field", "J"]) == 0
    assert fig.read_bytes()[:8] == PNG and json.loads(out.read_text())["format"] == "section-result/2"


@pytest.mark.parametrize("extra, message", [
    (["--plot-field", "J"], "--plot-field: draws the --plot figure"),
    (["--plot", "f.png", "--plot-field", "stress"], "--plot-field: unknown field 'stress'; use one of"),
    # known only once the model has run (the paper model has no stress): still nothing written
    (["--plot", "f.png", "--plot-field", "pressure", "--model", "paper"], "--plot-field: pressure is a stress"),
])
def test_a_bad_plot_field_is_refused_in_one_line_before_anything_is_written(tmp_path, capsys, extra, message):
    case = tmp_path / "case.json"
    case.write_text(json.dumps(stretch_case()))
    out = tmp_path / "r.json"
    extra = [str(tmp_path / e) if e.endswith(".png") else e for e in extra]
    assert main(["deform", str(case), "-o", str(out), *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0]
    assert not out.exists() and not list(tmp_path.glob("*.png"))


def test_field_values_refuse_an_unknown_name():
    result = Deformer(case_from_dict(stretch_case())).deform()
    with pytest.raises(CaseError, match=r"^--plot-field: unknown field"):
        field_values(result, "von_mises")


def test_fields_with_no_output_to_carry_them_are_refused_before_any_work(tmp_path, capsys):
    case = tmp_path / "case.json"
    case.write_text(json.dumps(stretch_case()))
    out = tmp_path / "r.svg"
    assert main(["deform", str(case), "-o", str(out), "--fields"]) == 2
    assert "--fields: no output carries them" in capsys.readouterr().err and not out.exists()
    vtu = tmp_path / "m.vtu"
    assert main(["deform", str(case), "-o", str(out), "--fields", "--mesh-out", str(vtu)]) == 0
    assert out.exists() and vtu.exists()
