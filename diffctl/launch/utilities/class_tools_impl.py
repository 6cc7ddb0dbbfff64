"""Instance and subclass checks used throughout launch."""

import inspect


def isclassinstance(obj) -> bool:
    """True when `obj` is an instance of some class (in Python 3, anything with a `__class__`)."""
    return hasattr(obj, '__class__')


def is_a(obj, entity_type) -> bool:
    """`isinstance(obj, entity_type)`, after checking that `entity_type` really is a class."""
    if not isclassinstance(obj):
        raise RuntimeError(f"obj '{obj}' is not a class instance")
    if not inspect.isclass(entity_type):
        raise RuntimeError(f"entity_type '{obj}' is not a class")
    return isinstance(obj, entity_type)


def is_a_subclass(obj, entity_type) -> bool:
    """True when `obj` is an instance of `entity_type` or is itself a subclass of it."""
    return is_a(obj, entity_type) or (inspect.isclass(obj) and issubclass(obj, entity_type))
