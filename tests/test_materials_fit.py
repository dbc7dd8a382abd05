"""Fitting rubber constants to homogeneous test data; the fit command."""

import json
from pathlib import Path

import numpy as np
import pytest

from sectiondeform.cli import main
from sectiondeform.errors import CaseError
from sectiondeform.materials import MooneyRivlin, NeoHookean, Yeoh, material_from_json
from sectiondeform.materials.fit import TestCurve, fit_material, read_test_data
from sectiondeform.materials.homogeneous import MODES, nominal_stress

TRELOAR = Path(__file__).parent / "data" / "materials" / "treloar-1944.csv"


def _write(tmp_path, material, modes=MODES, name="data.csv"):
    lines = ["# generated", "mode,stretch,nominal_stress"]
    for mode in modes:
        lam = np.linspace(1.05, 3.5 if mode != "equibiaxial" else 2.5, 12)
        for l, p in zip(lam, nominal_stress(material, mode, lam)):
            lines.append(f"{mode},{float(l)!r},{float(p)!r}")
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("material", [NeoHookean(0.6), MooneyRivlin(0.25, 0.07), Yeoh(0.3, -0.004, 0.0002)], ids=repr)
@pytest.mark.parametrize("modes", [("uniaxial",), MODES])
def test_fit_recovers_the_constants_of_the_model_that_made_the_data(tmp_path, material, modes):
    curves = read_test_data(_write(tmp_path, material, modes))
    fit = fit_material(material.model, curves, bulk_to_shear=500.0)
    for name in material.constants:
        assert getattr(fit.material, name) == pytest.approx(getattr(material, name), rel=1e-8, abs=1e-12)
    assert all(e < 1e-9 for e in fit.errors.values())
    assert set(fit.errors) == set(modes)
    assert fit.warnings == ()
    assert fit.material.bulk_to_shear == 500.0


def test_fit_of_a_richer_model_reduces_the_error_and_stays_in_bounds():
    curves = read_test_data(TRELOAR)
    assert [c.mode for c in curves] == list(MODES)
    fits = {m: fit_material(m, curves) for m in ("neo-hookean", "mooney-rivlin", "yeoh")}
    mean = {m: np.mean(list(f.errors.values())) for m, f in fits.items()}
    assert mean["yeoh"] < mean["mooney-rivlin"] < mean["neo-hookean"]
    assert fits["mooney-rivlin"].material.c01 >= 0.0
    assert fits["yeoh"].material.c30 >= 0.0
    # Treloar's rubber has an initial shear modulus of about 0.4 MPa.
    for f in fits.values():
        assert 0.3 < f.material.shear_modulus < 0.5


def test_separate_files_per_mode(tmp_path):
    m = MooneyRivlin(0.2, 0.05)
    lam = np.linspace(1.1, 3.0, 6)
    (tmp_path / "ps.csv").write_text("stretch,nominal_stress\n" + "\n".join(
        f"{float(l)!r},{float(p)!r}" for l, p in zip(lam, nominal_stress(m, "planar", lam))))
    curves = read_test_data(tmp_path / "ps.csv", "pure_shear")
    assert curves[0].mode == "planar"
    assert fit_material("neo-hookean", curves).material.shear_modulus == pytest.approx(0.5)
    with pytest.raises(CaseError, match="do not set the 2 constants of mooney-rivlin apart"):
        fit_material("mooney-rivlin", curves)
    (tmp_path / "ut.csv").write_text("stretch,nominal_stress\n" + "\n".join(
        f"{float(l)!r},{float(p)!r}" for l, p in zip(lam, nominal_stress(m, "uniaxial", lam))))
    curves += read_test_data(tmp_path / "ut.csv", "UT")
    assert fit_material("mooney-rivlin", curves).material.c01 == pytest.approx(0.05)


@pytest.mark.parametrize("text, where", [
    ("mode,stretch,nominal_stress\nuniaxial,1.5,0.3\nuniaxial,abc,0.4\n", "line 3, column stretch: expected a number, got 'abc'"),
    ("mode,stretch,nominal_stress\nuniaxial,1.5,nan\n", "line 2, column nominal_stress: expected a finite number"),
    ("mode,stretch,nominal_stress\nuniaxial,-1.5,0.3\n", "line 2, column stretch: must be within [0.001, 1000]"),
    # These two crashed the fit (SVD did not converge) and printed nan constants.
    ("mode,stretch,nominal_stress\nequibiaxial,1e-300,0.48\n", "line 2, column stretch: must be within [0.001, 1000]"),
    ("mode,stretch,nominal_stress\nplanar,3.4,1e+308\n", "line 2, column nominal_stress: must be within +-1e+06 MPa"),
    ("mode,stretch,nominal_stress\nshear,1.5,0.3\n", "line 2, column mode: unknown test mode 'shear'"),
    ("# c\nmode,stretch\nuniaxial,1.5\n", "line 2: no column 'nominal_stress'"),
    ("stretch,nominal_stress\n1.5,0.3\n", "line 1: no column 'mode'"),
    ("mode,stretch,nominal_stress\nuniaxial,1.5\n", "line 2, column nominal_stress: empty"),
    ("mode,stretch,nominal_stress\nuniaxial,1.0,0.0\n", "uniaxial: every point is at stretch 1"),
    ("# only comments\n", "no data"),
])
def test_bad_csv_gets_a_one_line_error_naming_line_and_column(tmp_path, text, where):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(CaseError) as info:
        read_test_data(path)
    msg = str(info.value)
    assert where in msg and str(path) in msg, msg
    assert "\n" not in msg


def test_too_few_points_are_refused():
    curves = [TestCurve("uniaxial", np.array([1.5, 2.0]), np.array([0.3, 0.5]))]
    with pytest.raises(CaseError, match="2 point\\(s\\) for 3 constants of yeoh"):
        fit_material("yeoh", curves)


@pytest.mark.parametrize("lam, stress", [([1e-300, 1.5], [0.5, 0.3]), ([1.5, 2.0, 2.5], [0.3, 0.5, 1e300])],
                         ids=["tiny-stretch", "huge-stress"])
@pytest.mark.parametrize("model", ["neo-hookean", "mooney-rivlin", "yeoh"])
def test_curves_built_in_python_out_of_range_are_one_line_not_nan(model, lam, stress):
    curves = [TestCurve("equibiaxial", np.array(lam), np.array(stress))]
    with np.errstate(all="raise"), pytest.raises(CaseError, match="^data: "):
        fit_material(model, curves)


@pytest.mark.parametrize("model", ["neo-hookean", "mooney-rivlin", "yeoh"])
def test_data_at_the_stretch_and_stress_bounds_give_finite_constants(model):
    lam = np.array([1e-3, 0.5, 2.0, 1e3])
    fit = fit_material(model, [TestCurve("uniaxial", lam, nominal_stress(NeoHookean(0.5), "uniaxial", lam))])
    assert np.isfinite(fit.material.shear_modulus) and all(np.isfinite(list(fit.errors.values())))


def test_falling_data_is_refused():
    lam = np.linspace(1.1, 2.0, 5)
    with pytest.raises(CaseError, match="no positive shear modulus"):
        fit_material("neo-hookean", [TestCurve("uniaxial", lam, -lam)])


# -- command line ---------------------------------------------------------------------------------------

def test_fit_command_writes_the_material_object_and_the_figure(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    out, fig = tmp_path / "rubber.json", tmp_path / "fit.png"
    assert main(["fit", str(TRELOAR), "--model", "yeoh", "-o", str(out), "--plot", str(fig)]) == 0
    text = capsys.readouterr().out
    assert "yeoh" in text and "c30" in text and "%" in text
    material = material_from_json(json.loads(out.read_text()))
    assert isinstance(material, Yeoh) and material.shear_modulus > 0
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_fit_command_all_models_and_max_stretch(tmp_path, capsys):
    m = Yeoh(0.3, -0.004, 0.0002)
    data = _write(tmp_path, m)
    assert main(["fit", str(data), "--max-stretch", "2"]) == 0
    text = capsys.readouterr().out
    assert "neo-hookean" in text and "mooney-rivlin" in text and "yeoh" in text
    assert "stretch 1.05..1.97" in text or "1.05..1.9" in text


def test_fit_command_bad_input_exits_2_and_writes_nothing(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("mode,stretch,nominal_stress\nuniaxial,x,1\n")
    out = tmp_path / "m.json"
    assert main(["fit", str(bad), "--model", "yeoh", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "line 2, column stretch" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()
    assert main(["fit", str(TRELOAR), "-o", str(out)]) == 2  # -o needs one model
    assert "--model" in capsys.readouterr().err
    assert not out.exists()
