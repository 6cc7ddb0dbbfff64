"""ROS name rules (rmw/rcl validators) with rclpy's exceptions, and topic/service name expansion."""

from __future__ import annotations

from diffctl.client.exceptions import (
    InvalidNamespaceException,
    InvalidNodeNameException,
    InvalidServiceNameException,
    InvalidTopicNameException,
)


def _bad_char(name: str, allowed: str) -> int:
    for i, c in enumerate(name):
        if not (c.isascii() and c.isalnum()) and c not in allowed:
            return i
    return -1


def validate_node_name(node_name: str) -> bool:
    if not node_name:
        raise InvalidNodeNameException(node_name, "node name must not be empty", 0)
    i = _bad_char(node_name, "_")
    if i >= 0:
        raise InvalidNodeNameException(
            node_name, "node name must not contain characters other than alphanumerics or '_'", i)
    if node_name[0].isdigit():
        raise InvalidNodeNameException(node_name, "node name must not start with a number", 0)
    if len(node_name) > 255:
        raise InvalidNodeNameException(node_name, "node name length should not exceed 255", 254)
    return True


def normalize_namespace(namespace: str | None) -> str:
    ns = namespace or "/"
    return ns if ns.startswith("/") else "/" + ns


def validate_namespace(namespace: str) -> bool:
    if not namespace:
        raise InvalidNamespaceException(namespace, "namespace must not be empty", 0)
    if not namespace.startswith("/"):
        raise InvalidNamespaceException(namespace, "namespace must be absolute, it must lead with a '/'", 0)
    if namespace == "/":
        return True
    if namespace.endswith("/"):
        raise InvalidNamespaceException(
            namespace, "namespace must not end with a '/', unless only a '/'", len(namespace) - 1)
    i = _bad_char(namespace, "_/")
    if i >= 0:
        raise InvalidNamespaceException(
            namespace, "namespace must not contain characters other than alphanumerics, '_', or '/'", i)
    i = namespace.find("//")
    if i >= 0:
        raise InvalidNamespaceException(namespace, "namespace must not contain repeated '/'", i + 1)
    pos = 0
    for token in namespace.split("/"):
        if token and token[0].isdigit():
            raise InvalidNamespaceException(namespace, "namespace must not have a token that starts with a number",
                                            pos)
        pos += len(token) + 1
    return True


def validate_topic_name(name: str, *, is_service: bool = False) -> bool:
    """rcl_validate_topic_name: the same checks and words for topics and services (only the exception's
    name differs)."""
    exc = InvalidServiceNameException if is_service else InvalidTopicNameException
    if not name:
        raise exc(name, "topic name must not be empty string", 0)
    if name.endswith("/"):
        raise exc(name, "topic name must not end with a forward slash", len(name) - 1)
    curly = -1
    for i, c in enumerate(name):
        if c.isascii() and (c.isalnum() or c == "_"):
            if curly >= 0 and i == curly + 1 and c.isdigit():
                raise exc(name, "substitution name must not start with a number", i)
        elif c == "/" and curly < 0:
            continue
        elif c == "~" and curly < 0:
            if i != 0:
                raise exc(name, "topic name must not have tilde '~' unless it is the first character", i)
        elif c == "{" and curly < 0:
            curly = i
        elif c == "}" and curly >= 0:
            curly = -1
        elif c in "{}":
            raise exc(name, "topic name must not have unmatched (unbalanced) curly braces '{}'", i)
        elif curly >= 0:
            raise exc(name, "substitution name must not contain characters other than alphanumerics or '_'", i)
        else:
            raise exc(name, "topic name must not contain characters other than alphanumerics, '_', '~', '{', or '}'",
                      i)
    if curly >= 0:
        raise exc(name, "topic name must not have unmatched (unbalanced) curly braces '{}'", curly)
    pos = 0
    for token in name.split("/"):
        if token and token[0].isdigit():
            raise exc(name, "topic name token must not start with a number", pos)
        pos += len(token) + 1
    return True


def expand_topic_name(name: str, node_name: str, namespace: str) -> str:
    """`~/x` → `/ns/node/x`, `x` → `/ns/x`, `{node}`/`{ns}` substituted, as rcl_expand_topic_name does."""
    ns = namespace.rstrip("/")
    out = name.replace("{node}", node_name).replace("{ns}", ns or "/").replace("{namespace}", ns or "/")
    if out.startswith("~"):
        out = f"{ns}/{node_name}{out[1:]}"
    elif not out.startswith("/"):
        out = f"{ns}/{out}"
    return out


def validate_full_topic_name(name: str, *, is_service: bool = False) -> bool:
    """A fully qualified name: absolute, no `~` or substitutions left."""
    exc = InvalidServiceNameException if is_service else InvalidTopicNameException
    what = "service name" if is_service else "topic name"
    if not name.startswith("/"):
        raise exc(name, f"{what} must be absolute, it must lead with a '/'", 0)
    i = _bad_char(name, "_/")
    if i >= 0:
        raise exc(name, f"{what} must not contain characters other than alphanumerics, '_', or '/'", i)
    return validate_topic_name(name, is_service=is_service)
