"""A placement the paper model itself judges meaningless is refused; milder figures stay warnings.

Beyond the height-scale range or the aspect limit (``docs/method.md``) the
layered map no longer means a deformation of the section: that is an error
naming the hyperelastic model, exit 2 on the command line and nothing
written, not a warning on a written result.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import sectiondeform as sd
from sectiondeform.applicability import ASPECT_LIMIT, HEIGHT_SCALE_LIMITS
from sectiondeform.errors import MeshError

from conftest import box_case


def squeezed(stretch, ratio):
    """A 40 x 4 box whose lower edge goes onto a straight target ``stretch`` times as long, under ``ratio``:
    the columns keep their count, so the height scale is k = ratio / stretch and an element's aspect
    changes k / stretch = ratio / stretch² (by hand).
    """
    return box_case(40.0, 4.0, target={"polyline": [[0.0, 0.0], [40.0 * stretch, 0.0]]}, ratio=ratio)


@pytest.mark.parametrize("stretch, ratio", [(0.4, 1.0), (0.45, 0.85)])
def test_layers_beyond_what_the_model_can_mean_are_refused_naming_the_fix(stretch, ratio):
    k, aspect = ratio / stretch, ratio / stretch**2
    assert k > HEIGHT_SCALE_LIMITS[1] or aspect > ASPECT_LIMIT  # the case is beyond one limit, by hand
    with pytest.raises(MeshError, match=r"beyond what the paper model can mean; refused: .*hyperelastic") as info:
        sd.deform(sd.case_from_dict(squeezed(stretch, ratio)), model="paper")
    assert "\n" not in str(info.value)


def test_the_milder_figures_stay_warnings():
    """A 20 % area loss on the box's own base: heights change by -20 %, beyond the 10 % limit: a warning only."""
    result = sd.deform(sd.case_from_dict(box_case(ratio=0.8)), model="paper")
    assert result.info.height_scale == pytest.approx(0.8, rel=1e-9)
    assert any("heights change by -20 %" in w for w in result.warnings)


def test_the_command_line_exits_2_and_writes_nothing(tmp_path):
    case = tmp_path / "case.json"
    case.write_text(json.dumps(squeezed(0.4, 1.0)))
    out = tmp_path / "result.json"
    run = subprocess.run([sys.executable, "-m", "sectiondeform", "deform", str(case), "-o", str(out), "--model", "paper"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and not out.exists()
    lines = [line for line in run.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and "hyperelastic" in lines[0]
