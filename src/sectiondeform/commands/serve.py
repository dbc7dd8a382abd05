"""Open the interactive page: drag the target, the law and the section, and watch the section follow.

Starts a local server (loopback only unless --host says otherwise) and opens
the page in the browser. CASE is a case JSON, DXF or SVG file; by default the
paper's example. Stop with Ctrl+C.

The address printed carries the run's secret token (?token=...): the server
answers nothing without it, so other users of this machine cannot drive it.

Example: sectiondeform serve profile.dxf --area-ratio 0.8 --port 8765
Needs the extra: pip install 'sectiondeform[app]'
"""

from __future__ import annotations

import re
import secrets
import threading
from pathlib import Path

from ..errors import CaseError, require
from ._io_args import add_input_args, read_input_case


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, nargs="?", help="case file (.json, .dxf, .svg); default: the paper's example")
    parser.add_argument("--port", type=int, default=8765, help="port (default 8765; 0 picks a free one)")
    parser.add_argument("--host", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1, this machine only)")
    parser.add_argument("--no-browser", action="store_true", help="do not open the page in the browser")
    parser.add_argument("--token", metavar="T",
                        help="the secret every request must carry (default: a new random one per run); "
                             "for scripts, at least 16 letters, digits, '-' or '_'")
    parser.add_argument("--area-ratio", type=float, metavar="R", help="the law of a drawing that gives none")
    add_input_args(parser)


def hosts_for(host: str, port: int) -> list[str]:
    """The ``Host`` header values the server answers to."""
    names = {host, "127.0.0.1", "localhost", "[::1]"}
    return sorted(f"{n if ':' not in n or n.startswith('[') else f'[{n}]'}:{port}" for n in names)


LOOPBACK = ("127.0.0.1", "localhost", "::1")


def token_of(args) -> str:
    """The run's token: ``--token`` if given (checked), else a new random one."""
    if args.token is None:
        return secrets.token_urlsafe(32)
    if not re.fullmatch(r"[A-Za-z0-9_-]{16,}", args.token):
        raise CaseError("--token", "use at least 16 letters, digits, '-' or '_' (or leave it out for a random one)")
    return args.token


def exposure(host: str, port: int) -> str:
    """What listening on a non-loopback ``host`` exposes, said plainly (one line)."""
    where = "every network interface of this machine" if host in ("0.0.0.0", "::", "") else host
    return (f"warning: listening on {host} ({where}), port {port}: anyone who can reach it and has the token can "
            "open the page, send it cases and drawings to compute and save the results; the connection is plain "
            "HTTP, so the token and the cases can be read on the network. Leave out --host to stay on this machine")


def run(args) -> int:
    from .. import example_case_path
    from ..app import engine

    require("starlette", "app", "the interactive page")
    uvicorn = require("uvicorn", "app", "the interactive page")
    from ..app.server import UVICORN_OPTIONS, create_app

    token = token_of(args)
    report: list[str] = []
    path = args.case or example_case_path()
    case = read_input_case(path, args, report)
    for line in report:
        print(f"  {line}")
    config = uvicorn.Config(None, host=args.host, port=args.port, log_level="warning", **UVICORN_OPTIONS)
    server = uvicorn.Server(config)
    sock = config.bind_socket()
    sock.listen(config.backlog)  # a page opened as soon as the address is printed waits for the start, not refused
    port = sock.getsockname()[1]
    if args.host not in LOOPBACK:
        print(exposure(args.host, port), flush=True)
    config.app = create_app(engine.case_json_of(case), hosts_for(args.host, port), token=token)
    shown = args.host if ":" not in args.host else f"[{args.host}]"
    url = f"http://{'127.0.0.1' if args.host in ('0.0.0.0', '::') else shown}:{port}/?token={token}"
    print(f"sectiondeform: {case.name} at {url} (Ctrl+C to stop)", flush=True)
    if not args.no_browser:
        import webbrowser

        threading.Timer(0.5, webbrowser.open, (url,)).start()
    server.run(sockets=[sock])
    return 0
