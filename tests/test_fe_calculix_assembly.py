"""CalculiX runs of section-case/2 decks (need ccx: skipped without it, failing when SECTIONDEFORM_REQUIRE_CCX=1)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from sectiondeform.cli import main
from sectiondeform.external.calculix import run_ccx
from sectiondeform.external.deck import build_deck, deck_text
from sectiondeform.external.solve import solve_calculix
from sectiondeform.io.case import case_from_dict

sys.path.insert(0, str(Path(__file__).parent))
from test_fe_assembly_decks import small_strip  # noqa: E402

RI, RO, HEIGHT, RI_FINAL = 20.0, 22.0, 20.0, 22.0


def ring_case() -> dict:
    """A tube r in [20, 22], z in [0, 20] about the y axis, its inner face pushed out to r = 22."""
    return {"format": "section-case/2", "name": "ring", "units": "mm",
            "support": {"polyline": [[RI, 0.0], [RI, HEIGHT]]},
            "target": {"polyline": [[RI_FINAL, 0.0], [RI_FINAL, HEIGHT]]},
            "revolution": {"axis": [[0.0, 0.0], [0.0, 1.0]]},
            "bodies": [{"name": "ring", "lower": {"polyline": [[RI, 0.0], [RI, HEIGHT]]},
                        "upper": {"polyline": [[RI, HEIGHT], [RO, HEIGHT], [RO, 0.0], [RI, 0.0]]},
                        "law": {"volume_ratio": 1.0}}]}


def test_axisymmetric_ring_keeps_area_times_radius(ccx):
    result = solve_calculix(case_from_dict(ring_case()), mesh_size=1.0)
    body = result.bodies[0]
    # Incompressible: the volume 2 pi * area * centroid radius is kept (to kappa = 1000 mu).
    assert body.volume_initial == pytest.approx(2 * np.pi * 40.0 * 21.0, rel=1e-12)
    assert abs(body.volume_final / body.volume_initial - 1) < 1e-3
    # Each annular strip keeps area x radius: at mid-height, far from the free ends, the tube is in
    # axial plane strain and r^2 - R^2 is the same for every fibre, so the outer face goes to
    # sqrt(Ro^2 + ri^2 - Ri^2).
    p0, p1 = body.initial_mesh.points, body.final_mesh.points
    mid = np.flatnonzero((np.abs(p0[:, 0] - RO) < 1e-9) & (np.abs(p0[:, 1] - HEIGHT / 2) < 2.0))
    expected = np.sqrt(RO ** 2 + RI_FINAL ** 2 - RI ** 2)
    assert len(mid) >= 3
    assert np.abs(p1[mid, 0] - expected).max() < 0.01 * (RO - RI)
    # Area of the section: area0 * (centroid radius before / after).
    centroid = 0.5 * (RI_FINAL + expected)
    assert body.area_final == pytest.approx(40.0 * 21.0 / centroid, rel=2e-3)
    out = body.to_json(meshes=False)
    assert set(out["volume"]) == {"initial", "target", "final", "relative_error"} and "target" not in out["area"]


def test_two_bonded_bodies_come_back_as_a_section_result_2(ccx, tmp_path):
    path = tmp_path / "strip.json"
    path.write_text(json.dumps(small_strip()))
    out = tmp_path / "r.json"
    assert main(["solve-fe", str(path), "--mesh-size", "1", "-o", str(out), "-q"]) == 0
    data = json.loads(out.read_text())
    assert data["format"] == "section-result/2" and data["model"] == "calculix"
    backing, cover = data["bodies"]
    # The shared piece y = 4: the backing's upper points there and the cover's lower nodes are one curve.
    b_up = np.array(backing["upper"])
    c_low = np.array(cover["lower"])
    shared = b_up[1:-1][np.abs(np.array(small_strip()["bodies"][0]["upper"]["polyline"])[1:-1, 1] - 4.0) < 1e-9]
    assert np.allclose(shared[1:-1], c_low[np.argmin(np.linalg.norm(c_low[None] - shared[1:-1, None], axis=2), axis=1)],
                       atol=1e-9)
    # The support went onto the target: the backing's lower nodes lie on the arc.
    low = np.array(backing["lower"])
    assert np.abs(np.hypot(low[:, 0] - 10.0, low[:, 1] + 39.0) - 40.0).max() < 1e-3
    # Plane strain, nearly incompressible: each body keeps its area (its law's ratio is not expressed).
    for body in (backing, cover):
        assert abs(body["area"]["final"] / body["area"]["initial"] - 1) < 2e-3
    assert len(data["warnings"]) == 2


def test_ccx_reads_the_nodes_and_the_support_motion_as_the_deck_means_them(ccx):
    # CalculiX reads only the first 20 characters of a real; this deck has a coordinate that took 21 when
    # written with 15 digits (-1.8e-15, read as -0.18). Its .frd gives back the nodes as read, and the
    # support's displacements, which *BOUNDARY prescribes exactly.
    deck = build_deck(case_from_dict(small_strip()), mesh_size=1.0)
    results, _ = run_ccx(deck_text(deck), job="numbers")
    assert results.nodes.tolist() == list(range(1, len(deck.mesh.points) + 1))
    assert np.abs(results.coordinates[:, :2] - deck.placed_points).max() < 1e-4  # .frd: 6 digits
    _, ids, disp = results.last("DISP")
    u = np.zeros((len(deck.mesh.points), 2))
    u[ids - 1] = disp[:, :2]
    assert np.abs(u[deck.mesh.lower_nodes] - deck.support_displacement).max() < 1e-4


def test_a_ccx_run_that_does_not_finish_is_stopped(tmp_path, monkeypatch):
    import time

    from sectiondeform.external.calculix import SolverFailedError, run_ccx

    fake = tmp_path / "ccx"
    fake.write_text("#!/bin/sh\necho ' increment 1 attempt 1'\nexec sleep 30\n")
    fake.chmod(0o755)
    monkeypatch.setenv("SECTIONDEFORM_CCX", str(fake))
    t0 = time.perf_counter()
    with pytest.raises(SolverFailedError, match="did not finish in 1 s"):
        run_ccx("*HEADING\n", timeout=1.0)
    assert time.perf_counter() - t0 < 20


def test_solve_fe_refuses_a_timeout_not_above_zero(tmp_path, capsys):
    path = tmp_path / "ring.json"
    path.write_text(json.dumps(ring_case()))
    assert main(["solve-fe", str(path), "--timeout", "0", "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--timeout" in err[0]
