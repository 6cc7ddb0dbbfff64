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

    ra = ros_args.current("foxglove_bridge")
    port = fg.check_port(port if port is not None else ra.params.get("port", 8765))
    address = fg.check_loopback(address or str(ra.params.get("address", "127.0.0.1")))
    from diffctl.signals import stop_on_signals

    stop = stop_on_signals()
    context = foxglove.Context()
    if bag_path is not None:
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
    from diffctl.foxglove.assets import DEFAULT_ALLOWLIST, AssetResolver
    from diffctl.foxglove.graph import GraphBridge
    from diffctl.foxglove.live import LiveBridge
    from diffctl.foxglove.parameters import ParameterBridge
    from diffctl.foxglove.services import ServiceBridge
    from diffctl.interfaces import types

    caps = fg.check_capabilities(list(ra.params.get("capabilities", fg.CAPABILITIES)))
    assets = AssetResolver(list(ra.params.get("asset_uri_allowlist", DEFAULT_ALLOWLIST))) if "assets" in caps else None
    started = component.start(lambda: Node("foxglove_bridge", client_library="rclcpp"))
    node = started.node
    wire = node.bus_node  # what the app sees and sends passes on raw endpoints: a measured hot path
    sim_time = bool(node.get_parameter("use_sim_time").value)
    live = LiveBridge(wire, context, say=info)
    services = ServiceBridge(wire, say=info) if "services" in caps else None
    params = ParameterBridge(node, say=info) if caps & {"parameters", "parametersSubscribe"} else None
    graph = GraphBridge(wire, live.wake) if "connectionGraph" in caps else None
    server = fg.start(address, port, live=live, context=context, sim_time=sim_time, services=services,
                      params=params, assets=assets, client_publish="clientPublish" in caps, graph=graph)
    if sim_time:
        wire.create_subscription("/clock", "rosgraph_msgs/msg/Clock",
                                 lambda m: server.broadcast_time(types.time_ns(m.clock)))
    live.start()
    info(f"Foxglove server on ws://{address}:{server.port} (connect from the Foxglove app)")
    stop.wait()
    live.close()
    server.stop()
    for part in (services, params):
        if part is not None:
            part.close()
    started.stop()
