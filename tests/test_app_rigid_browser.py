"""The page with rigid parts in Chromium (Playwright): the part drawn, its force, a travel changed, saved, read back.

Same set-up as test_app_browser.py (skips without Chromium or Playwright,
unless ``SECTIONDEFORM_REQUIRE_BROWSER=1``); the server starts on the bumper
pressed by a rigid plate (hyperelastic, about half a second per solve).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from test_app_browser import chromium, open_page, serve, wait_for

from sectiondeform.deform import Deformer
from sectiondeform.io import read_case
from sectiondeform.io.case import case_from_dict

BUMPER = Path(__file__).parent / "data" / "cases" / "v2" / "bumper-under-plate.json"
PART = ".rigid-part[data-part='0']"


@pytest.fixture(scope="module")
def server():
    yield from serve(str(BUMPER))


@pytest.fixture(scope="module")
def browser(server):
    yield from chromium()


@pytest.fixture()
def page(browser, server):
    yield from open_page(browser, server, f"{PART}[data-seq]", timeout=60_000)


def solved(page, travel: float) -> dict:
    """The part's figures once the full deformation for ``travel`` (mm, down) is shown."""
    want = json.dumps([0, -travel]).replace(" ", "")
    page.wait_for_function(f"document.querySelector(\"{PART}\").dataset.solvedTravel === '{want}' && "
                           "document.getElementById('view').dataset.final === '1'", timeout=20_000)
    return page.eval_on_selector(PART, "e => ({...e.dataset, force_text: e.querySelector('.r-force').textContent})")


def shown_force(text: str) -> float:
    """The force magnitude as printed, checked for its unit (N/mm: a plane section)."""
    match = re.match(r"([-\d.e+]+) N/mm ", text)
    assert match, text
    return float(match.group(1))


def path_points(d: str) -> np.ndarray:
    """The points of a drawn path, ``(n, 2)`` (world units, rounded to a twentieth of a screen pixel)."""
    return np.array([(float(x), float(y)) for x, y in re.findall(r"[ML]\s*(-?[\d.e+-]+)\s+(-?[\d.e+-]+)", d)])


def drawn(locator, want) -> None:
    np.testing.assert_allclose(path_points(locator.get_attribute("d")), want, atol=1e-3)


def test_the_plate_is_drawn_its_force_shown_and_a_travel_changed_and_saved(page, tmp_path):
    case = json.loads(BUMPER.read_text())
    plate = np.array(case["rigid"][0]["contour"]["polyline"][:-1])
    shape = page.locator("#rigid .rigid-shape[data-part='0']")
    drawn(shape.locator(".rigid-final"), plate)  # where it ends
    drawn(shape.locator(".rigid-initial"), plate + [0, 1.2])  # where it starts: 1.2 mm higher
    assert shape.locator(".rigid-initial").evaluate("e => getComputedStyle(e).strokeDasharray") != "none"
    assert shape.locator(".rigid-pressure path").count() > 0  # the pressure along the contact, coloured

    library = Deformer(case_from_dict(case)).deform().rigid[0]
    before = solved(page, 1.2)
    assert shown_force(before["force_text"]) == float(f"{math.hypot(*library.force):.6g}")
    length, unit = page.locator(f"{PART} .r-contact").inner_text().split()
    assert float(length) == float(f"{library.length:.6g}") and unit == "mm"
    peak, unit = page.locator(f"{PART} .r-pressure").inner_text().split()[:2]
    assert float(peak) == float(f"{library.pressure_max:.6g}") and unit == "MPa"

    field = page.locator(f"{PART} .travel-input")
    assert float(field.input_value()) == 1.2
    field.fill("1.5")
    field.press("Enter")
    after = solved(page, 1.5)
    assert shown_force(after["force_text"]) > shown_force(before["force_text"])  # more travel, more force
    assert float(after["forceY"]) > float(before["forceY"]) > 0
    drawn(shape.locator(".rigid-final"), plate - [0, 0.3])  # the end moved down, the start stayed
    drawn(shape.locator(".rigid-initial"), plate + [0, 1.2])

    with page.expect_download() as info:
        page.click("[data-save='case.json']")
    saved = tmp_path / "saved.json"
    info.value.save_as(saved)
    (part,) = read_case(saved).rigid
    assert part.travel == (0.0, -1.5) and part.name == "plate" and part.friction == 0.0


def test_dragging_the_plate_down_adds_travel_and_force(page):
    before = solved(page, 1.2)
    box = page.locator("circle[data-rigid='0']").bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(x + k, y + 4 * k)  # down, and a little sideways: only the travel's direction counts
    page.mouse.up()
    travel = float(page.eval_on_selector(PART, "e => e.dataset.travel"))
    assert 1.5 < travel < 3.0
    after = solved(page, travel)
    assert float(after["forceY"]) > float(before["forceY"])
    page.keyboard.press("Control+z")  # undo: back to the case's travel
    again = solved(page, 1.2)
    # the same prepared problem, warm-started from its first solve: the same force to the contact's tolerance
    assert float(again["forceY"]) == pytest.approx(float(before["forceY"]), rel=1e-3)


def test_the_bodies_follow_the_plate_in_previews_while_it_is_dragged(page):
    """Each move of the plate is answered by a preview (the contact linearised about the last full solve), the
    bumper pressed down with it; the release solves in full.
    """
    solved(page, 1.2)
    top = "() => Math.max(...sdState.result.bodies[0].contour.map((p) => p[1]))"  # the bumper's top, mm
    before = page.evaluate(top)
    page.evaluate("() => { sdState.latencies = []; }")
    box = page.locator("circle[data-rigid='0']").bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 9):
        page.mouse.move(x, y + 2 * k)
        page.wait_for_timeout(50)
    wait_for(page, "Number(d.pending) === sdState.shown")
    dragged = float(page.eval_on_selector(PART, "e => e.dataset.travel"))
    during = page.evaluate("() => ({final: sdState.result.final, previews: sdState.latencies.filter((r) => !r.final).length})")
    pressed = page.evaluate(top)
    page.mouse.up()
    assert dragged > 1.2 and not during["final"] and during["previews"] >= 4, (dragged, during)
    assert solved(page, dragged)["travel"] == str(dragged)
    after = page.evaluate(top)
    # The preview pressed the bumper down, most of the way to the full solve's shape (first order: the points
    # the plate reaches only in this drag do not push back in it).
    assert after < pressed < before and pressed - after < 0.5 * (before - after), (before, pressed, after)


def test_the_paper_model_says_it_refuses_rigid_parts(page):
    """The library's line once (the page's message), the panel greyed and the state naming both models."""
    solved(page, 1.2)
    page.select_option("#model", "paper")
    wait_for(page, "d.refusedSeq === d.pending")
    line = page.locator("#message").inner_text()
    assert line.startswith("refused: rigid: the paper model has no mechanics for rigid parts") and "\n" not in line
    assert line.endswith("(the last good shape is kept)")
    library = line.removeprefix("refused: ").removesuffix(" (the last good shape is kept)")
    assert page.locator("body").inner_text().count(library) == 1  # said once
    assert page.locator("#rigid-note").inner_text() == "not solved by the paper model"
    assert page.locator("#rigid .rigid-final").get_attribute("d")  # the part is still drawn
    assert page.locator(f"{PART}.stale").count() == 1  # the figures on screen are not the paper model's: greyed
    state = page.locator("#r-state").inner_text()
    assert state == "last good shape: full deformation (hyperelastic); the paper model refused", state


def test_an_edited_travel_survives_a_reload_of_the_tab(page):
    """Never losing work: the edited travel is kept in the tab, and the reopened page solves it again."""
    field = page.locator(f"{PART} .travel-input")
    field.fill("1.4")
    field.press("Enter")
    before = solved(page, 1.4)
    page.on("dialog", lambda d: d.accept())  # leaving with edits not saved as a case file: yes
    page.reload()
    page.wait_for_selector("#message[data-kind=info]")
    after = solved(page, 1.4)
    assert float(page.locator(f"{PART} .travel-input").input_value()) == 1.4
    assert float(after["forceY"]) == pytest.approx(float(before["forceY"]), rel=1e-3)
    assert page.locator("#rigid .rigid-final").get_attribute("d")  # drawn again, from the answer
