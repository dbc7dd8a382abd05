"""A hollow profile on the page in Chromium (Playwright): its hole drawn, initial and deformed, as the body's inside.

Same set-up as test_app_browser.py (skips without Chromium or Playwright,
unless ``SECTIONDEFORM_REQUIRE_BROWSER=1``); the server starts on the public
hollow profile roll-formed onto a carrier (the paper model).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from test_app_browser import chromium, open_page, serve, shown

from sectiondeform.deform import Deformer
from sectiondeform.io import read_case

HOLLOW = Path(__file__).parent / "data" / "cases" / "v2" / "hollow-on-arc.json"
BODY = "#bodies .body[data-body='0']"


@pytest.fixture(scope="module")
def server():
    yield from serve(str(HOLLOW))


@pytest.fixture(scope="module")
def browser(server):
    yield from chromium()


@pytest.fixture()
def page(browser, server):
    yield from open_page(browser, server)


def subpaths(d: str) -> list[np.ndarray]:
    """Each closed subpath of a drawn path as its points, ``(n, 2)`` (world units, as rounded by the page)."""
    number = r"(-?[\d.]+(?:e[+-]?\d+)?)"
    return [np.array([(float(x), float(y)) for x, y in re.findall(rf"[ML]{number} {number}", part)])
            for part in d.split("Z") if part.strip()]


def in_fill(page, selector: str, point) -> bool:
    """True if ``point`` (world units) is inside the drawn fill of the path ``selector`` (its fill rule obeyed)."""
    return page.eval_on_selector(selector, "(e, p) => e.isPointInFill(new DOMPoint(p[0], p[1]))", list(map(float, point)))


def test_the_hole_is_drawn_initial_and_deformed_as_the_bodys_inside(page):
    want = Deformer(read_case(HOLLOW)).deform().bodies[0]
    precision = 0.5 / page.evaluate("window.sdState.q") + 1e-9  # the page rounds to 1/q world units
    for kind, contour, holes in (("deformed", want.contour, want.holes),
                                 ("initial", want.initial_contour, want.initial_holes)):
        selector = f"{BODY} .body-{kind}"
        drawn = subpaths(page.get_attribute(selector, "d"))
        assert len(drawn) == 1 + len(holes) == 2  # the contour, then its one hole
        np.testing.assert_allclose(drawn[0], contour, rtol=0, atol=precision)
        for got, hole in zip(drawn[1:], holes):
            np.testing.assert_allclose(got, hole, rtol=0, atol=precision)
        assert page.eval_on_selector(selector, "e => getComputedStyle(e).fillRule") == "evenodd"
        hole = holes[0]
        centre, low = hole.mean(axis=0), hole[np.argmin(hole[:, 1])]
        assert not in_fill(page, selector, centre)  # the hole is not the body's: left unfilled
        assert in_fill(page, selector, low + (low - centre) * 0.25)  # the wall below it is
    # the readout's area is the library's, net of the hole
    assert float(shown(page)["areaFinal"]) == want.area_final


def boxes(page, selector: str) -> list[dict]:
    """The screen boxes of the elements ``selector``: ``{x, y, width, height}`` (CSS pixels)."""
    return page.eval_on_selector_all(selector, "es => es.map((e) => { const b = e.getBoundingClientRect(); "
                                               "return {x: b.x, y: b.y, width: b.width, height: b.height}; })")


def overlap(a: dict, b: dict) -> bool:
    return (a["x"] < b["x"] + b["width"] and b["x"] < a["x"] + a["width"]
            and a["y"] < b["y"] + b["height"] and b["y"] < a["y"] + a["height"])


def test_the_y_axis_label_never_covers_a_tick_label(page):
    """As opened, and with the view panned down one pixel at a time over a whole tick step: no overlap."""
    page.evaluate("document.fonts.ready")
    step = page.evaluate("window.sdState.view.s") * float(page.eval_on_selector(
        "#axes", "g => { const t = [...g.querySelectorAll('.tick-y')].map((e) => Number(e.textContent)); "
                 "return Math.abs(t[1] - t[0]); }"))
    ty0 = page.evaluate("window.sdState.view.ty")
    for shift in range(0, int(step) + 2):
        page.evaluate("t => { window.sdState.view.ty = t; window.dispatchEvent(new Event('resize')); }", ty0 + shift)
        (label,) = boxes(page, "#axis-y-label")
        ticks = boxes(page, "#axes .tick-y")
        assert ticks and label["width"] > 0
        assert not any(overlap(label, t) for t in ticks), (shift, label, ticks)
        assert label["y"] >= page.locator("#view").bounding_box()["y"]  # on the drawing, not above it


def test_the_assembly_hint_is_for_several_bodies_only(page):
    assert page.locator("#assembly-hint").is_hidden()  # one body: no body list to pick from
