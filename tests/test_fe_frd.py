"""The .frd reader on real CalculiX output (tests/data/fe/square.frd, from ccx 2.20 on square.inp)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sectiondeform.external.frd import FrdError, read_frd

DATA = Path(__file__).parent / "data" / "fe"


def deck_nodes_and_boundary():
    nodes, bc, key = {}, {}, None
    for line in (DATA / "square.inp").read_text().splitlines():
        if line.startswith("*"):
            key = line.split(",")[0]
            continue
        v = [t.strip() for t in line.split(",")]
        if key == "*NODE":
            nodes[int(v[0])] = [float(v[1]), float(v[2])]
        elif key == "*BOUNDARY":
            bc.setdefault(int(v[0]), [0.0, 0.0])[int(v[1]) - 1] = float(v[3])
    return nodes, bc


def test_nodes_match_the_deck():
    frd = read_frd(DATA / "square.frd")
    nodes, _ = deck_nodes_and_boundary()
    assert sorted(frd.nodes.tolist()) == sorted(nodes)
    xy = np.array([nodes[k] for k in frd.nodes])
    assert np.allclose(frd.coordinates[:, :2], xy, atol=1e-4 * 10)  # E12.5: 5 significant digits
    assert np.all(frd.coordinates[:, 2] == 0.0)


def test_last_displacements_are_the_prescribed_ones_on_the_support():
    frd = read_frd(DATA / "square.frd")
    time, ids, u = frd.last("DISP")
    assert time == pytest.approx(1.0)
    assert u.shape == (len(ids), 3)
    _, bc = deck_nodes_and_boundary()
    by_id = dict(zip(ids.tolist(), u[:, :2]))
    for node, value in bc.items():
        assert np.allclose(by_id[node], value, atol=1e-5)


def test_missing_block_and_bad_file_are_one_line_errors(tmp_path):
    frd = read_frd(DATA / "square.frd")
    with pytest.raises(FrdError, match="no TEMP results"):
        frd.last("TEMP")
    bad = tmp_path / "bad.frd"
    bad.write_text("nothing here\n")
    with pytest.raises(FrdError, match="no node block"):
        read_frd(bad)
