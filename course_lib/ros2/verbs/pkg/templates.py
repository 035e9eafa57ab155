"""The files `ros2 pkg create` writes, as Jazzy's ros2pkg writes them (pure: text in, text out).

Written from the real tool's output (tests/golden/pkg_create/ holds what ros2pkg 0.32.2
printed and wrote); the tests compare every file byte for byte.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "LICENSES",
    "NewPackage",
    "cmake_lists",
    "cpp_node",
    "license_text",
    "package_xml",
    "python_node",
    "setup_cfg",
    "setup_py",
    "test_file",
]

# ament_copyright's licenses, in the order ros2pkg lists them (SPDX identifiers).
LICENSES = (
    "Apache-2.0",
    "BSL-1.0",
    "BSD-2.0",
    "BSD-2-Clause",
    "BSD-3-Clause",
    "GPL-3.0-only",
    "LGPL-3.0-only",
    "MIT",
    "MIT-0",
)
_LICENSE_DIR = Path(__file__).resolve().parent / "licenses"
_OSRF = "Open Source Robotics Foundation, Inc."
_APACHE_HEADER = """\
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.
"""


@dataclass(frozen=True)
class NewPackage:
    """What `ros2 pkg create` was asked for."""

    name: str
    build_type: str
    package_format: int
    description: str
    license: str
    maintainer_name: str
    maintainer_email: str
    dependencies: tuple[str, ...]
    node_name: str | None = None

    @property
    def buildtool_dependencies(self) -> tuple[str, ...]:
        """Return the buildtool dependencies ros2pkg declares for this build type."""
        return ("ament_cmake",) if self.build_type == "ament_cmake" else ()

    @property
    def test_dependencies(self) -> tuple[str, ...]:
        """Return the test dependencies ros2pkg declares for this build type."""
        if self.build_type == "ament_cmake":
            return ("ament_lint_auto", "ament_lint_common")
        if self.build_type == "ament_python":
            return ("ament_copyright", "ament_flake8", "ament_pep257", "python3-pytest")
        return ()


def license_text(spdx: str) -> str:
    """Return the LICENSE file ros2pkg writes for one of LICENSES."""
    return (_LICENSE_DIR / f"{spdx}.txt").read_text()


def _block(tag: str, values: tuple[str, ...]) -> str:
    return "".join(f"  <{tag}>{v}</{tag}>\n" for v in values) + "\n" if values else ""


def package_xml(package: NewPackage) -> str:
    """Return package.xml."""
    fmt = package.package_format
    return (
        '<?xml version="1.0"?>\n'
        f'<?xml-model href="http://download.ros.org/schema/package_format{fmt}.xsd"'
        ' schematypens="http://www.w3.org/2001/XMLSchema"?>\n'
        f'<package format="{fmt}">\n'
        f"  <name>{package.name}</name>\n"
        "  <version>0.0.0</version>\n"
        f"  <description>{package.description}</description>\n"
        f'  <maintainer email="{package.maintainer_email}">{package.maintainer_name}'
        "</maintainer>\n"
        f"  <license>{package.license}</license>\n\n"
        + _block("buildtool_depend", package.buildtool_dependencies)
        + _block("depend", package.dependencies)
        + _block("test_depend", package.test_dependencies)
        + "  <export>\n"
        f"    <build_type>{package.build_type}</build_type>\n"
        "  </export>\n"
        "</package>\n"
    )


def setup_py(package: NewPackage) -> str:
    """Return setup.py of an ament_python package."""
    node = package.node_name
    script = f"            '{node} = {package.name}.{node}:main'\n" if node else ""
    return (
        "from setuptools import find_packages, setup\n\n"
        f"package_name = '{package.name}'\n\n"
        "setup(\n"
        "    name=package_name,\n"
        "    version='0.0.0',\n"
        "    packages=find_packages(exclude=['test']),\n"
        "    data_files=[\n"
        "        ('share/ament_index/resource_index/packages',\n"
        "            ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        "    ],\n"
        "    install_requires=['setuptools'],\n"
        "    zip_safe=True,\n"
        f"    maintainer='{package.maintainer_name}',\n"
        f"    maintainer_email='{package.maintainer_email}',\n"
        f"    description='{package.description}',\n"
        f"    license='{package.license}',\n"
        "    tests_require=['pytest'],\n"
        "    entry_points={\n"
        "        'console_scripts': [\n"
        f"{script}"
        "        ],\n"
        "    },\n"
        ")\n"
    )


def setup_cfg(package: NewPackage) -> str:
    """Return setup.cfg: the scripts go to lib/<package>, where `ros2 run` looks."""
    return (
        f"[develop]\nscript_dir=$base/lib/{package.name}\n"
        f"[install]\ninstall_scripts=$base/lib/{package.name}\n"
    )


def python_node(package: NewPackage) -> str:
    """Return the `--node-name` module of an ament_python package."""
    return (
        f"def main():\n    print('Hi from {package.name}.')\n\n\n"
        "if __name__ == '__main__':\n    main()\n"
    )


_LINTERS = {
    "test_copyright.py": (
        "2015",
        "from ament_copyright.main import main\nimport pytest\n\n\n"
        "# Remove the `skip` decorator once the source file(s) have a copyright header\n"
        "@pytest.mark.skip(reason='No copyright header has been placed in the generated source"
        " file.')\n@pytest.mark.copyright\n@pytest.mark.linter\ndef test_copyright():\n"
        "    rc = main(argv=['.', 'test'])\n    assert rc == 0, 'Found errors'\n",
    ),
    "test_flake8.py": (
        "2017",
        "from ament_flake8.main import main_with_errors\nimport pytest\n\n\n"
        "@pytest.mark.flake8\n@pytest.mark.linter\ndef test_flake8():\n"
        "    rc, errors = main_with_errors(argv=[])\n    assert rc == 0, \\\n"
        "        'Found %d code style errors / warnings:\\n' % len(errors) + \\\n"
        "        '\\n'.join(errors)\n",
    ),
    "test_pep257.py": (
        "2015",
        "from ament_pep257.main import main\nimport pytest\n\n\n"
        "@pytest.mark.linter\n@pytest.mark.pep257\ndef test_pep257():\n"
        "    rc = main(argv=['.', 'test'])\n    assert rc == 0, 'Found code style errors /"
        " warnings'\n",
    ),
}
TEST_FILES = tuple(_LINTERS)


def test_file(name: str) -> str:
    """Return one of the linter tests (TEST_FILES) of an ament_python package."""
    year, body = _LINTERS[name]
    return f"# Copyright {year} {_OSRF}\n{_APACHE_HEADER}\n{body}"


_LINT_SKIPS = """\
if(BUILD_TESTING)
  find_package(ament_lint_auto REQUIRED)
  # the following line skips the linter which checks for copyrights
  # comment the line when a copyright and license is added to all source files
  set(ament_cmake_copyright_FOUND TRUE)
  # the following line skips cpplint (only works in a git repo)
  # comment the line when this package is in a git repo and when
  # a copyright and license is added to all source files
  set(ament_cmake_cpplint_FOUND TRUE)
  ament_lint_auto_find_test_dependencies()
endif()
"""


def _cmake_node(node: str, dependencies: tuple[str, ...]) -> str:
    targets = "".join(f'  "{d}"\n' for d in dependencies)
    linked = f"ament_target_dependencies(\n  {node}\n{targets})\n" if dependencies else ""
    return (
        f"\nadd_executable({node} src/{node}.cpp)\n"
        f"target_include_directories({node} PUBLIC\n"
        "  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>\n"
        "  $<INSTALL_INTERFACE:include/${PROJECT_NAME}>)\n"
        f"target_compile_features({node} PUBLIC c_std_99 cxx_std_17)"
        "  # Require C99 and C++17\n"
        f"{linked}\n"
        f"install(TARGETS {node}\n  DESTINATION lib/${{PROJECT_NAME}})\n"
    )


def cmake_lists(package: NewPackage) -> str:
    """Return CMakeLists.txt of an ament_cmake package (with its `--node-name` executable)."""
    if package.dependencies:
        found = "".join(f"find_package({d} REQUIRED)\n" for d in package.dependencies)
    else:
        found = (
            "# uncomment the following section in order to fill in\n"
            "# further dependencies manually.\n"
            "# find_package(<dependency> REQUIRED)\n"
        )
    node = _cmake_node(package.node_name, package.dependencies) if package.node_name else ""
    return (
        "cmake_minimum_required(VERSION 3.8)\n"
        f"project({package.name})\n\n"
        'if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")\n'
        "  add_compile_options(-Wall -Wextra -Wpedantic)\n"
        "endif()\n\n"
        "# find dependencies\n"
        "find_package(ament_cmake REQUIRED)\n"
        f"{found}{node}\n{_LINT_SKIPS}\nament_package()\n"
    )


def cpp_node(package: NewPackage) -> str:
    """Return the `--node-name` source of an ament_cmake package."""
    return (
        "#include <cstdio>\n\n"
        "int main(int argc, char ** argv)\n{\n"
        "  (void) argc;\n  (void) argv;\n\n"
        f'  printf("hello world {package.name} package\\n");\n'
        "  return 0;\n}\n"
    )
