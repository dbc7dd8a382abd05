"""Measure the speed: pipeline, re-deformation, scaling, peers and command line, in one run.

Writes a JSON report and a Markdown table (docs/benchmarks.json and
docs/benchmarks.md by default), every figure beside its target. --quick
runs few repetitions and small N, for CI. The same as benchmarks/run.py.

Example: sectiondeform bench --quick --json /tmp/b.json --markdown /tmp/b.md
"""

from __future__ import annotations


def add_args(parser) -> None:
    from ..bench import add_args as _add

    _add(parser)


def run(args) -> int:
    from ..bench import run as _run

    return _run(args)
