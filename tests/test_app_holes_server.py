"""The page's server with hollow profiles: each body's holes in its answers and outline, kept when opened and saved.

The holes the page draws are the library's own (:attr:`BodyResult.holes`),
for both models, in full deformations and drag previews alike; the areas it
shows are net of the holes; a hollow case opened and saved reads back with
the same holes.
"""

from __future__ import annotations

import copy
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")

from starlette.testclient import TestClient  # noqa: E402
from test_app_server import ORIGIN, TOKEN, receive  # noqa: E402

from sectiondeform.app import engine  # noqa: E402
from sectiondeform.app.server import create_app  # noqa: E402
from sectiondeform.curves import curve_from_json  # noqa: E402
from sectiondeform.deform import Deformer  # noqa: E402
from sectiondeform.io.case import case_from_dict  # noqa: E402

HOLLOW = Path(__file__).parent / "data" / "cases" / "v2" / "hollow-on-arc.json"
NET_AREA = 24.0 * 12.0 - math.pi * 4.0**2  # the profile less its hole of radius 4 (mm²)
MODELS = ("paper", "hyperelastic")


@pytest.fixture(scope="module")
def hollow():
    return json.loads(HOLLOW.read_text())


@pytest.fixture(scope="module")
def client(hollow):
    client = TestClient(create_app(hollow, ["testserver"], token=TOKEN, message_limit=400_000, upload_limit=400_000))
    client.get(f"/?token={TOKEN}")  # the page's first load sets the token's cookie
    return client


def request(case, seq, model, final=True):
    return json.dumps({"seq": seq, "final": final, "case": case, "model": model, "ratio": None})


def tighter(case: dict, radius: float) -> dict:
    """The case rolled onto a carrier of ``radius`` (mm) instead, the arc's length kept (a dragged target)."""
    out = copy.deepcopy(case)
    arc = out["target"]["arc"]
    half = 0.5 * math.degrees(24.0 / radius)
    arc.update(center=[12.0, radius], radius=radius, start_deg=270.0 - half, end_deg=270.0 + half)
    return out


def same_holes(got, want) -> None:
    assert len(got) == len(want) > 0
    for g, w in zip(got, want):
        assert g.shape == w.shape
        np.testing.assert_allclose(g, w, rtol=0, atol=1e-12)


@pytest.mark.parametrize("model", MODELS)
def test_a_full_deformation_and_a_preview_carry_the_librarys_holes(client, hollow, model):
    deformer = Deformer(engine.with_model(case_from_dict(hollow), model), model=model)
    full = deformer.deform()
    moved = tighter(hollow, 45.0)
    target, laws = curve_from_json(moved["target"], "target"), engine.laws_of(moved)
    preview = deformer.preview(target, laws, start=full)  # the page's preview starts from its last full answer
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(hollow, 1, model))
        first = receive(ws)
        ws.send_text(request(moved, 2, model, final=False))
        second = receive(ws)
    assert first["type"] == second["type"] == "result" and first["final"] and not second["final"]
    (body,), (want,) = first["bodies"], full.bodies
    same_holes(body["holes"], want.holes)
    same_holes(body["initial_holes"], want.initial_holes)
    # the readout's area is the library's, net of the hole
    assert body["area_final"] == first["area_final"] == want.area_final
    assert first["area_initial"] == want.area_initial
    assert abs(want.area_initial - NET_AREA) <= 1e-12 * NET_AREA
    (moving,), (wanted,) = second["bodies"], preview.bodies
    same_holes(moving["holes"], wanted.holes)
    assert "initial_holes" not in moving  # the page keeps the last full answer's, as it keeps the initial contour
    assert not np.allclose(moving["holes"][0], body["holes"][0], atol=1e-6)  # the hole moves with the drag


def test_the_outline_before_any_answer_has_the_holes_and_the_net_area(client, hollow):
    (body,) = client.get("/api/start").json()["outline"]
    (hole,) = body["holes"]
    radius = np.hypot(*(np.array(hole) - [12.0, 6.5]).T)
    np.testing.assert_allclose(radius, 4.0, rtol=0, atol=1e-12)  # points of the hole's own circle
    assert len(hole) == engine.OUTLINE_SAMPLES - 1  # closed: the first point not repeated
    assert abs(body["area"] - NET_AREA) <= 1e-12 * NET_AREA


def saved(client, case: dict, model: str) -> dict:
    """The case file the page downloads for ``case``."""
    r = client.post("/api/save/case.json", headers=ORIGIN, json={"case": case, "model": model})
    assert r.status_code == 200, r.text
    return json.loads(r.content)


@pytest.mark.parametrize("model", MODELS)
def test_a_hollow_case_opened_and_saved_keeps_its_holes(client, hollow, model):
    files = {"file": ("hollow.json", io.BytesIO(HOLLOW.read_bytes()), "application/json")}
    opened = client.post("/api/open", files=files, headers=ORIGIN)
    assert opened.status_code == 200, opened.text
    data = opened.json()
    assert data["case"]["bodies"][0]["holes"] == hollow["bodies"][0]["holes"] and not data["report"]
    assert len(data["outline"][0]["holes"]) == 1
    for case in (hollow, data["case"]):  # as the server started with it, and as opened
        file = saved(client, case, model)
        assert file["bodies"][0]["holes"] == hollow["bodies"][0]["holes"]
        back = case_from_dict(file)  # read back by the library: the same holes
        assert [h.to_json() for h in back.bodies[0].holes] == hollow["bodies"][0]["holes"]
        assert back.model == model
