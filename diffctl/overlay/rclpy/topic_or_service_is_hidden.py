"""rclpy.topic_or_service_is_hidden."""

HIDDEN_TOPIC_PREFIX = "_"


def topic_or_service_is_hidden(name: str) -> bool:
    """A name any of whose tokens starts with an underscore (hidden from tools by default)."""
    return any(token.startswith(HIDDEN_TOPIC_PREFIX) for token in name.split("/"))
