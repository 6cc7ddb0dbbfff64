"""`~/get_type_description` of a bus node, answered from diffctl.interfaces.type_description."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from diffctl.interfaces import types
from diffctl.interfaces.type_description import SERVICE_TYPE, describe

if TYPE_CHECKING:
    from diffctl.bus.endpoints import Service
    from diffctl.bus.node import Node


class TypeDescriptionService:
    """`~/get_type_description`: answers for the types this node's endpoints use, matched by hash as rcl does."""

    def __init__(self, node: Node) -> None:
        from diffctl.bus.endpoints import Service

        self.node = node
        self.used: dict[str, str] = {}  # RIHS01 hash → type name
        self.service: Service = Service(node, "~/get_type_description", SERVICE_TYPE, self.handle)

    def use(self, typename: str) -> None:
        self.used.setdefault(types.type_hash(typename), typename)

    def handle(self, req: Any) -> dict[str, Any]:
        typename = self.used.get(str(req.type_hash))
        if typename is None:
            return {"successful": False, "failure_reason": "Type not currently in use by this node"}
        out: dict[str, Any] = {"successful": True, "type_description": describe(typename)}
        if req.include_type_sources:
            encoding = "srv" if "/srv/" in typename else "msg"
            out["type_sources"] = [{"type_name": typename, "encoding": encoding,
                                    "raw_file_contents": types.definition(typename)}]
        return out

    def close(self) -> None:
        self.service.close()
