"""`diffctl test`: run launch tests and the pytest files beside them (launch_test, colcon test).

Each file runs in a process of its own, on a Zenoh router and ROS_DOMAIN_ID of its own, `-j N` at a time; its
output is printed as `launch_test` prints it when it is done, then a summary; exit code 1 on any failure.
"""

from __future__ import annotations

import re
import sys
import tempfile
from pathlib import Path

import click

from diffctl.errors import ConfigError


@click.command("test")
@click.argument("paths", nargs=-1, type=click.Path(path_type=Path), metavar="[PATH ...] [NAME:=VALUE ...]")
@click.option("--packages-select", multiple=True, metavar="PKG",
              help="Only these packages' tests (`--packages-select a b`, as colcon, or repeated).")
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=1, show_default=True,
              help="Test files run at the same time, each on its own router and domain.")
@click.option("--junit-xml", type=click.Path(dir_okay=False, path_type=Path), help="Write JUnit XML results here.")
@click.option("--timeout", "timeout_s", type=click.FloatRange(min=0.1), default=120.0, show_default=True,
              help="Seconds a test file may take; then it and its processes are stopped.")
@click.option("--artifacts", type=click.Path(file_okay=False, path_type=Path),
              help="On failure, each process's log, an MCAP bag of the run and a picture of the scene, here.")
@click.option("--init", "init_package", metavar="PKG", help="Write a smoke test for the robot of package PKG.")
@click.option("-o", "--output", "init_output", type=click.Path(dir_okay=False, path_type=Path),
              help="With --init: the file to write (default: the package's test/test_<PKG>_smoke.launch.py).")
@click.option("--workspace", "workspace_dir", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="The ROS workspace (default: $DIFFCTL_WORKSPACE, else the enclosing one).")
def test(paths: tuple[Path, ...], packages_select: tuple[str, ...], jobs: int, junit_xml: Path | None,
         timeout_s: float, artifacts: Path | None, init_package: str | None, init_output: Path | None,
         workspace_dir: Path | None) -> int:
    """Run launch test files (generate_test_description) and pytest files, as launch_test and colcon test.

    PATH is a launch test file (test_*.launch.py, *_launch_test.py), a pytest file, or a folder of them.
    Without PATH, inside a workspace, every package's test/ folder is searched (as colcon test).
    NAME:=VALUE arguments go to every launch test's description (as launch_test's).

    \b
    Example:
      diffctl test test/test_bringup.launch.py
      diffctl test --packages-select my_robot -j 2 --junit-xml results.xml
      diffctl test --init my_robot
    """
    from diffctl.testing import discovery
    from diffctl.workspace import find_workspace, use_in_children

    workspace = find_workspace(explicit=workspace_dir)
    use_in_children(workspace)
    if init_package is not None:
        from diffctl.testing.smoke import write_smoke_test

        path = write_smoke_test(init_package, workspace, init_output)
        click.echo(f"wrote {path}")
        click.echo(f"run it: diffctl test {path}")
        return 0
    arguments = [p for p in map(str, paths) if ":=" in p]
    files = [Path(p) for p in map(str, paths) if ":=" not in p]
    for a in arguments:
        if a.startswith(":="):
            raise ConfigError(f"malformed launch argument {a!r}, expected format '<name>:=<value>'")
    if packages_select:
        # colcon's spelling, `--packages-select a b`, leaves b among the paths
        more = [str(f) for f in files if not f.exists()]
        if len(more) != len(files):
            raise click.UsageError("give PATHs or --packages-select, not both")
        packages_select = (*packages_select, *more)
        files = []
    if files:
        tests = discovery.from_paths(files)
    else:
        if workspace is None:
            local = Path("test")
            if not local.is_dir():
                raise ConfigError("no PATH given and no workspace here", hint="give test files, or run inside a "
                                  "workspace (a folder whose src/ holds packages)")
            tests = discovery.in_folder(local)
        else:
            tests = discovery.from_workspace(workspace, list(packages_select))
    if not tests:
        click.echo("no tests found")
        return 0
    return _run(tests, jobs, junit_xml, timeout_s, artifacts, arguments)


_MISSING_AMENT = re.compile(r"No module named '(ament_\w+)'")
LINT_EXTRA = {"ament_flake8", "ament_pep257", "ament_lint"}


def missing_linter_hint(output: str) -> str | None:
    """The install line for an ament linter a generated test file imports and this environment lacks."""
    match = _MISSING_AMENT.search(output)
    if match is None:
        return None
    name = match.group(1)
    if name in LINT_EXTRA:
        return f"hint: {name} is not installed; the linters of ros2 pkg create's tests: pip install 'diffctl[lint]'"
    return (f"hint: {name} (an ament linter) is not installed; try: pip install "
            f"ros-jazzy-{name.replace('_', '-')}")


def _run(tests: list, jobs: int, junit_xml: Path | None, timeout_s: float, artifacts: Path | None,
         arguments: list[str]) -> int:
    from diffctl.testing import junit
    from diffctl.testing.parallel import Outcome, run_all

    def show(outcome: Outcome) -> None:
        verdict = "passed" if outcome.ok else ("TIMED OUT" if outcome.timed_out else "FAILED")
        click.echo(f"===== {outcome.test.label} =====")
        sys.stdout.write(outcome.output if outcome.output.endswith("\n") or not outcome.output
                         else outcome.output + "\n")
        click.echo(f"===== {outcome.test.label}: {verdict} in {outcome.seconds:.1f} s =====")
        hint = None if outcome.ok else missing_linter_hint(outcome.output)
        if hint:
            click.echo(hint)
        sys.stdout.flush()

    with tempfile.TemporaryDirectory(prefix="diffctl-test-") as tmp:
        outcomes = run_all(tests, jobs=jobs, junit_dir=Path(tmp), arguments=arguments, timeout_s=timeout_s,
                           artifacts=artifacts, on_done=show)
        if junit_xml is not None:
            junit.merge([o.junit for o in outcomes if o.junit is not None], junit_xml)
    failed = [o for o in outcomes if not o.ok]
    click.echo(f"\nSummary: {len(outcomes)} test files, {len(outcomes) - len(failed)} passed, {len(failed)} failed")
    for o in failed:
        why = "timed out" if o.timed_out else f"exit code {o.returncode}"
        click.echo(f"  FAILED {o.test.label} ({why})")
    if any(o.returncode == 2 and not o.timed_out for o in failed):
        return 2  # a file that could not run (launch_test's and pytest's code for it): bad input
    return 1 if failed else 0


@click.command("test-child", hidden=True, add_help_option=False,
               context_settings={"ignore_unknown_options": True, "allow_extra_args": True})
@click.argument("runner")
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def test_child(runner: str, args: tuple[str, ...]) -> None:
    """(internal) RUNNER (launch_test, pytest) on ARGS in a test forked from `diffctl test`'s zygote."""
    import os

    from diffctl.testing.child import die_with_parent, run
    from diffctl.testing.zygotes import start_inherited

    if runner == "launch_test":
        start_inherited()  # first, while this process is single-threaded: its launch's fork server
    die_with_parent(runner)
    code = run(runner, list(args))
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
