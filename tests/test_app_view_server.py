"""The page's engineer's view, server side: drawing options, outlines, colour maps, the report figure (TestClient)."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")

from starlette.testclient import TestClient
from test_app_server import ORIGIN, TOKEN, receive, request

import sectiondeform as sd
from sectiondeform.app import engine
from sectiondeform.app.server import DRAWING_OPTIONS, create_app
from sectiondeform.commands._io_args import FLAGS
from sectiondeform.deform import Deformer
from sectiondeform.field_plot import field_values
from sectiondeform.io import read_case

from conftest import SEAL, box_case

SEAL_OPTIONS = {"bbox": [-21, -1, -12, 10], "snap": 0.05, "close_gap": 2.5, "split": [[-19.6, 0], [-18.4, 0]],
                "simplify": 0.01, "target_arc": 0.05}


@pytest.fixture(scope="module")
def case_json():
    return sd.case_to_dict(sd.load_case(sd.example_case_path()))


def client_for(case_json, **limits):
    client = TestClient(create_app(case_json, ["testserver"], token=TOKEN, **limits))
    assert client.get(f"/?token={TOKEN}").status_code == 200
    return client


@pytest.fixture()
def client(case_json):
    return client_for(case_json)


def upload(client, name: str, data: bytes, **form):
    return client.post("/api/open", files={"file": (name, data)}, data=form, headers=ORIGIN)


def test_the_page_offers_every_drawing_option_of_the_command_line():
    assert set(DRAWING_OPTIONS) == set(FLAGS)


def test_a_real_scan_opens_with_the_command_lines_options(client):
    """The seal scan needs a box, a snap, a closed gap and a split: given as the page sends them, it opens."""
    r = upload(client, "seal.dxf", SEAL.read_bytes(), options=json.dumps(SEAL_OPTIONS), area_ratio="0.8")
    assert r.status_code == 200, r.text
    data = r.json()
    expected = read_case(SEAL, **{**SEAL_OPTIONS, "bbox": tuple(SEAL_OPTIONS["bbox"]), "law": sd.AreaRatio(0.8)})
    assert data["case"] == {**sd.case_to_dict(expected), "name": "seal"}  # the library's reading; the file's own name
    assert data["outline"][0]["area"] == pytest.approx(27.6, abs=0.1)
    assert sum("gives no law" in line for line in data["report"]) == 1
    assert len(data["report"]) == len(set(data["report"]))  # each line once, though the law was added on a second read


def test_units_layers_and_lower_side_reach_the_reader(client, tmp_path):
    from sectiondeform.io import write_case

    path = tmp_path / "box.dxf"
    write_case(path, sd.case_from_dict(box_case(ratio=0.9)))
    r = upload(client, "box.dxf", path.read_bytes(), options=json.dumps(
        {"units": "cm", "layers": {"lower": "LOWER", "upper": "UPPER"}, "lower_side": "shorter"}))
    assert r.status_code == 200, r.text
    data = r.json()
    assert data["case"]["units"] == "cm"
    assert data["outline"][0]["area"] == pytest.approx(40.0 / 100, rel=1e-12)  # 10 x 4 mm in cm²


@pytest.mark.parametrize("options, field", [
    ({"bbox": [1, 0, 0, 1]}, "bbox"), ({"bbx": [0, 0, 1, 1]}, "bbx"), ({"layers": {"bottom": "X"}}, "layers"),
    ({"units": "furlong"}, "units"), ({"split": [[0, 0]]}, "split"), ({"snap": -1}, "snap"),
    ({"law": {"area_ratio": 0.5}}, "law"), ({"target": {"polyline": [[0, 0], [1, 0]]}}, "target"),
    ("[1, 2]", "options"),
])
def test_a_bad_drawing_option_is_one_line_naming_it(client, options, field):
    r = upload(client, "seal.dxf", b"0\nEOF\n", options=options if isinstance(options, str) else json.dumps(options))
    assert r.status_code == 422
    message = r.json()["error"]
    assert message.startswith(field) and "\n" not in message, message


def test_a_drawing_option_for_a_case_json_is_refused_naming_it(client, case_json):
    r = upload(client, "case.json", json.dumps(case_json).encode(), options=json.dumps({"bbox": [0, 0, 1, 1]}))
    assert r.status_code == 422 and "bbox" in r.json()["error"] and "drawings" in r.json()["error"]


def test_every_case_comes_with_its_outline_and_exact_area(case_json):
    box = box_case(width=10.0, height=4.0)
    start = client_for(box).get("/api/start").json()
    (body,) = start["outline"]
    assert body["area"] == 40.0                              # the curves' own area, exactly
    contour = np.array(body["contour"])
    assert contour[:, 0].min() == 0 and contour[:, 0].max() == 10 and contour[:, 1].max() == 4
    # the paper example: its curves' area, which the section's discretisation meets to its chordal error
    (paper,) = client_for(case_json).get("/api/start").json()["outline"]
    initial = Deformer(sd.case_from_dict(case_json)).deform().bodies[0].area_initial
    assert paper["area"] == pytest.approx(initial, rel=1e-4)


@pytest.mark.parametrize("model, name", [("paper", "J"), ("hyperelastic", "J"), ("hyperelastic", "max_principal_strain"),
                                         ("hyperelastic", "von_mises_stress"), ("hyperelastic", "pressure")])
def test_a_colour_map_comes_with_a_full_deformation(client, case_json, model, name):
    problem = engine.with_model(sd.case_from_dict(case_json), model)
    _, expected = field_values(Deformer(problem, model=model).deform(), name)
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        message = json.loads(request(case_json, 1, model=model))
        ws.send_text(json.dumps({**message, "field": name}))
        out = receive(ws)
    field = out["field"]
    assert field["name"] == name and len(out["mesh_final"]["cells"]) == len(field["values"])
    np.testing.assert_allclose(field["values"], expected[0], rtol=1e-9, atol=1e-12)
    assert field["min"] == field["values"].min() and field["max"] == field["values"].max()
    assert ("geometric" in field["label"]) == (model == "paper")


def test_a_stress_of_the_paper_model_is_a_line_and_a_preview_has_no_map(client, case_json):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(json.dumps({**json.loads(request(case_json, 1)), "field": "von_mises_stress"}))
        out = receive(ws)
        assert out["type"] == "result" and "paper model has no material" in out["field"]["error"]
        assert "\n" not in out["field"]["error"] and "--" not in out["field"]["error"]
        ws.send_text(json.dumps({**json.loads(request(case_json, 2, final=False)), "field": "J"}))
        assert "field" not in receive(ws)
        ws.send_text(json.dumps({**json.loads(request(case_json, 3)), "field": "stress"}))
        refused = receive(ws)
        assert refused["type"] == "refused" and refused["message"].startswith("field: unknown field 'stress'")


def test_the_report_figure_is_the_librarys(client, case_json):
    from PIL import Image

    r = client.post("/api/save/figure.png", json={"case": case_json, "model": "hyperelastic"}, headers=ORIGIN)
    assert r.status_code == 200 and r.headers["content-type"] == "image/png"
    image = Image.open(io.BytesIO(r.content))
    assert image.width > 1000 and image.height > 700


def test_the_report_figure_names_the_law_the_model_the_areas_and_the_units(case_json, tmp_path):
    import matplotlib

    path = tmp_path / "figure.svg"
    with matplotlib.rc_context({"svg.fonttype": "none"}):  # the texts kept as text
        engine.report_figure(case_json, "hyperelastic", path)
    text = path.read_text()
    result = engine.full_result(case_json, "hyperelastic")
    assert "area ratio 0.8" in text and "hyperelastic model" in text
    assert f"deformed {result.bodies[0].area_final:.1f} mm²" in text
    assert "x (mm)" in text and "y (mm)" in text


def test_no_other_figure_is_saved(client, case_json):
    r = client.post("/api/save/figure.vtu", json={"case": case_json}, headers=ORIGIN)
    assert r.status_code == 404 and "figure.png" in r.json()["error"]


def test_pages_on_the_same_case_share_one_preparation(case_json, monkeypatch):
    """Thirty pages of one case prepare it once; each page still gets the whole first answer (contours, cells)."""
    built = []
    real = engine.Deformer

    def counting(*args, **kwargs):
        built.append(kwargs.get("model"))
        return real(*args, **kwargs)

    monkeypatch.setattr(engine, "Deformer", counting)
    client = client_for(case_json)
    answers = []
    for _ in range(3):
        with client.websocket_connect("/ws", headers=ORIGIN) as ws:
            ws.send_text(request(case_json, 1, final=False))
            answers.append(receive(ws))
    assert built == ["paper"]
    assert all(a["prepared"] and len(a["initial_contour"]) and a["mesh_final"]["cells"] for a in answers)
    np.testing.assert_array_equal(answers[0]["contour"], answers[2]["contour"])


def test_the_shared_preparations_are_bounded():
    shared = engine.SharedDeformers(size=2)
    for key in "abcd":
        shared.get(key, object)
    assert len(shared) == 2
    first, _ = shared.get("d", lambda: pytest.fail("prepared twice"))
    assert first is shared.get("d", object)[0]
