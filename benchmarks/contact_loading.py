"""The work of a contact loading: factorisations, load steps and CPU time of each contact case, and its forces.

Factorisations are the cost that matters (each is a sparse LU of the whole
tangent) and, unlike seconds, they do not depend on the machine or its load:
every one the loading makes is counted, those of the solves that failed and
were halved included (the count wraps
:meth:`sectiondeform.fem.newton.NewtonSolver.tangent`). Each case runs at
the elements through the thickness given, so the cost of a finer mesh shows.

Run::

    python benchmarks/contact_loading.py                 # the contact cases of tests/data/cases/v2
    python benchmarks/contact_loading.py --through 4 8 16 --cases bumper-under-plate
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

CASES = Path(__file__).resolve().parents[1] / "tests" / "data" / "cases" / "v2"
DEFAULT = ("bumper-under-plate", "sleeve-on-shaft", "o-ring-squeeze-20", "o-ring-squeeze-20-k100")


def counted():
    """Count the tangent factorisations of every Newton solver from now on; returns the one-item counter."""
    from sectiondeform.fem import newton

    count = [0]
    real = newton.NewtonSolver.tangent

    def tangent(self, fields):
        count[0] += 1
        return real(self, fields)

    newton.NewtonSolver.tangent = tangent
    return count


def run(name: str, through, count) -> dict:
    """One case at ``through`` elements through the thickness (None: the case's own): its loading's work and forces."""
    from sectiondeform.deform import Deformer
    from sectiondeform.io.case import case_from_dict

    raw = json.loads((CASES / f"{name}.json").read_text(encoding="utf-8"))
    extra = {"elements_through_thickness": through} if through else {}
    raw["options"] = {**raw.get("options", {}), "model": "hyperelastic", **extra}
    count[0] = 0
    t0 = time.process_time()
    row = {"case": name, "through": through or "case"}
    try:
        result = Deformer(case_from_dict(raw)).deform()
    except Exception as exc:  # noqa: BLE001 - a refusal is a row of the table
        row.update(factorisations=count[0], seconds=time.process_time() - t0, outcome=str(exc).split(":")[0] + ": refused")
        return row
    part = result.rigid[0]
    row.update(factorisations=count[0], seconds=time.process_time() - t0, steps=len(result.history) - 1,
               force=max(part.force, key=abs), length=part.length, outcome="answered")
    return row


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=list(DEFAULT), help="case names in tests/data/cases/v2")
    parser.add_argument("--through", nargs="+", type=int, default=[0],
                        help="elements through the thickness (0: the case's own)")
    args = parser.parse_args(argv)
    count = counted()
    print("| case | elements through | factorisations | load steps | CPU s | force | contact length | outcome |")
    print("|---|---:|---:|---:|---:|---:|---:|---|")
    for name in args.cases:
        for through in args.through:
            r = run(name, through or None, count)
            steps = r.get("steps", "—")
            force = f"{r['force']:.6g}" if "force" in r else "—"
            length = f"{r['length']:.4g}" if "length" in r else "—"
            print(f"| {r['case']} | {r['through']} | {r['factorisations']} | {steps} | {r['seconds']:.2f} | {force} | "
                  f"{length} | {r['outcome']} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
