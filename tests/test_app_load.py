"""The page's server under load: no client waits for another's computation, and a gone client's work is dropped.

A real uvicorn server on 127.0.0.1 (in a thread of the test process, so that a
computation can be made slow: a sleep, which like numpy's heavy lifting lets
other threads run) and WebSocket clients from Python.
"""

from __future__ import annotations

import contextlib
import json
import threading
import time

import pytest

pytest.importorskip("starlette")
uvicorn = pytest.importorskip("uvicorn")
ws_client = pytest.importorskip("websockets.sync.client")

import sectiondeform as sd  # noqa: E402
from sectiondeform.app import engine  # noqa: E402
from sectiondeform.app.server import MAX_MESSAGE, UVICORN_OPTIONS, create_app  # noqa: E402

TOKEN = "a-token-for-these-tests-0123456789"
SLOW = 0.61  # the ratio whose computation is made slow (its height scale 0.70 is within the paper model's [0.5, 2])
SLOW_SECONDS = 1.5


@pytest.fixture(scope="module")
def case_json():
    return sd.case_to_dict(sd.load_case(sd.example_case_path()))


@contextlib.contextmanager
def running(case_json, **options):
    """A server on a free port of 127.0.0.1; yields the port."""
    config = uvicorn.Config(None, host="127.0.0.1", port=0, log_level="warning", **UVICORN_OPTIONS)
    server = uvicorn.Server(config)
    sock = config.bind_socket()
    port = sock.getsockname()[1]
    config.app = create_app(case_json, [f"127.0.0.1:{port}"], token=TOKEN, **options)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    for _ in range(500):
        if server.started:
            break
        time.sleep(0.01)
    try:
        yield port
    finally:
        server.should_exit = True
        thread.join(timeout=15)


def connect(port):
    return ws_client.connect(f"ws://127.0.0.1:{port}/ws?token={TOKEN}", origin=f"http://127.0.0.1:{port}",
                             max_size=None, open_timeout=10)


def request(case_json, seq, final=True, ratio=0.8):
    return json.dumps({"seq": seq, "final": final, "case": case_json, "model": "paper", "ratio": ratio})


def answer_to(ws, seq, timeout=20.0) -> dict:
    """The answer to request ``seq`` (its header only), skipping ``dropped`` notes and older answers."""
    end = time.monotonic() + timeout
    while True:
        data = ws.recv(timeout=max(0.01, end - time.monotonic()))
        if isinstance(data, bytes):
            n = int.from_bytes(data[:4], "little")
            header = json.loads(data[4:4 + n])
        else:
            header = json.loads(data)
        if header.get("seq") == seq and header["type"] != "dropped":
            return header


@pytest.fixture()
def slow_and_counted(monkeypatch):
    """``engine.answer`` made slow for the ratio SLOW; the ratios computed, in order."""
    real, computed = engine.answer, []

    def answer(cache, case, model, ratio, final, **kw):
        computed.append(ratio)
        if ratio == SLOW:
            time.sleep(SLOW_SECONDS)
        return real(cache, case, model, ratio, final, **kw)

    monkeypatch.setattr(engine, "answer", answer)
    return computed


def test_a_slow_preview_does_not_hold_another_client(case_json, slow_and_counted):
    """A heavy preview of a prepared section (it ran on the event loop) leaves the other clients' answers prompt."""
    with running(case_json, workers=2) as port, connect(port) as heavy, connect(port) as light:
        heavy.send(request(case_json, 1))
        answer_to(heavy, 1)  # the section is prepared: the next preview of it is the fast path
        light.send(request(case_json, 1))
        answer_to(light, 1)
        heavy.send(request(case_json, 2, final=False, ratio=SLOW))
        time.sleep(0.2)  # the heavy preview is being computed
        waits = []
        for seq in range(2, 6):
            t0 = time.perf_counter()
            light.send(request(case_json, seq, final=False, ratio=0.8 - 0.01 * seq))
            answer_to(light, seq)
            waits.append(time.perf_counter() - t0)
        assert answer_to(heavy, 2)["type"] == "result"
    assert max(waits) < SLOW_SECONDS / 3, waits


def test_the_newest_request_replaces_older_ones_waiting_for_a_worker(case_json, slow_and_counted):
    with running(case_json, workers=1) as port, connect(port) as busy, connect(port) as waiting:
        busy.send(request(case_json, 1, ratio=SLOW))
        time.sleep(0.3)  # the only worker is busy
        for seq in range(1, 6):
            waiting.send(request(case_json, seq, final=False, ratio=0.7 + 0.01 * seq))
        last = answer_to(waiting, 5)
        answer_to(busy, 1)
    assert last["type"] == "result"
    assert slow_and_counted == [SLOW, 0.75]  # only the newest of the waiting requests was computed


def test_the_waiting_work_of_a_closed_connection_is_dropped(case_json, slow_and_counted):
    """Requests of a client that has gone are not computed: a new client waits only for the one being computed."""
    with running(case_json, workers=1) as port:
        with connect(port) as busy:
            busy.send(request(case_json, 1, ratio=SLOW))
            time.sleep(0.3)
            with contextlib.ExitStack() as stack:
                for _ in range(4):
                    stack.enter_context(connect(port)).send(request(case_json, 1, ratio=SLOW))
                time.sleep(0.2)  # the four wait for the worker; then they go
        t0 = time.perf_counter()
        with connect(port) as fresh:
            fresh.send(request(case_json, 1, ratio=0.7))
            assert answer_to(fresh, 1)["type"] == "result"
        waited = time.perf_counter() - t0
    assert slow_and_counted.count(SLOW) == 1 and waited < SLOW_SECONDS + 1.0, (slow_and_counted, waited)


def test_a_message_over_the_limit_is_refused_before_it_is_buffered(case_json):
    """Over MAX_MESSAGE (also the upload limit) the WebSocket layer closes with 1009; the page says why."""
    from websockets.exceptions import ConnectionClosed

    codes = []
    # No solver processes starting beside: their start (a burst of CPU) can delay the server so long that the
    # client, still sending, loses the close frame to the connection's reset.
    with running(case_json, solvers=0) as port:
        with contextlib.suppress(ConnectionClosed), connect(port) as ws:
            ws.send(request(case_json, 1))
            answer_to(ws, 1)
            try:  # the server may close while the message is still being sent
                ws.send("x" * (MAX_MESSAGE + 1))
                ws.recv(timeout=10)
            except ConnectionClosed as exc:
                codes.append(exc.rcvd.code if exc.rcvd else None)
        with connect(port) as ws:  # the server goes on
            ws.send(request(case_json, 1))
            assert answer_to(ws, 1)["type"] == "result"
    assert codes == [1009]
