"""The message bus: Zenoh sessions, ROS-like nodes and the rmw_zenoh wire format. See API.md."""

from diffctl.bus import gz, types
from diffctl.bus.node import Node
from diffctl.bus.session import close_session, domain_id, open_session, router_endpoint

__all__ = ["Node", "close_session", "domain_id", "gz", "open_session", "router_endpoint", "types"]
