"""The local server of the interactive page (Starlette; run by uvicorn).

Routes
------
``GET /``, ``/static/...``
    The page: plain JavaScript and SVG shipped in the package.
``GET /api/start``
    The case the server was started with (``section-case/1``) and the models.
``WS /ws``
    Live deformation. The page sends ``{"seq", "final", "case", "model",
    "ratio"}``; only the latest pending request is computed (coalescing); the
    server answers a result as one binary frame (a JSON header and the point
    arrays as raw float64, see :func:`framed`), a refusal as the text
    ``{"type": "refused", "seq", "message"}``, and keeps running.
``POST /api/open``
    An uploaded case file (.json, .dxf, .svg, multipart field ``file``),
    read in a private temporary folder: the case as JSON.
``POST /api/save/{what}.{ext}``
    The case (``what = case``: .json, .dxf, .svg) or its full deformation
    (``what = result``: .json, .dxf, .svg, .vtu) as a download.

Safety: the ``Host`` header must be one of the server's own names (no DNS
rebinding) and WebSocket and POST requests must come from the page's own
``Origin``; request bodies and messages are size-limited; no path sent by the
page is ever read or written.
"""

from __future__ import annotations

import asyncio
import json
import struct
import tempfile
from importlib import resources
from pathlib import Path

import numpy as np
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.websockets import WebSocket, WebSocketDisconnect

from ..errors import CaseError, SectionDeformError
from . import engine

__all__ = ["MAX_MESSAGE", "MAX_UPLOAD", "STATIC", "UVICORN_OPTIONS", "create_app"]

MAX_UPLOAD = 8 * 1024 * 1024  # bytes of an uploaded drawing or a posted case
MAX_MESSAGE = 1024 * 1024  # characters of one WebSocket message
UVICORN_OPTIONS = {"ws_max_size": 4 * MAX_MESSAGE, "ws_per_message_deflate": False}
"""The WebSocket settings of the server (``uvicorn.Config`` keywords).

No per-message compression (uvicorn offers permessage-deflate by default):
on the loopback it only costs time, deflating each answer (about 20 kB of
float64 that hardly compress) on the server and inflating it in the
browser, and each request the other way; measured, about a millisecond per
round trip at the median and several at the 95th percentile
(docs/benchmarks-page.md).
"""
STATIC = Path(str(resources.files(__package__) / "static"))
OPEN_FORMATS = (".json", ".dxf", ".svg")
CASE_FORMATS = (".json", ".dxf", ".svg")
RESULT_FORMATS = (".json", ".dxf", ".svg", ".vtu")
MEDIA = {".json": "application/json", ".dxf": "application/dxf", ".svg": "image/svg+xml",
         ".vtu": "application/octet-stream"}


def host_ok(headers, hosts: frozenset) -> bool:
    """True if the request's ``Host`` is one of the server's own names."""
    return headers.get("host", "").lower() in hosts


def origin_ok(headers, hosts: frozenset) -> bool:
    """True if the request comes from the page this server serves (same ``Host``, matching ``Origin``)."""
    host = headers.get("host", "").lower()
    origin = headers.get("origin")
    return host in hosts and origin is not None and origin.lower() == f"http://{host}"


def framed(reply: dict) -> bytes:
    """A reply as one binary WebSocket frame: exact, and nothing to parse but a small header.

    Layout: a little-endian uint32 ``n``; ``n`` bytes of UTF-8 JSON (the
    reply, each float64 array replaced by ``{"f64": [offset, count, columns]}``,
    padded with spaces so that the data starts on an 8-byte boundary); then
    the arrays' little-endian float64 values, ``offset`` counting bytes from
    the start of the data.

    Parameters
    ----------
    reply : dict
        JSON values and ``(n, 2)`` float64 arrays, at any depth of dicts.

    Returns
    -------
    bytes
    """
    blobs: list[bytes] = []
    size = 0

    def walk(value):
        nonlocal size
        if isinstance(value, np.ndarray):
            data = np.ascontiguousarray(value, dtype="<f8")
            ref = {"f64": [size, int(data.size), int(data.shape[1]) if data.ndim == 2 else 1]}
            blobs.append(data.tobytes())
            size += data.nbytes
            return ref
        if isinstance(value, dict):
            return {k: walk(v) for k, v in value.items()}
        if isinstance(value, list) and value and isinstance(value[0], dict):  # an assembly's bodies
            return [walk(v) for v in value]
        return value

    header = json.dumps(walk(reply), separators=(",", ":")).encode("utf-8")
    header += b" " * ((-(4 + len(header))) % 8)
    return struct.pack("<I", len(header)) + header + b"".join(blobs)


def packed_json(value):
    """``value`` with each float64 array as a list of ``[x, y]`` pairs (for the page's plain JSON answers)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, dict):
        return {k: packed_json(v) for k, v in value.items()}
    if isinstance(value, list):
        return [packed_json(v) for v in value]
    return value


def _refusal(status: int, message: str) -> JSONResponse:
    return JSONResponse({"error": message}, status_code=status)


async def _body(request: Request, limit: int) -> bytes:
    """The request body, refused past ``limit`` bytes without reading it all."""
    declared = request.headers.get("content-length")
    if declared is not None and declared.isdigit() and int(declared) > limit:
        raise CaseError("request", f"too large ({int(declared)} bytes); the limit is {limit} bytes")
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise CaseError("request", f"too large; the limit is {limit} bytes")
        chunks.append(chunk)
    return b"".join(chunks)


def _read_upload(name: str, data: bytes, form: dict) -> dict:
    """Read an uploaded case file in a private temporary folder; the case as JSON."""
    from ..io import read_case

    ext = Path(name or "").suffix.lower()
    if ext not in OPEN_FORMATS:
        raise CaseError("file", f"unknown case format {ext or '(none)'!r}; open a .json, .dxf or .svg file")
    options = {}
    for key in ("snap", "close_gap", "join_tol", "simplify", "target_arc"):
        if form.get(key) not in (None, ""):
            try:
                options[key] = float(form[key])
            except ValueError:
                raise CaseError(key, f"expected a number, got {form[key]!r}") from None
    report: list[str] = []
    if ext == ".json":
        try:
            data_json = json.loads(data.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise CaseError("file", f"not valid JSON ({exc})".splitlines()[0]) from None
        if engine.is_assembly(data_json):
            return _assembly_opened(data_json)
    with tempfile.TemporaryDirectory(prefix="sectiondeform-") as tmp:
        path = Path(tmp) / f"upload{ext}"  # the server's own name, never the page's
        path.write_bytes(data)
        try:
            case = read_case(path, report=report, **options)
        except CaseError as exc:
            if exc.field != "law" or ext == ".json":
                raise
            ratio = float(form.get("area_ratio") or 0.8)
            case = read_case(path, report=report, law=engine.law_of(ratio), **options)
            report.append(f"the drawing gives no law: area ratio {ratio} used")
        except UnicodeDecodeError:
            raise CaseError("file", "not a text file") from None
    return {"case": engine.case_json_of(case), "model": engine.case_model(case), "report": report}


def _assembly_opened(case_json: dict) -> dict:
    """An assembly for the page: checked by the library, or, if it refuses it, its outline and the refusal.

    The page then shows the bodies as drawn and the library's message (a
    model or a feature it does not support yet); the same refusal comes
    back for each deformation until the case or the library changes.
    """
    report: list[str] = []
    try:
        case_json = engine.case_json_of(engine.case_from_json(case_json))
    except SectionDeformError as exc:
        report.append(f"the library refuses this assembly: {exc}")
    return {"case": case_json, "model": engine.model_of_json(case_json), "report": report,
            "outline": engine.outline(case_json)}


def _write(case_json: dict, model: str, what: str, ext: str) -> bytes:
    """The bytes of a case or result file, written in a private temporary folder."""
    from ..io import write_case, write_result

    with tempfile.TemporaryDirectory(prefix="sectiondeform-") as tmp:
        path = Path(tmp) / f"out{ext}"
        if what == "case":
            write_case(path, engine.with_model(engine.case_from_json(case_json), model))
        else:
            write_result(path, engine.full_result(case_json, model))
        return path.read_bytes()


def create_app(case_json: dict, hosts, message_limit: int = MAX_MESSAGE, upload_limit: int = MAX_UPLOAD):
    """The ASGI application of the page (a Starlette app behind a Host check).

    Parameters
    ----------
    case_json : dict
        The ``section-case/1`` object shown first.
    hosts : iterable of str
        Accepted ``Host`` header values (``"127.0.0.1:8765"``...).
    message_limit, upload_limit : int
        Largest WebSocket message (characters) and request body (bytes).
    """
    hosts = frozenset(h.lower() for h in hosts)
    start_model = engine.model_of_json(case_json)
    first = {"case": case_json, "model": start_model, "models": list(engine.MODELS)}
    if engine.is_assembly(case_json):
        first["outline"] = engine.outline(case_json)

    async def index(request: Request):
        if not host_ok(request.headers, hosts):
            return _refusal(400, "unknown host")
        return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-store"})

    async def start(request: Request):
        if not host_ok(request.headers, hosts):
            return _refusal(400, "unknown host")
        return JSONResponse(packed_json(first))

    async def open_file(request: Request):
        if not origin_ok(request.headers, hosts):
            return _refusal(403, "requests from another origin are refused")
        try:
            declared = request.headers.get("content-length")
            if declared is None or not declared.isdigit():
                raise CaseError("request", "a Content-Length is required")
            if int(declared) > upload_limit:
                raise CaseError("file", f"too large ({int(declared)} bytes); the limit is {upload_limit} bytes")
            async with request.form(max_files=1, max_fields=20) as form:
                upload = form.get("file")
                if upload is None or isinstance(upload, str):
                    raise CaseError("file", "no file was sent")
                data = await upload.read()
                fields = {k: v for k, v in form.items() if isinstance(v, str)}
                name = upload.filename or ""
            out = await asyncio.to_thread(_read_upload, name, data, fields)
        except SectionDeformError as exc:
            return _refusal(422, str(exc))
        except Exception as exc:  # noqa: BLE001 - any unreadable upload is the user's file, not a crash
            return _refusal(422, f"file: cannot be read ({type(exc).__name__}: {exc})".splitlines()[0])
        return JSONResponse(packed_json(out))

    async def save(request: Request):
        if not origin_ok(request.headers, hosts):
            return _refusal(403, "requests from another origin are refused")
        what, ext = request.path_params["what"], "." + request.path_params["ext"].lower()
        formats = CASE_FORMATS if what == "case" else RESULT_FORMATS if what == "result" else ()
        if ext not in formats:
            return _refusal(404, f"cannot save {what}{ext}")
        try:
            body = json.loads(await _body(request, upload_limit))
            if not isinstance(body, dict):
                raise CaseError("request", "expected a JSON object")
            data = await asyncio.to_thread(_write, body.get("case"), body.get("model", "paper"), what, ext)
        except json.JSONDecodeError:
            return _refusal(422, "request: not valid JSON")
        except SectionDeformError as exc:
            return _refusal(422, str(exc))
        name = f"{what}{ext}"
        return Response(data, media_type=MEDIA[ext], headers={"Content-Disposition": f'attachment; filename="{name}"'})

    async def live(ws: WebSocket):
        if not origin_ok(ws.headers, hosts):
            await ws.close(code=1008)
            return
        await ws.accept()
        cache = engine.DeformerCache()
        pending: dict = {}
        wake = asyncio.Event()
        closed = False

        async def receive():
            nonlocal closed
            try:
                while True:
                    text = await ws.receive_text()
                    if len(text) > message_limit:
                        await ws.send_json({"type": "refused", "seq": None,
                                            "message": f"request: too large; the limit is {message_limit} characters"})
                        continue
                    try:
                        msg = json.loads(text)
                        seq = int(msg["seq"])
                    except (ValueError, KeyError, TypeError):
                        await ws.send_json({"type": "refused", "seq": None, "message": "request: not a valid message"})
                        continue
                    if pending.get("seq", -1) < seq:
                        if pending:
                            await ws.send_json({"type": "dropped", "seq": pending["seq"]})
                        pending.clear()
                        pending.update(msg, seq=seq)
                        wake.set()
            except WebSocketDisconnect:
                pass
            finally:
                closed = True
                wake.set()

        async def work():
            last = -1
            while True:
                await wake.wait()
                wake.clear()
                if closed:
                    return
                if not pending:
                    continue
                msg = dict(pending)
                pending.clear()
                if msg["seq"] <= last:
                    continue
                last = msg["seq"]
                case, model, final = msg.get("case"), msg.get("model", "paper"), bool(msg.get("final"))
                try:
                    key = cache.ready(case, model)
                    if final or key is None:
                        out = await asyncio.to_thread(engine.answer, cache, case, model, msg.get("ratio"), final)
                    else:  # a preview of a prepared section: under a millisecond, not worth a thread hop
                        out = engine.answer(cache, case, model, msg.get("ratio"), final, key=key)
                    reply = framed({"type": "result", "seq": msg["seq"], **out})
                except SectionDeformError as exc:
                    reply = {"type": "refused", "seq": msg["seq"], "message": str(exc)}
                except Exception as exc:  # noqa: BLE001 - the server keeps running whatever one request does
                    reply = {"type": "refused", "seq": msg["seq"],
                             "message": f"internal error: {type(exc).__name__}: {exc}".splitlines()[0]}
                try:
                    if isinstance(reply, bytes):
                        await ws.send_bytes(reply)
                    else:
                        await ws.send_json(reply)
                except (WebSocketDisconnect, RuntimeError):
                    return

        reader = asyncio.create_task(receive())
        try:
            await work()
        finally:
            reader.cancel()

    routes = [
        Route("/", index),
        Route("/api/start", start),
        Route("/api/open", open_file, methods=["POST"]),
        Route("/api/save/{what}.{ext}", save, methods=["POST"]),
        WebSocketRoute("/ws", live),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    app = Starlette(routes=routes)

    async def guarded(scope, receive, send):
        """Refuse any request whose Host is not one of the server's own names (DNS rebinding)."""
        if scope["type"] in ("http", "websocket"):
            headers = {k.decode("latin-1"): v.decode("latin-1") for k, v in scope.get("headers", [])}
            if not host_ok(headers, hosts):
                if scope["type"] == "http":
                    await _refusal(400, "unknown host")(scope, receive, send)
                else:
                    await send({"type": "websocket.close", "code": 1008})
                return
        await app(scope, receive, send)

    guarded.app = app
    return guarded
