"""Part-2 golden cases with nothing else running in the domain, through both doors."""

from __future__ import annotations

import pytest
from ros2_golden import console_env, run_api, run_console
from ros2_golden_part2 import CASES, compare2, names

pytestmark = pytest.mark.ros


@pytest.fixture(params=["api", "console"])
def door(request, ros_session, daemon):  # type: ignore[no-untyped-def]
    if request.param == "api":
        return run_api
    env = console_env(ros_session)
    return lambda command: run_console(env, command)


@pytest.mark.parametrize("name", names("empty"))
def test_golden_case_matches(name: str, door) -> None:  # type: ignore[no-untyped-def]
    compare2(CASES[name], door(CASES[name]["command"]))
