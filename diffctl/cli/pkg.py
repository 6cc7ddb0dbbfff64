"""`diffctl pkg list|prefix|xml|executables`: the `ros2 pkg` counterpart — which packages were found, and where.

Packages come from the user's workspace (the enclosing folder whose src/ holds package.xml files, or
--workspace / $DIFFCTL_WORKSPACE), then AMENT_PREFIX_PATH / COLCON_PREFIX_PATH install trees, then diffctl.
"""

from __future__ import annotations

import os
from pathlib import Path

import click

from diffctl.console import console, table, warn


@click.group()
@click.option(
    "--workspace",
    "workspace_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="The workspace to use (default: $DIFFCTL_WORKSPACE, else the one enclosing the current directory).",
)
def pkg(workspace_dir: Path | None) -> None:
    """Show the packages diffctl finds and where each comes from (ros2 pkg).

    \b
    Example:
      diffctl pkg list
      diffctl pkg prefix my_robot_description --share
      diffctl pkg --workspace ~/ros2_ws list
    """
    from diffctl.workspace import WORKSPACE_ENV, find_workspace

    if workspace_dir is not None:
        os.environ[WORKSPACE_ENV] = str(find_workspace(explicit=workspace_dir))


@pkg.command("list")
def pkg_list() -> None:
    """List every package found: name, where it comes from, its folder (ros2 pkg list).

    A workspace package shows its source folder; rules of its CMakeLists.txt or setup.py that install
    nothing (a missing folder, code diffctl does not run) are listed as warnings.

    \b
    Example:
      diffctl pkg list
    """
    from diffctl.errors import ConfigError
    from diffctl.workspace import find_workspace, list_packages
    from diffctl.workspace.package_index import component_packages
    from diffctl.workspace.resolve import install_index, scan_workspace

    ws = find_workspace()
    scan = scan_workspace(ws) if ws is not None else None
    packages = list_packages(ws, scan=scan)
    rows = [(p.name, p.origin, p.build_type, str(p.source or p.prefix or p.share)) for p in packages]
    named = {p.name for p in packages}
    rows += [(name, "diffctl", "executables only", "") for name in sorted(component_packages() - named)]
    title = f"workspace: {ws}" if ws is not None else "no workspace (none encloses the current directory)"
    console.print(table(title, ["package", "from", "build type", "location"], rows, box=None))
    if scan is not None:
        for name, paths in sorted(scan.duplicates.items()):
            warn(f"package {name!r} is defined twice: " + " and ".join(str(p) for p in paths))
        for problem in scan.broken:
            warn(problem)
        for name, manifest in sorted(scan.manifests.items()):
            try:
                problems = install_index(manifest).problems
            except ConfigError as e:  # a broken CMakeLists.txt of one package must not hide the others
                problems = [str(e)]
            for problem in problems:
                warn(f"{name}: {problem}")


@pkg.command("prefix")
@click.argument("package")
@click.option("--share", is_flag=True, help="Print the share directory instead of the prefix.")
def pkg_prefix(package: str, share: bool) -> None:
    """Print PACKAGE's install prefix, or its share directory with --share (ros2 pkg prefix).

    A workspace package's prefix is a symlink tree in diffctl's cache, refreshed from its sources.

    \b
    Example:
      diffctl pkg prefix my_robot_description --share
    """
    from diffctl.workspace import find_package

    found = find_package(package)
    if share:
        click.echo(str(found.share))
    else:
        click.echo(str(found.prefix if found.prefix is not None else found.share))


@pkg.command("xml")
@click.argument("package")
def pkg_xml(package: str) -> None:
    """Print PACKAGE's package.xml (ros2 pkg xml).

    \b
    Example:
      diffctl pkg xml my_robot_description
    """
    from diffctl.errors import ConfigError
    from diffctl.workspace import find_package

    found = find_package(package)
    manifest = (found.source / "package.xml") if found.source is not None else found.share / "package.xml"
    if not manifest.is_file():
        raise ConfigError(f"package {package!r} has no package.xml", hint=f"looked in {manifest.parent}")
    click.echo(manifest.read_text(errors="replace"), nl=False)


@pkg.command("executables")
@click.argument("package", required=False)
def pkg_executables(package: str | None) -> None:
    """List executables as `PACKAGE EXECUTABLE` lines, of one package or of all (ros2 pkg executables).

    \b
    Example:
      diffctl pkg executables controller_manager
    """
    from diffctl.workspace import find_package, list_packages
    from diffctl.workspace.package_index import component_packages, executables

    if package is not None:
        if package not in component_packages():
            find_package(package)  # an unknown package is an error naming what was searched
        names = [package]
    else:
        names = sorted({p.name for p in list_packages()} | component_packages())
    for name in names:
        for exe in executables(name):
            click.echo(f"{name} {exe}")
