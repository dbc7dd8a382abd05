"""An engineer's view of the page (Playwright, Chromium): the case drawn before any answer, axes, scale bar,
pointer read-out, thickness probe, colour maps, warnings, the model's figures, the report figure, drawing options.

Skips like tests/test_app_browser.py without Chromium or Playwright.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from test_app_browser import browser, page, server, shown, wait_for  # noqa: F401 - the shared fixtures

import sectiondeform as sd
from sectiondeform.app import engine
from sectiondeform.field_plot import field_values

from conftest import SEAL

SETTLED = "d.final === '1' && d.pending === d.seq"
READOUTS = ["#r-initial", "#r-target", "#r-final", "#r-error", "#r-jacobian", "#r-compute", "#r-roundtrip", "#r-state"]


def view(page) -> dict:  # noqa: F811 - a page, not the fixture
    return page.evaluate("() => ({...sdState.view})")


def to_screen(page, p) -> tuple[float, float]:  # noqa: F811 - a page, not the fixture
    """A world point's position in the page (CSS pixels), from the page's own view transform."""
    v, box = view(page), page.locator("#view").bounding_box()
    return box["x"] + v["s"] * p[0] + v["tx"], box["y"] - v["s"] * p[1] + v["ty"]


def test_the_case_is_drawn_from_its_own_curves_before_the_first_answer(browser, server):  # noqa: F811
    context = browser.new_context(viewport={"width": 1200, "height": 700})
    page = context.new_page()  # noqa: F811
    held, relay = [], {"hold": True}

    def route(ws):
        relay["page"] = ws
        ws.connect_to_server().on_message(lambda m: held.append(m) if relay["hold"] else ws.send(m))

    page.route_web_socket(re.compile(r".*/ws$"), route)
    try:
        page.goto(server)
        page.wait_for_function("document.getElementById('r-initial').textContent.endsWith('mm²')")
        area = engine.outline(sd.case_to_dict(sd.load_case(sd.example_case_path())))[0]["area"]
        initial, target = (page.text_content(r) for r in ("#r-initial", "#r-target"))
        assert initial.endswith(" mm²") and float(initial.split()[0]) == pytest.approx(area, rel=5e-6)  # 6 digits
        assert float(target.split()[0]) == pytest.approx(0.8 * area, rel=5e-6)
        assert all(page.text_content(r) not in ("", "—") for r in READOUTS)
        assert shown(page).get("seq") is None                   # no answer drawn yet
        assert page.locator("#bodies path.body-initial").get_attribute("d").count("L") > 100
        # the handles sit on the case's own points, not in the top-left corner
        target = page.evaluate("() => Geo.points(sdState.case.target)")
        for i, p in enumerate(target):
            box = page.locator(f'circle[data-curve=target][data-index="{i}"]').bounding_box()
            x, y = to_screen(page, p)
            assert abs(box["x"] + box["width"] / 2 - x) < 1 and abs(box["y"] + box["height"] / 2 - y) < 1
            assert x > 100 and y > 100
        relay["hold"] = False                                    # the answers let through
        while held:
            relay["page"].send(held.pop(0))
        page.wait_for_selector("#view[data-final='1']")
        assert page.locator("#bodies path").count() == 0          # the outline gives way to the answer
    finally:
        context.close()


def test_axes_scale_bar_and_pointer_read_out(page):  # noqa: F811
    assert page.text_content("#axis-x-label") == "x (mm)" and page.text_content("#axis-y-label") == "y (mm)"
    ticks = [float(t) for t in page.locator("#axes text.tick-x").all_text_contents()]
    steps = set(np.round(np.diff(ticks), 9))
    assert len(ticks) >= 3 and len(steps) == 1                   # evenly spaced, a round step
    bar = page.eval_on_selector("#scale", "e => ({...e.dataset})")
    s = view(page)["s"]
    assert float(bar["pixels"]) == pytest.approx(float(bar["length"]) * s, rel=1e-12)
    assert 40 <= float(bar["pixels"]) <= 250
    assert page.text_content("#scale-label") == f"{float(bar['length']):g} mm"
    box, v = page.locator("#view").bounding_box(), view(page)
    page.mouse.move(box["x"] + 300, box["y"] + 200)
    x, y = (float(t) for t in page.text_content("#r-pointer").removesuffix(" mm").split(","))
    assert x == pytest.approx((300 - v["tx"]) / v["s"], abs=0.5 / v["s"])
    assert y == pytest.approx((v["ty"] - 200) / v["s"], abs=0.5 / v["s"])


def distance_to_polyline(p, line) -> float:
    a, b = line[:-1], line[1:]
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.einsum("ij,ij->i", ab, ab), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * ab - p).T)))


def test_the_thickness_probe(page):  # noqa: F811
    page.click("#probe")
    box = page.locator("#view").bounding_box()
    lower = np.array(page.evaluate("() => sdState.result.lower"))
    top = lower[len(lower) // 2] + [0.0, 20.0]                  # 20 mm above the middle of the lower curve
    x, y = to_screen(page, top)
    page.mouse.click(x, y)
    probe = np.array(page.evaluate("() => sdState.probe"))
    marks = page.eval_on_selector("#probe-marks", "e => ({...e.dataset})")
    assert float(marks["lowerDistance"]) == pytest.approx(distance_to_polyline(probe[0], lower), rel=1e-12)
    assert float(marks["lowerDistance"]) == pytest.approx(20.0, abs=1.0 / view(page)["s"])
    assert "to the deformed lower curve" in page.text_content("#r-probe")
    page.mouse.click(box["x"] + 200, box["y"] + 150)
    probe = np.array(page.evaluate("() => sdState.probe"))
    marks = page.eval_on_selector("#probe-marks", "e => ({...e.dataset})")
    assert float(marks["distance"]) == pytest.approx(float(np.hypot(*(probe[1] - probe[0]))), rel=1e-12)
    assert "|AB| =" in page.text_content("#r-probe")
    assert shown(page)["seq"] == shown(page)["pending"]         # probing sent nothing


def test_colour_maps_on_the_final_mesh(page):  # noqa: F811
    stress = page.locator("#field option[data-stress]")
    assert all(stress.nth(i).is_disabled() for i in range(stress.count()))  # the paper model has no stresses
    page.select_option("#field", "J")
    page.wait_for_selector("#field-overlay[data-field=J]")
    overlay = page.eval_on_selector("#field-overlay", "e => ({...e.dataset, fills: [...e.children].map((c) => c.getAttribute('fill'))})")
    assert int(overlay["cells"]) == len(page.evaluate("() => sdState.result.mesh_final.cells"))
    assert len(set(overlay["fills"])) >= 3
    assert "geometric" in page.text_content("#colourbar-label")
    page.select_option("#model", "hyperelastic")
    page.wait_for_function("document.getElementById('view').dataset.model === 'hyperelastic'")
    page.select_option("#field", "von_mises_stress")
    page.wait_for_selector("#field-overlay[data-field=von_mises_stress]")
    case = page.evaluate("() => sdState.case")
    problem = engine.with_model(sd.case_from_dict(case), "hyperelastic")
    _, (values,) = field_values(sd.Deformer(problem, model="hyperelastic").deform(), "von_mises_stress")
    overlay = page.eval_on_selector("#field-overlay", "e => ({...e.dataset})")
    # the page's solve starts from its last one: the same solution to the Newton tolerance, not bit for bit
    assert float(overlay["min"]) == pytest.approx(values.min(), rel=1e-5)
    assert float(overlay["max"]) == pytest.approx(values.max(), rel=1e-5)
    assert "shear modulus" in page.text_content("#colourbar-label")


def test_warnings_in_their_colour_and_gone_with_the_model(page):  # noqa: F811
    seq = shown(page)["seq"]
    page.locator("#ratio-value").fill("0.7")                   # the paper model warns: heights change by 18 %
    page.locator("#ratio-value").press("Enter")
    wait_for(page, f"d.seq > {seq} && {SETTLED}")
    warnings = page.locator("#warnings")
    assert warnings.is_visible() and "heights change" in warnings.inner_text()
    assert warnings.evaluate("e => getComputedStyle(e).color") == "rgb(122, 74, 0)"   # amber, not the green of info
    assert "heights change" not in page.text_content("#message")
    page.select_option("#model", "hyperelastic")
    assert not warnings.is_visible()                            # at once: they were the paper model's
    wait_for(page, f"d.model === 'hyperelastic' && {SETTLED}")
    assert not warnings.is_visible()


def test_the_model_figures_are_a_table_with_whole_numbers(page):  # noqa: F811
    page.select_option("#model", "hyperelastic")
    wait_for(page, f"d.model === 'hyperelastic' && {SETTLED}")
    rows = {r.get_attribute("data-key"): r.locator("td").all_text_contents() for r in page.locator("#info-rows tr").all()}
    assert rows["newton_full"][0] == "newton full" and re.fullmatch(r"\d+", rows["newton_full"][1])
    assert rows["warm_start"][1] in ("yes", "no")
    assert not any(cells[1].endswith(".0000") for cells in rows.values())
    assert float(rows["out_of_plane_stretch"][1]) == pytest.approx(1.25, rel=1e-3)


def test_the_report_figure_is_the_librarys(page, tmp_path):  # noqa: F811
    from PIL import Image

    with page.expect_download() as info:
        page.click("[data-save='figure.png']")
    path = tmp_path / "figure.png"
    info.value.save_as(path)
    assert info.value.suggested_filename.endswith("figure.png")
    image = Image.open(path)
    assert image.size == (1430, 1040)                            # the library's 11 x 8 in figure at 130 dpi


def test_a_real_scan_opens_with_the_drawing_options(page):  # noqa: F811
    page.click("#drawing-options summary")
    for field, value in {"#o-bbox": "-21,-1,-12,10", "#o-snap": "0.05", "#o-close-gap": "2.5",
                         "#o-split-a": "-19.6,0", "#o-split-b": "-18.4,0", "#o-simplify": "0.01",
                         "#o-target-arc": "0.05", "#o-area-ratio": "0.8"}.items():
        page.fill(field, value)
    seq = shown(page)["seq"]
    page.evaluate("""() => { window.shownMessages = [];  // every message the page shows, however briefly
        new MutationObserver(() => window.shownMessages.push(document.getElementById('message').textContent))
            .observe(document.getElementById('message'), {childList: true, characterData: true, subtree: true}); }""")
    page.set_input_files("#file", str(SEAL))
    # Bent onto its fitted arc the seal's layers change aspect 190-fold: the paper model (the file's) refuses
    # naming the hyperelastic model (test_drawing_options), and the engineer switches to it.
    wait_for(page, f"d.refusedSeq > {seq}")
    assert "hyperelastic" in page.text_content("#message")
    page.select_option("#model", "hyperelastic")
    d = wait_for(page, f"d.seq > {seq} && d.model === 'hyperelastic' && {SETTLED}")
    assert page.locator("#case-name").inner_text() == SEAL.stem
    assert float(d["areaInitial"]) == pytest.approx(27.6, abs=0.1)
    assert float(d["areaTarget"]) == pytest.approx(0.8 * float(d["areaInitial"]), rel=1e-12)
    assert any("closed a gap" in m for m in page.evaluate("() => window.shownMessages"))  # the reader's report on opening
    page.fill("#o-bbox", "1,0,0,1")                             # a wrong option: the library's one line
    page.once("dialog", lambda dialog: dialog.accept())          # the model chosen is an edit the new file replaces
    page.set_input_files("#file", str(SEAL))
    page.wait_for_selector("#message[data-kind=error]")
    assert re.search(r"bbox: expected xmin, ymin, xmax, ymax", page.text_content("#message"))
