"""The secured multi-host deployment (config/security/), end to end on two network-namespace hosts.

Host A runs router A (TLS with mutual certificates, user/password, deny-by-default access control) and the
robot: simulator, controller manager, robot_state_publisher, bridge. Host B runs router B, linked to A over
TLS, and an operator's tools: both spawners, a TwistStamped publisher, `topic echo` of odometry. The car
drives from B, and a client with the shipped client.json5 reads odometry straight from router A. A client
without a certificate, with one from another CA, with a wrong password, or logged in but outside the
access-control list can neither publish cmd_vel nor read odometry.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import Procs
from tests.security.conftest import Running
from tests.security.deployment import Deployment, build
from tests.security.netns import Host, HostPair

HERE = Path(__file__).resolve().parent
CMD_VEL = "/diffbot_base_controller/cmd_vel"
ODOM = "/diffbot_base_controller/odom"
TWIST = "geometry_msgs/msg/TwistStamped"
ODOMETRY = "nav_msgs/msg/Odometry"
X_RE = re.compile(r"^x: (-?[0-9.e+-]+)$", re.M)


def diffctl(host: Host, *args: str, config: Path | None) -> list[str]:
    """`diffctl ARGS` on `host`, its session configured by `config` (ZENOH_SESSION_CONFIG_URI)."""
    # Domain 0: the shipped access-control lists name rmw_zenoh keys of domain 0 (config/security/README.md),
    # whatever ROS_DOMAIN_ID the shell running the tests exports.
    env = ["env", "-u", "DIFFCTL_ROUTER", "-u", "ZENOH_CONFIG_OVERRIDE", "-u", "ZENOH_ROUTER_CONFIG_URI"]
    env += [f"ZENOH_SESSION_CONFIG_URI={config}"] if config else ["-u", "ZENOH_SESSION_CONFIG_URI"]
    env += ["ROS_DOMAIN_ID=0"]  # env's unsets come before its assignments
    return host.argv(*env, sys.executable, "-u", "-m", "diffctl", *args)


def start(procs: Procs, argv: list[str]) -> Running:
    return Running(procs.start(argv, cwd=str(HERE.parents[1])))


def xs(text: str) -> list[float]:
    return [float(v) for v in X_RE.findall(text)]


def interrupt(run: Running, timeout_s: float = 10.0) -> int:
    os.killpg(run.proc.pid, signal.SIGINT)
    return run.proc.wait(timeout_s)


def bring_up(hosts: HostPair, procs: Procs, d: Deployment, log_dir: Path) -> tuple[Running, ...]:
    router_a = start(procs, diffctl(hosts.a, "router", "--config", str(d.router_a), config=None))
    router_a.wait_for(r"^router \S+ listening")
    router_b = start(procs, diffctl(hosts.b, "router", "--config", str(d.router_b), config=None))
    router_b.wait_for(r"^router \S+ listening")
    robot = start(
        procs,
        diffctl(
            hosts.a,
            "launch",
            str(HERE / "data" / "robot_host.yaml"),
            "--log-dir",
            str(log_dir),
            "--no-color",
            config=d.session_a,
        ),
    )
    return router_a, router_b, robot


def run_to_end(procs: Procs, argvs: dict[str, list[str]], timeout_s: float = 90.0) -> dict[str, tuple[int, str]]:
    """Run several commands at once; each one's exit code and output."""
    running = {name: start(procs, argv) for name, argv in argvs.items()}
    results = {}
    for name, run in running.items():
        try:
            code = run.proc.wait(timeout_s)
        except subprocess.TimeoutExpired:
            raise AssertionError(f"{name} still runs after {timeout_s} s:\n{run.output()}") from None
        time.sleep(0.1)  # the pump's last lines
        results[name] = (code, run.output())
    return results


@pytest.mark.slow
def test_two_hosts_drive_over_tls_and_strangers_get_nothing(hosts: HostPair, procs: Procs, tmp_path: Path) -> None:
    if shutil.which("openssl") is None:
        pytest.skip(reason="openssl is not installed (`make system-deps` installs it): no certificates to test with")
    d = build(tmp_path / "deploy", hosts.a.address, hosts.b.address)
    router_a, router_b, robot = bring_up(hosts, procs, d, tmp_path / "log")
    try:
        # Host B: the spawners reach the controller manager on A through both routers (services + graph).
        spawned = run_to_end(
            procs,
            {
                "diffbot": diffctl(
                    hosts.b,
                    "spawn",
                    "controller",
                    "diffbot_base_controller",
                    "--param-file",
                    "config/diff_drive_controller.yaml",
                    "--controller-manager-timeout",
                    "90",
                    config=d.session_b,
                )
            },
        )
        assert spawned["diffbot"][0] == 0, spawned["diffbot"][1]
        spawned = run_to_end(
            procs,
            {
                "jsb": diffctl(
                    hosts.b,
                    "spawn",
                    "controller",
                    "joint_state_broadcaster",
                    "--controller-manager-timeout",
                    "30",
                    config=d.session_b,
                )
            },
        )
        assert spawned["jsb"][0] == 0, spawned["jsb"][1]

        odom_b = start(
            procs,
            diffctl(hosts.b, "topic", "echo", ODOM, ODOMETRY, "--field", "pose.pose.position", config=d.session_b),
        )
        seen_on_a = start(
            procs, diffctl(hosts.a, "topic", "echo", CMD_VEL, TWIST, "--field", "twist.linear", config=d.session_a)
        )
        odom_b.wait_for(r"^x: ", timeout_s=30)
        x0 = xs(odom_b.output())[-1]

        # Host B drives (sim-time stamps, from /clock that router A lets through) and the car moves.
        teleop = start(
            procs,
            diffctl(
                hosts.b,
                "topic",
                "pub",
                CMD_VEL,
                TWIST,
                "{twist: {linear: {x: 0.5}}}",
                "--rate",
                "10",
                config=d.session_b,
            ),
        )
        deadline = time.monotonic() + 60
        while max(xs(odom_b.output()), default=x0) < x0 + 0.5:
            assert time.monotonic() < deadline, f"the car did not move:\n{teleop.output()}\n{robot.output()}"
            assert teleop.proc.poll() is None, teleop.output()
            time.sleep(0.2)
        interrupt(teleop)
        assert 0.5 in xs(seen_on_a.output()), "host A's own subscriber did not see host B's commands"

        # Strangers, straight at router A's TLS port from host B.
        refused = {name: d.client(name) for name in ("no_certificate", "other_ca", "wrong_password")}
        argvs = {}
        for name, cfg in refused.items():
            argvs[f"{name} pub"] = diffctl(
                hosts.b, "topic", "pub", CMD_VEL, TWIST, "{twist: {linear: {x: 0.777}}}", "--once", config=cfg
            )
            argvs[f"{name} echo"] = diffctl(
                hosts.b, "topic", "echo", ODOM, ODOMETRY, "--once", "--timeout", "5", config=cfg
            )
        # The shipped client config, in router A's access-control list, reads odometry the same way…
        argvs["laptop echo"] = diffctl(
            hosts.b,
            "topic",
            "echo",
            ODOM,
            ODOMETRY,
            "--once",
            "--timeout",
            "20",
            "--field",
            "pose.pose.position",
            config=d.client("laptop"),
        )
        # …where one logged in with a good certificate and password, but in no policy, gets nothing.
        visitor = d.client("visitor")
        argvs["visitor echo"] = diffctl(
            hosts.b, "topic", "echo", ODOM, ODOMETRY, "--once", "--timeout", "5", config=visitor
        )
        visitor_pub = start(
            procs,
            diffctl(
                hosts.b,
                "topic",
                "pub",
                CMD_VEL,
                TWIST,
                "{twist: {linear: {x: 0.777}}}",
                "--rate",
                "20",
                "-w",
                "0",
                config=visitor,
            ),
        )
        odom_count = len(xs(odom_b.output()))
        results = run_to_end(procs, argvs)
        for name, (code, out) in results.items():
            if name.startswith(("visitor", "laptop")):
                continue
            assert code == 2, f"{name}: exit {code}\n{out}"
            assert f"router at tls/{hosts.a.address}:7448 refused this session" in out, f"{name}:\n{out}"
            assert "Traceback" not in out
        code, out = results["laptop echo"]
        assert code == 0 and xs(out), f"the shipped client.json5 reads no odometry:\n{out}"
        code, out = results["visitor echo"]
        assert code == 2 and f"no message on {ODOM} within 5 s" in out, out
        visitor_pub.wait_for(r"publishing #1")
        time.sleep(1.0)
        assert interrupt(visitor_pub) == 0, visitor_pub.output()
        assert "0.777" in visitor_pub.output()  # it did publish, from its side
        assert 0.777 not in xs(seen_on_a.output()), "router A let the visitor's cmd_vel through"
        assert len(xs(odom_b.output())) > odom_count + 20, "odometry stopped flowing to host B meanwhile"

        for run in (odom_b, seen_on_a):
            interrupt(run)
        for run in (robot, router_b, router_a):
            assert interrupt(run, 20) in (0, -signal.SIGINT), run.output()[-3000:]
    except BaseException:
        for name, run in (("router A", router_a), ("router B", router_b), ("host A launch", robot)):
            print(f"----- {name}\n{run.output()[-4000:]}")
        raise
