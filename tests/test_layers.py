"""No import runs back up the layer list (ARCHITECTURE.md, "Layers and who may import whom"):
cli → components → client → bus → interfaces, and launch imports none of them.

The launch family: the core (launch, its frontends, supervision, diffctl's launch-file extensions, launch_testing,
launch_pytest) imports only itself and errors/console; the ROS part (launch_ros, launch_testing_ros, nav2_common,
controller_manager's launch_utils) may also use the client (rclpy's API, as upstream's import rclpy) and the package
index. No component or layer of the chain imports any of them: only the command line does.

Every import statement of every module counts, those inside functions too (imported late is still imported).
The packages outside the chain (errors, console, ros_args, description, workspace, …) are shared by all."""

from __future__ import annotations

import ast
from pathlib import Path

DIFFCTL = Path(__file__).resolve().parents[1] / "diffctl"
# lowest first; a package not named here is a component
CHAIN = ("interfaces", "bus", "client")
TOOLS = ("cli", "gz", "overlay", "testing", "__main__")  # the command line and the ROS-named overlay: the top
SHARED = ("errors", "console", "ros_args", "source_paths", "signals", "description", "fuel", "workspace",
          "__init__", "module_alias")
LAUNCH_CORE = ("launch", "launch_xml", "launch_yaml", "supervision", "launch_extensions", "launch_testing",
               "launch_pytest")
LAUNCH_ROS = ("launch_ros", "launch_testing_ros", "nav2_common", "controller_manager")
LAUNCH_CORE_MAY_USE = (*LAUNCH_CORE, "errors", "console")
LAUNCH_ROS_MAY_USE = (*LAUNCH_CORE_MAY_USE, *LAUNCH_ROS, "client", "workspace", "interfaces")


def _level(package: str) -> int | None:
    if package in CHAIN:
        return CHAIN.index(package)
    if package in TOOLS:
        return len(CHAIN) + 1
    if package in SHARED:
        return None
    return len(CHAIN)  # a component


def _imports(path: Path) -> list[tuple[int, str]]:
    out = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            out.append((node.lineno, node.module))
            if node.module == "diffctl":
                out += [(node.lineno, f"diffctl.{a.name}") for a in node.names]
    return [(line, name) for line, name in out if name.startswith("diffctl.")]


def _package(path: Path) -> str:
    parts = path.relative_to(DIFFCTL).parts
    return parts[0] if len(parts) > 1 else parts[0].removesuffix(".py")


def test_no_import_runs_back_up_the_layers() -> None:
    wrong = []
    for path in sorted(DIFFCTL.rglob("*.py")):
        pkg = _package(path)
        for line, name in _imports(path):
            target = name.split(".")[1]
            if target == pkg:
                continue
            where = f"{path.relative_to(DIFFCTL.parent)}:{line}"
            if pkg in LAUNCH_CORE or pkg in LAUNCH_ROS:
                allowed = LAUNCH_CORE_MAY_USE if pkg in LAUNCH_CORE else LAUNCH_ROS_MAY_USE
                if target not in allowed:
                    wrong.append(f"{where}: {pkg} imports {name}")
                continue
            if target in LAUNCH_CORE or target in LAUNCH_ROS:
                if pkg not in TOOLS:
                    wrong.append(f"{where}: {pkg} imports {name}; only the command line starts launches")
                continue
            mine, theirs = _level(pkg), _level(target)
            if mine is not None and theirs is not None and theirs > mine:
                wrong.append(f"{path.relative_to(DIFFCTL.parent)}:{line}: {pkg} imports {name}, a layer above it")
    assert not wrong, "\n".join(wrong)


def test_the_chain_is_there() -> None:
    # the test above would pass vacuously on a renamed package
    assert all((DIFFCTL / p).is_dir() for p in (*CHAIN, "cli", *LAUNCH_CORE, *LAUNCH_ROS))
    assert any(_package(p) == "bus" and n.startswith("diffctl.interfaces") for p in DIFFCTL.rglob("*.py")
               for _, n in _imports(p))
