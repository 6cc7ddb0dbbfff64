"""`diffctl viz`: the rviz2 counterpart, a web page served on loopback and fed live from the bus."""

from __future__ import annotations

import asyncio
import signal
import sys

import click

from diffctl import ros_args
from diffctl.viz.rviz_config import default_config, load_rviz
from diffctl.viz.settings import VizSettings

DEFAULT_NODE_NAME = "rviz2"


@click.command("viz", context_settings={"help_option_names": ["-h", "--help"]})
@click.option(
    "-d",
    "--display-config",
    type=click.Path(dir_okay=False),
    default=None,
    help="RViz2 .rviz file: fixed frame and displays with their topics.",
)
@click.option("-f", "--fixed-frame", default=None, help="Fixed frame (overrides the .rviz file's).")
@click.option("--host", default=None, help="Address to serve on [default: 127.0.0.1, loopback only].")
@click.option("--port", type=int, default=None, help="TCP port [default: 8080; 0 picks a free one].")
@click.option(
    "--teleop-topic",
    default=None,
    help="Default topic of the teleop panel [default: /diffbot_base_controller/cmd_vel].",
)
@click.option("--max-linear", type=float, default=None, help="Teleop speed limit in m/s [default: 1.0].")
@click.option("--max-angular", type=float, default=None, help="Teleop turn-rate limit in rad/s [default: 2.0].")
def viz(
    display_config: str | None,
    fixed_frame: str | None,
    host: str | None,
    port: int | None,
    teleop_topic: str | None,
    max_linear: float | None,
    max_angular: float | None,
) -> None:
    """Serve the browser visualizer (rviz2): robot model, TF, odometry, laser scan, camera, joint states,
    controllers, topics, sim time, plus teleop and message publisher panels.

    The URL printed at start carries a token; only a page opened with it may publish commands.
    Launch files start it as package rviz2 with `-d FILE` and `--ros-args -p use_sim_time:=true`.

    \b
    Example:
      diffctl viz -d config/diffbot.rviz
      diffctl viz --port 0 --ros-args -p use_sim_time:=true
    """
    # Everything the user gave is checked before anything starts: a bad file or value exits 2 here.
    config = load_rviz(display_config) if display_config else default_config()
    ra = ros_args.current(DEFAULT_NODE_NAME)
    settings = VizSettings.from_params(
        ra.params,
        host=host,
        port=port,
        fixed_frame=fixed_frame,
        teleop_topic=teleop_topic,
        max_linear_mps=max_linear,
        max_angular_radps=max_angular,
    )
    # Said by the node's logger once it exists, so --log-level governs them as every line of a ROS node.
    warnings: list[str] = []
    if config.ignored:
        warnings.append(f"{config.source}: display classes not shown: {', '.join(config.ignored)}")
    if settings.host not in ("127.0.0.1", "localhost", "::1"):
        warnings.append(f"serving on {settings.host}: the page is reachable from other machines "
                        "(read-only without the token)")
    asyncio.run(_serve(config, settings, ra, warnings))


async def _serve(config, settings: VizSettings, ra: ros_args.RosArgs, warnings: list[str]) -> None:
    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter
    from diffctl.viz.bus_feed import BusFeed
    from diffctl.viz.scene import Scene
    from diffctl.viz.security import new_token
    from diffctl.viz.server import VizServer

    started = component.start(lambda: Node(
        DEFAULT_NODE_NAME, client_library="rclcpp",
        parameter_overrides=[Parameter("use_sim_time", value=settings.use_sim_time)]))
    node = started.node
    log = node.get_logger()
    for text in warnings:
        log.warning(text)
    log.info(f"visualizer fixed frame {settings.fixed_frame or config.fixed_frame}")
    feed = None
    try:
        scene = Scene(config, settings)
        feed = BusFeed(node, scene, config, settings)
        server = VizServer(scene, feed, config, new_token(), node.get_logger())
        port = await server.start()
        shown_host = settings.host if ":" not in settings.host else f"[{settings.host}]"
        print(f"diffctl viz: open http://{shown_host}:{port}/?token={server.token}", flush=True)
        stop = asyncio.Event()
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, stop.set)
        await server.run(stop)
    finally:
        if feed is not None:
            feed.close()
        started.stop()
        sys.stdout.flush()
