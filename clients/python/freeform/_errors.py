"""FreeformError: a failed call, with the field the server named.

freeformd answers a request that breaks a rule with INVALID_ARGUMENT (or
RESOURCE_EXHAUSTED over a limit) and a ``google.rpc.Status`` in the binary
trailer ``grpc-status-details-bin`` whose details hold a
``google.rpc.BadRequest``: one field violation per broken rule, each the
full path of the field in the request (``curve.bspline.knots[4]``) and the
rule (docs/clients.md).

The google.rpc messages are decoded in a descriptor pool of this module's
own, built from the descriptor set generated with the package
(``_google_rpc.binpb``), so that this package never registers
``google/rpc/*.proto`` in protobuf's default pool, where another package
(googleapis-common-protos) may hold a different version of the same files.
"""

from __future__ import annotations

import functools
from importlib import resources
from typing import Any, NamedTuple, Optional, Tuple

import grpc
from google.protobuf import descriptor_pb2, descriptor_pool, message_factory
from google.protobuf.message import DecodeError

_DETAILS_KEY = "grpc-status-details-bin"
_BAD_REQUEST = "google.rpc.BadRequest"


class FieldViolation(NamedTuple):
    """One broken rule: the request field's full path and the rule."""

    field: str
    description: str


@functools.lru_cache(maxsize=None)
def _message_classes():
    """The (Status, BadRequest) classes, from the package's descriptor set."""
    data = resources.files("freeform").joinpath("_google_rpc.binpb")
    files = descriptor_pb2.FileDescriptorSet.FromString(data.read_bytes())
    pool = descriptor_pool.DescriptorPool()
    for file in files.file:
        pool.Add(file)
    get_class = getattr(message_factory, "GetMessageClass", None)
    if get_class is None:  # protobuf < 4.22
        get_class = message_factory.MessageFactory(pool).GetPrototype
    return (get_class(pool.FindMessageTypeByName("google.rpc.Status")),
            get_class(pool.FindMessageTypeByName(_BAD_REQUEST)))


def field_violations(details: bytes) -> Tuple[FieldViolation, ...]:
    """The BadRequest field violations of a serialized google.rpc.Status."""
    status_class, bad_request_class = _message_classes()
    violations = []
    for detail in status_class.FromString(details).details:
        # type.googleapis.com/google.rpc.BadRequest (any host).
        if detail.type_url.rpartition("/")[2] == _BAD_REQUEST:
            for violation in bad_request_class.FromString(
                    detail.value).field_violations:
                violations.append(FieldViolation(violation.field,
                                                 violation.description))
    return tuple(violations)


class FreeformError(Exception):
    """A call that failed: the gRPC status code and message and, when the
    server named them, the offending fields.

    Attributes:
      code: the ``grpc.StatusCode`` (INVALID_ARGUMENT, RESOURCE_EXHAUSTED,
        DEADLINE_EXCEEDED, UNAVAILABLE, ...).
      message: the status message (for a bad request it starts with the
        field's path).
      violations: every ``FieldViolation`` of the google.rpc.BadRequest
        detail (empty when there is none).
      field, description: those of the first violation, or None.
      rpc_error: the ``grpc.RpcError`` this error was made from, if any.
    """

    def __init__(self, code: grpc.StatusCode, message: str,
                 violations: Tuple[FieldViolation, ...] = (),
                 rpc_error: Optional[grpc.RpcError] = None):
        super().__init__("%s: %s" % (code.name, message))
        self.code = code
        self.message = message
        self.violations = violations
        self.rpc_error = rpc_error

    def __reduce__(self) -> Any:
        # Picklable (to cross process pools), without the gRPC error.
        return (type(self), (self.code, self.message, self.violations))

    @property
    def field(self) -> Optional[str]:
        return self.violations[0].field if self.violations else None

    @property
    def description(self) -> Optional[str]:
        return self.violations[0].description if self.violations else None

    @classmethod
    def from_rpc_error(cls, error: grpc.RpcError) -> "FreeformError":
        """The FreeformError of a failed gRPC call, with its BadRequest."""
        code = error.code() if hasattr(error, "code") else None
        if not isinstance(code, grpc.StatusCode):
            code = grpc.StatusCode.UNKNOWN
        message = error.details() if hasattr(error, "details") else None
        violations: Tuple[FieldViolation, ...] = ()
        metadata = (error.trailing_metadata()
                    if hasattr(error, "trailing_metadata") else None)
        for key, value in metadata or ():
            if key == _DETAILS_KEY:
                try:
                    violations += field_violations(value)
                except DecodeError:
                    pass  # The code and message still say what failed.
        return cls(code, message or str(error), violations, error)
