"""twist_mux (Jazzy): velocity commands from several topics, by priority, with timeouts and locks."""
