"""Benchmark of the interactive page in Chromium: pointer move to redrawn section.

Starts ``sectiondeform serve`` on the paper example, drags the target's middle
handle with 300 real pointer moves, and measures in the page the time from the
pointer event to the deformed section redrawn (its SVG path updated with the
server's answer), for both models:

* **in step**: each move waits for its answer before the next (latency: median, p95);
* **free running**: the 300 moves as fast as Playwright sends them; the server
  coalesces, the page drops stale answers (updates drawn per second).

Usage::

    python benchmarks/page.py [--moves 300] [--out docs/benchmarks-page.md] [--images docs/img]
    python benchmarks/page.py --socket [--moves 300]   # the server alone, from a Python WebSocket client
    python benchmarks/page.py --profile                # the paper preview's parts, in one process
    python benchmarks/page.py --trace trace.json       # also a Chromium trace of 60 moves (chrome://tracing)

Needs the extras ``[app]``, Playwright for Python and a Chromium (``--chromium``,
default the ``chromium`` on the PATH). ``--images`` also writes the README
screenshot (page.png) and a drag as an animated GIF (page-drag.gif, Pillow).
"""

from __future__ import annotations

import argparse
import io
import math
import os
import platform
import re
import secrets
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

READING = """Reading: the page's own share (building and sending the request, decoding the binary answer and
setting the paths) is about 1 ms; the server's compute is about 1 ms at the median. The rest of the wait is
the way there and back (the browser's renderer and network processes, the WebSocket, the server's event
loop), each hop waiting for a core on a machine shared with other jobs: the p95 follows the machine's load
far more than the page. The free-running rate is bounded by how fast the script sends pointer moves (one
browser round trip each), not by the page; every answer drawn is the latest one.
"""

LAUNCH_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
               "--disable-sync", "--no-first-run"]


TOKEN = "benchmark-" + secrets.token_urlsafe(16)
"""The server's token for this run (given with --token; the page's address carries it)."""


def start_server(*extra: str) -> tuple[subprocess.Popen, str]:
    """The serve command on a free port of 127.0.0.1 with :data:`TOKEN`; its page's address (with ``?token=``)."""
    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", "--port", "0", "--no-browser",
                             "--token", TOKEN, *extra], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    line = proc.stdout.readline()
    match = re.search(r"(http://\S+/\?token=\S+)", line)
    if not match:
        proc.kill()
        raise SystemExit(f"the server did not start: {line}")
    return proc, match.group(1)


def handle_centre(page, selector: str) -> tuple[float, float]:
    box = page.locator(selector).bounding_box()
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def path(x: float, y: float, moves: int) -> list[tuple[float, float]]:
    """A drag of the target's middle down and back up, twice, with some sideways wobble (pixels)."""
    return [(x + 15 * math.sin(4 * math.pi * i / moves), y + 60 * math.sin(2 * math.pi * i / moves) ** 2)
            for i in range(1, moves + 1)]


def settle(page) -> None:
    page.wait_for_function("(() => { const d = document.getElementById('view').dataset; return d.pending === d.seq; })()")


def drag(page, moves: int, in_step: bool) -> dict:
    """One scripted drag; the page's latency records and the wall time."""
    page.evaluate("() => { sdState.latencies = []; }")
    x, y = handle_centre(page, 'circle[data-curve=target][data-index="1"]')
    page.mouse.move(x, y)
    page.mouse.down()
    t0 = time.perf_counter()
    for px, py in path(x, y, moves):
        page.mouse.move(px, py)
        if in_step:
            settle(page)
    settle(page)
    seconds = time.perf_counter() - t0
    records = page.evaluate("() => sdState.latencies.filter((r) => !r.final)")
    page.mouse.up()
    settle(page)
    page.click("#undo")
    settle(page)
    return {"records": records, "seconds": seconds}


def p95(values: list[float]) -> float:
    return statistics.quantiles(values, n=20, method="inclusive")[-1]


def load() -> str:
    """The 1-minute load average (the machine is shared), or '?'."""
    return f"{os.getloadavg()[0]:.1f}" if hasattr(os, "getloadavg") else "?"


def run(moves: int, chromium: str, images: Path | None, models=("paper", "hyperelastic"), meshes: bool = True,
        trace: Path | None = None) -> list[dict]:
    from playwright.sync_api import sync_playwright

    proc, url = start_server()
    rows = []
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=chromium, args=LAUNCH_ARGS)
            page = browser.new_page(viewport={"width": 1200, "height": 700})
            page.goto(url)
            page.wait_for_selector("#view[data-final='1']")
            if images:
                write_images(page, images)
            if not meshes:
                page.uncheck("#show-mesh")
            for model in models:
                page.select_option("#model", model)
                page.wait_for_function(f"document.getElementById('view').dataset.model === '{model}'")
                settle(page)
                drag(page, 20, True)  # warm up
                if trace:
                    browser.start_tracing(page=page, path=str(trace.with_name(f"{trace.stem}-{model}{trace.suffix}")),
                                          categories=["devtools.timeline", "toplevel", "blink"])
                    drag(page, 60, True)
                    browser.stop_tracing()
                start_load = load()
                step = drag(page, moves, True)
                free = drag(page, moves, False)
                lat = [r["ms"] for r in step["records"]]
                comp = [r["compute"] for r in step["records"]]
                rows.append({
                    "model": model, "moves": moves, "answers": len(lat),
                    "median_ms": statistics.median(lat), "p95_ms": p95(lat),
                    "compute_median_ms": statistics.median(comp), "compute_p95_ms": p95(comp),
                    **{f"{k}_median_ms": statistics.median(r[k] for r in step["records"]) for k in ("send", "wait", "draw")},
                    "free_drawn": len(free["records"]), "free_seconds": free["seconds"],
                    "updates_per_s": len(free["records"]) / free["seconds"],
                    "step_updates_per_s": len(lat) / step["seconds"],
                    "load": f"{start_load} to {load()}",
                })
                print(rows[-1], flush=True)
            browser.close()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    return rows


def socket_run(requests: int, models=("paper", "hyperelastic")) -> list[dict]:
    """The server alone: preview requests over the WebSocket from Python, each waiting for its answer.

    A drag of the paper example's target (its arc's radius and centre, as the page would send them),
    sent by a ``websockets`` client that offers per-message compression as browsers do: the round trip
    against the server's own compute time, without a browser's processes in between.
    """
    import json
    import struct

    from websockets.sync.client import connect

    from sectiondeform import example_case_path

    case = json.loads(Path(example_case_path()).read_text(encoding="utf-8"))
    arc = case["target"]["arc"]

    def message(i: int, model: str, final: bool = False) -> str:
        radius = arc["radius"] * (1 + 0.3 * math.sin(i / 30))
        target = {"arc": {**arc, "radius": radius, "center": [arc["center"][0], arc["center"][1] + radius - arc["radius"]]}}
        return json.dumps({"seq": i, "final": final, "case": {**case, "target": target}, "model": model, "ratio": 0.8})

    proc, url = start_server()
    host = url.split("//", 1)[1].split("/", 1)[0]
    rows = []
    try:
        for model in models:
            for _ in range(200):  # the address is printed just before the server listens
                try:
                    ws = connect(f"ws://{host}/ws?token={TOKEN}", origin=f"http://{host}", compression="deflate",
                                 max_size=None)
                    break
                except ConnectionRefusedError:
                    time.sleep(0.05)
            with ws:
                extension = ws.response.headers.get("Sec-WebSocket-Extensions") or "none"
                ws.send(message(0, model, True))
                ws.recv()
                start_load, rtt, compute = load(), [], []
                for i in range(1, requests + 31):
                    t0 = time.perf_counter()
                    ws.send(message(i, model))
                    data = ws.recv()
                    ms = 1e3 * (time.perf_counter() - t0)
                    (n,) = struct.unpack_from("<I", data, 0)
                    if i > 30:  # warmed up
                        rtt.append(ms)
                        compute.append(json.loads(data[4:4 + n])["compute_ms"])
            beyond = [a - b for a, b in zip(rtt, compute)]
            rows.append({"model": model, "requests": requests, "extension": extension.split(";")[0],
                         "bytes": len(data), "load": f"{start_load} to {load()}",
                         **{f"{k}_{q}": f(v) for k, v in (("rtt", rtt), ("compute", compute), ("beyond", beyond))
                            for q, f in (("median", statistics.median), ("p95", p95))}})
            print(rows[-1], flush=True)
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    return rows


def server_profile(calls: int = 1000) -> str:
    """The paper preview of one request, part by part, in this process (medians of ``calls`` calls, ms)."""
    import json

    import numpy as np
    import shapely

    from sectiondeform import example_case_path
    from sectiondeform.app import engine
    from sectiondeform.app.server import framed
    from sectiondeform.applicability import aspect_change, bend_change, edges, stretch_range
    from sectiondeform.curves import curve_from_json
    from sectiondeform.laws import AreaRatio
    from sectiondeform.layers import corner_jacobians, node_frames

    case = json.loads(Path(example_case_path()).read_text(encoding="utf-8"))
    text = json.dumps({"seq": 1, "final": False, "case": case, "model": "paper", "ratio": 0.8})
    cache = engine.DeformerCache()
    engine.answer(cache, case, "paper", 0.8, True)
    d, _ = cache.get(case, "paper")
    prep, sec, law = d.prepared, d.section, AreaRatio(0.8)
    curve = curve_from_json(case["target"], "target")
    nodes = d.target_nodes(curve)
    res = d.preview(curve, law)
    grid = res.final_mesh.points.reshape(prep.mesh.nodes.shape)
    placed = prep.place(nodes, law)
    e0, e1 = prep.edges, edges(grid)
    key = engine.section_key(case, "paper")
    parts = {
        "whole request (read, key, preview, describe, frame)": lambda: framed(
            {"type": "result", "seq": 1, **engine.answer(cache, json.loads(text)["case"], "paper", 0.8, False,
                                                          key=cache.ready(case, "paper"))}),
        "Deformer.preview": lambda: d.preview(curve, law),
        "  placement (PaperPrepared.place)": lambda: prep.place(nodes, law),
        "    bend figure (applicability.bend_change)": lambda: bend_change(sec.lower, nodes, prep.height),
        "    corner Jacobians": lambda: corner_jacobians(grid[..., 0], grid[..., 1], sec.orientation),
        "    element edges and extent figures": lambda: (stretch_range(e0, edges(grid)), aspect_change(e0, e1)),
        "    three placement maps": lambda: [prep._map(i, nodes) for i in range(3)],
        "    frames of the target": lambda: node_frames(prep.extended_target(nodes), sec.orientation),
        "    law's polynomial (area coefficients)": lambda: law.coefficients(res.contour, res.contour),
        "    initial quantity, computed (now kept per law)": lambda: law.quantity(sec.contour),
        "  target sampled + its deviation": lambda: d._deviation(curve, d._sample(curve)),
        "  deformer's checks and result (Deformer._result)": lambda: d._result(nodes, placed, law, 0.0),
        "    of which simple contour (shapely)": lambda: shapely.is_simple(shapely.linearrings(res.contour)),
        "request read (json)": lambda: json.loads(text),
        "section key": lambda: engine.section_key(case, "paper"),
        "describe + frame the answer": lambda: framed({"type": "result", "seq": 1,
                                                       **engine.describe(res, False, False, True, 1.0)}),
    }
    assert key == cache.ready(case, "paper")
    lines = [f"| part | median ms ({calls} calls) |", "|---|---|"]
    for name, f in parts.items():
        f()
        times = np.empty(calls)
        for i in range(calls):
            t0 = time.perf_counter()
            f()
            times[i] = time.perf_counter() - t0
        lines.append(f"| {name} | {1e3 * float(np.median(times)):.3f} |")
    return "\n".join(lines + ["", f"Load average {load()}; mesh {prep.mesh.nodes.shape[0]} x {prep.mesh.nodes.shape[1]} nodes, "
                                   f"{len(sec.upper)} upper points.", ""])


def socket_report(rows: list[dict], command: str) -> str:
    lines = ["| model | requests | compression | answer bytes | round trip median / p95 ms | server compute median / p95 ms "
             "| beyond compute median / p95 ms | load average |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['model']} | {r['requests']} | {r['extension']} | {r['bytes']} | {r['rtt_median']:.2f} / {r['rtt_p95']:.2f} "
                     f"| {r['compute_median']:.2f} / {r['compute_p95']:.2f} | {r['beyond_median']:.2f} / {r['beyond_p95']:.2f} "
                     f"| {r['load']} |")
    return "\n".join(lines + ["", f"Command: `{command}`", ""])


def write_images(page, folder: Path) -> None:
    """The README screenshot and a GIF of a drag of the target's middle handle."""
    from PIL import Image

    folder.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(folder / "page.png"))
    x, y = handle_centre(page, 'circle[data-curve=target][data-index="1"]')
    clip = page.locator("#view").bounding_box()
    frames = []
    page.mouse.move(x, y)
    page.mouse.down()
    for i, (px, py) in enumerate(path(x, y, 48)):
        page.mouse.move(px, py)
        settle(page)
        if i % 3 == 0:
            shot = page.screenshot(clip={"x": clip["x"], "y": clip["y"], "width": clip["width"], "height": clip["height"]})
            frames.append(Image.open(io.BytesIO(shot)).convert("RGB").resize((int(clip["width"]) * 2 // 5, int(clip["height"]) * 2 // 5)))
    page.mouse.up()
    settle(page)
    page.click("#undo")
    settle(page)
    frames[0].save(folder / "page-drag.gif", save_all=True, append_images=frames[1:], duration=80, loop=0, optimize=True)


def report(rows: list[dict], command: str) -> str:
    lines = [
        "# Interactive page: pointer move to redrawn section",
        "",
        "Measured in Chromium (headless, software rendering) driving the page of `sectiondeform serve` on the",
        "paper example: a scripted drag of the target's middle handle with real pointer events. The time is",
        "taken in the page, from the pointer event to the deformed section's SVG path updated with the",
        "server's answer (the browser paints it at its next frame). *In step*: each move waits for its answer",
        "(latency). *Free running*: the moves as fast as they are sent; the server computes only the latest",
        "pending request and the page drops stale answers (updates drawn per second). Target: p95 <= 16 ms.",
        "",
        "| model | moves | median ms | p95 ms | of which: page send / wait for answer / draw, medians ms | server compute median / p95 ms | updates/s in step | free running: drawn, updates/s | load average |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['model']} | {r['moves']} | {r['median_ms']:.2f} | {r['p95_ms']:.2f} | "
            f"{r['send_median_ms']:.1f} / {r['wait_median_ms']:.1f} / {r['draw_median_ms']:.1f} | "
            f"{r['compute_median_ms']:.2f} / {r['compute_p95_ms']:.2f} | {r['step_updates_per_s']:.0f} | "
            f"{r['free_drawn']} of {r['moves']}, {r['updates_per_s']:.0f} | {r['load']} |"
        )
    machine = (f"Machine: {platform.machine()}, {platform.system()}, Python {platform.python_version()}; "
               f"{os.cpu_count()} cores shared with other jobs (load average in the table, before and after "
               "each model's drag), so the figures are upper bounds.")
    verdict = ", ".join(f"{r['model']} {'met' if r['p95_ms'] <= 16 else 'not met'} ({r['p95_ms']:.1f} ms)" for r in rows)
    lines += ["", f"Target p95 <= 16 ms: {verdict}.", "", READING, machine, "", f"Command: `{command}`", ""]
    return "\n".join(lines)


def kept_sections(path: Path) -> str:
    """The sections of an existing report after its first (``## ...`` and below), kept when it is rewritten."""
    if not path.exists():
        return ""
    text = path.read_text(encoding="utf-8")
    match = re.search(r"^## ", text, flags=re.MULTILINE)
    return "\n" + text[match.start():] if match else ""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moves", type=int, default=300)
    parser.add_argument("--out", type=Path, help="write the Markdown report here")
    parser.add_argument("--images", type=Path, help="write page.png and page-drag.gif in this folder")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    parser.add_argument("--models", default="paper,hyperelastic", help="comma-separated models to drag with")
    parser.add_argument("--no-meshes", action="store_true", help="drag with the meshes hidden (to measure their cost)")
    parser.add_argument("--socket", action="store_true",
                        help="no browser: preview requests over the WebSocket from Python (round trip against compute)")
    parser.add_argument("--profile", action="store_true", help="no browser: the paper preview's parts, in this process")
    parser.add_argument("--trace", type=Path, help="write a Chromium trace (devtools.timeline) of 60 moves in step here")
    args = parser.parse_args(argv)
    command = "python benchmarks/page.py " + " ".join(argv if argv is not None else sys.argv[1:])
    if args.profile:
        print(server_profile())
        return 0
    if args.socket:
        print(socket_report(socket_run(args.moves, tuple(args.models.split(","))), command))
        return 0
    rows = run(args.moves, args.chromium, args.images, tuple(args.models.split(",")), not args.no_meshes, args.trace)
    text = report(rows, command)
    print(text)
    if args.out:
        args.out.write_text(text + kept_sections(args.out), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
