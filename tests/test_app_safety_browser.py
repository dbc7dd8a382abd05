"""The page in Chromium on a server that needs its token; failed saves are reported (Playwright).

Skips like tests/test_app_browser.py without Chromium or Playwright.
"""

from __future__ import annotations

import re

import pytest
from test_app_browser import browser, page, server  # noqa: F401 - the shared fixtures


def test_the_token_leaves_the_address_bar_and_a_reload_still_works(page, server):  # noqa: F811
    assert "token=" in server
    assert "token" not in page.url  # the cookie carries it now, the address bar does not
    page.reload()
    page.wait_for_selector("#view[data-final='1']")


def test_the_page_without_the_token_gets_nothing(browser, server):  # noqa: F811
    context = browser.new_context()
    try:
        r = context.new_page().goto(server.split("?")[0])
        assert r.status == 403 and "token" in r.text()
    finally:
        context.close()


def test_the_page_refuses_to_be_framed(page, server):  # noqa: F811
    r = page.request.get(server)
    assert r.headers["x-frame-options"] == "DENY" and "frame-ancestors 'none'" in r.headers["content-security-policy"]


@pytest.mark.parametrize("how", ["abort", "500"])
def test_a_failed_save_is_reported(page, how):  # noqa: F811
    """A save that fails (the server gone, or an answer that is no JSON) says so on the page."""
    def fail(route):
        if how == "abort":
            route.abort("connectionrefused")
        else:
            route.fulfill(status=500, body="Internal Server Error", content_type="text/plain")

    page.route("**/api/save/**", fail)
    page.click("[data-save='case.json']")
    page.wait_for_function("document.getElementById('message').dataset.kind === 'error'")
    text = page.text_content("#message")
    assert re.search(r"not saved: case\.json", text), text
    assert ("cannot be reached" in text) if how == "abort" else ("HTTP 500" in text), text
