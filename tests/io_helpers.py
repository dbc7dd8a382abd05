"""Shared helpers of the CAD input/output tests: the cases kept in tests/data."""

from __future__ import annotations

import numpy as np

from conftest import CASES_DIR, SEAL, data_case_path

__all__ = ["CASES_DIR", "FRACTIONS", "SEAL", "same_curve", "shared_case"]
FRACTIONS = np.linspace(0.0, 1.0, 201)


def shared_case(name: str):
    """A case from ``tests/data/cases``, parsed; raises if the file is absent."""
    from sectiondeform.io.case import load_case

    return load_case(data_case_path(name))


def same_curve(a, b, tol=1e-9) -> float:
    """Largest distance between two curves at equal arc-length fractions."""
    return float(np.abs(a.at_fractions(FRACTIONS) - b.at_fractions(FRACTIONS)).max())
