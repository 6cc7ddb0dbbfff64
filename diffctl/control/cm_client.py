"""A client of one controller manager's services, shared by the spawner and the `diffctl control` verbs.

It works on a client Node (rclpy's API), which it spins itself while it waits for an answer, as
controller_manager_services.py does with rclpy.spin_until_future_complete. Each call retries on a timeout
(3 attempts, as the spawner does) and raises RuntimeFailure with the service name when the manager cannot be
reached.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.parameter import Parameter
from diffctl.control.lifecycle import State
from diffctl.errors import ConfigError, RuntimeFailure
from diffctl.interfaces.runtime.set_message import set_message_fields

CM = "controller_manager_msgs/srv/"
# One token of a ROS name (rcl_validate_topic_name): a letter or "_" first, then letters, digits and "_".
_NAME_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
SRV_TYPES = {
    "list_controllers": CM + "ListControllers",
    "list_controller_types": CM + "ListControllerTypes",
    "list_hardware_components": CM + "ListHardwareComponents",
    "list_hardware_interfaces": CM + "ListHardwareInterfaces",
    "load_controller": CM + "LoadController",
    "configure_controller": CM + "ConfigureController",
    "cleanup_controller": CM + "CleanupController",
    "unload_controller": CM + "UnloadController",
    "switch_controller": CM + "SwitchController",
    "set_hardware_component_state": CM + "SetHardwareComponentState",
    "reload_controller_libraries": CM + "ReloadControllerLibraries",
    "set_parameters": "rcl_interfaces/srv/SetParameters",
}


def manager_fqn(name: str, namespace: str = "/") -> str:
    """The manager's fully qualified node name, as rcl expands `-c`: `/robot1/controller_manager` as given,
    a relative `controller_manager` or `robot1/controller_manager` under the caller's namespace."""
    text = name.strip()
    tokens = text.strip("/").split("/")
    if not text or text == "/" or "//" in text or text.endswith("/") or not all(_NAME_TOKEN.match(t) for t in tokens):
        raise ConfigError(
            f"-c/--controller-manager {name!r} is not a ROS node name",
            field="--controller-manager",
            hint="e.g. controller_manager or /robot1/controller_manager (letters, digits and '_' between '/')",
        )
    if text.startswith("/"):
        return text
    return f"{namespace.rstrip('/')}/{text}"


class ManagerClient:
    def __init__(
        self, node: Any, manager: str = "controller_manager", call_timeout_s: float = 10.0, attempts: int = 3
    ) -> None:
        from diffctl.client.executors import SingleThreadedExecutor

        self.node = node
        self.log = node.get_logger()
        self.manager = manager_fqn(manager, node.get_namespace())
        self.call_timeout_s = call_timeout_s
        self.attempts = attempts
        self._clients: dict[str, Any] = {}
        self._executor = SingleThreadedExecutor(context=node.context)
        self._executor.add_node(node)
        self._in_call = False
        self._interrupted = False
        self._interrupt_pending = False

    def interrupt(self) -> None:
        """From a signal handler: raise KeyboardInterrupt where it is safe. A call in progress ends at the next
        slice of its wait, never from inside the executor: an interrupt landing there could drop the reply being
        handled, and the caller would wait out its timeout and retry (a spawner -u stopped right after its
        switch hung 30 s). A second interrupt raises at once."""
        if self._in_call and not self._interrupted:
            self._interrupted = self._interrupt_pending = True
            return
        self._interrupted = True
        raise KeyboardInterrupt

    def close(self) -> None:
        self._executor.shutdown(timeout_sec=1.0)

    def client(self, service: str) -> Any:
        if service not in self._clients:
            self._clients[service] = self.node.create_client(cls(SRV_TYPES[service]), f"{self.manager}/{service}")
        return self._clients[service]

    def wait(
        self,
        service: str,
        timeout_s: float,
        say: Callable[[str], None] | None = None,
        warn: Callable[[str], None] | None = None,
    ) -> None:
        """Wait for `service`: forever when timeout_s == 0 (saying so, warning every 10 s), else up to timeout_s."""
        cli = self.client(service)
        name = f"{self.manager}/{service}"
        if cli.service_is_ready():
            return
        if say:
            say(f"waiting for service {name} to become available...")
        start = time.monotonic()
        while True:
            step = 10.0 if timeout_s == 0 else max(0.0, min(10.0, timeout_s - (time.monotonic() - start)))
            if cli.wait_for_service(timeout_sec=step):
                return
            if timeout_s and time.monotonic() - start >= timeout_s:
                raise RuntimeFailure(
                    f"Could not contact service {name} within {timeout_s:g} s",
                    hint="is the controller manager running and has it got a robot_description?",
                )
            if warn:
                warn(f"Could not contact service {name}")

    def call(self, service: str, request: Any = None, timeout_s: float | None = None) -> Any:
        """The response to `request` (the request message, or a dict of its fields)."""
        if self._interrupt_pending:  # interrupted as the previous call's reply came: that call had its answer
            self._interrupt_pending = False
            raise KeyboardInterrupt
        cli = self.client(service)
        timeout = timeout_s or self.call_timeout_s
        msg = request
        if not isinstance(request, cli.srv_type.Request):
            msg = cli.srv_type.Request()
            if request:
                set_message_fields(msg, request)
        for k in range(1, self.attempts + 1):
            self._in_call = True  # from the request on: a reply may come (and be handled) at once
            try:
                future = cli.call_async(msg)
                self._wait_for(future, timeout)
            finally:
                self._in_call = False
            if future.done():
                error = future.exception()
                if error is not None:
                    raise RuntimeFailure(
                        f"{self.manager}/{service}: {error}",
                        hint="is the controller manager running? `diffctl service list` shows it",
                    ) from error
                return future.result()
            cli.remove_pending_request(future)
            self.log.warn(
                f"Failed getting a result from calling {self.manager}/{service} in "
                f"{timeout:g} s. (Attempt {k} of {self.attempts}.)"
            )
        raise RuntimeFailure(f"could not get a result from {self.manager}/{service} after {self.attempts} attempts")

    def interrupt_handled(self) -> None:
        """The interrupt was taken (the caller now unloads what it spawned): calls run to their end again."""
        self._interrupt_pending = False

    def _wait_for(self, future: Any, timeout_s: float) -> None:
        """Spin until `future` is done or `timeout_s` passed, in slices, so that an interrupt comes between two."""
        deadline = time.monotonic() + timeout_s
        while not future.done():
            left = deadline - time.monotonic()
            if left <= 0:
                return
            self._executor.spin_until_future_complete(future, timeout_sec=min(0.1, left))
            if self._interrupt_pending and not future.done():
                self._interrupt_pending = False
                raise KeyboardInterrupt

    # --- typed helpers -----------------------------------------------------------------------------------
    def list_controllers(self) -> list[Any]:
        return list(self.call("list_controllers").controller)

    def controller_state(self, name: str) -> str | None:
        for c in self.list_controllers():
            if c.name == name:
                return str(c.state)
        return None

    def ok(self, service: str, name: str) -> bool:
        return bool(self.call(service, {"name": name}).ok)

    def switch(
        self, activate: list[str], deactivate: list[str], strictness: int, activate_asap: bool, timeout_s: float
    ) -> tuple[bool, str]:
        sec = int(timeout_s)
        req = {
            "activate_controllers": activate,
            "deactivate_controllers": deactivate,
            "strictness": strictness,
            "activate_asap": activate_asap,
            "timeout": {"sec": sec, "nanosec": round((timeout_s - sec) * 1e9)},
        }
        # The manager waits up to timeout_s for its loop; give the call itself that much more.
        resp = self.call("switch_controller", req, timeout_s=max(self.call_timeout_s, timeout_s + 2.0))
        return bool(resp.ok), str(resp.message)

    def set_parameters(self, values: dict[str, Any]) -> None:
        """Set parameters of the manager node (raises RuntimeFailure with the node's reason)."""
        params = [Parameter(k, value=v).to_parameter_msg() for k, v in values.items()]
        resp = self.call("set_parameters", cls(SRV_TYPES["set_parameters"]).Request(parameters=params))
        for p, r in zip(params, resp.results, strict=False):
            if not r.successful:
                raise RuntimeFailure(f"could not set {p.name} on {self.manager}: {r.reason}")

    def set_controller_params(self, name: str, type_name: str | None, params_files: list[str]) -> None:
        values: dict[str, Any] = {f"{name}.params_file": list(params_files)}
        if type_name:
            values[f"{name}.type"] = type_name
        self.set_parameters(values)

    def set_hardware_state(self, name: str, state: State) -> tuple[bool, str]:
        resp = self.call(
            "set_hardware_component_state", {"name": name, "target_state": {"id": state.id, "label": state.value}}
        )
        return bool(resp.ok), str(resp.state.label)

