"""A ``section-case/2`` case read for the solver decks: bodies, their laws and rubbers, the axis.

The bodies, support, target and options are read and checked by the
project's own reader (:func:`~sectiondeform.assembly.assembly_from_dict`:
how the bodies rest on each other, bonded pieces, one-line errors). What a
deck needs beyond it is read here, as the case format defines it:

* ``revolution``: the axis (:func:`~sectiondeform.assembly.revolution_from_json`);
* each body's ``law``: ``{"area_ratio": r}``, or ``{"volume_ratio": r}``
  with ``revolution`` (the law only decides what the deck cannot express:
  a solver keeps a rubber's volume);
* each body's ``material``: a neo-Hookean, Mooney–Rivlin or Yeoh rubber
  (:func:`~sectiondeform.materials.models.material_from_json`), κ from
  ``bulk_modulus``, ``bulk_to_shear`` or ``options.bulk_to_shear`` (default 1000).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

from ..assembly import Assembly, Revolution, assembly_from_dict, revolution_from_json
from ..checks import number
from ..errors import CaseError
from ..laws import RATIO_RANGE
from ..materials.models import material_from_json

__all__ = ["FeAssembly", "FeLaw", "read_fe_assembly"]

LAW_KEYS = ("area_ratio", "volume_ratio")


@dataclass(frozen=True)
class FeLaw:
    """A body's law as the deck sees it.

    Attributes
    ----------
    key : str
        ``"area_ratio"`` or ``"volume_ratio"``.
    ratio : float
    """

    key: str
    ratio: float

    @property
    def text(self) -> str:
        """E.g. ``"area ratio 0.9"``."""
        return f"{self.key.replace('_', ' ')} {self.ratio:.6g}"


@dataclass(frozen=True, eq=False)
class FeAssembly:
    """A version-2 case for the decks.

    Attributes
    ----------
    assembly : Assembly
        Bodies, support, target, options and layout, as the project reads
        them (laws the project's reader does not know yet are read as area
        ratio 1 there; :attr:`laws` has the case's).
    laws : tuple of FeLaw
        Per body.
    materials : tuple
        Per body, a :mod:`sectiondeform.materials.models` rubber.
    revolution : Revolution or None
    """

    assembly: Assembly
    laws: tuple
    materials: tuple
    revolution: Revolution | None

    @property
    def name(self) -> str:
        return self.assembly.name

    @property
    def units(self) -> str:
        return self.assembly.units


def _law(obj, field: str, revolution: bool) -> FeLaw:
    if not isinstance(obj, dict) or len(obj) != 1:
        raise CaseError(field, f"expected one law object such as {{\"area_ratio\": 0.8}}, got {obj!r}")
    (key, value), = obj.items()
    if key not in LAW_KEYS:
        raise CaseError(field, f"unknown law {key!r}; use one of {', '.join(LAW_KEYS)}")
    if key == "volume_ratio" and not revolution:
        raise CaseError(f"{field}.volume_ratio", "a volume ratio needs a body of revolution (a \"revolution\" axis); "
                        "use area_ratio for a plane section")
    low, high = RATIO_RANGE
    return FeLaw(key, number(value, f"{field}.{key}", low=low, high=high))


def read_fe_assembly(data: dict) -> FeAssembly:
    """Read a parsed ``section-case/2`` object for the decks.

    Raises
    ------
    CaseError, GeometryError
        One line naming the field, as the project's reader does.
    """
    if not isinstance(data, dict):
        raise CaseError("case", f"expected a JSON object, got {type(data).__name__}")
    revolution = revolution_from_json(data["revolution"]) if "revolution" in data else None
    plane = copy.deepcopy({k: v for k, v in data.items() if k != "revolution"})
    raw = plane.get("bodies")
    laws = []
    if isinstance(raw, list):
        for i, body in enumerate(raw):
            if isinstance(body, dict) and "law" in body:
                laws.append(_law(body["law"], f"bodies[{i}].law", revolution is not None))
                body["law"] = {"area_ratio": 1.0}  # checked above; the reader checks everything else
    assembly = assembly_from_dict(plane)
    default_k = dict(assembly.options.model_values).get("bulk_to_shear")
    materials = tuple(material_from_json(b.material_data, f"bodies[{i}].material", default_bulk_to_shear=default_k)
                      for i, b in enumerate(assembly.bodies))
    return FeAssembly(assembly=assembly, laws=tuple(laws), materials=materials, revolution=revolution)
