"""Shared fixtures: the shared cases, small hand-made cases."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared"
SHARED_CASES = sorted((SHARED / "cases").glob("*.json"))


def shared_case_ids():
    return [p.stem for p in SHARED_CASES]


@pytest.fixture(params=SHARED_CASES, ids=shared_case_ids())
def shared_case(request):
    """Each case of the shared folder, parsed."""
    return sd.load_case(request.param)


def box_case(width=10.0, height=4.0, target=None, ratio=1.0, upper=None, **options):
    """A rectangle section on [0, width] x [0, height] as a case dict."""
    lower = [[0.0, 0.0], [width, 0.0]]
    upper = upper or [[width, 0.0], [width, height], [0.0, height], [0.0, 0.0]]
    d = {
        "format": "section-case/1",
        "name": "box",
        "lower": {"polyline": lower},
        "upper": {"polyline": upper},
        "target": target or {"polyline": lower},
        "law": {"area_ratio": ratio},
    }
    if options:
        d["options"] = options
    return d


def rigid(points, angle_deg, shift):
    """Rotate ``(N, 2)`` points by ``angle_deg`` about the origin, then shift."""
    a = np.radians(angle_deg)
    rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    return np.asarray(points, dtype=float) @ rot.T + np.asarray(shift, dtype=float)
