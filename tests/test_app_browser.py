"""The interactive page end to end in Chromium (Playwright), with real mouse events.

Runs the ``serve`` command on a free port and drives the Debian ``chromium``.
Without Chromium or Playwright the tests skip with the reason, unless
``SECTIONDEFORM_REQUIRE_BROWSER=1`` (set by the CI script): then they fail.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import sectiondeform as sd

LAUNCH_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
               "--disable-sync", "--no-first-run"]


def _missing() -> str | None:
    """Why the browser tests cannot run here, or None."""
    for module in ("playwright", "starlette", "uvicorn"):
        try:
            __import__(module)
        except ImportError:
            return f"the package {module!r} is not installed"
    if chromium_path() is None:
        return "no Chromium found (install the Debian package 'chromium')"
    return None


def chromium_path() -> str | None:
    """The Chromium executable: SECTIONDEFORM_CHROMIUM, else 'chromium' on the PATH."""
    path = os.environ.get("SECTIONDEFORM_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")
    return path if path and os.path.isfile(path) else None


def serve(*args: str):
    """Run ``sectiondeform serve ARGS`` on a free port; yield the page's address with its token, then stop it.

    Skips with the reason where Chromium or Playwright is missing, unless
    ``SECTIONDEFORM_REQUIRE_BROWSER=1``: then it fails.
    """
    why = _missing()
    if why:
        if os.environ.get("SECTIONDEFORM_REQUIRE_BROWSER") == "1":
            pytest.fail(f"browser tests required but cannot run: {why}")
        pytest.skip(why)
    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", *args, "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    line = proc.stdout.readline()
    match = re.search(r"(http://\S+/\?token=\S+)", line)
    if not match:
        proc.kill()
        pytest.fail(f"the server did not start: {line}{proc.stdout.read()}")
    yield match.group(1)
    proc.terminate()
    proc.wait(timeout=10)


def chromium():
    """Yield the system Chromium driven by Playwright, then close it."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=chromium_path(), args=LAUNCH_ARGS)
        yield b
        b.close()


def open_page(browser, address: str, ready: str = "#view[data-final='1']", timeout: float = 30_000):
    """Yield a new page at ``address`` once ``ready`` (a selector) shows; after the test, no script error on it."""
    context = browser.new_context(viewport={"width": 1200, "height": 700}, accept_downloads=True)
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(address)
    page.wait_for_selector(ready, timeout=timeout)
    yield page
    context.close()
    assert not errors, errors


@pytest.fixture(scope="module")
def server():
    yield from serve()


@pytest.fixture(scope="module")
def browser(server):
    yield from chromium()


@pytest.fixture()
def page(browser, server):
    yield from open_page(browser, server)


def shown(page) -> dict:
    """The numbers of the last answer drawn (the page's data- attributes)."""
    return page.eval_on_selector("#view", "e => ({...e.dataset})")


def wait_for(page, condition: str) -> dict:
    page.wait_for_function(f"(() => {{ const d = document.getElementById('view').dataset; return {condition}; }})()",
                           timeout=20_000)
    return shown(page)


def on_law(d: dict) -> bool:
    return abs(float(d["areaFinal"]) - float(d["areaTarget"])) <= 1e-9 * float(d["areaTarget"])


def centre(page, selector: str) -> tuple[float, float]:
    box = page.locator(selector).bounding_box()
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def test_the_page_shows_the_paper_example(page):
    d = shown(page)
    assert d["model"] == "paper" and d["final"] == "1"
    assert float(d["areaTarget"]) == pytest.approx(0.8 * float(d["areaInitial"]), rel=1e-12)
    assert on_law(d)
    assert page.locator("#deformed").get_attribute("d").count("L") > 100
    assert page.locator("circle[data-curve=target]").count() >= 3


def test_dragging_a_target_handle_follows_the_law(page):
    before = shown(page)
    x, y = centre(page, 'circle[data-curve=target][data-index="1"]')
    page.mouse.move(x, y)
    page.mouse.down()
    seen = []
    for i in range(1, 16):
        page.mouse.move(x + i, y + 2 * i)
        seen.append(wait_for(page, "d.pending === d.seq"))
    assert all(d["final"] == "0" for d in seen)
    assert all(on_law(d) for d in seen)
    assert len({d["contourHash"] for d in seen}) > 5          # the section moved with the pointer
    assert seen[-1]["contourHash"] != before["contourHash"]
    page.mouse.up()
    after = wait_for(page, "d.final === '1' && d.pending === d.seq")
    assert on_law(after) and float(after["jacobianMin"]) > 0
    # undo brings back the shape before the drag
    page.keyboard.press("Control+z")
    undone = wait_for(page, f"d.seq > {after['seq']} && d.final === '1'")
    assert undone["contourHash"] == before["contourHash"]


def test_a_whole_curve_handle_and_a_section_handle(page):
    before = shown(page)
    for selector in ("circle[data-whole=bend]", 'circle[data-curve=upper][data-index="4"]'):
        x, y = centre(page, selector)
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x, y + 15, steps=5)
        page.mouse.up()
        d = wait_for(page, "d.final === '1' && d.pending === d.seq")
        assert on_law(d) and d["contourHash"] != before["contourHash"]
        before = d
    # the section edit changed the initial area
    assert float(d["areaInitial"]) != pytest.approx(4378.96, abs=0.01)


def test_switching_models(page):
    page.select_option("#model", "hyperelastic")
    d = wait_for(page, "d.model === 'hyperelastic' && d.final === '1'")
    assert on_law(d)
    page.select_option("#model", "paper")
    assert on_law(wait_for(page, "d.model === 'paper' && d.final === '1'"))


def test_a_dropped_dxf_loads(page, tmp_path):
    pytest.importorskip("ezdxf")
    from sectiondeform.io import write_case

    case = sd.load_case(sd.example_case_path())
    path = tmp_path / "drop.dxf"
    write_case(path, sd.case_from_dict({**sd.case_to_dict(case), "law": {"area_ratio": 0.7}, "name": "dropped"}))
    seq = shown(page)["seq"]
    page.evaluate("""([text]) => {
        const dt = new DataTransfer();
        dt.items.add(new File([text], 'drop.dxf'));
        document.dispatchEvent(new DragEvent('drop', {dataTransfer: dt, bubbles: true, cancelable: true}));
    }""", [path.read_text()])
    d = wait_for(page, f"d.seq > {seq} && d.final === '1' && d.pending === d.seq")
    assert float(d["areaTarget"]) == pytest.approx(0.7 * float(d["areaInitial"]), rel=1e-12)
    assert page.locator("#case-name").inner_text() == "dropped"


def test_an_invalid_file_shows_a_message_and_the_page_keeps_working(page, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"format": "section-case/1", "lower": {"polyline": [[0, 0]]}}))
    page.set_input_files("#file", str(bad))
    page.wait_for_selector("#message[data-kind=error]")
    assert "bad.json" in page.locator("#message").inner_text()
    seq = shown(page)["seq"]
    page.locator("#ratio").fill("0.9")
    d = wait_for(page, f"d.seq > {seq} && d.pending === d.seq")
    assert float(d["areaTarget"]) == pytest.approx(0.9 * float(d["areaInitial"]), rel=1e-12)


def test_a_refusal_is_shown_and_the_last_shape_stays(page):
    good = shown(page)
    page.locator("#ratio-value").fill("3")  # three times the area: out of the paper model's reach
    page.locator("#ratio-value").press("Enter")
    page.wait_for_selector("#message[data-kind=error]")
    assert "refused" in page.locator("#message").inner_text()
    d = wait_for(page, "d.refusedSeq === d.pending")
    assert int(d["seq"]) < int(d["refusedSeq"])              # the shape drawn is the last good one
    assert page.locator("#deformed").get_attribute("d").count("L") > 100
    # the state says so: not the shape of the refused request
    assert page.locator("#r-state").inner_text() == "last good shape: full deformation (paper); the paper model refused"
    page.click("#undo")                                         # and the page goes on
    back = wait_for(page, f"d.seq > {d['refusedSeq']} && d.final === '1'")
    assert back["contourHash"] == good["contourHash"]
    page.wait_for_selector("#message[data-kind=none]", state="attached")


@pytest.mark.parametrize("name", ["result.json", "case.json"])
def test_saving_downloads_a_valid_file(page, tmp_path, name):
    with page.expect_download() as info:
        page.click(f"[data-save='{name}']")
    path = tmp_path / name
    info.value.save_as(path)
    data = json.loads(Path(path).read_text())
    if name == "case.json":
        assert sd.case_from_dict(data).law.ratio == pytest.approx(0.8)
    else:
        assert abs(data["area"]["final"] - data["area"]["target"]) <= 1e-9 * data["area"]["target"]


def test_nudge_zoom_pan_and_reset(page):
    before = shown(page)
    page.click('circle[data-curve=target][data-index="2"]')   # select the target's end
    assert page.locator("circle.selected").count() == 1
    seq = before["seq"]
    for _ in range(3):
        page.keyboard.press("Shift+ArrowUp")
    d = wait_for(page, f"d.seq > {seq} && d.final === '1' && d.pending === d.seq")
    assert on_law(d) and d["contourHash"] != before["contourHash"]
    view = page.evaluate("() => ({...sdState.view})")
    page.mouse.move(400, 300)
    page.mouse.wheel(0, -300)                                   # zoom in about the pointer
    page.wait_for_function(f"sdState.view.s > {view['s']} * 1.2")
    page.mouse.move(200, 600)                                   # pan from the background
    page.mouse.down()
    page.mouse.move(260, 640, steps=3)
    page.mouse.up()
    zoomed = page.evaluate("() => ({...sdState.view})")
    assert zoomed["s"] > view["s"] and zoomed["ty"] != view["ty"]
    asked = []
    page.once("dialog", lambda dialog: (asked.append(dialog.type), dialog.accept()))
    page.click("#reset")                                        # the case as opened (asked first); the view stays
    assert asked == ["confirm"]
    d = wait_for(page, f"d.seq > {d['seq']} && d.final === '1' && d.pending === d.seq")
    assert d["contourHash"] == before["contourHash"]
    page.click("#fit")
    assert page.evaluate("() => sdState.view.s") == pytest.approx(view["s"])



def test_a_drag_shows_previews_then_the_full_deformation_and_a_late_answer_does_not_hide_the_edit(browser, server):
    """While dragging, the edited curve is drawn with its answer; if the answer is late, it is drawn alone.

    The server's answers pass through a relay that can hold them (Playwright's WebSocket routing): with
    answers held, the moved target still appears on screen, no answer drawn; let through, the preview is
    drawn and labelled as one; on release of the mouse the full deformation replaces it.
    """
    context = browser.new_context(viewport={"width": 1200, "height": 700})
    page = context.new_page()
    held, relay = [], {"hold": False}

    def route(ws):
        relay["page"] = ws
        ws.connect_to_server().on_message(lambda m: held.append(m) if relay["hold"] else ws.send(m))

    page.route_web_socket(re.compile(r".*/ws$"), route)
    try:
        page.goto(server)
        page.wait_for_selector("#view[data-final='1']")
        before = shown(page)
        target = page.locator("#target-polygon").get_attribute("d")
        x, y = centre(page, 'circle[data-curve=target][data-index="1"]')
        page.mouse.move(x, y)
        page.mouse.down()
        relay["hold"] = True
        page.mouse.move(x, y + 30)
        page.wait_for_function(f"document.getElementById('target-polygon').getAttribute('d') !== {json.dumps(target)}",
                               timeout=20_000)
        late = shown(page)
        assert late["seq"] == before["seq"] and int(late["pending"]) > int(late["seq"])  # the edit alone, no answer
        page.wait_for_timeout(300)  # the answer reaches the relay and is held
        relay["hold"] = False
        while held:
            relay["page"].send(held.pop(0))
        preview = wait_for(page, "d.pending === d.seq")
        assert preview["final"] == "0" and on_law(preview)
        assert page.locator("#r-state").inner_text().startswith("preview")
        assert preview["contourHash"] != before["contourHash"]
        page.mouse.up()
        full = wait_for(page, f"d.seq > {preview['seq']} && d.final === '1' && d.pending === d.seq")
        assert page.locator("#r-state").inner_text().startswith("full deformation") and on_law(full)
    finally:
        context.close()
