"""diffctl.launch_legacy imports its names on first use: the fork server and forked components skip the engine."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

import diffctl.launch_legacy as api


def test_every_public_name_resolves_to_its_module() -> None:
    for name in api.__all__:
        assert getattr(api, name) is getattr(importlib.import_module(api._ORIGIN[name]), name), name
    assert sorted(dir(api)) == sorted(api.__all__)
    with pytest.raises(AttributeError):
        api.NoSuchAction  # noqa: B018


def test_the_fork_server_module_imports_no_engine() -> None:
    code = (
        "import sys, diffctl.launch_legacy.zygote, diffctl.launch_legacy.fork_server, "
        "diffctl.launch_legacy.environment\n"
        "print(sorted(m for m in sys.modules if m.startswith('diffctl.launch_legacy.')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    loaded = eval(out)  # a printed list of module names
    assert loaded == [
        "diffctl.launch_legacy.environment",
        "diffctl.launch_legacy.fork_server",
        "diffctl.launch_legacy.zygote",
    ]


def test_a_launch_file_missing_name_lists_what_diffctl_launch_provides() -> None:
    from diffctl.launch_legacy.python_frontend import missing

    err = missing("diffctl.launch_legacy", "NoSuchAction")
    assert "LaunchDescription" in str(err.hint) and "OnProcessExit" in str(err.hint)
