"""The ``*HYPERELASTIC`` card of a rubber: the case's material in Abaqus / CalculiX terms.

Both solvers write the strain energy as the project does
(:mod:`sectiondeform.materials.models`), with the volumetric part
(J − 1)² / D1, so D1 = 2 / κ:

* neo-Hookean: ``*HYPERELASTIC, NEO HOOKE`` with C10 = μ/2, D1;
* Mooney–Rivlin: ``*HYPERELASTIC, MOONEY-RIVLIN`` with C10, C01, D1;
* Yeoh: ``*HYPERELASTIC, YEOH`` with C10, C20, C30, D1, D2 = D3 = 0.
"""

from __future__ import annotations

from .inp_number import inp_real

__all__ = ["hyperelastic_card", "material_summary"]


def hyperelastic_card(material) -> list[str]:
    """The ``*HYPERELASTIC`` keyword line and its data line.

    Parameters
    ----------
    material : NeoHookean or MooneyRivlin or Yeoh
        From :func:`sectiondeform.materials.models.material_from_json`.

    Returns
    -------
    list of str
        Two lines.

    Examples
    --------
    >>> from sectiondeform.materials.models import NeoHookean, Yeoh
    >>> hyperelastic_card(NeoHookean(1.0))
    ['*HYPERELASTIC, NEO HOOKE', '0.5, 0.002']
    >>> hyperelastic_card(Yeoh(0.5, -0.01, 0.001, bulk_modulus=1000.0))
    ['*HYPERELASTIC, YEOH', '0.5, -0.01, 0.001, 0.002, 0, 0']
    """
    d1 = 2.0 / material.kappa
    if material.model == "neo-hookean":
        return ["*HYPERELASTIC, NEO HOOKE", ", ".join(map(inp_real, (material.coefficients[0], d1)))]
    if material.model == "mooney-rivlin":
        return ["*HYPERELASTIC, MOONEY-RIVLIN", ", ".join(map(inp_real, (material.c10, material.c01, d1)))]
    if material.model == "yeoh":
        c10, c20, c30 = material.coefficients
        return ["*HYPERELASTIC, YEOH", ", ".join(map(inp_real, (c10, c20, c30, d1))) + ", 0, 0"]
    raise ValueError(f"no *HYPERELASTIC card for the material model {material.model!r}")  # pragma: no cover


def material_summary(material) -> str:
    """One line for the deck's comment block, e.g. ``neo-hookean: C10 = 0.5, D1 = 0.002 (mu 1, kappa 1000)``."""
    card = hyperelastic_card(material)
    names = {"neo-hookean": ("C10", "D1"), "mooney-rivlin": ("C10", "C01", "D1"),
             "yeoh": ("C10", "C20", "C30", "D1", "D2", "D3")}[material.model]
    values = ", ".join(f"{n} = {v.strip()}" for n, v in zip(names, card[1].split(",")))
    return f"{material.model}: {values} (mu {material.shear_modulus:.6g}, kappa {material.kappa:.6g})"
