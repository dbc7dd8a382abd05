"""The interactive page's server: safety checks, refusals, coalescing, files (Starlette's TestClient)."""

from __future__ import annotations

import io
import json
import re
import struct

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")

from starlette.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

import sectiondeform as sd
from sectiondeform.app.server import create_app
from sectiondeform.commands.serve import hosts_for

ORIGIN = {"origin": "http://testserver"}
TOKEN = "test-token-of-this-run-0123456789"


@pytest.fixture(scope="module")
def case_json():
    return sd.case_to_dict(sd.load_case(sd.example_case_path()))


@pytest.fixture()
def client(case_json):
    client = TestClient(create_app(case_json, ["testserver"], token=TOKEN, message_limit=200_000, upload_limit=100_000))
    assert client.get(f"/?token={TOKEN}").status_code == 200  # the page's first load sets the token's cookie
    return client


def receive(ws) -> dict:
    """The next answer: a text JSON message, or a binary result frame decoded here from its documented layout."""
    message = ws.receive()
    if message.get("text") is not None:
        return json.loads(message["text"])
    data = message["bytes"]
    (n,) = struct.unpack_from("<I", data, 0)
    assert (4 + n) % 8 == 0  # the float64 data are aligned
    header = json.loads(data[4:4 + n].decode("utf-8"))

    def arrays(value):
        if isinstance(value, dict) and isinstance(value.get("f64"), list):
            offset, count, columns = value["f64"]
            flat = np.frombuffer(data, dtype="<f8", count=count, offset=4 + n + offset)
            return flat.reshape(-1, columns) if columns > 1 else flat
        if isinstance(value, dict):
            return {k: arrays(v) for k, v in value.items()}
        if isinstance(value, list) and value and isinstance(value[0], dict):  # an assembly's bodies
            return [arrays(v) for v in value]
        return value

    return arrays(header)


def request(case_json, seq, final=True, model="paper", ratio=0.8, target=None):
    case = dict(case_json, target=target or case_json["target"])
    return json.dumps({"seq": seq, "final": final, "case": case, "model": model, "ratio": ratio})


def test_the_page_and_its_files_are_served(client):
    assert "sectiondeform" in client.get("/").text
    for name in ("app.js", "geometry.js", "style.css"):
        assert client.get(f"/static/{name}").status_code == 200
    start = client.get("/api/start").json()
    assert start["model"] == "paper" and start["case"]["format"] == "section-case/1"


def test_a_foreign_host_is_refused_everywhere(client):
    # DNS rebinding: a page at another name resolving to 127.0.0.1 sends its own Host
    for url in ("/", "/static/app.js", "/api/start"):
        assert client.get(url, headers={"host": "evil.example:8765"}).status_code == 400


@pytest.mark.parametrize("headers", [{}, {"origin": "http://evil.example"}, {"origin": "null"}])
def test_websocket_refuses_another_origin(client, headers):
    with pytest.raises(WebSocketDisconnect), client.websocket_connect("/ws", headers=headers) as ws:
        receive(ws)


@pytest.mark.parametrize("url", ["/api/open", "/api/save/case.json"])
def test_post_refuses_another_origin(client, url, case_json):
    r = client.post(url, headers={"origin": "http://evil.example"}, content=json.dumps({"case": case_json}))
    assert r.status_code == 403


def test_the_answer_meets_the_law(client, case_json):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 1, ratio=0.7))
        r = receive(ws)
    assert r["type"] == "result" and r["seq"] == 1 and r["final"]
    assert abs(r["area_final"] - 0.7 * r["area_initial"]) <= 1e-9 * r["area_final"]
    assert r["jacobian_min"] > 0


def test_a_refusal_is_answered_and_the_server_keeps_going(client, case_json):
    # a target folded back on itself cannot carry the section
    folded = {"polyline": [[0.0, 0.0], [110.0, 0.0], [10.0, 1.0]]}
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 1, target=folded))
        bad = receive(ws)
        ws.send_text(request(case_json, 2, ratio=-1.0))
        bad_law = receive(ws)
        ws.send_text(request(case_json, 3))
        good = receive(ws)
    assert bad["type"] == "refused" and bad["seq"] == 1 and bad["message"]
    assert bad_law["type"] == "refused" and ("ratio" in bad_law["message"] or "law" in bad_law["message"])
    assert good["type"] == "result" and good["seq"] == 3


def test_malformed_and_oversized_messages_are_refused(client, case_json):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text("not json")
        assert receive(ws)["type"] == "refused"
        ws.send_text(json.dumps({"seq": 1, "pad": "x" * 250_000}))
        r = receive(ws)
        assert r["type"] == "refused" and "limit" in r["message"]
        ws.send_text(request(case_json, 2))
        assert receive(ws)["type"] == "result"


def test_requests_are_coalesced(client, case_json):
    """While one request is computed, only the latest of those arriving meanwhile is computed next."""
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 1, model="hyperelastic"))  # prepares the hyperelastic model: slow
        for seq in range(2, 7):
            ws.send_text(request(case_json, seq, final=False, model="hyperelastic", ratio=0.8 - 0.01 * seq))
        answers = []
        while not answers or answers[-1].get("seq") != 6 or answers[-1]["type"] != "result":
            answers.append(receive(ws))
    results = [a["seq"] for a in answers if a["type"] == "result"]
    dropped = [a["seq"] for a in answers if a["type"] == "dropped"]
    assert results[0] == 1 and results[-1] == 6
    assert len(results) < 6 and sorted(dropped + results) == list(range(1, 7))
    last = answers[-1]
    assert abs(last["area_final"] - (0.8 - 0.06) * last["area_initial"]) <= 1e-9 * last["area_final"]


def test_an_older_request_after_a_newer_one_is_ignored(client, case_json):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 5))
        assert receive(ws)["seq"] == 5
        ws.send_text(request(case_json, 3))
        ws.send_text(request(case_json, 6))
        assert receive(ws)["seq"] == 6


def test_a_dxf_upload_opens(client, case_json, tmp_path):
    pytest.importorskip("ezdxf")
    from sectiondeform.io import write_case

    path = tmp_path / "drawn.dxf"
    write_case(path, sd.case_from_dict(case_json))
    r = client.post("/api/open", headers=ORIGIN, files={"file": ("my drawing.dxf", path.read_bytes())})
    assert r.status_code == 200, r.text
    case = sd.case_from_dict(r.json()["case"])
    assert case.law.ratio == pytest.approx(0.8)
    assert case.lower.length == pytest.approx(110.0)


def test_a_drawing_without_law_takes_the_forms_ratio(client, case_json, tmp_path):
    pytest.importorskip("ezdxf")
    import ezdxf

    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (10, 0)], dxfattribs={"layer": "LOWER"})
    msp.add_lwpolyline([(10, 0), (10, 5), (0, 5), (0, 0)], dxfattribs={"layer": "UPPER"})
    msp.add_lwpolyline([(0, 0), (10, -1)], dxfattribs={"layer": "TARGET"})
    buf = io.StringIO()
    doc.write(buf)
    r = client.post("/api/open", headers=ORIGIN, files={"file": ("box.dxf", buf.getvalue().encode())},
                    data={"area_ratio": "0.9"})
    assert r.status_code == 200, r.text
    assert r.json()["case"]["law"] == {"area_ratio": 0.9}
    assert any("no law" in line for line in r.json()["report"])


@pytest.mark.parametrize("name, content, words", [
    ("broken.json", b"{not json", "json"),
    ("broken.dxf", b"this is no drawing", ""),
    ("picture.png", b"\x89PNG", "format"),
])
def test_an_invalid_file_gets_a_one_line_message(client, name, content, words):
    r = client.post("/api/open", headers=ORIGIN, files={"file": (name, content)})
    assert r.status_code == 422
    message = r.json()["error"]
    assert message and "\n" not in message and words in message.lower()


def test_an_upload_over_the_limit_is_refused(client):
    r = client.post("/api/open", headers=ORIGIN, files={"file": ("big.json", b" " * 200_000)})
    assert r.status_code == 413 and "limit" in r.json()["error"] and "\n" not in r.json()["error"]


@pytest.mark.parametrize("name", ["result.json", "result.svg", "case.json", "case.svg"])
def test_saving_gives_the_file(client, case_json, name):
    r = client.post(f"/api/save/{name}", headers=ORIGIN, json={"case": case_json, "model": "paper"})
    assert r.status_code == 200
    assert name in r.headers["content-disposition"]
    if name == "case.json":
        assert sd.case_from_dict(json.loads(r.content)).law.ratio == pytest.approx(0.8)
    if name == "result.json":
        area = json.loads(r.content)["area"]
        assert abs(area["final"] - 0.8 * area["initial"]) <= 1e-9 * area["final"]


@pytest.mark.parametrize("name", ["result.dxf", "result.vtu"])
def test_saving_cad_files(client, case_json, name):
    pytest.importorskip("ezdxf")
    pytest.importorskip("meshio")
    r = client.post(f"/api/save/{name}", headers=ORIGIN, json={"case": case_json, "model": "paper"})
    assert r.status_code == 200 and len(r.content) > 1000


@pytest.mark.parametrize("name", ["case.vtu", "result.png", "..%2Fetc%2Fpasswd.json", "passwd.json"])
def test_no_other_file_is_saved(client, case_json, name):
    r = client.post(f"/api/save/{name}", headers=ORIGIN, json={"case": case_json})
    assert r.status_code == 404


def test_an_invalid_case_is_not_saved(client, case_json):
    r = client.post("/api/save/result.json", headers=ORIGIN, json={"case": {**case_json, "law": {"area_ratio": -2}}})
    assert r.status_code == 422 and r.json()["error"]


def test_hosts_are_loopback_names_and_the_given_one():
    assert hosts_for("127.0.0.1", 8765) == ["127.0.0.1:8765", "[::1]:8765", "localhost:8765"]
    assert "192.168.1.5:80" in hosts_for("192.168.1.5", 80)


def test_points_arrive_exactly(client, case_json):
    """The framed contour decodes to the library's own result, bit for bit."""
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 1, ratio=0.75))
        r = receive(ws)
    contour = r["contour"]
    expected = sd.Deformer(sd.case_from_dict(case_json)).deform(law=sd.AreaRatio(0.75)).contour
    np.testing.assert_array_equal(contour, expected)
    assert len(r["mesh_final"]["cells"]) == len(r["mesh_initial"]["cells"])


def test_serve_warns_for_another_host():
    """Listening on any address but loopback names prints a warning first (127.0.0.2: still this machine)."""
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", "--host", "127.0.0.2", "--port", "0",
                             "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        first, second = proc.stdout.readline(), proc.stdout.readline()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    assert first.startswith("warning: listening on 127.0.0.2")
    assert "http://127.0.0.2:" in second


def test_a_preview_carries_only_what_moves(client, case_json):
    """While dragging, the answer has the contour and the final mesh's points, not the initial data or the cells."""
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 1, ratio=0.8))
        full = receive(ws)
        ws.send_text(request(case_json, 2, final=False, ratio=0.78))
        preview = receive(ws)
    assert full["final"] and "initial_contour" in full and "cells" in full["mesh_final"]
    assert not preview["final"] and preview["seq"] == 2
    assert "initial_contour" not in preview and "mesh_initial" not in preview and "cells" not in preview["mesh_final"]
    assert preview["mesh_final"]["points"].shape == full["mesh_final"]["points"].shape
    assert preview["contour"].shape[1] == 2 and np.all(np.isfinite(preview["contour"]))
    assert abs(preview["area_final"] - 0.78 * preview["area_initial"]) <= 1e-9 * preview["area_initial"]


def test_the_server_refuses_websocket_compression(case_json):
    """The serve command's WebSocket takes no permessage-deflate: a client offering it gets no extension back.

    Compressing about 20 kB of float64 per answer costs time on both ends and saves nothing on the loopback
    (docs/benchmarks-page.md); uvicorn would accept it by default.
    """
    import subprocess
    import sys
    import time

    ws_client = pytest.importorskip("websockets.sync.client")
    pytest.importorskip("uvicorn")
    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        host, token = re.search(r"http://(\S+)/\?token=(\S+)", proc.stdout.readline()).groups()
        for _ in range(200):  # the address is printed just before the server listens
            try:
                ws = ws_client.connect(f"ws://{host}/ws?token={token}", origin=f"http://{host}", compression="deflate")
                break
            except ConnectionRefusedError:
                time.sleep(0.05)
        else:
            pytest.fail("the server did not listen")
        with ws:
            offered = ws.request.headers.get("Sec-WebSocket-Extensions") or ""
            assert "permessage-deflate" in offered  # the client asked for it...
            assert ws.response.headers.get("Sec-WebSocket-Extensions") is None  # ...and the server declined
            ws.send(request(case_json, 1, final=False))
            data = ws.recv()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    assert isinstance(data, bytes)
    (n,) = struct.unpack_from("<I", data, 0)
    header = json.loads(data[4:4 + n])
    assert header["type"] == "result" and header["seq"] == 1
    assert header["final"] is False  # a preview is labelled as one


def test_a_prepared_section_is_found_by_its_key(case_json):
    """The cache tells a prepared section by its key, which the answer then reuses: the same deformer, no new preparation."""
    from sectiondeform.app import engine

    cache = engine.DeformerCache()
    assert cache.ready(case_json, "paper") is None
    engine.answer(cache, case_json, "paper", 0.8, True)
    key = cache.ready(case_json, "paper")
    assert key == engine.section_key(case_json, "paper")
    moved = dict(case_json, target={"polyline": [[0.0, 0.0], [60.0, -8.0], [112.0, 0.0]]})
    assert cache.ready(moved, "paper") == key  # the target is not part of the section
    assert cache.ready(moved, "hyperelastic") is None and cache.ready(moved, "no such model") is None
    assert cache.ready({**case_json, "upper": {"polyline": [[110.0, 0.0], [0.0, 30.0], [0.0, 0.0]]}}, "paper") is None
    preview = engine.answer(cache, moved, "paper", 0.8, False, key=key)
    assert preview["prepared"] is False and preview["final"] is False
    other = engine.DeformerCache()
    engine.answer(other, case_json, "paper", 0.8, True)
    expected = engine.answer(other, moved, "paper", 0.8, False)  # the key found again
    np.testing.assert_array_equal(preview["contour"], expected["contour"])


def test_the_worst_element_is_each_models_own_figure(case_json):
    """The paper model's smallest corner Jacobian (units²); the hyperelastic model's smallest det F (a ratio), apart."""
    from sectiondeform.app import engine
    from sectiondeform.io.case import case_from_dict

    cache = engine.DeformerCache()
    paper = engine.answer(cache, case_json, "paper", 0.8, True)
    physics = engine.answer(cache, case_json, "hyperelastic", 0.8, True)
    assert paper["jacobian_min"] > 0 and paper["det_f_min"] is None
    assert physics["jacobian_min"] is None
    expected = sd.Deformer(case_from_dict(case_json), "hyperelastic").deform().bodies[0].quality.final.area_stretch_min
    assert physics["det_f_min"] == pytest.approx(expected, rel=1e-9) and 0 < physics["det_f_min"] < 1.5
