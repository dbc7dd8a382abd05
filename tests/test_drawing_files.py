"""A case JSON naming a drawing reads only the files its caller allows (never an absolute path or ``..`` out)."""

from __future__ import annotations

import json
import os

import pytest

import sectiondeform as sd
from sectiondeform.errors import CaseError
from sectiondeform.io import read_case, write_case


@pytest.fixture()
def folders(tmp_path):
    """``tmp/cases/`` for the case JSON, ``tmp/secret.svg`` (a valid drawing) outside it."""
    cases = tmp_path / "cases"
    cases.mkdir()
    case = sd.load_case(sd.example_case_path())
    write_case(tmp_path / "secret.svg", case)
    write_case(cases / "inside.svg", case)
    return cases, tmp_path / "secret.svg"


def case_naming(folder, file):
    path = folder / "case.json"
    path.write_text(json.dumps({"format": "section-case/1", "drawing": {"file": str(file)}}))
    return path


def refusal(path, **options) -> CaseError:
    with pytest.raises(CaseError) as info:
        read_case(path, **options)
    return info.value


def test_a_drawing_beside_the_case_is_read(folders):
    cases, _ = folders
    case = read_case(case_naming(cases, "inside.svg"))
    assert case.lower.length == pytest.approx(110.0)


@pytest.mark.parametrize("name", ["../secret.svg", "ABSOLUTE", "sub/../../secret.svg"])
def test_a_drawing_outside_the_cases_folder_is_refused_without_telling_if_it_exists(folders, name):
    cases, secret = folders
    name = str(secret) if name == "ABSOLUTE" else name
    exists = refusal(case_naming(cases, name))
    missing = refusal(case_naming(cases, name.replace("secret", "nothing-here")))
    assert exists.field == missing.field == "drawing.file"
    assert str(exists).replace("secret", "X") == str(missing).replace("nothing-here", "X")  # same words either way
    assert "\n" not in str(exists)


def test_a_link_out_of_the_folder_is_refused(folders):
    cases, secret = folders
    try:
        os.symlink(secret, cases / "link.svg")
    except OSError:
        pytest.skip("no symbolic links here")
    assert refusal(case_naming(cases, "link.svg")).field == "drawing.file"


def test_no_files_at_all_when_the_caller_allows_none(folders):
    cases, _ = folders
    error = refusal(case_naming(cases, "inside.svg"), allow_files=False)
    assert error.field == "drawing.file" and "no drawing files" in str(error)


def test_the_caller_may_allow_a_wider_folder(folders):
    cases, secret = folders
    case = read_case(case_naming(cases, "../secret.svg"), allow_files=secret.parent)
    assert case.lower.length == pytest.approx(110.0)
