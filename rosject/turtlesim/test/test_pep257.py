"""Docstring check with ament_pep257 (runs under `colcon test` on a ROS 2 machine)."""

import pytest


@pytest.mark.linter
@pytest.mark.pep257
def test_pep257():
    main = pytest.importorskip('ament_pep257.main').main
    assert main(argv=['.', 'test']) == 0, 'docstring problems found, see above'
