"""Package environment hooks: dsv semantics against colcon-core's own prefix scripts (the oracle), and a
workspace's `ament_environment_hooks()` applied as sourcing its setup.bash would."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.errors import ConfigError
from diffctl.workspace.env_hooks import HookEnv, apply_install_tree, configure, order_packages, process_dsv
from tests.workspace.conftest import package_xml, write_tree

colcon_shell = pytest.importorskip("colcon_core.shell.sh", reason="colcon-core is the oracle")
from colcon_core.shell.dsv import DsvShell  # noqa: E402
from colcon_core.shell.sh import ShShell  # noqa: E402


def _install_package(install: Path, name: str, deps: list[str], files: dict[str, str]) -> Path:
    """One package of an isolated colcon install tree, its package.dsv written by colcon itself."""
    prefix = install / name
    write_tree(prefix, {f"share/colcon-core/packages/{name}": os.pathsep.join(deps), **files})
    hooks = [(f"share/{name}/local_setup.{ext}", ()) for ext in ("bash", "dsv", "sh", "zsh")]
    DsvShell().create_package_script(prefix, name, hooks)
    return prefix


def _sourced_by_colcon(install: Path, env: dict[str, str]) -> dict[str, str]:
    ShShell().create_prefix_script(install, False)  # local_setup.sh + _local_setup_util_sh.py
    out = subprocess.run(
        ["sh", "-c", f'. "{install}/local_setup.sh" && env -0'], env=env, capture_output=True, check=True, timeout=60
    )
    return dict(item.split("=", 1) for item in out.stdout.decode().split("\0") if "=" in item)


def test_dsv_semantics_and_order_match_colcons_prefix_scripts(tmp_path: Path) -> None:
    install = tmp_path / "install"
    _install_package(
        install,
        "robot_description",
        [],
        {
            "share/robot_description/models/robot/model.config": "<model/>",
            "share/robot_description/local_setup.dsv": "source;share/robot_description/environment/models.dsv\n"
            "source;share/robot_description/environment/models.sh\n",
            # the .dsv sibling wins: this .sh must not run
            "share/robot_description/environment/models.sh": "export WRONG=1\n",
            "share/robot_description/environment/models.dsv": "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;"
            "share/robot_description/models;share\n"
            "prepend-non-duplicate-if-exists;GZ_SIM_RESOURCE_PATH;share/robot_description/nowhere\n"
            "append-non-duplicate;SDF_PATH;share/robot_description/models\n"
            "set;ROBOT_HOME;share/robot_description\n"
            "set;ROBOT_MODE;literal-value\n"
            "set-if-unset;ALREADY;ignored\n"
            "set-if-unset;FRESH;fresh\n"
            "# a comment\n",
        },
    )
    _install_package(
        install,
        "robot_gazebo",
        ["robot_description", "not_in_this_tree"],
        {
            "share/robot_gazebo/worlds/w.sdf": "<sdf/>",
            "share/robot_gazebo/local_setup.dsv": "source;share/robot_gazebo/environment/paths.dsv\n"
            "source;share/robot_gazebo/environment/shell_only.sh\n",
            "share/robot_gazebo/environment/paths.dsv": "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;"
            "share/robot_gazebo/worlds;share\n",
            "share/robot_gazebo/environment/shell_only.sh": 'export GAZEBO_WORLDS_DIR="$COLCON_CURRENT_PREFIX/w"\n',
        },
    )
    _install_package(
        install,
        "another",
        [],
        {
            "share/another/local_setup.dsv": "source;share/another/environment/a.dsv\n",
            "share/another/environment/a.dsv": "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share\n",
        },
    )
    base = {"PATH": os.environ["PATH"], "HOME": str(tmp_path), "GZ_SIM_RESOURCE_PATH": "/usr/share/x", "ALREADY": "1"}
    expected = _sourced_by_colcon(install, dict(base))
    env = dict(base)
    changed = apply_install_tree(env, install)
    for name in ("GZ_SIM_RESOURCE_PATH", "SDF_PATH", "ROBOT_HOME", "ROBOT_MODE", "ALREADY", "FRESH"):
        assert env.get(name) == expected.get(name), name
    assert env["GAZEBO_WORLDS_DIR"] == expected["GAZEBO_WORLDS_DIR"] == f"{install}/robot_gazebo/w"
    assert "WRONG" not in env and "WRONG" not in expected
    assert env["GZ_SIM_RESOURCE_PATH"].split(":")[:2] == [
        f"{install}/robot_gazebo/share",
        f"{install}/robot_gazebo/share/robot_gazebo/worlds",
    ]  # dependents end up first: robot_gazebo is sourced after robot_description and prepends
    assert "GZ_SIM_RESOURCE_PATH" in changed


def test_unknown_hook_type_is_one_located_error(tmp_path: Path) -> None:
    hook = tmp_path / "x.dsv"
    hook.write_text("prepend-non-duplicate;A;b\nprepend-unique;GZ_SIM_RESOURCE_PATH;share\n")
    with pytest.raises(ConfigError) as e:
        process_dsv(HookEnv({}), str(hook), str(tmp_path))
    assert e.value.line == 2 and "prepend-unique" in str(e.value) and "prepend-non-duplicate" in str(e.value)
    # what no environment can hold (the Fuel and hook fuzz found a NUL) is a located error, not a ValueError
    for line, said in (("set;GZ SIM;x", "'GZ SIM' is not an environment variable name"),
                       ("prepend-non-duplicate;\0A;share", "is not an environment variable name"),
                       ("append-non-duplicate;A;share/\0x", "holds a NUL character")):
        hook.write_text(f"set;OK;1\n{line}\n")
        with pytest.raises(ConfigError, match=said) as e:
            process_dsv(HookEnv({}), str(hook), str(tmp_path))
        assert e.value.line == 2


def test_a_configured_hooks_error_names_the_users_dsv_in_and_line(tmp_path: Path) -> None:
    """`ament_environment_hooks(hooks/x.dsv.in)` is configured in memory for the package's prefix in diffctl's
    cache: an error in it names the user's `hooks/x.dsv.in` and its line (before: the cached copy's path),
    and a shell hook's complaint names the user's `.sh.in` too (a shell sourcing it goes on, so does diffctl)."""
    from diffctl.workspace import use_in_children

    ws = tmp_path / "ws"
    pkg = ws / "src" / "my_robot_gazebo"
    write_tree(pkg, {
        "package.xml": package_xml("my_robot_gazebo"),
        "CMakeLists.txt": "project(my_robot_gazebo)\ninstall(DIRECTORY worlds DESTINATION share/${PROJECT_NAME})\n"
        'ament_environment_hooks("${CMAKE_CURRENT_SOURCE_DIR}/hooks/${PROJECT_NAME}.dsv.in" hooks/paths.sh.in)\n',
        "hooks/my_robot_gazebo.dsv.in": "# worlds\n"
        "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share/@PROJECT_NAME@/worlds\n"
        "prepend-non-duplcate;GZ_SIM_RESOURCE_PATH;share\n",
        "hooks/paths.sh.in": "export ROBOT_HOOK=1\nif [ then\n",
        "worlds/w.sdf": "<sdf/>",
    })
    env = {"PATH": os.environ["PATH"], "XDG_CACHE_HOME": str(tmp_path / "cache")}
    with pytest.raises(ConfigError) as e:
        use_in_children(ws, env)
    assert str(e.value).startswith(
        f"{pkg / 'hooks/my_robot_gazebo.dsv.in'}:3: unknown environment hook type 'prepend-non-duplcate' "
        "(did you mean 'prepend-non-duplicate'"), str(e.value)

    (pkg / "hooks/my_robot_gazebo.dsv.in").write_text("prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share\n")
    shown = subprocess.run(
        [sys.executable, "-c", "import os\nfrom pathlib import Path\nfrom diffctl.workspace import use_in_children\n"
         f"env = dict(os.environ)\nuse_in_children(Path({str(ws)!r}), env)\nprint(env['ROBOT_HOOK'])"],
        env={**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")}, capture_output=True, text=True, timeout=60)
    assert shown.stdout == "1\n", shown.stderr
    assert shown.stderr.startswith(f"warning: {pkg / 'hooks/paths.sh.in'}: line "), shown.stderr
    assert "diffctl-hook" not in shown.stderr and "/cache/" not in shown.stderr

def test_order_is_topological_then_alphabetical() -> None:
    assert order_packages({"c": set(), "b": {"a"}, "a": {"c"}, "d": set()}) == ["c", "a", "b", "d"]
    with pytest.raises(ConfigError, match="circular"):
        order_packages({"a": {"b"}, "b": {"a"}})


def test_configure_substitutes_at_variables_only() -> None:
    text = "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;@CMAKE_INSTALL_PREFIX@/share/@PROJECT_NAME@/${X}@NOPE@"
    assert configure(text, {"PROJECT_NAME": "p", "CMAKE_INSTALL_PREFIX": "/i"}) == (
        "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;/i/share/p/${X}"
    )


def test_workspace_hooks_from_cmakelists_reach_the_environment(tmp_path: Path, monkeypatch) -> None:
    from diffctl.workspace import use_in_children

    ws = tmp_path / "ws"
    write_tree(
        ws / "src" / "my_robot_gazebo",
        {
            "package.xml": package_xml("my_robot_gazebo").replace(
                "<export>", "<exec_depend>my_robot_description</exec_depend><export>"
            ),
            "CMakeLists.txt": "cmake_minimum_required(VERSION 3.8)\nproject(my_robot_gazebo)\n"
            "find_package(ament_cmake REQUIRED)\n"
            "install(DIRECTORY worlds DESTINATION share/${PROJECT_NAME})\n"
            'ament_environment_hooks("${CMAKE_CURRENT_SOURCE_DIR}/hooks/${PROJECT_NAME}.dsv.in")\n'
            "ament_package()\n",
            "hooks/my_robot_gazebo.dsv.in": "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share/@PROJECT_NAME@/worlds\n",
            "worlds/w.sdf": "<sdf/>",
        },
    )
    write_tree(
        ws / "src" / "my_robot_description",
        {
            "package.xml": package_xml("my_robot_description"),
            "CMakeLists.txt": "project(my_robot_description)\n"
            "install(DIRECTORY models DESTINATION share/${PROJECT_NAME})\n"
            "ament_environment_hooks(hooks/models.sh.in)\n"
            "ament_package()\n",
            # a shell hook alone is sourced (with ament's helper functions defined, as its local_setup.sh does)
            "hooks/models.sh.in": 'ament_prepend_unique_value GZ_SIM_RESOURCE_PATH "@CMAKE_INSTALL_PREFIX@/share"\n',
            "models/robot/model.config": "<model/>",
        },
    )
    env = {"PATH": os.environ["PATH"]}
    use_in_children(ws, env)
    paths = env["GZ_SIM_RESOURCE_PATH"].split(":")
    assert len(paths) == 2
    gazebo, description = Path(paths[0]), Path(paths[1])
    assert (gazebo / "w.sdf").is_file()  # the dependent's entry comes first
    assert (description / "my_robot_description" / "models" / "robot" / "model.config").is_file()
    before = dict(env)
    use_in_children(ws, env)  # idempotent, as sourcing twice is
    assert env == before


ROBOT_WORLDS_SETUP = """from setuptools import setup

package_name = 'robot_worlds'
setup(
    name=package_name,
    version='0.0.1',
    packages=[],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/hook', ['hooks/models.dsv', 'hooks/models.sh', 'hooks/home.dsv']),
        ('share/' + package_name + '/models/robot', ['models/robot/model.config']),
    ],
)
"""
ROBOT_WORLDS_HOOKS = {
    "hooks/models.dsv": "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share/robot_worlds/models\n",
    "hooks/models.sh": "export WRONG_SH=1\n",  # its .dsv sibling wins, in colcon as here
    "hooks/home.dsv": "set;ROBOT_WORLDS_HOME;share/robot_worlds\n",
}
# colcon-metadata's colcon.pkg: YAML, hooks relative to the install prefix ([path, args…] accepted)
COLCON_PKG = """hooks:
  - share/robot_worlds/hook/models.dsv
  - share/robot_worlds/hook/models.sh
  - [share/robot_worlds/hook/home.dsv, unused-argument]
"""


def test_colcon_pkg_hooks_of_a_source_package_apply_as_colcons_package_dsv(tmp_path: Path) -> None:
    """An ament_python package whose colcon.pkg lists hooks it installs with data_files: diffctl applies them
    from its sources as sourcing colcon's install of it does (colcon-core's own descriptor update, package
    script and prefix script are the oracle)."""
    import yaml
    from colcon_core.package_augmentation import update_descriptor
    from colcon_core.package_descriptor import PackageDescriptor

    from diffctl.workspace import use_in_children

    ws = tmp_path / "ws"
    files = {
        "package.xml": package_xml("robot_worlds", "ament_python"),
        "setup.py": ROBOT_WORLDS_SETUP,
        "resource/robot_worlds": "",
        "colcon.pkg": COLCON_PKG,
        "models/robot/model.config": "<model/>",
        **ROBOT_WORLDS_HOOKS,
    }
    src = write_tree(ws / "src" / "robot_worlds", files)
    # the oracle: colcon's install of the package, its package.dsv listing the descriptor's hooks
    desc = PackageDescriptor(src)
    desc.type, desc.name = "ros.ament_python", "robot_worlds"
    update_descriptor(desc, yaml.safe_load(COLCON_PKG))
    install = tmp_path / "install"
    prefix = install / "robot_worlds"
    write_tree(
        prefix,
        {
            "share/colcon-core/packages/robot_worlds": "",
            "share/robot_worlds/models/robot/model.config": "<model/>",
            **{f"share/robot_worlds/hook/{Path(k).name}": v for k, v in ROBOT_WORLDS_HOOKS.items()},
        },
    )
    hooks = [(h[0], h[1:]) if isinstance(h, list) else (h, ()) for h in desc.hooks]
    DsvShell().create_package_script(prefix, "robot_worlds", hooks)
    base = {"PATH": os.environ["PATH"], "GZ_SIM_RESOURCE_PATH": "/opt/user/models"}
    expected = _sourced_by_colcon(install, dict(base))
    env = dict(base)
    use_in_children(ws, env)
    ours = env["GZ_SIM_RESOURCE_PATH"].split(":")
    theirs = expected["GZ_SIM_RESOURCE_PATH"].split(":")
    assert ours[1:] == theirs[1:] == ["/opt/user/models"]
    # the same place inside each prefix: diffctl's from the sources, colcon's in its install
    ours_prefix = Path(ours[0]).parents[2]
    models = Path("share/robot_worlds/models")
    assert Path(ours[0]).relative_to(ours_prefix) == Path(theirs[0]).relative_to(prefix) == models
    assert (Path(ours[0]) / "robot" / "model.config").is_file()
    home = Path(env["ROBOT_WORLDS_HOME"]).relative_to(ours_prefix)
    assert home == Path(expected["ROBOT_WORLDS_HOME"]).relative_to(prefix) == Path("share/robot_worlds")
    assert "WRONG_SH" not in env and "WRONG_SH" not in expected


def test_colcon_pkg_with_bad_hooks_is_one_located_error(tmp_path: Path) -> None:
    from diffctl.workspace.env_hooks import colcon_pkg_hooks

    (tmp_path / "colcon.pkg").write_text("hooks: share/x/hook/a.dsv\n")
    with pytest.raises(ConfigError) as e:
        colcon_pkg_hooks(tmp_path)
    assert e.value.source == str(tmp_path / "colcon.pkg") and "'hooks' must be a list" in str(e.value)
    (tmp_path / "colcon.pkg").write_text("name: x\nhooks: [a.dsv\n")
    with pytest.raises(ConfigError) as e:
        colcon_pkg_hooks(tmp_path)
    assert "not valid YAML" in str(e.value) and e.value.line is not None
    (tmp_path / "colcon.pkg").write_text('{"name": "x", "hooks": ["share/x/hook/a.dsv", ["share/x/hook/b.sh", "1"]]}')
    assert colcon_pkg_hooks(tmp_path) == ["share/x/hook/a.dsv", "share/x/hook/b.sh"]


def test_an_unsourced_install_tree_applies_as_its_local_setup_would(tmp_path: Path) -> None:
    """A workspace built with colcon whose install/ the shell never sourced: the packages only the install
    holds are applied as colcon's local_setup.sh applies them; a package whose sources are in the workspace
    comes from them, not from its (possibly stale) build; a sourced install/ is left to the shell."""
    from diffctl.workspace import use_in_children

    ws = tmp_path / "ws"
    install = ws / "install"
    _install_package(
        install,
        "scenery",
        [],
        {
            "share/scenery/local_setup.dsv": "source;share/scenery/hook/models.dsv\n",
            "share/scenery/hook/models.dsv": "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share/scenery/models\n"
            "set;SCENERY_HOME;share/scenery\n",
            "share/scenery/models/tree/model.config": "<model/>",
        },
    )
    _install_package(
        install,
        "robot_worlds",
        ["scenery"],
        {
            "share/robot_worlds/local_setup.dsv": "source;share/robot_worlds/hook/stale.dsv\n",
            "share/robot_worlds/hook/stale.dsv": "set;STALE_BUILD;1\n",
        },
    )
    write_tree(ws / "src" / "robot_worlds", {"package.xml": package_xml("robot_worlds")})
    base = {"PATH": os.environ["PATH"]}
    expected = _sourced_by_colcon(install, dict(base))
    env = dict(base)
    use_in_children(ws, env)
    assert env["GZ_SIM_RESOURCE_PATH"] == expected["GZ_SIM_RESOURCE_PATH"] == f"{install}/scenery/share/scenery/models"
    assert env["SCENERY_HOME"] == expected["SCENERY_HOME"]
    assert expected["STALE_BUILD"] == "1" and "STALE_BUILD" not in env  # the sources win over the build
    sourced = {**base, "COLCON_PREFIX_PATH": str(install)}
    use_in_children(ws, sourced)
    assert "SCENERY_HOME" not in sourced and "GZ_SIM_RESOURCE_PATH" not in sourced
