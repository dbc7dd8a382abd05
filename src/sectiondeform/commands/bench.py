"""Measure the speed: pipeline, re-deformation, scaling, peers and command line, in one run.

Writes a JSON report and a Markdown table (docs/benchmarks.json and
docs/benchmarks.md by default), every figure beside its target. --quick
runs few repetitions and small N, for CI. The same as benchmarks/run.py.

Example: sectiondeform bench --quick --json /tmp/b.json --markdown /tmp/b.md
"""

from __future__ import annotations

from pathlib import Path


def add_args(parser) -> None:
    """Options shared with ``benchmarks/run.py`` (the benchmark itself is imported only to run)."""
    parser.add_argument("--quick", action="store_true", help="few repetitions and small N (CI smoke run)")
    parser.add_argument("--cases", type=Path, help="folder of case files (default: benchmarks/cases)")
    parser.add_argument("--json", type=Path, default=Path("docs/benchmarks.json"), help="JSON report to write")
    parser.add_argument("--markdown", type=Path, default=Path("docs/benchmarks.md"), help="Markdown table to write")
    parser.add_argument("--changes", type=Path, help="Markdown file appended to the table (what changed, what it gained)")
    parser.add_argument("--no-profile", action="store_true", help="leave pyinstrument's profile out")


def run(args) -> int:
    from ..bench import run as _run

    return _run(args)
