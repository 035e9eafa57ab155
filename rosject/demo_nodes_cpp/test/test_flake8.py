"""Style check with ament_flake8 (runs under `colcon test` on a ROS 2 machine)."""

import pytest


@pytest.mark.flake8
@pytest.mark.linter
def test_flake8():
    main_with_errors = pytest.importorskip('ament_flake8.main').main_with_errors
    rc, errors = main_with_errors(argv=[])
    assert rc == 0, f'{len(errors)} style problems:\n' + '\n'.join(errors)
