"""Run the speed benchmark and write docs/benchmarks.json and docs/benchmarks.md.

Usage: python benchmarks/run.py [--quick] [--cases DIR] [--json PATH] [--markdown PATH]
(the same as ``sectiondeform bench``; see :mod:`sectiondeform.bench`).
"""

import sys

from sectiondeform.bench import main

if __name__ == "__main__":
    sys.exit(main())
