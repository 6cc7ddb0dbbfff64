"""topic_tools (Jazzy): relay, throttle, drop, delay, mux, demux and relay_field on diffctl's client Node.

The tools forward any message type as raw CDR, with the type and QoS of the input's publishers found on
the graph (`source_qos`), as upstream's generic publishers and subscriptions do; what to let through is
decided by the pure gates of `gates`.
"""
