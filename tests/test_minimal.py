"""The core works without any optional extra, and a missing extra names itself.

Each check runs in a fresh interpreter in which the optional packages cannot
be imported (their entries in ``sys.modules`` are set to None).
"""

import json
import subprocess
import sys

import pytest

from conftest import SHARED_CASES

BLOCK = "import sys\nfor m in ('matplotlib', 'ezdxf', 'skfem', 'meshio', 'svgelements', 'triangle'):\n    sys.modules[m] = None\n"


def _run(code, *args):
    return subprocess.run([sys.executable, "-c", BLOCK + code, *args], capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("model", ["paper", "hyperelastic"])
def test_core_deforms_without_extras(model, tmp_path):
    out = tmp_path / "r.json"
    code = "from sectiondeform.cli import main\nsys.exit(main(sys.argv[1:]))"
    proc = _run(code, "deform", str(SHARED_CASES[0]), "-o", str(out), "--model", model)
    assert proc.returncode == 0, proc.stderr
    assert abs(json.loads(out.read_text())["area"]["relative_error"]) <= 1e-9


@pytest.mark.parametrize(
    "args, extra",
    [(["--plot", "fig.png"], "plot"), (["--mesh-out", "m.vtu"], "cad")],
)
def test_missing_extra_is_named(args, extra, tmp_path):
    out = tmp_path / "r.json"
    args = [str(tmp_path / a) if "." in a else a for a in args]
    code = "from sectiondeform.cli import main\nsys.exit(main(sys.argv[1:]))"
    proc = _run(code, "deform", str(SHARED_CASES[0]), "-o", str(out), *args)
    assert proc.returncode == 2
    assert f"pip install 'sectiondeform[{extra}]'" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
    assert not out.exists()
