"""ROS names: rmw's and rcl's validators, rcl's expansion and resolution, with the exceptions and texts rclpy
gives users (rclpy reaches rcl through pybind11, so its failures carry rcl's `, at <file>:<line>` tails).

Each `*_problem` function answers `(what is wrong, index)` or None; the `validate_*` functions raise rclpy's
exceptions from that; `expand_topic_name` and `resolve_name` fail as rclpy's bindings of rcl do.
"""

from __future__ import annotations

from diffctl.client.exceptions import (
    InvalidNamespaceException,
    InvalidNodeNameException,
    InvalidServiceNameException,
    InvalidTopicNameException,
    RCLError,
)

NODE_NAME_MAX = 255  # rmw's limits
TOPIC_NAME_MAX = 255 - 8
NAMESPACE_MAX = TOPIC_NAME_MAX - 2

# Where rcl sets each error a user can see (rcl 9.2's sources, as the Jazzy wheels report them).
_AT_EXPAND_TOPIC = "/project/src/rcl/expand_topic_name.c:73"
_AT_EXPAND_NODE = "/project/src/rcl/expand_topic_name.c:84"
_AT_EXPAND_NAMESPACE = "/project/src/rcl/expand_topic_name.c:94"
_AT_EXPAND_SUBSTITUTION = "/project/src/rcl/expand_topic_name.c:163"
_AT_RESOLVE_FULL = "/project/src/rcl/node_resolve_name.c:102"
_AT_VALIDATE_NULL = "/project/src/rcl/validate_topic_name.c:35"

Problem = tuple[str, int] | None


def _word(c: str) -> bool:
    """rcutils_isalnum_no_locale or '_': ASCII only, whatever the locale."""
    return c == "_" or ("a" <= c <= "z") or ("A" <= c <= "Z") or ("0" <= c <= "9")


def _digit(c: str) -> bool:
    return "0" <= c <= "9"


def _check_str(value: object, what: str) -> str:
    if value is None:  # pybind11 hands None to rcl as a null pointer
        raise RCLError(f"failed to validate name: {what} argument is null, at {_AT_VALIDATE_NULL}")
    if not isinstance(value, str):
        raise TypeError(f"incompatible function arguments: {what} must be str, not {type(value).__name__}")
    return value


def rmw_result_code(reason: str) -> int:
    """The number rmw gives a node name's or a namespace's problem (rcl prints it as `result: N`)."""
    for codes in (_NODE_NAME_CODES, _NAMESPACE_CODES):
        if reason in codes:
            return codes.index(reason) + 1
    return 0


def node_name_problem(name: str) -> Problem:
    if not name:
        return "node name must not be empty", 0
    for i, c in enumerate(name):
        if not _word(c):
            return "node name must not contain characters other than alphanumerics or '_'", i
    if _digit(name[0]):
        return "node name must not start with a number", 0
    if len(name) > NODE_NAME_MAX:
        return f"node name length should not exceed '{NODE_NAME_MAX}'", NODE_NAME_MAX - 1
    return None


def full_topic_name_problem(name: str) -> Problem:
    """rmw_validate_full_topic_name: an expanded, absolute name as the middleware gets it."""
    if not name:
        return "topic name must not be empty", 0
    if name[0] != "/":
        return "topic name must be absolute, it must lead with a '/'", 0
    if name[-1] == "/":
        return "topic name must not end with a '/'", len(name) - 1
    for i, c in enumerate(name):
        if c != "/" and not _word(c):
            return "topic name must not contain characters other than alphanumerics, '_', or '/'", i
    for i in range(len(name) - 1):
        if name[i] == "/":
            if name[i + 1] == "/":
                return "topic name must not contain repeated '/'", i + 1
            if _digit(name[i + 1]):
                return "topic name must not have a token that starts with a number", i + 1
    if len(name) > TOPIC_NAME_MAX:
        # rmw stringifies its macro's expression, not its value
        return "topic length should not exceed '255U - 8U'", TOPIC_NAME_MAX - 1
    return None


_NAMESPACE_WORDS = {
    "topic name must not be empty": "namespace must not be empty",
    "topic name must be absolute, it must lead with a '/'": "namespace must be absolute, it must lead with a '/'",
    "topic name must not end with a '/'": "namespace must not end with a '/', unless only a '/'",
    "topic name must not contain characters other than alphanumerics, '_', or '/'":
        "namespace must not contain characters other than alphanumerics, '_', or '/'",
    "topic name must not contain repeated '/'": "namespace must not contain repeated '/'",
    "topic name must not have a token that starts with a number":
        "namespace must not have a token that starts with a number",
}


_NODE_NAME_CODES = ("node name must not be empty",
                    "node name must not contain characters other than alphanumerics or '_'",
                    "node name must not start with a number", f"node name length should not exceed '{NODE_NAME_MAX}'")
_NAMESPACE_CODES = (*_NAMESPACE_WORDS.values(), "namespace should not exceed 'RMW_NAMESPACE_MAX_NAME_LENGTH'")


def namespace_problem(namespace: str) -> Problem:
    """rmw_validate_namespace: a full topic name's rules in a namespace's words, and a shorter limit."""
    if namespace == "/":
        return None
    problem = full_topic_name_problem(namespace)
    if problem is not None and problem[0] in _NAMESPACE_WORDS:
        return _NAMESPACE_WORDS[problem[0]], problem[1]
    if len(namespace) > NAMESPACE_MAX:
        # the macro rmw names here does not exist, so its name is what gets stringified
        return "namespace should not exceed 'RMW_NAMESPACE_MAX_NAME_LENGTH'", NAMESPACE_MAX - 1
    return None


def topic_name_problem(name: str) -> Problem:
    """rcl_validate_topic_name: a name as a user writes it (relative, `~`, `{substitutions}`)."""
    if not name:
        return "topic name must not be empty string", 0
    if _digit(name[0]):
        return "topic name token must not start with a number", 0
    if name[-1] == "/":
        return "topic name must not end with a forward slash", len(name) - 1
    brace = -1  # index of the open '{', while inside one
    for i, c in enumerate(name):
        if _word(c):
            if brace >= 0 and i == brace + 1 and _digit(c):
                return "substitution name must not start with a number", i
        elif c == "~":
            if i != 0:
                return "topic name must not have tilde '~' unless it is the first character", i
        elif c == "}":
            if brace < 0:
                return "topic name must not have unmatched (unbalanced) curly braces '{}'", i
            brace = -1
        elif brace >= 0:  # '/', '{' or anything else inside a substitution
            return "substitution name must not contain characters other than alphanumerics or '_'", i
        elif c == "{":
            brace = i
        elif c != "/":
            return "topic name must not contain characters other than alphanumerics, '_', '~', '{', or '}'", i
    if brace >= 0:
        return "topic name must not have unmatched (unbalanced) curly braces '{}'", brace
    for i in range(len(name) - 1):
        if name[i] == "/":
            if _digit(name[i + 1]):
                return "topic name token must not start with a number", i + 1
        elif i == 1 and name[0] == "~":
            return "topic name must not have a tilde '~' that is not followed by a forward slash '/'", 1
    return None


def validate_node_name(node_name: str) -> bool:
    problem = node_name_problem(_check_str(node_name, "node_name"))
    if problem is not None:
        raise InvalidNodeNameException(node_name, *problem)
    return True


def validate_namespace(namespace: str) -> bool:
    problem = namespace_problem(_check_str(namespace, "namespace"))
    if problem is not None:
        raise InvalidNamespaceException(namespace, *problem)
    return True


def validate_topic_name(name: str, *, is_service: bool = False) -> bool:
    problem = topic_name_problem(_check_str(name, "topic_name"))
    if problem is not None:
        raise (InvalidServiceNameException if is_service else InvalidTopicNameException)(name, *problem)
    return True


def validate_full_topic_name(name: str, *, is_service: bool = False) -> bool:
    problem = full_topic_name_problem(_check_str(name, "topic_name"))
    if problem is not None:
        raise (InvalidServiceNameException if is_service else InvalidTopicNameException)(name, *problem)
    return True


def normalize_namespace(namespace: str | None) -> str:
    """What rcl_node_init makes of a namespace: '' is '/', a relative one is made absolute."""
    ns = namespace or "/"
    return ns if ns.startswith("/") else "/" + ns


class _ExpandError(Exception):
    """A failed expansion: rcl's words and where rcl set them, and which argument was at fault."""

    def __init__(self, what: str, value: str, reason: str, where: str) -> None:
        super().__init__(reason)
        self.what, self.value, self.reason, self.where = what, value, reason, where


def _expand(name: str, node_name: str, namespace: str) -> str:
    """rcl_expand_topic_name: `~` first, then the `{node}`/`{ns}`/`{namespace}` substitutions, then the
    namespace in front of a relative result."""
    problem = topic_name_problem(name)
    if problem is not None:
        raise _ExpandError("topic name", name, problem[0], _AT_EXPAND_TOPIC)
    problem = node_name_problem(node_name)
    if problem is not None:
        raise _ExpandError("node name", node_name, problem[0], _AT_EXPAND_NODE)
    problem = namespace_problem(namespace)
    if problem is not None:
        raise _ExpandError("node namespace", namespace, problem[0], _AT_EXPAND_NAMESPACE)
    if name[0] == "/" and "{" not in name:
        return name
    # namespace '/' adds no separator of its own
    prefix = namespace if namespace == "/" else namespace + "/"
    out = prefix + node_name + name[1:] if name[0] == "~" else name
    while "{" in out:
        start = out.index("{")
        end = out.index("}", start)
        key = out[start:end + 1]
        if key == "{node}":
            value = node_name
        elif key in ("{ns}", "{namespace}"):
            value = namespace
        else:  # rcl's default substitution map is empty
            raise _ExpandError("topic name", name, f"unknown substitution: {key}", _AT_EXPAND_SUBSTITUTION)
        out = out.replace(key, value)
    return out if out[0] == "/" else prefix + out


def expand_topic_name(topic_name: str, node_name: str, node_namespace: str) -> str:
    """rclpy.expand_topic_name: `~/x` → `/ns/node/x`, `x` → `/ns/x`, `{node}`/`{ns}` substituted; an invalid
    argument raises ValueError naming it, with rcl's reason."""
    for value, what in ((topic_name, "topic_name"), (node_name, "node_name"), (node_namespace, "node_namespace")):
        if not isinstance(value, str):
            raise TypeError(f"rclpy_expand_topic_name(): incompatible function arguments: {what} must be str, "
                            f"not {type(value).__name__}")
    try:
        return _expand(topic_name, node_name, node_namespace)
    except _ExpandError as e:
        raise ValueError(f"{e.what} '{e.value}' is invalid: {e.reason}, at {e.where}") from None


def resolve_name(name: str, node_name: str, namespace: str, remaps: dict[str, str], *,
                 only_expand: bool = False) -> str:
    """rcl_node_resolve_name: expanded, remapped (the first matching rule), then checked as a full name; a
    failure raises rclpy's RCLError with rcl's reason."""
    if name is None:
        raise RCLError("failed to resolve name: input_topic_name argument is null, at "
                       "/project/src/rcl/expand_topic_name.c:60")
    if not isinstance(name, str):
        raise TypeError("rclpy_resolve_name(): incompatible function arguments: the name must be str, "
                        f"not {type(name).__name__}")
    try:
        full = _expand(name, node_name, namespace)
    except _ExpandError as e:
        raise RCLError(f"failed to resolve name: {e.reason}, at {e.where}") from None
    if not only_expand:
        full = remaps.get(full, full)
    problem = full_topic_name_problem(full)
    if problem is not None:
        raise RCLError(f"failed to resolve name: {problem[0]}, at {_AT_RESOLVE_FULL}")
    return full
