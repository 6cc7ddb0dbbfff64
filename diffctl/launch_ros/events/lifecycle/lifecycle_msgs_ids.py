"""The ids of lifecycle_msgs/msg/Transition and lifecycle_msgs/msg/State (Jazzy) with their constant names.

Written out here so that importing launch_ros does not build the message classes (most launches have no
managed node); tests/launch_ros check them against the message definitions.
"""

TRANSITIONS: dict[int, str] = {
    0: "TRANSITION_CREATE",
    1: "TRANSITION_CONFIGURE",
    2: "TRANSITION_CLEANUP",
    3: "TRANSITION_ACTIVATE",
    4: "TRANSITION_DEACTIVATE",
    5: "TRANSITION_UNCONFIGURED_SHUTDOWN",
    6: "TRANSITION_INACTIVE_SHUTDOWN",
    7: "TRANSITION_ACTIVE_SHUTDOWN",
    8: "TRANSITION_DESTROY",
}

STATES: dict[int, str] = {
    0: "PRIMARY_STATE_UNKNOWN",
    1: "PRIMARY_STATE_UNCONFIGURED",
    2: "PRIMARY_STATE_INACTIVE",
    3: "PRIMARY_STATE_ACTIVE",
    4: "PRIMARY_STATE_FINALIZED",
    10: "TRANSITION_STATE_CONFIGURING",
    11: "TRANSITION_STATE_CLEANINGUP",
    12: "TRANSITION_STATE_SHUTTINGDOWN",
    13: "TRANSITION_STATE_ACTIVATING",
    14: "TRANSITION_STATE_DEACTIVATING",
    15: "TRANSITION_STATE_ERRORPROCESSING",
}
