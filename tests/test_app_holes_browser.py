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
