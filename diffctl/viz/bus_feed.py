"""The visualizer's bus side: subscriptions that feed the scene, graph and controller polling, publishers.

Subscriptions are a short callback set into `Scene`. The streams a page draws (/tf, odometry, scans, joint
states, /clock, ground truth) are subscribed only while a page is open, as foxglove_bridge subscribes for its
clients: with no one looking, decoding them cost a sixth of a core at rtf 0 and the simulator its share of it.
The latched topics (/tf_static, robot descriptions) and world statistics stay subscribed, so a page opens
onto the robot's model and frames at once and the moving parts follow within one period of each stream.
Topic rates for the topics panel come from plain Zenoh subscribers on the topics' keys (no ROS subscriber
appears in the graph, so lazy bridges stay lazy); they too exist only while a page is open, and image topics
are left out unless the camera panel is open, because counting them means receiving them.
"""

from __future__ import annotations

import contextlib
import threading
from typing import Any

from diffctl.bus import gz, wire
from diffctl.errors import DiffctlError, MessageError
from diffctl.interfaces import types
from diffctl.viz.commands import PublishJob, TeleopCommand, fill_now
from diffctl.viz.rviz_config import RvizConfig
from diffctl.viz.scene import Scene
from diffctl.viz.settings import VizSettings

HEAVY_TYPES = ("sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage", "sensor_msgs/msg/PointCloud2")
LIST_CONTROLLERS = "/controller_manager/list_controllers"
LIST_CONTROLLERS_TYPE = "controller_manager_msgs/srv/ListControllers"


class BusFeed:
    def __init__(self, node: Any, scene: Scene, config: RvizConfig, settings: VizSettings) -> None:
        """`node`: the visualizer's client Node; the feed is a measured hot path, so its endpoints are raw ones
        on the node's wire presence."""
        self.node = node.bus_node
        self._resolve = node.resolve_topic_name
        self._clock = node.get_clock()
        self.scene = scene
        self.settings = settings
        self._lock = threading.Lock()
        self._rate_subs: dict[tuple[str, str], Any] = {}
        self._image_subs: dict[str, Any] = {}
        self._publishers: dict[tuple[str, str], Any] = {}
        self._controllers_client: Any = None

        def sub(topic: str, typename: str, callback: Any, **kw: Any) -> Any:
            return self.node.create_subscription(self._resolve(topic), typename, callback, **kw)

        sub("/tf_static", "tf2_msgs/msg/TFMessage", lambda m: scene.on_tf(m, static=True), latched=True)
        # Every display's topic, enabled or not: the page can switch a display on at any time.
        for topic in config.topics("robot_model", enabled_only=False):
            sub(topic, "std_msgs/msg/String", lambda m, t=topic: scene.set_robot_description(m.data, t), latched=True)
        # (topic, type, callback) of the streams taken while a page is open.
        self._live_specs: list[tuple[str, str, Any]] = [("/tf", "tf2_msgs/msg/TFMessage", scene.on_tf)]
        for topic in config.topics("odometry", enabled_only=False):
            self._live_specs.append((topic, "nav_msgs/msg/Odometry", lambda m, t=topic: scene.on_odometry(t, m)))
        for topic in config.topics("laser_scan", enabled_only=False):
            self._live_specs.append((topic, "sensor_msgs/msg/LaserScan", lambda m, t=topic: scene.on_scan(t, m)))
        self._live_specs += [
            ("/joint_states", "sensor_msgs/msg/JointState", scene.on_joint_states),
            ("/clock", "rosgraph_msgs/msg/Clock", lambda m: scene.on_clock(m.clock.sec + m.clock.nanosec * 1e-9)),
        ]
        self._live_subs: list[Any] = []
        # The simulator side, as Gazebo's own GUI reads it: ground truth and world statistics.
        # A robot shown with a TF prefix is the simulated model of that name (a fleet's robotK): its ground
        # truth places its own odom tree in the world.
        # Ground truth is not a ROS subscription (nothing in the graph changes) and the simulator computes it
        # only while someone listens: it is taken only while a page is open to draw it.
        zs = self.node.session
        self._truth_models = list(dict.fromkeys([settings.ground_truth_model,
                                                 *(p for _, p in config.robot_models() if p)]))
        self._truth_subs: list[Any] = []
        self._gz_subs = [zs.declare_subscriber(gz.key("/world/*/stats"), self._on_gz_stats)]

    def watch_live(self, on: bool) -> None:
        """Take the streams a page draws and the models' ground truth (on), or drop them (off): called as the
        first page opens and the last one closes."""
        with self._lock:
            if on and not self._live_subs:
                self._live_subs = [self.node.create_subscription(self._resolve(t), ty, cb)
                                   for t, ty, cb in self._live_specs]
                self._truth_subs = [
                    self.node.session.declare_subscriber(gz.key(f"/model/{m}/pose"),
                                                         lambda s, m=m: self._on_gz_pose(s, m))
                    for m in self._truth_models
                ]
            elif not on:
                live, self._live_subs = self._live_subs, []
                truth, self._truth_subs = self._truth_subs, []
                for s in live:
                    with contextlib.suppress(Exception):
                        self.node.destroy_subscription(s)
                for sub in truth:
                    with contextlib.suppress(Exception):
                        sub.undeclare()

    # ---- gz side ---------------------------------------------------------------------------------------

    def _on_gz_pose(self, sample: Any, model: str) -> None:
        try:
            _, fields = gz.decode(sample.payload.to_bytes(), "gz.msgs.Pose_V")
            self.scene.on_ground_truth(fields, model)
        except (MessageError, ValueError, TypeError):
            pass

    def _on_gz_stats(self, sample: Any) -> None:
        try:
            _, fields = gz.decode(sample.payload.to_bytes())
            self.scene.on_stats(fields)
        except MessageError:
            pass

    # ---- polled (from the server's worker thread, about once a second) --------------------------------

    def poll_graph(self, count_rates: bool = True) -> None:
        """The graph for the topics panel; with `count_rates`, a counting subscriber on every published topic.

        Counting means receiving every sample (Zenoh's transport costs tens of µs per sample here, whatever the
        callback does), so the counters exist only while a page is open to show them."""
        graph = self.node.graph
        topics = []
        wanted: set[tuple[str, str]] = set()
        for name, type_names in graph.topics().items():
            pubs, subs = graph.publishers(name), graph.subscribers(name)
            topics.append(
                {
                    "name": name,
                    "types": type_names,
                    "publishers": len([p for p in pubs if p.node_fqn != self.node.fqn]),
                    "subscribers": len([s for s in subs if s.node_fqn != self.node.fqn]),
                }
            )
            for t in type_names if count_rates else ():
                if any(p.type == t for p in pubs) and (t not in HEAVY_TYPES or name in self._image_subs):
                    wanted.add((name, t))
        with self._lock:
            for key in [k for k in self._rate_subs if k not in wanted]:
                self._rate_subs.pop(key).undeclare()
            for name, t in wanted - set(self._rate_subs):
                try:
                    k = wire.topic_key(self.node.domain, name, t)
                except Exception:  # a type our store lacks: listed, but not counted
                    continue
                self._rate_subs[(name, t)] = self.node.session.declare_subscriber(
                    k, lambda _s, n=name: self.scene.count(n)
                )
        self.scene.set_topics(topics)

    def poll_controllers(self) -> None:
        """controller_manager's list, while one is running; None (panel hidden) otherwise."""
        if not self.node.graph.servers(LIST_CONTROLLERS):
            self.scene.set_controllers(None)
            return
        if self._controllers_client is None:
            self._controllers_client = self.node.create_client(LIST_CONTROLLERS, LIST_CONTROLLERS_TYPE)
        try:
            resp = self._controllers_client.call({}, timeout=1.0)
        except DiffctlError:
            return
        self.scene.set_controllers(
            [
                {"name": c.name, "state": c.state, "type": c.type, "claimed": list(c.claimed_interfaces)}
                for c in resp.controller
            ]
        )

    # ---- camera panel ------------------------------------------------------------------------------------

    def watch_image(self, topic: str, on: bool) -> None:
        """Subscribe to an image topic only while some page has its camera panel open (cameras are lazy)."""
        with self._lock:
            if on and topic not in self._image_subs:
                self._image_subs[topic] = self.node.create_subscription(
                    self._resolve(topic), "sensor_msgs/msg/Image", lambda m, t=topic: self._on_image(t, m), depth=1
                )
            elif not on and topic in self._image_subs:
                self.node.destroy_subscription(self._image_subs.pop(topic))

    def _on_image(self, topic: str, msg: Any) -> None:
        self.scene.count(topic)
        self.scene.on_image(topic, msg)

    # ---- commands from the page ------------------------------------------------------------------------

    def _publisher(self, topic: str, type_name: str) -> Any:
        with self._lock:
            pub = self._publishers.get((topic, type_name))
            if pub is None:
                pub = self._publishers[(topic, type_name)] = self.node.create_publisher(self._resolve(topic),
                                                                                        type_name)
            return pub

    def other_types(self, topic: str, type_name: str) -> list[str]:
        """Types other endpoints use on `topic` (a TwistStamped controller fed Twist is the classic)."""
        return [t for t in self.node.graph.topics().get(topic, []) if t != type_name]

    def publish_teleop(self, cmd: TeleopCommand) -> None:
        stamp = types.time_msg(self._clock.now().nanoseconds)
        fields = cmd.fields({"sec": stamp.sec, "nanosec": stamp.nanosec}, self.settings.teleop_frame_id)
        self._publisher(cmd.topic, cmd.type_name).publish(types.new(cmd.type_name, fields))

    def publish_job(self, job: PublishJob) -> None:
        now = types.time_msg(self._clock.now().nanoseconds)
        fields = fill_now(job.fields, {"sec": now.sec, "nanosec": now.nanosec})
        self._publisher(job.topic, job.type_name).publish(types.new(job.type_name, fields))

    def close(self) -> None:
        self.watch_live(False)
        for s in self._gz_subs:
            try:
                s.undeclare()
            except Exception:
                pass
        with self._lock:
            for s in self._rate_subs.values():
                try:
                    s.undeclare()
                except Exception:
                    pass
            self._rate_subs.clear()
