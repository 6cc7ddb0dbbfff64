"""`diffctl launch` starts its fork server before click and the commands are imported (cli/launch_start.py),
and the command keeps that server only when click read the same working options."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import psutil
import pytest

from diffctl.cli import launch_start


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["sim_control", "viz_port:=0"], (None, None)),
        (["--log-dir", "/tmp/a", "pkg", "f.py", "--log-dir=/tmp/b", "--no-color"], (None, Path("/tmp/b"))),
        (["--workspace=/ws", "-d", "f.yaml", "--exit-code", "ros"], (Path("/ws"), None)),
        (["f.yaml", "-s"], None),  # describes only: no server
        (["f.yaml", "--print"], None),
        (["--help"], None),
        (["f.yaml", "-ds"], None),  # a cluster of short flags: click's to read
        (["--log-dir"], None),
        (["--no-router"], None),  # no launch file
        (["f.yaml", "--ros-args", "-r", "a:=b"], None),
    ],
)
def test_the_early_reading_of_the_command_line(args, expected) -> None:
    assert launch_start.working_options(args) == expected


def test_the_fork_server_is_execd_before_click_and_serves_the_launch(tmp_path) -> None:
    launch_file = tmp_path / "one.yaml"
    launch_file.write_text(
        "launch:\n- executable: {cmd: $(env PYTHON) -m diffctl --version, name: version, output: screen}\n"
    )
    program = textwrap.dedent(
        """
        import subprocess, sys
        before = set(sys.modules)
        real = subprocess.Popen.__init__
        def popen(self, args, *a, **k):
            if "diffctl.supervision.zygote" in args:
                print("imported at the server's start:", "click" in sys.modules, "diffctl.cli.main" in sys.modules,
                      flush=True)
                # nor what only later steps use (each a few ms before the server's exec)
                later = {"typing", "concurrent.futures", "difflib", "asyncio"}
                print("also:", sorted(later & (set(sys.modules) - before)), flush=True)
            real(self, args, *a, **k)
        subprocess.Popen.__init__ = popen
        sys.argv = ["diffctl", "launch", sys.argv[1], "--log-dir", sys.argv[2], "--no-router"]
        from diffctl.__main__ import run
        run()
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", program, str(launch_file), str(tmp_path / "log")],
        capture_output=True,
        text=True,
        timeout=120,
        env=dict(os.environ, PYTHON=sys.executable),
    )
    out = done.stdout + done.stderr
    assert done.returncode == 0, out
    lines = out.splitlines()
    # one server, started first thing; the component it forked printed the version
    assert [line for line in lines if line.startswith("imported at")] == ["imported at the server's start: False False"]
    assert [line for line in lines if line.startswith("also:")] == ["also: []"]
    assert any("diffctl, version" in line for line in lines), out


def test_an_early_server_is_kept_only_for_the_options_click_read(tmp_path) -> None:
    before = dict(os.environ)
    try:
        launch_start.early_start(["launch", "f.yaml", "--log-dir", str(tmp_path / "a")])
        first = launch_start._early[4].pid if launch_start._early else None
        assert first is not None and psutil.Process(first).is_running()
        assert launch_start.take_early(None, tmp_path / "b") is None  # read differently: gone, environment back
        assert dict(os.environ) == before
        assert not psutil.pid_exists(first)  # killed and reaped

        launch_start.early_start(["launch", "f.yaml", "--log-dir", str(tmp_path / "a")])
        taken = launch_start.take_early(None, tmp_path / "a")
        assert taken is not None
        _, run_dir, server = taken
        assert run_dir == tmp_path / "a" and psutil.Process(server.pid).is_running()
        assert os.environ["DIFFCTL_LOG_DIR"] == str((tmp_path / "a").resolve())
        assert launch_start.take_early(None, tmp_path / "a") is None  # taken once
        server.close(kill=True)
    finally:
        launch_start._discard()
        os.environ.clear()
        os.environ.update(before)
