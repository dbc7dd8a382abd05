"""Studies over rigid parts: the travel (squeeze) and friction as vary axes, the forces tabulated per part."""

from __future__ import annotations

import json

import pytest

from sectiondeform.studies.study import StudyError, study_from_dict

from conftest import CASES_DIR

BUMPER = str(CASES_DIR / "v2" / "bumper-under-plate.json")
STRIP = str(CASES_DIR / "v2" / "two-layer-strip.json")


def test_a_squeeze_sweep_tabulates_rising_forces():
    pytest.importorskip("pyarrow")
    from sectiondeform.studies.api import sweep

    study = {"format": "section-study/1", "name": "squeeze", "cases": [BUMPER],
             "vary": {"travel_scale": [0.5, 1.0], "friction": [0.0, 0.5]}}
    table = sweep(study, workers=0).to_pylist()
    assert [(r["travel_scale"], r["friction"]) for r in table] == [(0.5, 0.0), (0.5, 0.5), (1.0, 0.0), (1.0, 0.5)]
    assert all(r["ok"] for r in table), [r["error"] for r in table]
    parts = [json.loads(r["rigid"]) for r in table]
    for p in parts:
        assert set(p["plate"]) == {"force_x", "force_y", "contact_length", "pressure_max"}
        # The forces balance whatever the squeeze (nothing else loads the bumper).
        assert abs(p["plate"]["force_y"] + p["support"]["force_y"]) < 1e-3 * p["plate"]["force_y"]
    # A deeper squeeze (the same start, twice the travel) presses harder over a longer contact.
    for lo, hi in ((parts[0], parts[2]), (parts[1], parts[3])):
        assert hi["plate"]["force_y"] > 2 * lo["plate"]["force_y"] > 0
        assert hi["plate"]["contact_length"] > lo["plate"]["contact_length"]
    # Half the travel of the case is the case with its plate's travel halved.
    import sectiondeform as sd
    from sectiondeform.io.case import case_from_dict

    d = json.loads(open(BUMPER).read())
    d["rigid"][0]["travel"] = [0.0, -0.6]
    d["rigid"][0]["contour"]["polyline"] = [[x, y + 0.6] for x, y in d["rigid"][0]["contour"]["polyline"]]
    half = sd.Deformer(case_from_dict(d)).deform()
    assert abs(half.rigid[0].force[1] / parts[0]["plate"]["force_y"] - 1.0) < 1e-9


def test_rigid_axes_are_checked():
    with pytest.raises(StudyError, match=r"^vary.friction\[0\]: .*>= 0"):
        study_from_dict({"format": "section-study/1", "name": "s", "cases": [BUMPER], "vary": {"friction": [-0.1]}})
    with pytest.raises(StudyError, match=r"^vary.travel_scale\[0\]: must be > 0"):
        study_from_dict({"format": "section-study/1", "name": "s", "cases": [BUMPER], "vary": {"travel_scale": [0]}})
    with pytest.raises(StudyError, match=r"^vary.travel_scale: case .* has no rigid parts"):
        study_from_dict({"format": "section-study/1", "name": "s", "cases": [STRIP], "vary": {"travel_scale": [2.0]}})
