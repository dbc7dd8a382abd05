"""The hyperelastic cost benchmark's pieces: the peer solves the model's own mesh, the growth table's figures.

No time limits: the benchmark reports figures, it does not assert them.
"""

import numpy as np
import pytest

from conftest import ROOT, load_benchmark

pytest.importorskip("skfem")

CASES = ROOT / "tests" / "data" / "cases"


@pytest.fixture(scope="module")
def cost():
    return load_benchmark("hyperelastic_cost")


@pytest.mark.parametrize("name", ["paper-example.json", "v2/two-layer-strip.json", "v2/sleeve-on-shaft.json"])
def test_the_peer_solves_the_models_own_triangles_with_as_many_unknowns_and_no_residual_at_rest(cost, name):
    import sectiondeform as sd
    from sectiondeform.deform import Deformer

    deformer = Deformer(sd.load_case(CASES / name), "hyperelastic")
    peer = cost._same_mesh_peer(deformer)
    prep = deformer.prepared
    assert peer.n_u == 2 * len(prep.mesh.nodes) and peer.n_p == prep.mesh.n_pressures
    assert len(peer.dirichlet) > 0
    # At rest both residuals vanish (no load, no stress), each to its own rounding.
    r = peer.residual(np.zeros(peer.n_u + peer.n_p), 1.0)
    assert np.abs(r).max() < 1e-9 * max(float(r.size), 1.0)
    cost._peer_iteration(peer)
    cost._our_iteration(deformer)


def test_the_growth_table_has_more_unknowns_on_finer_meshes_and_an_exponent(cost):
    rows = cost.bench_growth([CASES / "paper-example.json"], (2, 4), repeats=1)
    (row,) = rows
    (n2, u2, t2), (n4, u4, t4) = row["points"]
    assert (n2, n4) == (2, 4) and u4 > 2 * u2 and t2 > 0 and t4 > 0
    assert row["exponent"] == pytest.approx(np.log(t4 / t2) / np.log(u4 / u2))
    lines = cost.growth_markdown(rows)
    assert any("exponent" in line for line in lines)
