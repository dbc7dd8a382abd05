"""Rubber materials: models, stress and strain measures, homogeneous tests and fits to test data.

- :mod:`.models`: neo-Hookean, Mooney–Rivlin and Yeoh rubbers (frozen
  dataclasses), their energy, stress and tangent as functions of F, and the
  case format's ``material`` object.
- :mod:`.measures`: Cauchy stress, von Mises stress, pressure, principal
  stretches and strains, for result output.
- :mod:`.homogeneous`: incompressible uniaxial, equibiaxial and planar
  nominal stresses, and the stability check.
- :mod:`.fit`: test data from CSV, least-squares fit, figure.
"""

from .models import (
    DEFAULT_BULK_TO_SHEAR,
    MATERIAL_MODELS,
    Material,
    MooneyRivlin,
    NeoHookean,
    Yeoh,
    gradient_3d,
    material_from_json,
    material_to_json,
)

__all__ = [
    "DEFAULT_BULK_TO_SHEAR", "MATERIAL_MODELS", "Material", "MooneyRivlin", "NeoHookean", "Yeoh",
    "gradient_3d", "material_from_json", "material_to_json",
]
