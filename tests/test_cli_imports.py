"""The command line builds its parser without the heavy optional parts (the whole process's start-up time)."""

import subprocess
import sys

HEAVY = ("sectiondeform.external.deck", "sectiondeform.reference", "sectiondeform.app.server", "matplotlib",
         "scipy.spatial", "pyarrow", "dask")


def test_building_the_parser_of_every_command_imports_nothing_heavy():
    code = ("import sys; from sectiondeform.cli import build_parser; build_parser(); "
            f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "", f"imported while building the parser: {out}"
