"""Every entry point over every kind of problem and both models: one pipeline, written once.

The kinds: a ``section-case/1`` case (the paper's one body), a one-body
``section-case/2`` case, several bonded bodies, and bodies of revolution.
Each test asserts properties computed here, independently of the code under
test: the laws (shoelace areas, Pappus volumes), bonded interfaces (every
resting lower node on its foundation's deformed contour), round trips,
identity and rigid motion.
"""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd
from sectiondeform.cli import main
from sectiondeform.io.case import case_from_dict, case_to_dict, load_case
from sectiondeform.laws import AreaRatio, VolumeRatio

from conftest import chord_offset

DATA = Path(__file__).parent / "data" / "cases"
KINDS = {
    "v1": DATA / "paper-example.json",
    "one-body-v2": DATA / "v2" / "cover-alone-on-arc.json",
    "several-bodies": DATA / "v2" / "two-layer-strip.json",
    "revolution": DATA / "v2" / "tread-on-drum.json",
}
MODELS = ("paper", "hyperelastic")
MATRIX = [(k, m) for k in KINDS for m in MODELS]
IDS = [f"{k}-{m}" for k, m in MATRIX]


def shoelace(points: np.ndarray) -> float:
    x, y = points[:, 0] - points[0, 0], points[:, 1] - points[0, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)))


def pappus_volume(points: np.ndarray, axis) -> float:
    """2 pi |A| r_c of a closed polygon about the line through two points (independent of sectiondeform.pappus)."""
    p0, p1 = (np.asarray(p, dtype=float) for p in axis)
    u = (p1 - p0) / np.hypot(*(p1 - p0))
    rel = points - p0
    r = rel[:, 0] * u[1] - rel[:, 1] * u[0]  # signed distance to the axis
    s = rel @ u
    c = s * np.roll(r, -1) - np.roll(s, -1) * r
    first = (c * (r + np.roll(r, -1))).sum() / 6.0  # first moment of area about the axis
    return 2.0 * math.pi * abs(first)


def check_laws_and_bonds(problem: sd.Problem, result: sd.Result, laws=None) -> None:
    laws = laws or [b.law for b in problem.bodies]
    assert [b.name for b in result.bodies] == [b.name for b in problem.bodies]
    for body, law in zip(result.bodies, laws):
        ring = np.concatenate((body.lower, body.contour[len(body.lower):]))
        # The laws hold against the given curves' exact area (volume), reported as the initial one; the
        # initial polygon's chords miss at most 2e-5 of it (the section's bound, INITIAL_AREA_TOLERANCE).
        if law.measure == "area":
            assert shoelace(body.contour) == pytest.approx(law.ratio * body.area_initial, rel=2e-9)
            assert body.area_initial == pytest.approx(shoelace(body.initial_contour), rel=2e-5)
            assert body.area_final == pytest.approx(shoelace(ring), rel=1e-9)
        else:
            axis = problem.revolution.axis
            assert pappus_volume(body.contour, axis) == pytest.approx(law.ratio * body.volume_initial, rel=1e-8)
            assert body.volume_initial == pytest.approx(pappus_volume(body.initial_contour, axis), rel=2e-5)
    size = problem.size
    for b, body in enumerate(result.bodies):
        for f in problem.layout.foundations[b]:
            under = result.bodies[f].contour
            d = np.hypot(*(body.lower[:, None, :] - under[None, :, :]).transpose(2, 0, 1)).min(axis=1)
            on_support = problem.layout.on_support[b]
            if not on_support:
                assert d.max() <= 1e-9 * size, f"{body.name} comes off {result.bodies[f].name}"


def case_json(kind: str) -> dict:
    return json.loads(KINDS[kind].read_text())


@pytest.fixture(scope="module")
def deformers():
    cache = {}

    def get(kind, model):
        if (kind, model) not in cache:
            cache[kind, model] = sd.Deformer(load_case(KINDS[kind]), model=model)
        return cache[kind, model]

    return get


@pytest.mark.parametrize("kind", list(KINDS))
def test_load_case_reads_every_kind_as_a_problem_and_writes_it_back_in_its_dialect(kind):
    problem = load_case(KINDS[kind])
    assert isinstance(problem, sd.Problem)
    data = case_to_dict(problem)
    assert data["format"] == case_json(kind)["format"]
    assert case_from_dict(json.loads(json.dumps(data))) == problem


@pytest.mark.parametrize(("kind", "model"), MATRIX, ids=IDS)
def test_deform_meets_every_law_and_keeps_every_bond(kind, model, deformers):
    problem = load_case(KINDS[kind])
    result = sd.deform(problem, model)
    check_laws_and_bonds(problem, result)
    out = result.to_json(meshes=False)
    assert out["format"] == ("section-result/1" if problem.dialect == "section-case/1" else "section-result/2")
    if len(problem.bodies) == 1:
        assert result.area_final == result.bodies[0].area_final
    else:
        with pytest.raises(sd.CaseError, match=r"bodies\[i\]"):
            _ = result.contour


@pytest.mark.parametrize(("kind", "model"), MATRIX, ids=IDS)
def test_deformer_drag_path_preview_and_warm_start_meet_the_laws(kind, model, deformers):
    deformer = deformers(kind, model)
    problem = deformer.problem
    full = deformer.deform()
    nodes = deformer.target_nodes()
    fast = deformer.deform(target_nodes=nodes)
    check_laws_and_bonds(problem, fast)
    if model == "paper":  # the same nodes give the same placement, bit for bit
        for a, b in zip(full.bodies, fast.bodies):
            assert np.array_equal(a.upper, b.upper)
    moved = nodes + np.array([0.0, 0.01 * problem.size])
    preview = deformer.preview(target_nodes=moved, start=full)
    check_laws_and_bonds(problem, preview)
    again = deformer.deform(target_nodes=moved, start=full)
    cold = deformer.deform(target_nodes=moved)
    for a, b in zip(again.bodies, cold.bodies):
        assert np.abs(a.upper - b.upper).max() <= 1e-6 * problem.size


@pytest.mark.parametrize(("kind", "model"), MATRIX, ids=IDS)
def test_identity_and_rigid_motion_are_exact(kind, model, deformers):
    deformer = deformers(kind, model)
    problem = deformer.problem
    unit = [VolumeRatio(1.0) if b.law.measure == "volume" else AreaRatio(1.0) for b in problem.bodies]
    same = deformer.deform(problem.support, law=unit if len(unit) > 1 else unit[0])
    offset = chord_offset(same) + 1e-9 * problem.size  # the law holds against the exact area: the chords' offset
    for body in same.bodies:
        assert np.abs(body.upper - body.initial_upper).max() <= offset
    if problem.revolution is not None:  # a rigid motion along the axis keeps every volume
        p0, p1 = (np.asarray(p, float) for p in problem.revolution.axis)
        q, t = np.eye(2), 0.3 * problem.size * (p1 - p0) / np.hypot(*(p1 - p0))
    else:
        a = 0.4
        q, t = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]), np.array([12.0, -7.0])
    target = problem.support.transformed(q, t)
    moved = deformer.deform(target, law=unit if len(unit) > 1 else unit[0])
    for body, still in zip(moved.bodies, same.bodies):  # the identity, moved rigidly
        assert np.abs(body.upper - (still.upper @ q.T + t)).max() <= 1e-8 * problem.size


@pytest.mark.parametrize(("kind", "model"), MATRIX, ids=IDS)
def test_deform_command_writes_the_result_its_figure_and_fields(kind, model, tmp_path):
    out, fig = tmp_path / "r.json", tmp_path / "r.png"
    assert main(["deform", str(KINDS[kind]), "-o", str(out), "--model", model, "--plot", str(fig), "--fields"]) == 0
    data = json.loads(out.read_text())
    problem = load_case(KINDS[kind])
    bodies = [data] if data["format"] == "section-result/1" else data["bodies"]
    assert len(bodies) == len(problem.bodies)
    for body in bodies:
        assert body["area"]["final"] == pytest.approx(shoelace(np.array(body["contour"])), rel=1e-9)
        fields = body["fields"]
        j = fields["J"] if model == "hyperelastic" else fields["geometric_J"]  # det F per element, > 0: no element turned over
        assert len(j) == len(body["meshes"]["final"]["cells"]) and min(j) > 0
    assert fig.stat().st_size > 10_000 and fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("kind", list(KINDS))
@pytest.mark.parametrize("ext", [".dxf", ".svg"])
def test_convert_round_trips_every_kind_through_drawings(kind, ext, tmp_path):
    drawing, back = tmp_path / f"case{ext}", tmp_path / "back.json"
    assert main(["convert", str(KINDS[kind]), str(drawing)]) == 0
    assert main(["convert", str(drawing), str(back)]) == 0
    a, b = load_case(KINDS[kind]), load_case(back)
    assert len(a.bodies) == len(b.bodies)
    assert (a.revolution is None) == (b.revolution is None)
    sa, sb = sd.Deformer(a).stack.sections, sd.Deformer(b).stack.sections
    for x, y in zip(sa, sb):
        assert y.area == pytest.approx(x.area, rel=1e-6)


@pytest.mark.parametrize("kind", list(KINDS))
def test_export_fe_writes_a_set_per_body_and_reals_calculix_reads_whole(kind, tmp_path):
    deck = tmp_path / "deck.inp"
    assert main(["export-fe", str(KINDS[kind]), "-o", str(deck), "--mesh-size", "4"]) == 0
    text = deck.read_text()
    problem = load_case(KINDS[kind])
    names = [b.name for b in problem.bodies] if problem.dialect == "section-case/2" else ["BODY"]
    for name in names:
        assert f"ELSET={name}".upper() in text.upper().replace(" ", "")
    lines = text.splitlines()
    for previous, line in zip(["", *lines], lines):
        if line and not line.startswith(("*", "**")) and previous.upper() != "*HEADING":  # the title is free text
            assert all(len(tok.strip()) <= 20 for tok in line.split(","))


@pytest.mark.parametrize("kind", list(KINDS))
def test_sweep_rows_are_deform_runs_for_every_kind(kind, tmp_path):
    pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    shutil.copy(KINDS[kind], tmp_path / "case.json")
    study = {"format": "section-study/1", "name": "m", "cases": [{"case": "case.json", "vary": {"stretch": [0.98, 1.0]}}]}
    (tmp_path / "study.json").write_text(json.dumps(study))
    assert main(["sweep", str(tmp_path / "study.json"), "-o", str(tmp_path / "out"), "--workers", "0", "--quiet"]) == 0
    rows = pq.read_table(tmp_path / "out" / "rows.parquet").to_pylist()
    assert len(rows) == 2 and all(r["ok"] for r in rows), [r["error"] for r in rows]  # the table's column is "ok"


@pytest.mark.parametrize(("kind", "model"), MATRIX, ids=IDS)
def test_the_page_opens_drags_and_saves_every_kind(kind, model, tmp_path):
    from sectiondeform.app import engine
    from sectiondeform.io import write_case, write_result

    cache = engine.DeformerCache()
    data = case_json(kind)
    ratio = data.get("law", {}).get("area_ratio", 1.0)
    drag = engine.answer(cache, data, model, ratio, final=False)
    done = engine.answer(cache, data, model, ratio, final=True)
    assert drag and done
    problem = engine.case_from_json(data)
    write_case(tmp_path / "saved.json", problem)
    assert load_case(tmp_path / "saved.json") == problem
    result = engine.full_result(data, model)
    for ext in (".json", ".dxf", ".svg", ".vtu"):
        write_result(tmp_path / f"result{ext}", result)
        assert (tmp_path / f"result{ext}").stat().st_size > 0
    check_laws_and_bonds(problem, result)


@pytest.mark.parametrize(("kind", "model"), [("v1", "hyperelastic"), ("several-bodies", "paper"), ("revolution", "hyperelastic")],
                         ids=["v1", "several", "revolution"])
def test_validate_measures_every_body_against_the_reference(kind, model, tmp_path):
    pytest.importorskip("skfem")
    pytest.importorskip("triangle")
    report = tmp_path / "v.json"
    assert main(["validate", str(KINDS[kind]), "--model", model, "--mesh-size", "3", "-o", str(report), "-q"]) == 0
    data = json.loads(report.read_text())
    rows = data["bodies"] if "bodies" in data else [data]
    assert len(rows) == len(load_case(KINDS[kind]).bodies)


# Several bodies and bodies of revolution through CalculiX: tests/test_fe_calculix_assembly.py (coarse decks of a
# two-layer strip and a small axisymmetric tube; the shared assemblies at solve-fe's default mesh take CalculiX minutes).
@pytest.mark.parametrize("kind", ["v1"])
def test_solve_fe_reads_calculix_back_into_a_result_of_every_body(kind, tmp_path, ccx):
    out = tmp_path / "fe.json"
    assert main(["solve-fe", str(KINDS[kind]), "-o", str(out), "-q"]) == 0
    data = json.loads(out.read_text())
    bodies = [data] if data["format"] == "section-result/1" else data["bodies"]
    assert len(bodies) == len(load_case(KINDS[kind]).bodies)
    for body in bodies:
        assert np.isfinite(np.array(body["contour"])).all()
