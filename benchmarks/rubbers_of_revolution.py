"""Figures of docs/hyperelastic.md on other rubbers of revolution and on stresses at interfaces.

    PYTHONPATH=src .venv/bin/python benchmarks/rubbers_of_revolution.py

Prints, on a shared machine (times are indicative only):

1. The undertread of ``tread-on-drum.json`` alone, its rubber Mooney–Rivlin
   (c10 0.3, c01 0.1) or Yeoh (0.3, −0.01, 0.002): largest and median
   distance of an upper point to the finite-element reference (mesh size
   0.2) over T, at 2 and 4 elements through T.
2. A ring 3 walls long bonded inside and expanded from radius 10 to 14:
   how far the Mooney–Rivlin (c10 0.1, c01 0.4) upper curve moves from the
   neo-Hookean one in the reference (mesh size 0.12), and how far the
   hyperelastic model's move misses it, at 2 and 4 elements through the wall.
3. Two blocks stacked (shear moduli 1 and 3, same bulk-to-shear ratio)
   stretched equibiaxially by 1.2, whose exact state is homogeneous:
   the largest node distance from the affine map over the layer height and
   the median pressure of each body over the exact one (each body has its
   own pressure field, so the pressure jumps at the bonded interface as
   the exact one does).
4. The thick ring of 3. in ``tests/test_stress_fields.py``, two bonded
   layers of shear moduli 1 (inner) and 3 (outer), expanded radially: the
   largest pressure error far from the ends, over the largest pressure,
   per layer.
5. The two shared problems of several bodies against their finite-element reference (mesh
   size 0.1): per body the Hausdorff distance of the hyperelastic model's
   upper curve over its T, and its law correction over T.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from sectiondeform import Deformer, case_from_dict  # noqa: E402
from sectiondeform.reference import solve_reference  # noqa: E402

DRUM = ROOT / "tests" / "data" / "cases" / "v2" / "tread-on-drum.json"


def undertread() -> None:
    rubbers = {"mooney-rivlin": {"model": "mooney-rivlin", "c10": 0.3, "c01": 0.1},
               "yeoh": {"model": "yeoh", "c10": 0.3, "c20": -0.01, "c30": 0.002}}
    for name, material in rubbers.items():
        data = json.loads(DRUM.read_text())
        data["bodies"] = data["bodies"][:1]
        data["bodies"][0]["material"] = material
        reference = solve_reference(case_from_dict(data), mesh_size=0.2).bodies[0]
        for through in (2.0, 4.0):
            data["options"] = {**data.get("options", {}), "elements_through_thickness": through}
            body = Deformer(case_from_dict(data), model="hyperelastic").deform().bodies[0]
            d = np.hypot(*(body.upper - reference.upper).T) / 3.0
            print(f"undertread {name:14s} {through:.0f} through T: largest {d.max():.2e} T, median {np.median(d):.2e} T")


def ring() -> None:
    from test_hyperelastic_revolution import T, ring_case

    rubbers = {"nh": {"shear_modulus": 1.0}, "mr": {"model": "mooney-rivlin", "c10": 0.1, "c01": 0.4}}
    model, reference = {}, {}
    for name, material in rubbers.items():
        case = ring_case(1.0, length=3 * T)
        case["bodies"][0]["material"] = {**material, "bulk_to_shear": 1000.0}
        case["target"] = {"polyline": [[0.0, 14.0], [3 * T, 14.0]]}
        for through in (2.0, 4.0):
            case["options"]["elements_through_thickness"] = through
            model[name, through] = Deformer(case_from_dict(case)).deform().bodies[0].upper
        reference[name] = solve_reference(case_from_dict(case), mesh_size=0.12).bodies[0].upper
    effect = reference["mr"] - reference["nh"]
    print(f"short ring: Mooney-Rivlin moves the upper curve by {np.hypot(*effect.T).max() / T:.2e} T (reference)")
    for through in (2.0, 4.0):
        miss = np.hypot(*(model["mr", through] - model["nh", through] - effect).T).max() / T
        print(f"short ring: the hyperelastic model misses that move by {miss:.2e} T at {through:.0f} through the wall")


def stacked() -> None:
    from test_stress_fields import HEIGHT, LAM, block, homogeneous, pressure_and_von_mises

    lz, sigma = homogeneous(0.5, 0.0, 1000.0)
    exact = pressure_and_von_mises(sigma)[0]
    bodies = []
    for i, mu in enumerate((1.0, 3.0)):
        lower, upper = block(0.0, i * HEIGHT)
        bodies.append({"name": f"layer{i}", "lower": {"polyline": lower}, "upper": {"polyline": upper},
                       "law": {"area_ratio": 1.0 / lz}, "material": {"shear_modulus": mu}})
    case = {"format": "section-case/2", "name": "stack", "support": {"polyline": [[0, 0], [10, 0]]},
            "target": {"polyline": [[0, 0], [LAM * 10, 0]]}, "bodies": bodies,
            "options": {"model": "hyperelastic", "newton_tolerance": 1e-10}}
    result = Deformer(case_from_dict(case)).deform()
    for body, data, mu in zip(result.bodies, result.to_json(fields=True)["bodies"], (1.0, 3.0)):
        off = np.abs(body.final_mesh.points - LAM * body.initial_mesh.points).max() / HEIGHT
        p = np.median(data["fields"]["pressure"]) / (mu * exact)
        print(f"stacked blocks, shear modulus {mu:.0f}: nodes off the affine map by {off:.2e} H, "
              f"median pressure {p:.4f} of the exact")


def layered_ring() -> None:
    import test_stress_fields as t

    for body, error in zip(("inner", "outer"), t.two_layer_ring_pressure_errors()):
        print(f"two-layer ring, {body} layer: largest pressure error {error:.2e} of the largest pressure")


def against_reference() -> None:
    from sectiondeform.compare import hausdorff_distance

    for name in ("two-layer-strip", "tread-on-drum"):
        problem = case_from_dict(json.loads((DRUM.parent / f"{name}.json").read_text()))
        reference = solve_reference(problem, mesh_size=0.1)
        deformer = Deformer(problem, model="hyperelastic")
        result = deformer.deform()
        for body, ref, section in zip(result.bodies, reference.bodies, deformer.stack.sections):
            t = section.thickness
            d = hausdorff_distance(body.upper, ref.upper)
            print(f"{name} {body.name}: Hausdorff to the reference {100 * d / t:.2f} % T, "
                  f"law correction {body.info.area_correction:.2e} T")


if __name__ == "__main__":
    undertread()
    ring()
    stacked()
    layered_ring()
    against_reference()
