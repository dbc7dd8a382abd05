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
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

READING = """Reading: the page's own share (building and sending the request, decoding the binary answer and
setting the paths) is about 1 ms; the server's compute is 1 to 2 ms at the median. The rest of the wait is
the way there and back (the browser's network process, the WebSocket, the server's event loop), each hop
waiting for a core on a machine shared with other jobs: the p95 follows the machine's load far more than
the page. The free-running rate is bounded by how fast the script sends pointer moves (one browser round
trip each), not by the page; every answer drawn is the latest one.
"""

LAUNCH_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
               "--disable-sync", "--no-first-run"]


def start_server() -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    line = proc.stdout.readline()
    match = re.search(r"(http://\S+/)", line)
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


def run(moves: int, chromium: str, images: Path | None, models=("paper", "hyperelastic"), meshes: bool = True) -> list[dict]:
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
                })
                print(rows[-1], flush=True)
            browser.close()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    return rows


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
        "| model | moves | median ms | p95 ms | of which: page send / wait for answer / draw, medians ms | server compute median / p95 ms | updates/s in step | free running: drawn, updates/s |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['model']} | {r['moves']} | {r['median_ms']:.2f} | {r['p95_ms']:.2f} | "
            f"{r['send_median_ms']:.1f} / {r['wait_median_ms']:.1f} / {r['draw_median_ms']:.1f} | "
            f"{r['compute_median_ms']:.2f} / {r['compute_p95_ms']:.2f} | {r['step_updates_per_s']:.0f} | "
            f"{r['free_drawn']} of {r['moves']}, {r['updates_per_s']:.0f} |"
        )
    load = f", load average {os.getloadavg()[0]:.1f} at the end" if hasattr(os, "getloadavg") else ""
    machine = (f"Machine: {platform.machine()}, {platform.system()}, Python {platform.python_version()}; "
               f"a shared machine of 2 cores{load}, so the figures are upper bounds.")
    verdict = ", ".join(f"{r['model']} {'met' if r['p95_ms'] <= 16 else 'not met'} ({r['p95_ms']:.1f} ms)" for r in rows)
    lines += ["", f"Target p95 <= 16 ms: {verdict}.", "", READING, machine, "", f"Command: `{command}`", ""]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moves", type=int, default=300)
    parser.add_argument("--out", type=Path, help="write the Markdown report here")
    parser.add_argument("--images", type=Path, help="write page.png and page-drag.gif in this folder")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    parser.add_argument("--models", default="paper,hyperelastic", help="comma-separated models to drag with")
    parser.add_argument("--no-meshes", action="store_true", help="drag with the meshes hidden (to measure their cost)")
    args = parser.parse_args(argv)
    rows = run(args.moves, args.chromium, args.images, tuple(args.models.split(",")), not args.no_meshes)
    text = report(rows, "python benchmarks/page.py " + " ".join(argv if argv is not None else sys.argv[1:]))
    print(text)
    if args.out:
        args.out.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
