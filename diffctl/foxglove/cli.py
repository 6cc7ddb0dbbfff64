"""`diffctl foxglove-bridge`: foxglove_bridge's counterpart; also what `Node(package='foxglove_bridge',
executable='foxglove_bridge')` starts, taking `port` and `address` from `--ros-args -p` as the real one."""

from __future__ import annotations

from pathlib import Path

import click

from diffctl.console import info


@click.command("foxglove-bridge")
@click.option("--port", type=int, default=None, help="WebSocket port (default 8765; 0 picks a free one).")
@click.option("--address", default=None, help="Loopback address to listen on (default 127.0.0.1).")
@click.option("--bag", "bag_path", type=click.Path(path_type=Path), default=None,
              help="Serve this bag with playback controls instead of the live graph.")
@click.option("--rate", type=float, default=1.0, help="Bag playback rate.")
def foxglove_bridge(port: int | None, address: str | None, bag_path: Path | None, rate: float) -> None:
    """Serve ROS topics to the Foxglove app over its WebSocket protocol (foxglove_bridge).

    Every topic is advertised with its ros2msg schema and cdr encoding; clients may publish (cmd_vel), call
    the graph's services, get, set and watch the nodes' parameters, and fetch package:// assets (meshes).
    With --bag, the server plays a bag instead, under the app's play/pause/seek controls.

    \b
    Example:
      diffctl foxglove-bridge --port 8765
      diffctl foxglove-bridge --bag run1
    """
    import foxglove

    from diffctl import ros_args
    from diffctl.foxglove import server as fg
    from diffctl.signals import stop_on_signals

    port_option, address_option = port, address
    stop = stop_on_signals()
    context = foxglove.Context()
    if bag_path is not None:
        # A bag served on its own: no node, no bus; the --ros-args parameters still give port and address.
        ra = ros_args.current("foxglove_bridge")
        port = fg.check_port(port if port is not None else ra.params.get("port", 8765))
        address = fg.check_loopback(address or str(ra.params.get("address", "127.0.0.1")))
        from diffctl.bag.reader import Bag
        from diffctl.bag.timing import check_rate
        from diffctl.foxglove.playback import BagPlayback

        check_rate(rate)
        bag = Bag(bag_path)
        playback = BagPlayback(bag, context, rate)
        server = fg.start(address, port, playback=playback, context=context)
        playback.start(paused=True)
        info(f"Foxglove server on ws://{address}:{server.port} playing {bag_path} (paused; play it from the app)")
        stop.wait()
        playback.close()
        server.stop()
        bag.close()
        return
    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter
    from diffctl.foxglove.assets import AssetResolver
    from diffctl.foxglove.graph import GraphBridge
    from diffctl.foxglove.live import LiveBridge
    from diffctl.foxglove.parameters import ParameterBridge
    from diffctl.foxglove.services import ServiceBridge
    from diffctl.foxglove.settings import DECLARATIONS, BridgeSettings, declare, settings_from
    from diffctl.interfaces import types

    # The options given on the command line stand for the node's parameters of the same names. What the node
    # will be given is checked first: bad input stops the bridge before it joins the graph.
    options = {name: v for name, v in (("port", port_option), ("address", address_option)) if v is not None}
    settings_from({k: v for k, v in ros_args.current("foxglove_bridge").params.items() if k in DECLARATIONS}
                  | options)
    given = [Parameter(name, value=v) for name, v in options.items()]
    declared: list[BridgeSettings] = []

    def make() -> Node:
        # declared before the node spins: a `param list` answered in between would list half of them
        made = Node("foxglove_bridge", client_library="rclcpp", parameter_overrides=given)
        declared.append(declare(made))
        return made

    started = component.start(make)
    node = started.node
    log = node.get_logger()
    settings = declared[0]
    caps = settings.capabilities
    wire = node.bus_node  # what the app sees and sends passes on raw endpoints: a measured hot path
    live = LiveBridge(wire, context, log, settings)
    services = ServiceBridge(wire, log, settings) if "services" in caps else None
    params = ParameterBridge(node, log, settings) if caps & {"parameters", "parametersSubscribe"} else None
    graph = GraphBridge(wire, live.wake) if "connectionGraph" in caps else None
    assets = AssetResolver(settings.asset_uri_allowlist) if "assets" in caps else None
    try:
        server = fg.start(settings.address, settings.port, live=live, context=context, sim_time=settings.use_sim_time,
                          services=services, params=params, assets=assets, client_publish="clientPublish" in caps,
                          graph=graph, tls=(settings.tls_cert, settings.tls_key) if settings.tls_cert else None)
    except BaseException:
        started.stop()
        raise
    if settings.use_sim_time:
        wire.create_subscription("/clock", "rosgraph_msgs/msg/Clock",
                                 lambda m: server.broadcast_time(types.time_ns(m.clock)))
    live.start()
    scheme = "wss" if settings.tls_cert else "ws"
    log.info(f"Foxglove server on {scheme}://{settings.address}:{server.port} (connect from the Foxglove app)")
    stop.wait()
    log.info("Shutting down foxglove_bridge")
    live.close()
    server.stop()
    for part in (services, params):
        if part is not None:
            part.close()
    started.stop()
