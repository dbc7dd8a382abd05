"""The local server of the interactive page (Starlette; run by uvicorn).

Routes
------
``GET /``, ``/static/...``
    The page: plain JavaScript and SVG shipped in the package.
``GET /api/start``
    The case the server was started with, the models, its bodies' outlines
    and its rigid parts as drawn (:func:`engine.rigid_outline`).
``WS /ws``
    Live deformation. The page sends ``{"seq", "final", "case", "model",
    "ratio"}``; only the latest pending request is computed (coalescing); the
    server answers a result as one binary frame (a JSON header and the point
    arrays as raw float64, see :func:`framed`; a full deformation with rigid
    parts carries each part's contact, :func:`engine.contact_view`), a refusal as the text
    ``{"type": "refused", "seq", "message"}`` (with the request's ``"model"``
    when the request itself was read), and keeps running.
``POST /api/open``
    An uploaded case file (.json, .dxf, .svg, multipart field ``file``),
    read in a private temporary folder: the case as JSON.
``POST /api/save/{what}.{ext}``
    The case (``what = case``: .json, .dxf, .svg), its full deformation
    (``what = result``: .json, .dxf, .svg, .vtu) or the library's report
    figure of it (``what = figure``: .png, .svg, .pdf) as a download.

Safety: every request needs the run's secret token (``?token=`` once, then
the cookie the page's first load sets); the ``Host`` header must be one of
the server's own names (no DNS rebinding) and WebSocket and POST requests
must come from the page's own ``Origin``; request bodies and messages share
one size limit, checked before they are buffered; no path sent by the page
is ever read or written; every answer forbids framing and content sniffing,
and every error is one line without the server's paths.

Load: every computation runs off the event loop, the paper model's and
file work on a bounded pool of worker threads, the hyperelastic model's in
solver processes of their own, each page pinned to one (:mod:`.pools`: one
page's solve of a second never holds another's previews, and the solvers'
memory is given back); a connection has at most one request in a pool, and
while it waits for a worker its newer requests replace the older (so a
closed connection leaves at most the one being computed); connections are
capped.
"""

from __future__ import annotations

import asyncio
import contextlib
import hashlib
import hmac
import json
import os
import re
import struct
import tempfile
import threading
import uuid
from collections import OrderedDict
from importlib import resources
from pathlib import Path

import numpy as np
from starlette.applications import Starlette
from starlette.requests import HTTPConnection, Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.websockets import WebSocket

from ..errors import CaseError, SectionDeformError, spelled
from . import engine
from .pools import Solver, Solvers, Workers, resident_mb

__all__ = ["MAX_CONNECTIONS", "MAX_MESSAGE", "MAX_UPLOAD", "STATIC", "UVICORN_OPTIONS", "WORKERS", "cookie_name",
           "create_app", "one_line"]

MAX_MESSAGE = 2 * 1024 * 1024
"""Bytes of one WebSocket message and of one request body (an upload or a posted case): one limit for both."""
MAX_UPLOAD = MAX_MESSAGE
MAX_CONNECTIONS = 64
"""Open WebSocket connections (pages) at once; one more is refused with a message."""
WORKERS = max(2, min(4, os.cpu_count() or 2))
"""Worker threads computing previews for all connections (the bound of the pool: nothing waits in its queue)."""
SOLVERS = max(1, (os.cpu_count() or 2) // 2)
"""Solver processes running the hyperelastic model's work for all connections (:class:`~.pools.Solvers`)."""
SOLVER_PAGES = 16
"""Pages whose prepared sections a solver process keeps."""
DIED = "server: the solver process stopped before answering (out of memory?); a new one is ready, try again"
CACHE_SIZE = 2
"""Prepared sections kept per connection (the section being dragged and one other, e.g. the other model)."""
SHARED_SECTIONS = 8
"""Prepared sections shared by all connections (pages on the same case prepare it once)."""
MAX_DEPTH = 32
"""Deepest nesting of a request's JSON (a case needs about eight levels)."""
UVICORN_OPTIONS = {"ws_max_size": MAX_MESSAGE, "ws_per_message_deflate": False}
"""The WebSocket settings of the server (``uvicorn.Config`` keywords).

``ws_max_size`` is :data:`MAX_MESSAGE`, the same limit as for uploads: a
larger message is refused by the WebSocket layer before it is buffered
(close code 1009, which the page reports). No per-message compression
(uvicorn offers permessage-deflate by default): on the loopback it only
costs time, deflating each answer (about 20 kB of float64 that hardly
compress) on the server and inflating it in the browser, and each request
the other way; measured, about a millisecond per round trip at the median
and several at the 95th percentile (docs/benchmarks-page.md).
"""
STATIC = Path(str(resources.files(__package__) / "static"))
OPEN_FORMATS = (".json", ".dxf", ".svg")
CASE_FORMATS = (".json", ".dxf", ".svg")
RESULT_FORMATS = (".json", ".dxf", ".svg", ".vtu")
FIGURE_FORMATS = (".png", ".svg", ".pdf")
SAVE_FORMATS = {"case": CASE_FORMATS, "result": RESULT_FORMATS, "figure": FIGURE_FORMATS}
MEDIA = {".json": "application/json", ".dxf": "application/dxf", ".svg": "image/svg+xml",
         ".vtu": "application/octet-stream", ".png": "image/png", ".pdf": "application/pdf"}
DRAWING_OPTIONS = ("layers", "split", "split_tol", "lower_side", "target_arc", "bbox", "snap", "close_gap",
                   "join_tol", "simplify", "chordal_error", "units")
"""The drawing options the page may send with an upload: every one the command line has (``--layers``...),
by their :class:`~sectiondeform.io.outline.DrawingOptions` names; the law comes as ``area_ratio``."""
SECURITY_HEADERS = [
    (b"x-frame-options", b"DENY"),
    (b"content-security-policy", b"frame-ancestors 'none'"),
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
]
"""Added to every HTTP answer: no framing by another page (clickjacking), no content sniffing, no token in a Referer."""

# An absolute path in a message (POSIX, or a Windows drive): the server's folders are nobody else's business.
_PATH = re.compile(r"(?<![\w.:/\\])/(?:[^\s'\"/]+/)+[^\s'\",;)]*|\b[A-Za-z]:\\[^\s'\",;)]*")


PAGE_OPTIONS = {
    "model": "model NAME", "layers": "layers ROLE=NAME,...", "split": "split A, split B", "split_tol": "split tol",
    "snap": "snap D", "simplify": "simplify TOL", "chordal_error": "chordal error",
}
"""The page's spelling of each library option a message may name: its control's label
(:func:`~sectiondeform.errors.spelled`; the command line's is ``commands._common.OPTION_FLAGS``)."""


def one_line(text: str, names: dict | None = None, limit: int = 400) -> str:
    """A message for the page: its first non-blank line, the server's paths replaced.

    Parameters
    ----------
    text : str
    names : dict, optional
        Strings to replace first (a temporary path -> the uploaded file's own name).
    limit : int
        Longest message (characters); a longer one ends with "...".
    """
    if names:
        pattern = re.compile("|".join(re.escape(k) for k in sorted(names, key=len, reverse=True) if k))
        text = pattern.sub(lambda m: names[m.group(0)], text)
    line = next((s.strip() for s in text.splitlines() if s.strip()), "")
    line = spelled(_PATH.sub("(a file of the server)", line), PAGE_OPTIONS)
    return line if len(line) <= limit else line[:limit - 3] + "..."


class Refused(Exception):
    """A request the page gets one line back for (``message``), with an HTTP status for the routes."""

    def __init__(self, message: str, status: int = 422):
        super().__init__(message)
        self.message, self.status = message, status


def _failure(exc: BaseException, what: str, names: dict | None = None) -> str:
    """The one line for an exception raised by work done for the page (never its class name or a path)."""
    if isinstance(exc, SectionDeformError):
        return one_line(str(exc), names)
    detail = one_line(str(exc), names)
    if isinstance(exc, RecursionError):
        detail = "nested too deeply"
    elif isinstance(exc, MemoryError):
        detail = "out of memory"
    return f"{what}: failed ({detail})" if detail else f"{what}: failed; the server keeps running"


def _guarded(fn, what: str, names: dict | None = None):
    """``fn`` wrapped so that whatever it raises comes back as a value: ``(True, result)`` or ``(False, line)``.

    Run in a worker thread: no exception crosses into the event loop, not
    even ``StopIteration``, which an asyncio future cannot carry (the request
    would never be answered).
    """
    def call(*args):
        try:
            return True, fn(*args)
        except Exception as exc:  # noqa: BLE001 - any failure of one request is that request's answer
            return False, _failure(exc, what, names)

    return call


def cookie_name(token: str) -> str:
    """The name of the cookie carrying ``token``: its own per run, so that two servers on one machine do not clash."""
    return "sectiondeform-" + hashlib.sha256(token.encode("utf-8")).hexdigest()[:16]


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
        JSON values and ``(n, 2)`` float64 arrays, at any depth of dicts and
        lists of them (an assembly's bodies, a body's holes).

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
        if isinstance(value, list) and value and isinstance(value[0], (dict, np.ndarray)):  # bodies, holes
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


def _no_constant(name: str):
    raise CaseError("request", f"{name} is not a number JSON allows; send finite numbers")


def depth_of(value) -> int:
    """How deeply lists and dicts nest in ``value`` (iteratively: no recursion limit)."""
    deepest, stack = 0, [(value, 1)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, (list, dict)):
            deepest = max(deepest, depth)
            if depth > MAX_DEPTH:
                return depth
            stack.extend((v, depth + 1) for v in (item.values() if isinstance(item, dict) else item))
    return deepest


def parse_json(text: str | bytes, what: str) -> object:
    """JSON from the page: finite numbers only, nested at most :data:`MAX_DEPTH` deep; else a one-line CaseError."""
    try:
        value = json.loads(text, parse_constant=_no_constant)
    except CaseError:
        raise
    except RecursionError:
        raise CaseError(what, f"nested too deeply; at most {MAX_DEPTH} levels") from None
    except ValueError as exc:  # JSONDecodeError, UnicodeDecodeError
        raise CaseError(what, one_line(f"not valid JSON ({exc})")) from None
    if depth_of(value) > MAX_DEPTH:
        raise CaseError(what, f"nested too deeply; at most {MAX_DEPTH} levels")
    return value


def parse_request(text: str) -> dict:
    """One WebSocket request: a JSON object with a whole ``seq`` in [0, 2^53); else a one-line CaseError."""
    msg = parse_json(text, "request")
    if not isinstance(msg, dict):
        raise CaseError("request", "expected a JSON object {\"seq\", \"final\", \"case\", \"model\", \"ratio\"}")
    seq = msg.get("seq")
    if isinstance(seq, bool) or not isinstance(seq, int) or not 0 <= seq < 2 ** 53:
        raise CaseError("seq", f"expected a whole number from 0 to 2^53, got {one_line(repr(seq), limit=40)}")
    return msg


async def _body(request: Request, limit: int) -> bytes:
    """The request body, refused (413) past ``limit`` bytes without reading it all."""
    declared = request.headers.get("content-length")
    if declared is not None and declared.isdigit() and int(declared) > limit:
        raise Refused(f"request: too large ({int(declared)} bytes); the limit is {limit} bytes", 413)
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise Refused(f"request: too large; the limit is {limit} bytes", 413)
        chunks.append(chunk)
    return b"".join(chunks)


def _read_upload(name: str, data: bytes, form: dict) -> dict:
    """Read an uploaded case file in a private temporary folder; the case as JSON.

    A case JSON naming a drawing file (``"drawing": {"file": ...}``) is
    refused before anything is read: the server reads no path the page
    sends (and the library is told to read no drawing file at all).
    """
    from ..io import read_case

    shown = Path(name or "").name or "the file"
    ext = Path(shown).suffix.lower()
    if ext not in OPEN_FORMATS:
        raise CaseError("file", f"unknown case format {ext or '(none)'!r}; open a .json, .dxf or .svg file")
    options = _drawing_options(form)
    report: list[str] = []
    if ext == ".json":
        data_json = parse_json(data, "file")
        if isinstance(data_json, dict) and "drawing" in data_json:
            raise CaseError("drawing", "the page reads no file a case names; open the drawing (.dxf, .svg) "
                                       "itself, or give the curves in the case")
        if engine.is_assembly(data_json):
            return _assembly_opened(data_json)
        options["allow_files"] = False
    with tempfile.TemporaryDirectory(prefix="sectiondeform-") as tmp:
        path = Path(tmp) / f"upload{ext}"  # the server's own name, never the page's
        names = {str(path): shown, str(tmp): "", path.name: shown}
        try:
            path.write_bytes(data)
            try:
                case = read_case(path, report=report, **options)
            except CaseError as exc:
                if exc.field != "law" or ext == ".json":
                    raise
                ratio = float(form.get("area_ratio") or 0.8)
                report.clear()  # read again with the law: its report once
                case = read_case(path, report=report, law=engine.law_of(ratio), **options)
                report.append(f"the drawing gives no law: area ratio {ratio} used")
            except UnicodeDecodeError:
                raise CaseError("file", "not a text file") from None
            if case.name == path.stem:  # named after the file: the user's, not the server's
                case = case.replace(name=Path(shown).stem)
            out = {"case": engine.case_json_of(case), "model": engine.case_model(case), "report": report}
            out["outline"] = engine.outline(out["case"])
            out["rigid"] = engine.rigid_outline(out["case"])
        except SectionDeformError as exc:
            raise CaseError("file", one_line(str(exc), names)) from None
        except Exception as exc:  # noqa: BLE001 - any unreadable upload is the user's file, not a crash
            raise CaseError("file", "cannot be read" + (f" ({one_line(str(exc), names)})" if str(exc) else "")) from None
    return {**out, "report": [one_line(line, names) for line in report]}


def _drawing_options(form: dict) -> dict:
    """The reader's options from an upload's form: checked by the library, one line naming the field if wrong.

    ``options`` is a JSON object of :data:`DRAWING_OPTIONS` (``{"bbox": [xmin,
    ymin, xmax, ymax], "split": [[xa, ya], [xb, yb]], "layers": {"lower":
    "BASE"}, "lower_side": "longer", "units": "mm", ...}``); the single
    numeric fields ``snap``, ``close_gap``, ``join_tol``, ``simplify`` and
    ``target_arc`` are read too. Nothing here is a path.
    """
    from ..io.outline import DrawingOptions

    options = {}
    for key in ("snap", "close_gap", "join_tol", "simplify", "target_arc"):
        if form.get(key) not in (None, ""):
            try:
                options[key] = float(form[key])
            except ValueError:
                raise CaseError(key, f"expected a number, got {one_line(repr(form[key]), limit=40)}") from None
    if form.get("options") not in (None, ""):
        given = parse_json(form["options"], "options")
        if not isinstance(given, dict):
            raise CaseError("options", "expected a JSON object of drawing options")
        options.update({k: v for k, v in given.items() if v is not None})
    DrawingOptions.from_mapping(options, allowed=DRAWING_OPTIONS)  # unknown names and bad values: one line each
    return options


def _opened(name: str, data: bytes, form: dict, limit: int) -> bytes:
    """The answer to an upload (JSON bytes), refused if the page could not send its case back in one message."""
    out = _read_upload(name, data, form)
    size = len(json.dumps(out["case"]).encode("utf-8"))
    room = limit - 4096  # the request around the case: seq, model, ratio
    if size > room:
        raise CaseError("file", f"the case read from it takes {size} bytes, more than the page can send per "
                                f"request ({room}); simplify the drawing (the simplify option) or deform it with "
                                "the command line")
    return json.dumps(packed_json(out)).encode("utf-8")


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
    try:
        rigid = engine.rigid_outline(case_json)
    except SectionDeformError:  # the library's refusal, in the report, names it
        rigid = []
    return {"case": case_json, "model": engine.model_of_json(case_json), "report": report,
            "outline": engine.outline(case_json), "rigid": rigid}


def _write(case_json, model, what: str, ext: str) -> bytes:
    """The bytes of a case, result or figure file, written in a private temporary folder."""
    from ..io import write_case, write_result

    if not isinstance(case_json, dict):
        raise CaseError("case", "expected the case as a JSON object")
    if not isinstance(model, str):
        raise CaseError("model", f"expected one of {', '.join(engine.MODELS)}")
    with tempfile.TemporaryDirectory(prefix="sectiondeform-") as tmp:
        path = Path(tmp) / f"out{ext}"
        if what == "case":
            write_case(path, engine.with_model(engine.case_from_json(case_json), model))
        elif what == "figure":
            engine.report_figure(case_json, model, path)
        else:
            write_result(path, engine.full_result(case_json, model))
        return path.read_bytes()


def _compute(cache: engine.DeformerCache, msg: dict) -> bytes:
    """The answer to one WebSocket request, framed (run on a worker thread)."""
    out = engine.answer(cache, msg.get("case"), msg.get("model", "paper"), msg.get("ratio"), bool(msg.get("final")),
                        key=cache.ready(msg.get("case"), msg.get("model", "paper")), field=msg.get("field"))
    return framed({"type": "result", "seq": msg["seq"], **out})


def _in_solver(model, what: str = "result") -> bool:
    """Whether a request is the hyperelastic model's work (run in a solver process, :class:`~.pools.Solvers`).

    Its previews too: each starts from the page's last full solve, whose
    factorisation stays in the process that computed it.
    """
    return model == "hyperelastic" and what != "case"


_SOLVER_PAGES: OrderedDict[str, engine.DeformerCache] = OrderedDict()
"""In a solver process: the prepared sections (and warm starts) of the pages it has solved for, by page."""
_SOLVER_SHARED = engine.SharedDeformers(SHARED_SECTIONS)


def _solve(page: str, msg: dict) -> tuple[tuple[bool, bytes | str], float]:
    """In a solver process: the framed answer to ``page``'s request (guarded), and the process's memory (MB)."""
    cache = _SOLVER_PAGES.pop(page, None) or engine.DeformerCache(size=CACHE_SIZE, shared=_SOLVER_SHARED)
    _SOLVER_PAGES[page] = cache
    while len(_SOLVER_PAGES) > SOLVER_PAGES:
        _SOLVER_PAGES.popitem(last=False)
    return _guarded(_compute, "request")(cache, msg), resident_mb()


def _save(case_json, model, what: str, ext: str) -> tuple[tuple[bool, bytes | str], float]:
    """In a solver process: :func:`_write` guarded, and the process's memory (MB)."""
    return _guarded(_write, "save")(case_json, model, what, ext), resident_mb()


def create_app(case_json: dict, hosts, *, token: str, message_limit: int = MAX_MESSAGE,
               upload_limit: int = MAX_UPLOAD, max_connections: int = MAX_CONNECTIONS, workers: int = WORKERS,
               cache_size: int = CACHE_SIZE, solvers: int = SOLVERS):
    """The ASGI application of the page (a Starlette app behind the token, Host and header checks).

    Parameters
    ----------
    case_json : dict
        The ``section-case/1`` object shown first.
    hosts : iterable of str
        Accepted ``Host`` header values (``"127.0.0.1:8765"``...).
    token : str
        The run's secret: every request carries it as ``?token=`` or in the
        cookie :func:`cookie_name` that a page load with ``?token=`` sets.
    message_limit, upload_limit : int
        Largest WebSocket message and request body (bytes); the serve
        command gives both :data:`MAX_MESSAGE`, the WebSocket layer's limit.
    max_connections : int
        Open WebSocket connections at once; one more gets a refusal and is closed (code 1013).
    workers : int
        Worker threads computing previews (and reading and writing files) for all connections.
    cache_size : int
        Prepared sections kept per connection.
    solvers : int
        Solver processes running the hyperelastic model's work (started with
        the server, each page pinned to one, replaced when grown,
        :class:`~.pools.Solvers`); 0: that work runs on the worker threads too.
    """
    if not isinstance(token, str) or not token:
        raise ValueError("create_app needs a non-empty token")
    hosts = frozenset(h.lower() for h in hosts)
    secret = token.encode("utf-8")
    cookie = cookie_name(token)
    start_model = engine.model_of_json(case_json)
    first = {"case": case_json, "model": start_model, "models": list(engine.MODELS),
             "fields": list(engine.FIELDS), "limit": message_limit, "outline": engine.outline(case_json),
             "rigid": engine.rigid_outline(case_json)}
    shared = Workers(workers)
    prepared = engine.SharedDeformers(SHARED_SECTIONS)
    connections = 0
    processes: list[Solvers] = []
    starting = threading.Lock()

    def solving() -> Solvers:
        """The solver processes (started with the server, in the background; else on first use)."""
        with starting:
            if not processes:
                processes.append(Solvers(solvers, preload=(__name__,)))
        return processes[0]

    async def solve(solver: Solver, job, *args, acquired: bool = False):
        """Run a solver job (:func:`_solve`, :func:`_save`) in ``solver``'s process: ``(ok, value or line)``."""
        if not acquired:
            await solver.acquire()
        return await solver.run(job, *args, died=(False, DIED))

    async def offload(fn, *args, what: str, names: dict | None = None):
        ok, value = await shared.call(_guarded(fn, what, names), *args)
        if not ok:
            raise Refused(value)
        return value

    async def index(request: Request):
        return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-store"})

    async def start(request: Request):
        return JSONResponse(packed_json(first), headers={"Cache-Control": "no-store"})

    async def open_file(request: Request):
        if not origin_ok(request.headers, hosts):
            return _refusal(403, "request: from another origin; use the page this server serves")
        try:
            declared = request.headers.get("content-length")
            if declared is None or not declared.isdigit():
                raise Refused("request: a Content-Length is required", 411)
            if int(declared) > upload_limit:
                raise Refused(f"file: too large ({int(declared)} bytes); the limit is {upload_limit} bytes", 413)
            async with request.form(max_files=1, max_fields=20, max_part_size=64 * 1024) as form:
                upload = form.get("file")
                if upload is None or isinstance(upload, str):
                    raise CaseError("file", "no file was sent")
                data = await upload.read()
                fields = {k: v for k, v in form.items() if isinstance(v, str)}
                name = upload.filename or ""
            body = await offload(_opened, name, data, fields, message_limit, what="file")
        except Refused as exc:
            return _refusal(exc.status, exc.message)
        except SectionDeformError as exc:
            return _refusal(422, one_line(str(exc)))
        except Exception as exc:  # noqa: BLE001 - a malformed form is the user's request, not a crash
            return _refusal(400, _failure(exc, "request"))
        return Response(body, media_type="application/json")

    async def save(request: Request):
        if not origin_ok(request.headers, hosts):
            return _refusal(403, "request: from another origin; use the page this server serves")
        what, ext = request.path_params["what"], "." + request.path_params["ext"].lower()
        if ext not in SAVE_FORMATS.get(what, ()):
            return _refusal(404, one_line(f"save: cannot save {what}{ext}; save case.json/.dxf/.svg, "
                                          "result.json/.dxf/.svg/.vtu or figure.png/.svg/.pdf", limit=140))
        try:
            raw = await _body(request, upload_limit)
            body = await offload(parse_json, raw, "request", what="request")
            if not isinstance(body, dict):
                raise CaseError("request", "expected a JSON object {\"case\", \"model\"}")
            model = body.get("model", "paper")
            if solvers and _in_solver(model, what):
                ok, data = await solve(solving().assign(), _save, body.get("case"), model, what, ext)
                if not ok:
                    raise Refused(data)
            else:
                data = await offload(_write, body.get("case"), model, what, ext, what="save")
        except Refused as exc:
            return _refusal(exc.status, exc.message)
        except SectionDeformError as exc:
            return _refusal(422, one_line(str(exc)))
        except Exception as exc:  # noqa: BLE001 - a broken request gets its line, never a bare 500
            return _refusal(400, _failure(exc, "request"))
        name = f"{what}{ext}"
        return Response(data, media_type=MEDIA[ext], headers={"Content-Disposition": f'attachment; filename="{name}"'})

    async def live(ws: WebSocket):
        nonlocal connections
        if not origin_ok(ws.headers, hosts):
            await ws.close(code=1008)
            return
        await ws.accept()
        if connections >= max_connections:
            await ws.send_json({"type": "refused", "seq": None,
                                "message": f"server: busy, {connections} pages are connected, the most it serves; "
                                           "close another page and reload this one"})
            await ws.close(code=1013)
            return
        connections += 1
        cache = engine.DeformerCache(size=cache_size, shared=prepared)
        page = uuid.uuid4().hex  # this page's prepared sections in its solver process
        pinned: list[Solver] = []  # the page's solver process, once it has hyperelastic work
        pending: dict = {}
        wake = asyncio.Event()

        async def refuse(seq, message: str) -> None:
            await ws.send_json({"type": "refused", "seq": seq, "message": message})

        async def receive():
            while True:
                message = await ws.receive()
                if message["type"] == "websocket.disconnect":
                    return
                text = message.get("text")
                if text is None:
                    await refuse(None, "request: a binary message; send the request as JSON text")
                    continue
                if len(text) > message_limit:
                    await refuse(None, f"request: too large; the limit is {message_limit} characters")
                    continue
                try:
                    if len(text) > 64 * 1024:  # parsing a large case takes milliseconds: not on the event loop
                        ok, msg = await asyncio.to_thread(_guarded(parse_request, "request"), text)
                        if not ok:
                            raise CaseError("request", msg.removeprefix("request: "))
                    else:
                        msg = parse_request(text)
                except SectionDeformError as exc:
                    await refuse(None, one_line(str(exc)))
                    continue
                seq = msg["seq"]
                if pending.get("seq", -1) < seq:
                    if pending:
                        await ws.send_json({"type": "dropped", "seq": pending["seq"]})
                    pending.clear()
                    pending.update(msg, seq=seq)
                    wake.set()

        def in_process(msg: dict) -> bool:
            return bool(solvers) and _in_solver(msg.get("model"))

        def solver() -> Solver:
            if not pinned:
                pinned.append(solving().assign())
            return pinned[0]

        async def work():
            last = -1
            while True:
                await wake.wait()
                wake.clear()
                if not pending:
                    continue
                heavy = in_process(pending)
                pool = solver() if heavy else shared
                await pool.acquire()  # newer requests keep replacing the pending one meanwhile
                if not pending or pending["seq"] <= last or in_process(pending) != heavy:
                    pool.release()  # gone, or replaced by one for the other pool: look again
                    if pending and pending["seq"] > last:
                        wake.set()
                    else:
                        pending.clear()
                    continue
                msg = dict(pending)
                pending.clear()
                last = msg["seq"]
                if heavy:
                    ok, reply = await solve(pool, _solve, page, msg, acquired=True)
                else:
                    ok, reply = await shared.run(_guarded(_compute, "request"), cache, msg)
                if not ok:
                    reply = {"type": "refused", "seq": msg["seq"], "model": msg["model"], "message": reply}
                if isinstance(reply, bytes):
                    await ws.send_bytes(reply)
                else:
                    await ws.send_json(reply)

        reader = asyncio.create_task(receive())
        worker = asyncio.create_task(work())
        try:  # until the page goes (or a send to it fails)
            await asyncio.wait({reader, worker}, return_when=asyncio.FIRST_COMPLETED)
        finally:
            connections -= 1
            for task in (reader, worker):
                task.cancel()  # a request waiting for a worker is dropped; one being computed ends on its own
            with contextlib.suppress(BaseException):
                await asyncio.gather(reader, worker, return_exceptions=True)

    @contextlib.asynccontextmanager
    async def lifespan(app):
        if solvers:  # the processes start with the server (the first solve does not wait), not before it listens
            threading.Thread(target=solving, name="sectiondeform-solvers", daemon=True).start()
        yield
        shared.close()
        for pool in processes:
            pool.close()

    routes = [
        Route("/", index),
        Route("/api/start", start),
        Route("/api/open", open_file, methods=["POST"]),
        Route("/api/save/{what}.{ext}", save, methods=["POST"]),
        WebSocketRoute("/ws", live),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    app = Starlette(routes=routes, lifespan=lifespan)

    def token_in(conn: HTTPConnection) -> tuple[bool, bool]:
        """Whether the request carries the token, and whether in its query (then the page's cookie is set)."""
        given = conn.query_params.get("token")
        if given is not None and hmac.compare_digest(given.encode("utf-8"), secret):
            return True, True
        kept = conn.cookies.get(cookie)
        return kept is not None and hmac.compare_digest(kept.encode("utf-8"), secret), False

    async def guarded(scope, receive, send):
        """The checks in front of every route: security headers, the Host (DNS rebinding), the token."""
        if scope["type"] not in ("http", "websocket"):
            await app(scope, receive, send)
            return
        set_cookie = False

        async def send_with_headers(message):
            if message["type"] == "http.response.start":
                headers = [h for h in message.get("headers", []) if h[0].lower() not in dict(SECURITY_HEADERS)]
                headers += SECURITY_HEADERS
                if set_cookie:
                    headers.append((b"set-cookie", f"{cookie}={token}; Path=/; HttpOnly; SameSite=Strict".encode()))
                message = {**message, "headers": headers}
            await send(message)

        conn = HTTPConnection(scope)
        if not host_ok(conn.headers, hosts):
            if scope["type"] == "http":
                await _refusal(400, "request: unknown host; open the address the serve command printed")(
                    scope, receive, send_with_headers)
            else:
                await send({"type": "websocket.close", "code": 1008})
            return
        ok, in_query = token_in(conn)
        if not ok:
            if scope["type"] == "http":
                await _refusal(403, "token: missing or wrong; open the address the serve command printed "
                                    "(it ends in ?token=...)")(scope, receive, send_with_headers)
            else:
                await send({"type": "websocket.close", "code": 1008})
            return
        set_cookie = in_query and scope["type"] == "http"
        await app(scope, receive, send_with_headers)

    guarded.app = app
    guarded.cookie = cookie
    return guarded
