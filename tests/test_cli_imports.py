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


def test_deforming_the_paper_example_from_the_command_line_imports_no_module_it_does_not_use(tmp_path):
    """numpy.ma (first ``np.unique``, 20-40 ms), statistics, webbrowser, the material fits: none on this path."""
    from sectiondeform import example_case_path

    unused = ("numpy.ma", "statistics", "webbrowser", "sectiondeform.materials.fit")
    code = ("import sys; from sectiondeform.cli import main; "
            f"status = main(['deform', {str(example_case_path())!r}, '-o', {str(tmp_path / 'out.json')!r}]); "
            f"print(status, ','.join(m for m in {unused!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.splitlines()[-1].split()
    assert out[0] == "0" and out[1:] == [], f"imported by `deform`: {out[1:]}"
