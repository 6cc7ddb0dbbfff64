"""The world's `create` service with a ros2_control model: the description is parsed and the controller
manager's node built on the request's thread, not the simulation loop's; a refused create leaves no manager."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest
from sim_helpers import CAR_CONTROL, EMPTY_WORLD, REPO

from diffctl.description.sdf_loader import load_world
from diffctl.errors import RuntimeFailure

CONTROLLERS = REPO / "config" / "diff_drive_controller.yaml"


def test_create_builds_the_manager_off_the_sim_thread_and_a_refused_create_closes_it(
    router: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    from diffctl.bus import open_session
    from diffctl.sim import services as services_mod
    from diffctl.sim.plugins.gz_ros2_control import PreparedManager
    from diffctl.sim.runner import Simulation
    from diffctl.sim.services import WorldServices
    from diffctl.sim.world_client import call, wait_for_world
    from tests.probe import Probe

    built: list[tuple[PreparedManager, threading.Thread]] = []
    parsed_on: list[threading.Thread] = []
    init, parse = PreparedManager.__init__, services_mod.parse_description

    def recording_init(self: PreparedManager, *a: Any, **k: Any) -> None:
        built.append((self, threading.current_thread()))
        init(self, *a, **k)

    def recording_parse(*a: Any, **k: Any) -> Any:
        parsed_on.append(threading.current_thread())
        return parse(*a, **k)

    monkeypatch.setattr(PreparedManager, "__init__", recording_init)
    monkeypatch.setattr(services_mod, "parse_description", recording_parse)
    session = open_session()
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0, paused=True, session=session)
    WorldServices(sim)
    stop = threading.Event()
    loop = threading.Thread(target=sim.run, args=(stop,), name="sim-loop")
    loop.start()
    client = Probe("create_test_client")
    try:
        text = CAR_CONTROL.read_text().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", str(CONTROLLERS))
        deadline = time.monotonic() + 20.0
        world = wait_for_world(session, None, deadline)
        assert call(session, world, "create", {"sdf": text, "name": "robot"}, deadline)["name"] == "robot"
        assert len(built) == 1 and built[0][1] is not loop and parsed_on[0] is not loop
        first = built[0][0]
        assert first.adopted and sim.models["robot"].control is not None
        assert sim.models["robot"].control.node is first.node
        # The adopted manager serves as before: its hardware is active.
        listing = client.create_client(
            "/controller_manager/list_hardware_components", "controller_manager_msgs/srv/ListHardwareComponents"
        )
        assert listing.wait_for_service(10.0)
        comps = listing.call({}, timeout=10.0).component
        assert [(c.name, c.state.label) for c in comps] == [("robot", "active")]

        # The name is taken: refused on the sim thread after the manager was built, which is then closed.
        with pytest.raises(RuntimeFailure, match="already exists"):
            call(session, world, "create", {"sdf": text, "name": "robot"}, time.monotonic() + 20.0)
        assert len(built) == 2
        refused = built[1][0]
        assert not refused.adopted and refused.node is None and refused.stop.is_set()
        assert list(sim.models) == ["ground_plane", "robot"]
        assert sim.models["robot"].control.node is first.node
        # A bad description is refused on the request's thread, before the sim thread sees it.
        with pytest.raises(RuntimeFailure, match="no such file"):
            call(session, world, "create", {"sdf_filename": "/nonexistent.sdf"}, time.monotonic() + 20.0)
        assert len(built) == 2
    finally:
        client.close()
        stop.set()
        loop.join(10.0)
        sim.close()
