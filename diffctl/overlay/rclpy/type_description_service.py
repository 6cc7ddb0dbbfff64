"""rclpy.type_description_service (diffctl: diffctl.client.type_description_service)."""

from diffctl.client.type_description_service import (  # noqa: F401
    START_TYPE_DESCRIPTION_SERVICE_PARAM,
    TypeDescriptionService,
)

TOPIC_SEPARATOR_STRING = "/"
