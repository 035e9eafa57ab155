"""`ros2 pkg create`: a new ament_python or ament_cmake package, as Jazzy's ros2pkg makes it."""

from __future__ import annotations

import argparse
import getpass
import os
import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ...verbkit.context import Context
from ...verbkit.registry import verb
from . import templates as t

__all__ = ["add_arguments", "main"]

_CPP_LIBRARY = (
    "The course's `ros2 pkg create` makes ament_python packages (with --node-name and"
    " --library-name) and ament_cmake packages (with --node-name); a C++ library or a plain"
    " cmake package is not offered: try --build-type ament_python --library-name {library}."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of `ros2 pkg create`, in ros2pkg 0.32.2's order with its help texts."""
    parser.add_argument("package_name", help="The package name")
    parser.add_argument(
        "--package-format",
        "--package_format",
        type=int,
        default=3,
        choices=[2, 3],
        help="The package.xml format.",
    )
    parser.add_argument(
        "--description",
        default="TODO: Package description",
        help="The description given in the package.xml",
    )
    parser.add_argument(
        "--license",
        default="TODO: License declaration",
        help="The license attached to this package; this can be an arbitrary string, but a "
        "LICENSE file will only be generated if it is one of the supported licenses "
        "(pass '?' to get a list)",
    )
    parser.add_argument(
        "--destination-directory",
        default=os.curdir,
        help="Directory where to create the package directory",
    )
    parser.add_argument(
        "--build-type",
        default="ament_cmake",
        choices=["cmake", "ament_cmake", "ament_python"],
        help="The build type to process the package with",
    )
    parser.add_argument("--dependencies", nargs="+", default=[], help="list of dependencies")
    parser.add_argument(
        "--maintainer-email", help="email address of the maintainer of this package"
    )
    parser.add_argument(
        "--maintainer-name",
        default=getpass.getuser(),
        help="name of the maintainer of this package",
    )
    parser.add_argument("--node-name", help="name of the empty executable")
    parser.add_argument("--library-name", help="name of the empty library")


def _git_email(cwd: str) -> str:
    """Return `git config user.email` (what ros2pkg uses when no email is given), or ''."""
    git = shutil.which("git")
    if git is None:
        return ""
    done = subprocess.run(
        [git, "config", "user.email"], cwd=cwd, capture_output=True, text=True, check=False
    )
    return done.stdout.rstrip()


def _summary(package: t.NewPackage, destination: str, library: str | None) -> str:
    lines = [
        "going to create a new package",
        f"package name: {package.name}",
        f"destination directory: {destination}",
        f"package format: {package.package_format}",
        "version: 0.0.0",
        f"description: {package.description}",
        f"maintainer: {[f'{package.maintainer_name} <{package.maintainer_email}>']}",
        f"licenses: {[package.license]}",
        f"build type: {package.build_type}",
        f"dependencies: {list(package.dependencies)}",
    ]
    lines += [f"node_name: {package.node_name}"] if package.node_name else []
    lines += [f"library_name: {library}"] if library else []
    return "".join(f"{line}\n" for line in lines)


class _Writer:
    """Create folders and files under `base`, printing each as ros2pkg does."""

    def __init__(self, base: Path, out: Callable[[str], None]) -> None:
        self.base, self.out = base, out

    def folder(self, path: str) -> str:
        self.out(f"creating folder {path}\n")
        (self.base / path).mkdir(parents=True, exist_ok=True)
        return path

    def file(self, path: str, text: str) -> None:
        self.out(f"creating {path}\n")
        (self.base / path).parent.mkdir(parents=True, exist_ok=True)
        (self.base / path).write_text(text)


def _python(package: t.NewPackage, w: _Writer, root: str, library: str | None) -> None:
    w.out("creating source folder\n")
    source = w.folder(os.path.join(root, package.name))
    w.file(os.path.join(root, "setup.py"), t.setup_py(package))
    w.file(os.path.join(root, "setup.cfg"), t.setup_cfg(package))
    w.file(os.path.join(w.folder(os.path.join(root, "resource")), package.name), "")
    w.file(os.path.join(source, "__init__.py"), "")
    tests = w.folder(os.path.join(root, "test"))
    for name in t.TEST_FILES:
        w.file(os.path.join(tests, name), t.test_file(name))
    if package.node_name:
        w.file(os.path.join(source, f"{package.node_name}.py"), t.python_node(package))
    if library:
        w.file(os.path.join(w.folder(os.path.join(source, library)), "__init__.py"), "")


def _cmake(package: t.NewPackage, w: _Writer, root: str) -> None:
    w.out("creating source and include folder\n")
    source = w.folder(os.path.join(root, "src"))
    w.folder(os.path.join(root, "include", package.name))
    w.file(os.path.join(root, "CMakeLists.txt"), t.cmake_lists(package))
    if package.node_name:
        w.file(os.path.join(source, f"{package.node_name}.cpp"), t.cpp_node(package))


def _node_name(args: argparse.Namespace, ctx: Context) -> str | None:
    if args.node_name and args.node_name == args.library_name:
        ctx.console.err("[WARNING] node name can not be equal to the library name\n")
        ctx.console.err(f"[WARNING] renaming node to {args.node_name}_node\n")
        return f"{args.node_name}_node"
    return args.node_name


@verb("pkg", "create", "Create a new ROS 2 package", arguments=add_arguments, graph=False)
def main(args: argparse.Namespace, ctx: Context) -> Any:
    """`ros2 pkg create <package_name> [options]`."""
    if args.license == "?":
        ctx.console.out("Supported licenses:\n" + "\n".join(t.LICENSES) + "\n")
        return 0
    if (args.library_name and args.build_type != "ament_python") or args.build_type == "cmake":
        return _CPP_LIBRARY.format(library=args.library_name or "<name>")
    cwd = ctx.cwd or os.getcwd()
    email = args.maintainer_email or _git_email(cwd) or f"{args.maintainer_name}@todo.todo"
    if args.build_type == "ament_python" and args.package_name == "test":
        return (
            "Aborted since 'ament_python' packages can't be named 'test'. Please choose a "
            "different package name."
        )
    root = os.path.join(args.destination_directory, args.package_name)
    if os.path.exists(os.path.join(cwd, root)):
        return (
            f"\nAborted!\nThe directory already exists: {root}\nEither remove the directory "
            "or choose a different destination directory or package name"
        )
    package = t.NewPackage(
        name=args.package_name,
        build_type=args.build_type,
        package_format=args.package_format,
        description=args.description,
        license=args.license,
        maintainer_name=args.maintainer_name,
        maintainer_email=email,
        dependencies=tuple(args.dependencies),
        node_name=_node_name(args, ctx),
    )
    destination = os.path.normpath(os.path.join(cwd, args.destination_directory))
    ctx.console.out(_summary(package, destination, args.library_name))
    w = _Writer(Path(cwd), ctx.console.out)
    w.folder(root)
    w.file(os.path.join(root, "package.xml"), t.package_xml(package))
    if package.build_type == "ament_python":
        _python(package, w, root, args.library_name)
    else:
        _cmake(package, w, root)
    if package.license in t.LICENSES:
        (Path(cwd) / root / "LICENSE").write_text(t.license_text(package.license))
        return 0
    ctx.console.out(
        f"\n[WARNING]: Unknown license '{package.license}'.  This has been set in the "
        "package.xml, but no LICENSE file has been created.\nIt is recommended to use one of "
        "the ament license identifiers:\n" + "\n".join(t.LICENSES) + "\n"
    )
    return 0
