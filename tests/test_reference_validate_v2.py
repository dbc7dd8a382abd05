"""Validation of a version-2 case: one body is compared (with its material), several body by body."""

from __future__ import annotations

import numpy as np
import pytest

import sectiondeform as sd

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from sectiondeform.reference.validation import validate_case  # noqa: E402

LOWER = {"polyline": [[0.0, 0.0], [20.0, 0.0]]}
UPPER = {"polyline": [[20.0, 0.0], [20.0, 5.0], [10.0, 6.0], [0.0, 5.0], [0.0, 0.0]]}
TARGET = {"polyline": [[0.0, 0.0], [10.0, -2.0], [20.0, 0.0]]}


def one_body(material=None):
    body = {"name": "pad", "lower": LOWER, "upper": UPPER, "law": {"area_ratio": 0.9}}
    if material is not None:
        body["material"] = material
    from sectiondeform.assembly import assembly_from_dict

    return assembly_from_dict({"format": "section-case/2", "support": LOWER, "target": TARGET, "bodies": [body]})


def test_a_one_body_assembly_validates_as_its_version_one_case_with_its_material():
    v1 = sd.case_from_dict({"format": "section-case/1", "lower": LOWER, "upper": UPPER, "target": TARGET,
                            "law": {"area_ratio": 0.9}})
    a = validate_case(v1, mesh_size=0.4, fast_runs=1)
    b = validate_case(one_body(), mesh_size=0.4, fast_runs=1)
    np.testing.assert_allclose(b.reference.upper, a.reference.upper, atol=1e-10)
    np.testing.assert_allclose(b.fast.upper, a.fast.upper, atol=1e-12)
    c = validate_case(one_body({"model": "yeoh", "c10": 0.3, "c20": 0.05, "c30": 0.01}), mesh_size=0.4, fast_runs=1)
    assert c.reference.material.model == "yeoh"
    assert c.to_json()["reference"]["model"].startswith("finite elements: yeoh, generalised plane strain")
    assert np.abs(c.reference.upper - a.reference.upper).max() > 1e-6  # the stiffening rubber moves the free surface


def test_several_bodies_are_compared_body_by_body_and_a_body_s_bad_material_is_named():
    from sectiondeform.assembly import assembly_from_dict
    from sectiondeform.reference.validation import AssemblyValidation

    top = {"name": "cap", "lower": {"polyline": [[0.0, 5.0], [10.0, 6.0], [20.0, 5.0]]},
           "upper": {"polyline": [[20.0, 5.0], [20.0, 8.0], [0.0, 8.0], [0.0, 5.0]]}, "law": {"area_ratio": 0.95}}
    data = {"format": "section-case/2", "support": LOWER, "target": TARGET,
            "bodies": [{"name": "pad", "lower": LOWER, "upper": UPPER, "law": {"area_ratio": 0.9}}, top]}
    v = validate_case(assembly_from_dict(data), model="hyperelastic", mesh_size=0.8, fast_runs=1)
    assert isinstance(v, AssemblyValidation) and [b.name for b in v.bodies] == ["pad", "cap"]
    top["material"] = {"shear_modulus": 1.0, "bulk_to_shear": 50}
    with pytest.raises(sd.CaseError, match=r"^bodies\[1\]\.material\.bulk_to_shear: the reference is a nearly") as err:
        validate_case(assembly_from_dict(data), model="hyperelastic", mesh_size=0.8, fast_runs=1)
    assert "\n" not in str(err.value)
