"""Shared helpers of the CAD input/output tests: drawings built with ezdxf, the shared cases."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared"
SEAL = ROOT / "tests" / "data" / "vr6000_seal_scan.dxf"  # a copy of the shared scan, with its licence
FRACTIONS = np.linspace(0.0, 1.0, 201)


def shared_case(name: str):
    """A case from ../shared/cases, or skip."""
    from sectiondeform.case import load_case

    path = SHARED / "cases" / f"{name}.json"
    if not path.exists():
        pytest.skip(f"{path} is absent")
    return load_case(path)


def same_curve(a, b, tol=1e-9) -> float:
    """Largest distance between two curves at equal arc-length fractions."""
    return float(np.abs(a.at_fractions(FRACTIONS) - b.at_fractions(FRACTIONS)).max())
