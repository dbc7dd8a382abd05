"""Time your own case: preparation and re-deformation, medians of repeated runs.

Prepare is ``Deformer(case)`` (discretisation, initial meshes, location), for
one body or several;
re-deformation is ``deformer.deform()`` on the prepared section, the
interactive use. Nothing is written. The project's own benchmark, with its
targets, is ``python benchmarks/run.py`` in the source repository.

Example: sectiondeform bench case.json --repeat 50
"""

from __future__ import annotations

import time
from pathlib import Path

from ..deform import Deformer
from ..errors import CaseError
from ._common import add_model_args, apply_overrides


def add_args(parser) -> None:
    """``CASE``, ``--repeat`` and the model options."""
    parser.add_argument("case", type=Path, help="case file (JSON, DXF or SVG)")
    parser.add_argument("--repeat", type=int, default=20, metavar="N", help="timed runs of each stage (default: 20)")
    add_model_args(parser)


def _median_s(fn, repeat: int) -> float:
    import statistics

    fn()  # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def run(args) -> int:
    """Print the median preparation and re-deformation times of the case."""
    from ..io import read_case

    if not 1 <= args.repeat <= 100_000:
        raise CaseError("--repeat", f"must be a whole number from 1 to 100000, got {args.repeat}")
    problem = apply_overrides(read_case(args.case), args)
    deformer = Deformer(problem, element_size=args.element_size)
    prepare = _median_s(lambda: Deformer(problem, element_size=args.element_size), args.repeat)
    redeform = _median_s(deformer.deform, args.repeat)
    print(f"{problem.name}: median of {args.repeat} runs ({len(problem.bodies)} bodies)")
    print(f"  prepare         {1e3 * prepare:10.3f} ms   Deformer(case)")
    print(f"  re-deformation  {1e3 * redeform:10.3f} ms   deformer.deform()")
    return 0
