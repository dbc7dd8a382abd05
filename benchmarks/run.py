"""Run the project's speed benchmark and write its report.

Usage: python benchmarks/run.py [--quick] [--cases DIR] [-o DIR] [--changes FILE] [--no-profile] [--hyperelastic-only]

The full run writes ``docs/benchmarks.json`` and ``docs/benchmarks.md`` of this
repository unless ``-o DIR`` names another folder. ``--quick`` (few
repetitions, small N: the smoke run of the tests) never writes into docs/:
it writes into ``-o DIR`` or, without it, into a new temporary folder. The
folder written is printed. See :mod:`speed` for what is timed.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

import speed  # noqa: E402

DOCS = HERE.parent / "docs"


def build_parser() -> argparse.ArgumentParser:
    """The benchmark's arguments."""
    parser = argparse.ArgumentParser(prog="benchmarks/run.py", description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="few repetitions and small N (smoke run); writes to a temporary folder unless -o")
    parser.add_argument("--cases", type=Path, help="folder of case files (default: tests/data/cases)")
    parser.add_argument("-o", "--output", type=Path, metavar="DIR",
                        help="folder for benchmarks.json and benchmarks.md (default: docs/ for a full run, a temporary folder for --quick)")
    parser.add_argument("--changes", type=Path, help="Markdown file appended to the table (what changed, what it gained)")
    parser.add_argument("--no-profile", action="store_true", help="leave pyinstrument's profile out")
    parser.add_argument("--hyperelastic-only", action="store_true",
                        help="only section 8 (the hyperelastic model on every shared case): print its table, write nothing")
    return parser


def output_folder(output: Path | None, quick: bool) -> Path:
    """Where the report goes: ``output`` if given, else docs/ (full run) or a new temporary folder (quick run)."""
    if output is not None:
        return output
    if quick:
        return Path(tempfile.mkdtemp(prefix="sectiondeform-bench-"))
    return DOCS


def main(argv: list[str] | None = None) -> int:
    """Parse ``argv``, run the benchmark, write the report, print the targets and where it went."""
    args = build_parser().parse_args(argv)
    if args.hyperelastic_only:
        rows = speed.bench_hyperelastic_cases(speed.QUICK if args.quick else speed.FULL)
        print("\n".join(speed.hyperelastic_markdown(rows)))
        return 0
    report = speed.run_benchmark(args.cases, quick=args.quick, profile=not args.no_profile,
                                 log=lambda s: print(s, file=sys.stderr))
    report["command"] = " ".join(["python", os.path.relpath(__file__)] + (sys.argv[1:] if argv is None else list(argv)))
    changes = args.changes.read_text(encoding="utf-8") if args.changes else ""
    js, md = speed.write_report(report, output_folder(args.output, args.quick), changes)
    print(speed.targets_text(report))
    print(f"wrote {js} and {md}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
