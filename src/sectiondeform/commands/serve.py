"""Open the interactive page: drag the target, the law and the section, and watch the section follow.

Starts a local server (loopback only unless --host says otherwise) and opens
the page in the browser. CASE is a case JSON, DXF or SVG file; by default the
paper's example. Stop with Ctrl+C.

Example: sectiondeform serve profile.dxf --area-ratio 0.8 --port 8765
Needs the extra: pip install 'sectiondeform[app]'
"""

from __future__ import annotations

import threading
from pathlib import Path

from ..errors import require
from ._io_args import add_input_args, read_input_case


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, nargs="?", help="case file (.json, .dxf, .svg); default: the paper's example")
    parser.add_argument("--port", type=int, default=8765, help="port (default 8765; 0 picks a free one)")
    parser.add_argument("--host", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1, this machine only)")
    parser.add_argument("--no-browser", action="store_true", help="do not open the page in the browser")
    parser.add_argument("--area-ratio", type=float, metavar="R", help="the law of a drawing that gives none")
    add_input_args(parser)


def hosts_for(host: str, port: int) -> list[str]:
    """The ``Host`` header values the server answers to."""
    names = {host, "127.0.0.1", "localhost", "[::1]"}
    return sorted(f"{n if ':' not in n or n.startswith('[') else f'[{n}]'}:{port}" for n in names)


def run(args) -> int:
    from .. import example_case_path
    from ..app import engine

    require("starlette", "app", "the interactive page")
    uvicorn = require("uvicorn", "app", "the interactive page")
    from ..app.server import UVICORN_OPTIONS, create_app

    report: list[str] = []
    path = args.case or example_case_path()
    case = read_input_case(path, args, report)
    for line in report:
        print(f"  {line}")
    if args.host not in ("127.0.0.1", "localhost", "::1"):
        print(f"warning: listening on {args.host}: anyone who can reach this address can use the page")
    config = uvicorn.Config(None, host=args.host, port=args.port, log_level="warning", **UVICORN_OPTIONS)
    server = uvicorn.Server(config)
    sock = config.bind_socket()
    port = sock.getsockname()[1]
    config.app = create_app(engine.case_json_of(case), hosts_for(args.host, port))
    shown = args.host if ":" not in args.host else f"[{args.host}]"
    url = f"http://{'127.0.0.1' if args.host in ('0.0.0.0', '::') else shown}:{port}/"
    print(f"sectiondeform: {case.name} at {url} (Ctrl+C to stop)", flush=True)
    if not args.no_browser:
        import webbrowser

        threading.Timer(0.5, webbrowser.open, (url,)).start()
    server.run(sockets=[sock])
    return 0
