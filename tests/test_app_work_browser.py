"""The page never loses work (Playwright, Chromium): prompts before edits are replaced, undoable reset and open,
reconnection after a server restart with the page's own state, edits kept across a restart with a new token.

Skips like tests/test_app_browser.py without Chromium or Playwright.
"""

from __future__ import annotations

import json
import re
import socket
import subprocess
import sys

import pytest
from test_app_browser import browser, page, server, shown, wait_for  # noqa: F401 - the shared fixtures

from conftest import box_case

SETTLED = "d.final === '1' && d.pending === d.seq"


def nudge(page) -> dict:  # noqa: F811 - a page, not the fixture
    """An edit with real key presses (a user's gesture, which the browser needs before it may ask on leaving)."""
    seq = shown(page)["seq"]
    page.click('circle[data-curve=target][data-index="2"]')
    for _ in range(3):
        page.keyboard.press("Shift+ArrowUp")
    return wait_for(page, f"d.seq > {seq} && {SETTLED}")


def set_ratio(page, ratio: float) -> None:  # noqa: F811 - a page, not the fixture
    page.locator("#ratio-value").fill(str(ratio))
    page.locator("#ratio-value").press("Enter")


def test_reset_asks_before_replacing_edits_and_is_undone(page):  # noqa: F811
    opened = shown(page)
    edited = nudge(page)
    assert edited["contourHash"] != opened["contourHash"]
    asked = []
    page.once("dialog", lambda d: (asked.append((d.type, d.message)), d.dismiss()))
    page.click("#reset")
    page.wait_for_timeout(300)
    assert asked and asked[0][0] == "confirm" and "not saved" in asked[0][1]
    assert shown(page)["pending"] == edited["seq"]               # dismissed: nothing sent, the edits stay
    page.once("dialog", lambda d: d.accept())
    page.click("#reset")
    reset = wait_for(page, f"d.seq > {edited['seq']} && {SETTLED}")
    assert reset["contourHash"] == opened["contourHash"]
    page.click("#undo")                                         # the edits come back
    back = wait_for(page, f"d.seq > {reset['seq']} && {SETTLED}")
    assert back["contourHash"] == edited["contourHash"]


def test_a_clean_page_resets_without_asking(page):  # noqa: F811
    asked = []
    page.on("dialog", lambda d: (asked.append(d.type), d.accept()))
    seq = shown(page)["seq"]
    page.click("#reset")
    wait_for(page, f"d.seq > {seq} && {SETTLED}")
    assert asked == []


def test_opening_a_file_over_edits_asks_and_is_undone(page, tmp_path):  # noqa: F811
    name = page.locator("#case-name").inner_text()
    edited = nudge(page)
    path = tmp_path / "box.json"
    path.write_text(json.dumps(box_case(ratio=0.9)))
    page.once("dialog", lambda d: d.dismiss())
    page.set_input_files("#file", str(path))
    page.wait_for_timeout(500)
    assert page.locator("#case-name").inner_text() == name    # not opened
    page.once("dialog", lambda d: d.accept())
    page.set_input_files("#file", str(path))
    page.wait_for_function("document.getElementById('case-name').textContent === 'box'")
    opened = wait_for(page, f"d.seq > {edited['seq']} && {SETTLED}")
    assert float(opened["areaInitial"]) == pytest.approx(40.0)
    page.click("#undo")                                         # the edited case, not the one before it was edited
    back = wait_for(page, f"d.seq > {opened['seq']} && {SETTLED}")
    assert page.locator("#case-name").inner_text() == name
    assert back["contourHash"] == edited["contourHash"]


def test_leaving_the_page_with_unsaved_edits_asks(page):  # noqa: F811
    asked = []
    page.on("dialog", lambda d: (asked.append(d.type), d.dismiss()))
    nudge(page)
    page.close(run_before_unload=True)
    page.wait_for_timeout(500)
    assert asked == ["beforeunload"] and not page.is_closed()  # dismissed: the page stays, edits and all
    with page.expect_download():                               # saved as a case file: nothing to lose any more
        page.click("[data-save='case.json']")
    page.close(run_before_unload=True)
    page.wait_for_event("close", timeout=5000)
    assert asked == ["beforeunload"]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(port: int, token: str) -> subprocess.Popen:
    proc = subprocess.Popen([sys.executable, "-m", "sectiondeform", "serve", "--port", str(port), "--no-browser",
                             "--token", token], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    line = proc.stdout.readline()
    if "token=" not in line:
        proc.kill()
        pytest.fail(f"the server did not start: {line}{proc.stdout.read()}")
    return proc


def test_the_page_reconnects_after_a_restart_and_keeps_its_edits(browser):  # noqa: F811
    """The server stops: the page says so, keeps its edits (and reports a save); it restarts: the page
    reconnects by itself and sends its current case, edits made meanwhile included. Restarted with a new
    token, the page says it cannot reconnect; opened at the new address in the same tab, it has the edits.
    """
    port, token = free_port(), "restart-test-token-0123456789"
    proc = start_server(port, token)
    context = browser.new_context(viewport={"width": 1200, "height": 700})
    page = context.new_page()  # noqa: F811
    try:
        page.goto(f"http://127.0.0.1:{port}/?token={token}")
        page.wait_for_selector("#view[data-final='1']")
        set_ratio(page, 0.9)
        before = wait_for(page, f"Math.abs(d.areaTarget / d.areaInitial - 0.9) < 1e-12 && {SETTLED}")
        proc.terminate()
        proc.wait(timeout=10)
        page.wait_for_function("document.getElementById('view').dataset.connected === '0'", timeout=20_000)
        assert "reconnecting" in page.text_content("#message")
        page.click("[data-save='result.json']")                 # a save while the server is down is reported
        page.wait_for_function("document.getElementById('message').textContent.includes('not saved')")
        set_ratio(page, 0.7)                                     # an edit while it is down
        proc = start_server(port, token)
        after = wait_for(page, f"d.reconnects === '1' && d.seq > {before['seq']} && {SETTLED}")
        assert float(after["areaTarget"]) == pytest.approx(0.7 * float(after["areaInitial"]), rel=1e-12)
        assert "reconnected" in page.text_content("#message")
        # a restart with another token: the page cannot reconnect and says why
        proc.terminate()
        proc.wait(timeout=10)
        other = "another-token-of-the-restart-42"
        proc = start_server(port, other)
        page.wait_for_function("document.getElementById('view').dataset.closed === '1008'", timeout=30_000)
        assert re.search(r"token.*open the address", page.text_content("#message"))
        page.on("dialog", lambda d: d.accept())                 # leaving with unsaved edits: yes
        page.goto(f"http://127.0.0.1:{port}/?token={other}")
        kept = wait_for(page, SETTLED + " && Math.abs(d.areaTarget / d.areaInitial - 0.7) < 1e-12")
        assert on_ratio(kept, 0.7) and "are back" in page.text_content("#message")
    finally:
        context.close()
        proc.terminate()
        proc.wait(timeout=10)


def on_ratio(d: dict, ratio: float) -> bool:
    return abs(float(d["areaTarget"]) - ratio * float(d["areaInitial"])) <= 1e-12 * float(d["areaTarget"])
