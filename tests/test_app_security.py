"""The page's server on a shared machine: the token, no file read for the page, clean one-line errors, safe headers.

Starlette's TestClient; the serve command itself on 127.0.0.1 only.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")

from starlette.testclient import TestClient  # noqa: E402
from starlette.websockets import WebSocketDisconnect  # noqa: E402

import sectiondeform as sd  # noqa: E402
from sectiondeform.app.server import cookie_name, create_app  # noqa: E402

TOKEN = "a-token-for-these-tests-0123456789"
ORIGIN = {"origin": "http://testserver"}
HOSTS = ["testserver", "127.0.0.1:8765"]
TEMP = re.compile(r"/tmp|sectiondeform-|upload\.|[A-Za-z]:\\\\")
CLASS_NAMES = re.compile(r"\b(?:\w+Error|StopIteration|Exception|Traceback)\b")


@pytest.fixture(scope="module")
def case_json():
    return sd.case_to_dict(sd.load_case(sd.example_case_path()))


@pytest.fixture()
def app(case_json):
    return create_app(case_json, HOSTS, token=TOKEN, message_limit=200_000, upload_limit=100_000)


@pytest.fixture()
def client(app):
    client = TestClient(app)
    assert client.get(f"/?token={TOKEN}").status_code == 200
    return client


def clean(message: str) -> bool:
    """One line, no server path, no Python exception name."""
    return bool(message) and "\n" not in message and not TEMP.search(message) and not CLASS_NAMES.search(message)


def request(case_json, seq, **extra):
    return json.dumps({"seq": seq, "final": True, "case": case_json, "model": "paper", "ratio": 0.8, **extra})


# ---- the token -----------------------------------------------------------

@pytest.mark.parametrize("url", ["/", "/static/app.js", "/api/start", "/?token=wrong", "/api/start?token="])
def test_nothing_is_served_without_the_token(app, url):
    r = TestClient(app).get(url)
    assert r.status_code == 403 and clean(r.json()["error"]) and "token" in r.json()["error"]


def test_a_forged_loopback_host_does_not_help_without_the_token(app):
    """A remote script reaching a server on --host 0.0.0.0 can forge Host: 127.0.0.1:P; it still needs the token."""
    r = TestClient(app).get("/api/start", headers={"host": "127.0.0.1:8765"})
    assert r.status_code == 403
    ok = TestClient(app).get(f"/api/start?token={TOKEN}", headers={"host": "127.0.0.1:8765"})
    assert ok.status_code == 200


@pytest.mark.parametrize("url", ["/api/open", "/api/save/case.json"])
def test_posts_need_the_token(app, url, case_json):
    r = TestClient(app).post(url, headers=ORIGIN, content=json.dumps({"case": case_json}))
    assert r.status_code == 403


def test_the_websocket_needs_the_token(app, case_json):
    with pytest.raises(WebSocketDisconnect), TestClient(app).websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.receive()
    with TestClient(app).websocket_connect(f"/ws?token={TOKEN}", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 1))
        assert ws.receive().get("bytes")  # a result frame


def test_the_first_load_sets_a_private_cookie_that_then_suffices(app):
    client = TestClient(app)
    r = client.get(f"/?token={TOKEN}")
    cookie = r.headers["set-cookie"]
    assert cookie.startswith(f"{cookie_name(TOKEN)}={TOKEN};")
    assert "HttpOnly" in cookie and "SameSite=Strict" in cookie
    assert client.get("/api/start").status_code == 200  # the cookie alone now
    other = TestClient(app, cookies={cookie_name(TOKEN): "not-the-token"})
    assert other.get("/api/start").status_code == 403


def test_two_runs_have_their_own_cookies():
    assert cookie_name("one-token-0123456789") != cookie_name("another-token-0123456789")


# ---- headers -------------------------------------------------------------

@pytest.mark.parametrize("url, status", [(f"/?token={TOKEN}", 200), ("/static/app.js", 200), ("/api/start", 200),
                                         ("/static/none.js", 404), ("/api/start?x", 200)])
def test_every_answer_forbids_framing_and_sniffing(client, url, status):
    r = client.get(url)
    assert r.status_code == status
    assert r.headers["x-frame-options"] == "DENY"
    assert "frame-ancestors 'none'" in r.headers["content-security-policy"]
    assert r.headers["x-content-type-options"] == "nosniff"


def test_refusals_carry_the_headers_too(app):
    for r in (TestClient(app).get("/"), TestClient(app).get("/", headers={"host": "evil.example"})):
        assert r.status_code in (400, 403) and r.headers["x-frame-options"] == "DENY"


# ---- no file read for the page -------------------------------------------

@pytest.fixture()
def secret_drawing(tmp_path, case_json):
    """A valid drawing somewhere on the server's disk, and a name next to it that does not exist."""
    from sectiondeform.io import write_case

    path = tmp_path / "private" / "design.svg"
    path.parent.mkdir()
    write_case(path, sd.case_from_dict(case_json))
    return path, path.with_name("nothing.svg")


@pytest.mark.parametrize("how", ["absolute", "dotdot"])
def test_an_uploaded_case_naming_a_drawing_is_refused_without_reading_it(client, secret_drawing, how):
    exists, missing = secret_drawing
    answers = []
    for path in (exists, missing):
        name = str(path) if how == "absolute" else "../" * 12 + str(path).lstrip("/")
        body = json.dumps({"format": "section-case/1", "drawing": {"file": name}}).encode()
        answers.append(client.post("/api/open", headers=ORIGIN, files={"file": ("case.json", body)}))
    assert [r.status_code for r in answers] == [422, 422]
    messages = [r.json()["error"] for r in answers]
    assert messages[0] == messages[1]  # nothing tells whether the file exists
    assert "drawing" in messages[0] and clean(messages[0]) and "design" not in messages[0]
    assert "case" not in answers[0].json()


def test_a_drawing_key_in_a_live_request_reads_nothing(client, case_json, secret_drawing):
    exists, _ = secret_drawing
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request({**case_json, "drawing": {"file": str(exists)}}, 1))
        answer = json.loads(ws.receive()["text"])
    assert answer["type"] == "refused" and clean(answer["message"])


# ---- one clean line for every error --------------------------------------

def test_an_error_naming_the_uploaded_file_names_it_as_the_user_did(client):
    pytest.importorskip("ezdxf")
    import io

    import ezdxf

    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0), (10, 0), (10, 5), (0, 0)], dxfattribs={"layer": "BODY-a"})
    buf = io.StringIO()
    doc.write(buf)
    r = client.post("/api/open", headers=ORIGIN, files={"file": ("layup 2.dxf", buf.getvalue().encode())})
    assert r.status_code == 422
    message = r.json()["error"]
    assert clean(message), message


@pytest.mark.parametrize("content", [b"0\nSECTION\n2\nHEADER\n", b"0\nSECTION\n", b"", b"\xff\xfe\x00garbage"])
def test_a_truncated_or_broken_dxf_is_answered_in_one_line(client, content):
    r = client.post("/api/open", headers=ORIGIN, files={"file": ("cut.dxf", content)})
    assert r.status_code == 422 and clean(r.json()["error"]), r.json()


@pytest.mark.parametrize("raised", [StopIteration, KeyError, RecursionError, ZeroDivisionError])
def test_any_exception_in_the_work_comes_back_as_one_line(client, case_json, monkeypatch, raised):
    """Whatever a computation raises, even StopIteration (which an asyncio future cannot carry), is one line."""
    from sectiondeform.app import engine

    real = engine.answer

    def failing(cache, case, model, ratio, final, **kw):
        if ratio == 0.5:
            raise raised("/tmp/sectiondeform-x/secret detail")
        return real(cache, case, model, ratio, final, **kw)

    monkeypatch.setattr(engine, "answer", failing)
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        ws.send_text(request(case_json, 1, ratio=0.5))
        bad = json.loads(ws.receive()["text"])
        ws.send_text(request(case_json, 2))
        good = ws.receive()
    assert bad["type"] == "refused" and bad["seq"] == 1 and clean(bad["message"]), bad
    assert good.get("bytes")


@pytest.mark.parametrize("body", [
    b"[1, 2]", b"{\"case\": 3}", b"{\"case\": [1]}", b"{\"case\": {}, \"model\": 5}", b"\xff\xfe",
    b"[" * 100_000 + b"]" * 100_000, b"{\"case\": {\"lower\": NaN}}", b"{\"case\": {\"format\": \"section-case/2\"}}",
])
def test_a_bad_save_request_gets_a_line_never_a_bare_500(client, body):
    r = client.post("/api/save/result.json", headers={**ORIGIN, "content-type": "application/json"}, content=body)
    assert 400 <= r.status_code < 500 and clean(r.json()["error"]), (r.status_code, r.text[:200])


# ---- every bad message gets a line, and the connection stays usable -------

BAD_MESSAGES = [
    b"\x00\x01binary",
    '{"seq": Infinity}', '{"seq": NaN}', '{"seq": -Infinity, "case": {}}', '{"seq": 1e400}',
    '{"seq": true}', '{"seq": -1}', '{"seq": 9007199254740993}', '{"seq": "1"}', "[1]", "",
    "[" * 100_000 + "]" * 100_000, '{"seq": 1, "x": ' + "[" * 5_000 + "]" * 5_000 + "}",
    '{"seq": 1, "case": {"lower": {"polyline": [[0, 0], [Infinity, 0]]}}}',
]


@pytest.mark.parametrize("bad", BAD_MESSAGES, ids=lambda m: repr(m[:24]))
def test_a_bad_message_gets_a_line_and_the_connection_stays(client, case_json, bad):
    with client.websocket_connect("/ws", headers=ORIGIN) as ws:
        if isinstance(bad, bytes):
            ws.send_bytes(bad)
        else:
            ws.send_text(bad)
        answer = json.loads(ws.receive()["text"])
        ws.send_text(request(case_json, 10))
        good = ws.receive()
    assert answer["type"] == "refused" and clean(answer["message"]), answer
    assert good.get("bytes"), good


def test_connections_are_capped_with_a_clear_refusal(case_json):
    app = create_app(case_json, ["testserver"], token=TOKEN, max_connections=2)
    client = TestClient(app, cookies={cookie_name(TOKEN): TOKEN})
    with client.websocket_connect("/ws", headers=ORIGIN) as one, client.websocket_connect("/ws", headers=ORIGIN):
        with client.websocket_connect("/ws", headers=ORIGIN) as third:
            refused = json.loads(third.receive()["text"])
            closed = third.receive()
        one.send_text(request(case_json, 1))
        assert one.receive().get("bytes")  # the others keep working
    assert refused["type"] == "refused" and "busy" in refused["message"] and clean(refused["message"])
    assert closed["type"] == "websocket.close" and closed["code"] == 1013
    with client.websocket_connect("/ws", headers=ORIGIN) as again:  # a place is free again
        again.send_text(request(case_json, 1))
        assert again.receive().get("bytes")


# ---- sizes ---------------------------------------------------------------

def test_one_limit_for_messages_and_uploads():
    from sectiondeform.app.server import MAX_MESSAGE, MAX_UPLOAD, UVICORN_OPTIONS

    assert UVICORN_OPTIONS["ws_max_size"] == MAX_MESSAGE == MAX_UPLOAD


def test_an_oversize_upload_is_refused_with_413_before_it_is_read(client):
    r = client.post("/api/open", headers={**ORIGIN, "content-type": "multipart/form-data; boundary=x",
                                          "content-length": str(10 ** 9)}, content=b"--x--")
    assert r.status_code == 413 and clean(r.json()["error"]) and "limit" in r.json()["error"]
    r = client.post("/api/save/case.json", headers=ORIGIN, content=b" " * 150_000)
    assert r.status_code == 413 and clean(r.json()["error"])


def test_an_upload_whose_case_the_page_could_not_send_back_is_refused(case_json, tmp_path):
    """An upload within the limit that reads as a case larger than a message would fail at every drag: refused now."""
    from sectiondeform.io import write_case

    path = tmp_path / "drawn.svg"
    write_case(path, sd.case_from_dict(case_json))
    limit = 4096 + len(json.dumps(case_json)) // 2
    client = TestClient(create_app(case_json, ["testserver"], token=TOKEN, message_limit=limit, upload_limit=limit))
    client.cookies.set(cookie_name(TOKEN), TOKEN)
    assert path.stat().st_size < limit
    r = client.post("/api/open", headers=ORIGIN, files={"file": ("drawn.svg", path.read_bytes())})
    assert r.status_code == 422 and "simplify" in r.json()["error"] and clean(r.json()["error"])


# ---- the serve command ---------------------------------------------------

def serve(*extra) -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", "--port", "0", "--no-browser", *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return proc, proc.stdout.readline()


def test_serve_prints_an_address_with_a_fresh_token_each_run():
    tokens = []
    for _ in range(2):
        proc, line = serve()
        try:
            match = re.search(r"http://127\.0\.0\.1:\d+/\?token=([A-Za-z0-9_-]+)", line)
            assert match, line
            tokens.append(match.group(1))
        finally:
            proc.terminate()
            proc.wait(timeout=10)
    assert tokens[0] != tokens[1] and min(len(t) for t in tokens) >= 32


def test_serve_takes_a_fixed_token_for_scripts_and_refuses_a_weak_one():
    proc, line = serve("--token", "script-token-0123456789")
    proc.terminate()
    proc.wait(timeout=10)
    assert line.rstrip().split()[-4].endswith("/?token=script-token-0123456789"), line
    proc, line = serve("--token", "short")
    out = line + proc.stdout.read()
    proc.wait(timeout=10)
    assert proc.returncode != 0 and "--token" in out and "Traceback" not in out


def test_a_host_beyond_loopback_is_told_plainly_what_it_exposes():
    from sectiondeform.commands.serve import exposure

    line = exposure("0.0.0.0", 8765)
    assert "every network interface" in line and "8765" in line and "token" in line and "plain HTTP" in line
    assert "\n" not in line
