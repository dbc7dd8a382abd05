"""sectiondeform: real-time deformation of an elastomer cross-section under a mechanical law.

The paper's method (Trouvain et al., "Fast Deformation Method for a 2D
Shape"): a layered quad mesh grown from the section's lower curve, an empty
mesh of the same layers on the deformed lower curve sized by the law, and
the upper curve carried from one to the other at the same local coordinates.

>>> import sectiondeform as sd
>>> result = sd.deform(sd.load_case(sd.example_case_path()))
>>> round(result.area_initial), round(result.area_final, 1)
(4379, 3503.2)
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from .curves import Arc, BSpline, Chain, Curve, Polyline, curve_from_json
from .deform import Deformer, deform
from .errors import (
    CaseError,
    ConvergenceError,
    GeometryError,
    LawError,
    LocateError,
    MeshError,
    MissingExtraError,
    SectionDeformError,
)
from .io.case import case_from_dict, case_to_dict, load_case
from .laws import AreaRatio, Law, VolumeRatio
from .options import Options
from .problem import Body, Problem, Revolution
from .result import BodyResult, Result
from .section import Section, build_section

__version__ = "0.1.0"

__all__ = [
    "Arc", "AreaRatio", "BSpline", "Body", "BodyResult", "CaseError", "Chain", "ConvergenceError", "Curve",
    "Deformer", "GeometryError", "Law", "LawError", "LocateError", "MeshError", "MissingExtraError", "Options",
    "Polyline", "Problem", "Result", "Revolution", "Section", "SectionDeformError", "VolumeRatio", "build_section",
    "case_from_dict", "case_to_dict", "curve_from_json", "deform", "example_case_path", "load_case", "sweep",
]


def __getattr__(name):
    """``sd.sweep`` imported on first use, so importing sectiondeform does not import pyarrow."""
    if name == "sweep":
        from .studies import sweep

        return sweep
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def example_case_path() -> Path:
    """Path of the paper's example case shipped with the package."""
    return Path(str(resources.files(__package__) / "data" / "paper-example.json"))
