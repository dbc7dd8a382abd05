"""Shared fixtures: the cases kept in ``tests/data``, small hand-made cases.

The tests read their files only from ``tests/data`` (copies of the project's
shared cases and of one real scan), so that a clone of the repository alone
runs them; a missing fixture is an error, never a skip.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

import sectiondeform as sd

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
CASES_DIR = DATA / "cases"
SHARED_CASES = sorted(CASES_DIR.glob("*.json"))
SEAL = DATA / "real" / "vr6000_seal_scan.dxf"
if len(SHARED_CASES) < 3 or not SEAL.is_file():  # a missing fixture fails the run, it is not skipped
    raise FileNotFoundError(f"test fixtures missing in {DATA}: expected the case files and {SEAL.name}")


def load_benchmark(name: str):
    """The script ``benchmarks/<name>.py`` as a module (the benchmarks are scripts, not part of the package)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(f"bench_{name}", ROOT / "benchmarks" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def data_case_path(name: str) -> Path:
    """The path of a case kept in ``tests/data/cases``; raises if it is absent."""
    path = CASES_DIR / f"{name}.json"
    if not path.is_file():
        raise FileNotFoundError(f"test fixture {path} is missing")
    return path


def shared_case_ids():
    """Test ids: the case names."""
    return [p.stem for p in SHARED_CASES]


@pytest.fixture(params=SHARED_CASES, ids=shared_case_ids())
def shared_case(request):
    """Each case of ``tests/data/cases``, parsed."""
    return sd.load_case(request.param)


class Outcomes:
    """Counts of a property test's outcomes, so that a test cannot pass by refusing every example.

    Inside the ``@given`` body call :meth:`checked` when the property was
    checked, or :meth:`refused` (which also records a ``hypothesis.event``)
    when the example was refused; after the run, :meth:`assert_mostly_checked`.
    """

    def __init__(self):
        self.counts = {"checked": 0, "refused": 0}

    def checked(self):
        """Record one example whose property was asserted."""
        self.counts["checked"] += 1

    def refused(self, why: str):
        """Record one refused example (shown in hypothesis' statistics)."""
        from hypothesis import event

        event(f"refused: {why}")
        self.counts["refused"] += 1

    def assert_mostly_checked(self, at_least: int, max_refused_fraction: float):
        """At least ``at_least`` examples checked, refusals at most ``max_refused_fraction`` of all."""
        total = sum(self.counts.values())
        assert self.counts["checked"] >= at_least, self.counts
        assert self.counts["refused"] <= max_refused_fraction * total, self.counts


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


def chord_offset(result) -> float:
    """How far a ratio-1 identity may move the upper points of a curved section, units.

    The law holds against the exact area of the given curves, the contour
    is a polygon: on the identity the upper points move out by the area
    the polygon's chords miss, spread along the upper polyline (computed
    here from the result's own initial polygon, independently of the code).
    """
    out = 0.0
    for body in result.bodies:
        ring = body.initial_contour
        x, y = ring[:, 0] - ring[0, 0], ring[:, 1] - ring[0, 1]
        cross = x * np.roll(y, -1) - np.roll(x, -1) * y
        polygon = 0.5 * abs(float(cross.sum()))
        upper = np.hypot(*np.diff(body.initial_upper, axis=0).T).sum()
        if body.area_target is None and body.volume_initial is not None and result.axis is not None:
            # A volume law: the volume the chords miss, over the area an upper offset sweeps about the axis
            # (2 pi r per unit area, r the upper points' least distance to the axis).
            p0, p1 = (np.asarray(p, dtype=float) for p in result.axis)
            u = (p1 - p0) / np.hypot(*(p1 - p0))
            r = (ring - p0) @ np.array([u[1], -u[0]])
            moment = abs(float((cross * (r + np.roll(r, -1))).sum()) / 6.0)  # first moment about the axis
            upper_r = np.abs((body.initial_upper - p0) @ np.array([u[1], -u[0]])).min()
            polygon_volume = 2.0 * np.pi * moment
            out = max(out, 3.0 * abs(body.volume_initial - polygon_volume) / (2.0 * np.pi * upper_r * upper))
            continue
        exact = body.area_target if body.area_target is not None else polygon
        out = max(out, 3.0 * abs(exact - polygon) / upper)
    return out


@pytest.fixture(scope="session")
def ccx():
    """CalculiX's ``ccx`` (``SECTIONDEFORM_CCX`` or on the PATH): a skip with the reason on a developer's machine
    without it, a failure when ``SECTIONDEFORM_REQUIRE_CCX=1`` (CI).
    """
    exe = os.environ.get("SECTIONDEFORM_CCX") or shutil.which("ccx")
    if exe is None or shutil.which(exe) is None:
        if os.environ.get("SECTIONDEFORM_REQUIRE_CCX") == "1":
            pytest.fail("SECTIONDEFORM_REQUIRE_CCX=1 but CalculiX's ccx is not installed (apt-get install calculix-ccx)")
        pytest.skip("CalculiX's ccx is not installed (apt-get install calculix-ccx)")
    return exe


def one_body_mesh(ring, fixed, h: float):
    """The hyperelastic model's P2 mesh of one body (``union_mesh`` of one contour): ``ring`` ``(k, 2)``, the
    contour indices ``fixed`` that must be nodes, element size ``h``.
    """
    from sectiondeform.fem.union_mesh import union_mesh

    ring = np.asarray(ring, dtype=np.float64)
    size = float(np.ptp(ring, axis=0).max())
    return union_mesh([ring], [np.asarray(fixed, dtype=np.int64)], np.array([float(h)]), 1e-9 * size)
