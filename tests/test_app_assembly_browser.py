"""The interactive page with an assembly (section-case/2) in Chromium: bodies in colour, per-body readouts, refusals.

Same set-up as test_app_browser.py (skips without Chromium or Playwright,
unless ``SECTIONDEFORM_REQUIRE_BROWSER=1``); the server starts on the
two-layer strip.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from test_app_browser import centre, chromium, open_page, serve, shown, wait_for

from sectiondeform.errors import SectionDeformError
from sectiondeform.io.case import case_from_dict

CASES = Path(__file__).parent / "data" / "cases" / "v2"
STRIP = CASES / "two-layer-strip.json"
DRUM = CASES / "tread-on-drum.json"


@pytest.fixture(scope="module")
def server():
    yield from serve(str(STRIP))


@pytest.fixture(scope="module")
def browser(server):
    yield from chromium()


@pytest.fixture()
def page(browser, server):
    yield from open_page(browser, server, "#view[data-final='1']", timeout=60_000)


def bodies(d: dict) -> list[dict]:
    return json.loads(d["bodies"])


def test_each_body_in_its_own_colour_with_its_readouts(page):
    case = json.loads(STRIP.read_text())
    d = shown(page)
    got = bodies(d)
    assert [b["name"] for b in got] == [b["name"] for b in case["bodies"]]
    for b, case_body in zip(got, case["bodies"]):
        assert b["areaTarget"] == pytest.approx(case_body["law"]["area_ratio"] * b["areaInitial"], rel=1e-12)
        assert abs(b["areaFinal"] - b["areaTarget"]) <= 1e-9 * b["areaTarget"]
    groups = page.locator("#bodies g.body")
    assert groups.count() == 2
    strokes = {groups.nth(i).locator(".body-deformed").evaluate("e => getComputedStyle(e).stroke") for i in range(2)}
    assert len(strokes) == 2  # two colours
    assert all(groups.nth(i).locator(".body-deformed").get_attribute("d").count("L") > 50 for i in range(2))
    rows = page.locator("#bodies-rows tr")
    assert rows.count() == 2 and "backing" in rows.nth(0).inner_text() and "cover" in rows.nth(1).inner_text()
    assert page.locator("#body-label").is_visible()
    assert page.locator("#assembly-hint").is_visible()  # two bodies: the hint says what the body list picks


def test_dragging_the_target_moves_every_body_on_its_law(page):
    before = shown(page)
    x, y = centre(page, 'circle[data-curve=target][data-index="1"]')
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(x, y + 4 * k)
    d = wait_for(page, f"d.pending === d.seq && d.seq > {before['seq']}")
    page.mouse.up()
    d = wait_for(page, f"d.final === '1' && d.pending === d.seq && d.seq > {d['seq']}")
    assert d["contourHash"] != before["contourHash"]
    for b in bodies(d):
        assert abs(b["areaFinal"] - b["areaTarget"]) <= 1e-9 * b["areaTarget"]


def test_the_slider_sets_the_selected_bodys_law(page):
    page.select_option("#body", "1")
    assert page.locator("#ratio-value").input_value() == "0.900"
    seq = shown(page)["seq"]
    page.locator("#ratio-value").fill("0.85")
    page.locator("#ratio-value").press("Enter")
    d = wait_for(page, f"d.seq > {seq} && d.final === '1' && d.pending === d.seq")
    backing, cover = bodies(d)
    assert cover["areaTarget"] == pytest.approx(0.85 * cover["areaInitial"], rel=1e-12)
    assert backing["areaTarget"] == pytest.approx(0.95 * backing["areaInitial"], rel=1e-12)  # unchanged
    page.select_option("#body", "0")
    assert page.locator("#ratio-value").input_value() == "0.950"


def test_the_hyperelastic_model_deforms_the_assembly_on_each_bodys_law(page):
    good = shown(page)
    page.select_option("#model", "hyperelastic")
    d = wait_for(page, f"d.seq > {good['seq']} && d.final === '1' && d.pending === d.seq && d.model === 'hyperelastic'")
    assert d["contourHash"] != good["contourHash"]  # another model, another shape
    for b in bodies(d):
        assert abs(b["areaFinal"] - b["areaTarget"]) <= 1e-9 * b["areaTarget"]
    assert page.locator("#message").get_attribute("data-kind") != "error"  # warnings may show, no refusal


def test_a_refusal_is_shown_and_the_last_shape_stays(page, tmp_path):
    case = json.loads(DRUM.read_text())
    case["options"] = {**case.get("options", {}), "elements_through_thickness": 0.2}  # the paper model ignores it
    src = tmp_path / "tread-on-drum-coarse.json"
    src.write_text(json.dumps(case))
    page.set_input_files("#file", str(src))
    page.wait_for_function("document.getElementById('case-name').textContent === 'tread-on-drum'")
    good = wait_for(page, "d.pending === d.seq && d.final === '1'")
    page.select_option("#model", "hyperelastic")  # elements far larger than the bodies: refused by the library
    page.wait_for_selector("#message[data-kind=error]")
    assert "does not cover body" in page.locator("#message").inner_text()
    d = wait_for(page, "d.refusedSeq === d.pending")
    assert d["contourHash"] == good["contourHash"] and d["model"] == "paper"  # the last good shape stays
    page.select_option("#model", "paper")
    wait_for(page, f"d.seq > {d['refusedSeq']} && d.final === '1'")
    assert page.locator("#message").get_attribute("data-kind") != "error"  # warnings may show, no refusal


def test_a_body_of_revolution_opens_with_volumes_and_the_librarys_refusal(page):
    try:
        case_from_dict(json.loads(DRUM.read_text()))
        refusal = None
    except SectionDeformError as exc:
        refusal = str(exc)
    page.set_input_files("#file", str(DRUM))
    page.wait_for_function("document.getElementById('case-name').textContent === 'tread-on-drum'")
    assert page.locator("#ratio-label").inner_text() == "volume ratio"
    assert page.locator("#l-final").inner_text() == "final volume"
    assert page.locator("#ratio-value").input_value() == "1.000"  # the first body's volume ratio
    if refusal is None:  # the library deforms bodies of revolution
        d = wait_for(page, "d.pending === d.seq && d.final === '1'")
        assert all(abs(b["volumeError"]) <= 1e-6 for b in bodies(d))
        return
    page.wait_for_function(f"document.getElementById('message').textContent.includes({json.dumps(refusal)})")
    assert page.locator("#message").get_attribute("data-kind") == "error"
    assert page.locator("#bodies g.body").count() == 2  # the bodies as drawn
    assert page.locator("#bodies g.body .body-initial").first.get_attribute("d").count("L") > 50
    page.set_input_files("#file", str(STRIP))  # and the page goes on
    d = wait_for(page, "d.pending === d.seq && d.final === '1' && d.refusedSeq !== d.seq")
    assert [b["name"] for b in bodies(d)] == ["backing", "cover"]
