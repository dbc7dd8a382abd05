"""The page's server with rigid parts: their outlines with the case, each part's contact with a full deformation.

The figures the page shows are the library's own (``Result.rigid``), bit for
bit; a travel edited on the page (the part's end moved along its travel,
its start kept) is solved and saved like any other edit of the case.
"""

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

from sectiondeform import CaseError  # noqa: E402
from sectiondeform.app import engine  # noqa: E402
from sectiondeform.app.server import create_app, one_line  # noqa: E402
from sectiondeform.deform import Deformer  # noqa: E402
from sectiondeform.io.case import case_from_dict  # noqa: E402
from sectiondeform.result import contact_units  # noqa: E402

BUMPER = Path(__file__).parent / "data" / "cases" / "v2" / "bumper-under-plate.json"
TOKEN = "test-token-of-this-run-0123456789"


@pytest.fixture(scope="module")
def bumper():
    return json.loads(BUMPER.read_text())


@pytest.fixture(scope="module")
def client(bumper):
    client = TestClient(create_app(bumper, ["testserver"], token=TOKEN, message_limit=400_000, upload_limit=400_000))
    client.get(f"/?token={TOKEN}")  # the page's first load sets the token's cookie
    return client


@pytest.fixture(scope="module")
def library(bumper):
    """The library's own full deformation of the case."""
    return Deformer(case_from_dict(bumper)).deform()


def with_travel(case: dict, travel: float) -> dict:
    """The case with its plate travelling ``travel`` down from the same start, as the page edits it."""
    out = copy.deepcopy(case)
    part = out["rigid"][0]
    shift = -travel - part["travel"][1]
    part["contour"]["polyline"] = [[x, y + shift] for x, y in part["contour"]["polyline"]]
    part["travel"] = [0.0, -travel]
    return out


def request(case, seq, final=True, model="hyperelastic"):
    return json.dumps({"seq": seq, "final": final, "case": case, "model": model, "ratio": None})


def test_the_start_gives_each_part_as_drawn(client, bumper):
    data = client.get("/api/start").json()
    (part,) = data["rigid"]
    assert part["name"] == "plate" and part["travel"] == [0.0, -1.2]
    assert part["contour"] == bumper["rigid"][0]["contour"]["polyline"]  # a polygon's corners, exactly


def test_a_full_deformation_carries_the_librarys_contact_bit_for_bit(client, bumper, library):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(bumper, 1))
        r = receive(ws)
    assert r["type"] == "result" and r["final"]
    (part,), (want,) = r["rigid"], library.rigid
    assert part["name"] == want.name and part["travel"] == [0.0, -1.2]
    assert part["force"] == list(want.force) and part["length"] == want.length
    assert part["pressure_max"] == want.pressure_max and part["pressure_mean"] == want.pressure_mean
    assert part["penetration_max"] == want.penetration_max
    np.testing.assert_array_equal(part["pressure"], want.pressure)
    assert part["pressure"].shape[1] == 3 and part["pressure"][:, 2].max() == want.pressure_max
    np.testing.assert_array_equal(part["outline"], want.outline)
    assert r["support_force"] == list(library.support_force)
    assert [s["travel"] for s in r["history"]] == [s.travel for s in library.history]
    assert r["contact_units"] == {"length": "mm", "pressure": "MPa", "force": "N/mm"}


def test_a_preview_carries_no_contact_figures(client, bumper):
    """A preview's contact would be the last full deformation's: the page keeps that one instead."""
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(bumper, 1))
        assert "rigid" in receive(ws)
        ws.send_text(request(bumper, 2, final=False))
        r = receive(ws)
    assert r["type"] == "result" and not r["final"] and "rigid" not in r and "support_force" not in r


def test_more_travel_presses_harder_and_is_the_librarys_answer(client, bumper, library):
    moved = with_travel(bumper, 1.5)
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(moved, 1))
        r = receive(ws)
    (part,) = r["rigid"]
    assert part["travel"] == [0.0, -1.5]
    assert part["force"][1] > library.rigid[0].force[1] > 0  # the plate is pushed up, harder
    assert part["force"] == list(Deformer(case_from_dict(moved)).deform().rigid[0].force)
    # the plate ends 0.3 mm lower, from the same start
    np.testing.assert_allclose(part["outline"], library.rigid[0].outline - [0.0, 0.3], atol=1e-12)


def test_the_paper_model_refuses_rigid_parts_with_the_librarys_line(client, bumper):
    with pytest.raises(CaseError) as refused:
        Deformer(engine.with_model(case_from_dict(bumper), "paper"))
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(bumper, 1, model="paper"))
        r = receive(ws)
    # the library's line, with the option named as the page names it (its model control)
    assert r == {"type": "refused", "seq": 1, "model": "paper", "message": one_line(str(refused.value))}
    assert r["message"].endswith("use model hyperelastic")
    assert r["message"].startswith("rigid: ")


def test_a_saved_case_keeps_the_edited_travel(client, bumper):
    moved = with_travel(bumper, 1.5)
    r = client.post("/api/save/case.json", headers=ORIGIN, json={"case": moved, "model": "hyperelastic"})
    assert r.status_code == 200
    (part,) = case_from_dict(json.loads(r.content)).rigid
    assert part.travel == (0.0, -1.5)
    start = part.contour.at_fractions(np.linspace(0, 1, 9)) - part.travel
    original = case_from_dict(bumper).rigid[0]
    np.testing.assert_allclose(start, original.contour.at_fractions(np.linspace(0, 1, 9)) - original.travel, atol=1e-12)


def test_contact_units_follow_the_case_format():
    assert contact_units("mm", revolution=False)["force"] == "N/mm"
    assert contact_units("mm", revolution=True)["force"] == "N"  # the whole ring
    assert contact_units("m", revolution=False) == {"length": "m", "pressure": "MPa", "force": "MPa·m"}
    assert contact_units("m", revolution=True)["force"] == "MPa·m²"


@pytest.mark.parametrize("travel", [[0.0], [0.0, "1"], [0.0, True], None])
def test_a_rigid_outline_with_a_bad_travel_is_one_line(bumper, travel):
    case = copy.deepcopy(bumper)
    case["rigid"][0]["travel"] = travel
    with pytest.raises(CaseError, match=r"^rigid\[0\]\.travel: expected two finite numbers"):
        engine.rigid_outline(case)


def test_an_opened_case_brings_its_parts_as_drawn(client, bumper):
    moved = with_travel(bumper, 0.5)
    files = {"file": ("bumper.json", io.BytesIO(json.dumps(moved).encode()), "application/json")}
    r = client.post("/api/open", files=files, headers=ORIGIN)
    assert r.status_code == 200
    data = r.json()
    assert data["case"]["rigid"] == moved["rigid"] and data["model"] == "hyperelastic"
    assert data["rigid"] == [{"name": "plate", "contour": moved["rigid"][0]["contour"]["polyline"], "travel": [0.0, -0.5]}]


def test_a_ring_gets_the_whole_rings_force_in_newtons(client):
    """A body of revolution: the part's force is the whole ring's (N with MPa and mm), as the library gives it."""
    sleeve = json.loads((BUMPER.parent / "sleeve-on-shaft.json").read_text())
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(sleeve, 1))
        r = receive(ws)
    assert r["revolution"] and r["contact_units"]["force"] == "N"
    assert r["rigid"][0]["force"] == list(Deformer(case_from_dict(sleeve)).deform().rigid[0].force)
