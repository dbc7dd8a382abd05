"""The page's server with assemblies (section-case/2): per-body answers, law changes, the library's refusals."""

from __future__ import annotations

import copy
import io
import json
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")

from starlette.testclient import TestClient  # noqa: E402
from test_app_server import ORIGIN, receive  # noqa: E402

from sectiondeform import CaseError, curve_from_json  # noqa: E402
from sectiondeform.app import engine  # noqa: E402
from sectiondeform.app.server import create_app  # noqa: E402
from sectiondeform.deform import Deformer  # noqa: E402
from sectiondeform.io.case import case_from_dict  # noqa: E402

CASES = Path(__file__).parent / "data" / "cases" / "v2"


@pytest.fixture(scope="module")
def strip():
    return json.loads((CASES / "two-layer-strip.json").read_text())


@pytest.fixture(scope="module")
def drum():
    return json.loads((CASES / "tread-on-drum.json").read_text())


@pytest.fixture(scope="module")
def client(strip):
    token = "test-token-of-this-run-0123456789"
    client = TestClient(create_app(strip, ["testserver"], token=token, message_limit=400_000, upload_limit=400_000))
    client.get(f"/?token={token}")  # the page's first load sets the token's cookie
    return client


def request(case, seq, final=True, model="paper"):
    return json.dumps({"seq": seq, "final": final, "case": case, "model": model, "ratio": None})


def with_law(case, body, ratio):
    out = copy.deepcopy(case)
    out["bodies"][body]["law"] = {"area_ratio": ratio}
    return out


def test_each_body_meets_its_own_law(client, strip):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(strip, 1))
        r = receive(ws)
    assert r["type"] == "result" and r["assembly"] and not r["revolution"]
    assert [b["name"] for b in r["bodies"]] == [b["name"] for b in strip["bodies"]]
    for body, case_body in zip(r["bodies"], strip["bodies"]):
        ratio = case_body["law"]["area_ratio"]
        assert abs(body["area_final"] - ratio * body["area_initial"]) <= 1e-9 * body["area_final"]
        assert abs(body["relative_error"]) <= 1e-9 and body["jacobian_min"] > 0
        assert body["contour"].shape[1] == 2 and "cells" in body["mesh_final"] and "initial_contour" in body
    # the target is drawn from its own ends
    target = curve_from_json(strip["target"], "target")
    np.testing.assert_allclose(r["lower"][[0, -1]], np.array(target.ends), atol=1e-12)


def test_a_law_change_is_placed_without_preparing_again_and_matches_a_fresh_deformer(client, strip):
    """The slider moves one body's law: the answer is the library's own deformation of the changed case, bit for bit."""
    changed = with_law(strip, 1, 0.8)
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(strip, 1))
        receive(ws)
        ws.send_text(request(changed, 2, final=False))
        r = receive(ws)
    assert r["type"] == "result" and not r["prepared"]
    assert "initial_contour" not in r["bodies"][0] and "cells" not in r["bodies"][0]["mesh_final"]
    expected = Deformer(case_from_dict(changed)).deform()
    for body, exp in zip(r["bodies"], expected.bodies):
        np.testing.assert_array_equal(body["contour"], exp.contour)
        assert body["area_target"] == exp.area_target
    assert r["bodies"][1]["area_final"] == pytest.approx(0.8 * r["bodies"][1]["area_initial"], rel=1e-9)


def test_a_law_change_reuses_the_prepared_problem_and_keeps_its_case(strip):
    cache = engine.DeformerCache()
    deformer, fresh = cache.get(strip, "paper")
    changed = with_law(strip, 0, 0.7)
    again, prepared = cache.get(changed, "paper")
    assert fresh and not prepared and again is deformer
    out = engine.answer(cache, changed, "paper", None, True)
    backing = out["bodies"][0]
    assert backing["area_final"] == pytest.approx(0.7 * backing["area_initial"], rel=1e-9)
    assert deformer.problem.bodies[0].law.to_json() == strip["bodies"][0]["law"]


def test_a_refusal_comes_with_the_librarys_message_and_the_server_goes_on(client, drum):
    # a Yeoh rubber needs c10 > 0
    yeoh = json.loads(json.dumps(drum))
    yeoh["bodies"][1]["material"] = {"model": "yeoh", "c10": -0.4, "c20": 0.01, "c30": 0.0}
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(yeoh, 1, model="hyperelastic"))
        bad = receive(ws)
        ws.send_text(request(drum, 2))
        good = receive(ws)
    assert bad["type"] == "refused" and bad["seq"] == 1
    with pytest.raises(CaseError) as exc:
        Deformer(case_from_dict(yeoh), model="hyperelastic")
    assert bad["message"] == str(exc.value)
    assert good["type"] == "result" and good["seq"] == 2


def test_the_hyperelastic_model_deforms_a_plane_assembly_on_each_bodys_law(client, strip):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(strip, 1, model="hyperelastic"))
        answer = receive(ws)
    assert answer["type"] == "result" and answer["model"] == "hyperelastic"
    for body in answer["bodies"]:
        assert abs(body["relative_error"]) <= 1e-9


def test_a_body_of_revolution_opens_with_its_outline_and_the_librarys_refusal(client, drum):
    """Opened (its bodies drawn, the refusal in the report); each deformation is refused with the library's message."""
    files = {"file": ("tread-on-drum.json", io.BytesIO(json.dumps(drum).encode()), "application/json")}
    r = client.post("/api/open", files=files, headers=ORIGIN)
    assert r.status_code == 200
    data = r.json()
    assert data["case"]["revolution"] == drum["revolution"]
    assert len(data["outline"]) == len(drum["bodies"]) and all(len(b["contour"]) > 10 for b in data["outline"])
    try:
        case_from_dict(drum)
        refusal = None
    except CaseError as exc:
        refusal = str(exc)
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(data["case"], 1))
        answer = receive(ws)
    if refusal is None:  # the library deforms bodies of revolution: volumes and the volume law
        assert answer["type"] == "result" and answer["revolution"]
        for body, case_body in zip(answer["bodies"], drum["bodies"]):
            assert body["volume_target"] == pytest.approx(case_body["law"]["volume_ratio"] * body["volume_initial"], rel=1e-12)
            assert abs(body["volume_error"]) <= 1e-9
    else:
        assert any(refusal in line for line in data["report"])
        assert answer["type"] == "refused" and answer["message"] == refusal


def test_an_outline_of_an_assembly_is_its_closed_bodies(strip):
    out = engine.outline(strip)
    backing = out[0]["contour"]
    assert backing.shape[1] == 2
    xs, ys = backing[:, 0], backing[:, 1]
    assert (xs.min(), xs.max(), ys.min(), ys.max()) == pytest.approx((0.0, 100.0, 0.0, 4.0))


def test_the_start_of_an_assembly_and_its_saved_case(client, strip):
    start = client.get("/api/start").json()
    assert start["case"]["format"] == "section-case/2" and len(start["outline"]) == 2
    r = client.post("/api/save/case.json", json={"case": strip, "model": "paper"}, headers=ORIGIN)
    assert r.status_code == 200
    assert case_from_dict(json.loads(r.content)) == case_from_dict(strip)
    r = client.post("/api/save/result.json", json={"case": strip, "model": "paper"}, headers=ORIGIN)
    assert r.status_code == 200
    saved = json.loads(r.content)
    assert saved["format"] == "section-result/2" and [b["name"] for b in saved["bodies"]] == ["backing", "cover"]
    for body, case_body in zip(saved["bodies"], strip["bodies"]):
        assert body["area"]["final"] == pytest.approx(case_body["law"]["area_ratio"] * body["area"]["initial"], rel=1e-9)
