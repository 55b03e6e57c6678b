"""The shared balancing cases against their expected results (both the files in
../shared/cases, when present, and the copies embedded in ``_balance_cases``)."""

from __future__ import annotations

import json
import tomllib

import pytest

import balance
from tests.balance._balance_cases import CASE_NAMES, EXPECTED, SCENES, SHARED_CASES, assert_matches

needs_shared = pytest.mark.skipif(not SHARED_CASES.is_dir(),
                                  reason="../shared/cases is not beside this clone")


@needs_shared
@pytest.mark.parametrize("name", CASE_NAMES)
def test_shared_case_file(name: str) -> None:
    want = json.loads((SHARED_CASES / f"{name}.expected.json").read_text())
    assert_matches(balance.solve(SHARED_CASES / f"{name}.toml"), want)


@needs_shared
@pytest.mark.parametrize("name", CASE_NAMES)
def test_embedded_copies_equal_shared_files(name: str) -> None:
    """The embedded copies must not drift from the shared originals."""
    assert tomllib.loads(SCENES[name]) == tomllib.loads(
        (SHARED_CASES / f"{name}.toml").read_text())
    assert json.loads((SHARED_CASES / f"{name}.expected.json").read_text()) == EXPECTED[name]


@pytest.mark.parametrize("name", CASE_NAMES)
def test_embedded_case(name: str) -> None:
    assert_matches(balance.solve(SCENES[name]), EXPECTED[name])


@pytest.mark.parametrize("name", CASE_NAMES)
def test_bundled_scene(name: str) -> None:
    """The package's bundled copies give the same results."""
    assert_matches(balance.solve(balance.example_path(name)), EXPECTED[name])


@pytest.mark.parametrize("name", CASE_NAMES)
def test_scene_as_dict_and_path_string(name: str) -> None:
    raw = tomllib.loads(SCENES[name])
    assert_matches(balance.solve(raw), EXPECTED[name])
    assert_matches(balance.solve(str(balance.example_path(name))), EXPECTED[name])


def test_results_are_json_clean() -> None:
    for name in balance.examples():
        out = balance.solve(balance.example_path(name))
        json.dumps(out, allow_nan=False)   # no NaN, no numpy scalars
