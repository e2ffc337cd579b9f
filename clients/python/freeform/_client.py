"""freeform.Client: one gRPC channel to freeformd and its two services.

``client.curves`` and ``client.surfaces`` hold a method per RPC of
CurveService and SurfaceService (numpy arrays in and out); ``client.call``
and ``client.stream`` run any RPC with its request message. Every failure
is a FreeformError. A Client is thread-safe; close it (or use ``with``) to
release the channel.
"""

from __future__ import annotations

import functools
import json
from typing import (Any, Callable, Dict, Mapping, Optional, Sequence, Tuple,
                    TypeVar, Union)

import grpc
from google.protobuf import json_format
from google.protobuf import message as _message

from freeform._curves import Curves
from freeform._errors import FreeformError
from freeform._stream import Stream, converted
from freeform._surfaces import Surfaces
from freeform._wire import View
from freeform.v1 import curve_service_pb2 as _curves
from freeform.v1 import geometry_pb2 as _geometry
from freeform.v1 import query_pb2 as _query
from freeform.v1 import surface_service_pb2 as _surfaces

T = TypeVar("T")

# The services this package wraps, by their short names.
_SERVICES = {
    "CurveService": _curves.DESCRIPTOR.services_by_name["CurveService"],
    "SurfaceService": _surfaces.DESCRIPTOR.services_by_name["SurfaceService"],
}
# The message classes of freeform.v1, by full name.
_MESSAGE_CLASSES: Dict[str, Any] = {
    descriptor.full_name: getattr(module, name)
    for module in (_geometry, _query, _curves, _surfaces)
    for name, descriptor in module.DESCRIPTOR.message_types_by_name.items()
}


def tls_credentials(root_ca: Optional[str] = None,
                    cert: Optional[str] = None,
                    key: Optional[str] = None) -> grpc.ChannelCredentials:
    """TLS credentials from PEM files: the CA that signed the server
    (default: the system's roots) and, for mutual TLS, the client's
    certificate chain and key. Pass them as ``Client(..., tls=...)``."""

    def read(path: Optional[str]) -> Optional[bytes]:
        if path is None:
            return None
        with open(path, "rb") as file:
            return file.read()

    if (cert is None) != (key is None):
        raise ValueError("mutual TLS needs both cert and key")
    return grpc.ssl_channel_credentials(read(root_ca), read(key), read(cert))


def _service_config(round_robin: bool, retry_unavailable: bool) -> str:
    """The channel's service config: the load balancing policy and, as the
    C++ client does, up to 4 attempts of a call that fails UNAVAILABLE."""
    config: Dict[str, Any] = {"loadBalancingConfig": [
        {"round_robin" if round_robin else "pick_first": {}}]}
    if retry_unavailable:
        config["methodConfig"] = [{
            "name": [{"service": service.full_name}
                     for service in _SERVICES.values()],
            "retryPolicy": {
                "maxAttempts": 4, "initialBackoff": "0.05s",
                "maxBackoff": "1s", "backoffMultiplier": 2,
                "retryableStatusCodes": ["UNAVAILABLE"]},
        }]
    return json.dumps(config)


@functools.lru_cache(maxsize=None)
def _method(name: str):
    """The method descriptor of "CurveService.Evaluate",
    "freeform.v1.CurveService/Evaluate" or its path "/freeform.v1.../..."."""
    service_name, separator, method_name = (
        name.lstrip("/").replace("/", ".").rpartition("."))
    service = _SERVICES.get(service_name.rpartition(".")[2])
    if (not separator or service is None or
            service_name not in (service.name, service.full_name) or
            method_name not in service.methods_by_name):
        raise ValueError(
            "unknown method %r: give Service.Method, e.g. "
            "'CurveService.Evaluate' (services: %s)" %
            (name, ", ".join(_SERVICES)))
    return service.methods_by_name[method_name]


def _serialize(request: _message.Message) -> bytes:
    return request.SerializeToString()


def _path(method) -> str:
    return "/%s/%s" % (method.containing_service.full_name, method.name)


class Client:
    """A connection to freeformd.

    Args:
      address: a gRPC target: "host:port", "dns:///name:port",
        "ipv4:a:p,b:p", ...
      timeout: the deadline of each call in seconds (None: no deadline; the
        server still bounds a call by its --max_call_time). Every method
        also takes ``timeout=`` for one call.
      tls: False (plaintext), True (TLS with the system's root
        certificates) or grpc.ChannelCredentials (``tls_credentials``).
      metadata: (key, value) pairs sent with every call.
      max_receive_message_bytes: the largest answer accepted (the server
        sends up to its --max_message_bytes, 64 MiB by default); larger
        answers need the *_stream methods.
      retry_unavailable: retry a call that fails UNAVAILABLE (4 attempts).
      round_robin: balance calls over every address ``address`` resolves
        to.
      options: more gRPC channel options.
      channel: use this channel instead of making one (the other
        connection arguments are then ignored; close() closes it).

    Attributes:
      curves: CurveService's methods (freeform.Curves).
      surfaces: SurfaceService's methods (freeform.Surfaces).
    """

    def __init__(self, address: str = "localhost:50051", *,
                 timeout: Optional[float] = 30.0,
                 tls: Union[bool, grpc.ChannelCredentials] = False,
                 metadata: Sequence[Tuple[str, str]] = (),
                 max_receive_message_bytes: int = 64 << 20,
                 retry_unavailable: bool = True,
                 round_robin: bool = False,
                 options: Sequence[Tuple[str, Any]] = (),
                 channel: Optional[grpc.Channel] = None):
        self.timeout = timeout
        self.metadata = tuple(metadata)
        if channel is None:
            channel_options = [
                ("grpc.max_receive_message_length", max_receive_message_bytes),
                ("grpc.service_config",
                 _service_config(round_robin, retry_unavailable)),
                ("grpc.enable_retries", int(retry_unavailable)),
            ] + list(options)
            if isinstance(tls, grpc.ChannelCredentials):
                channel = grpc.secure_channel(address, tls, channel_options)
            elif tls:
                channel = grpc.secure_channel(
                    address, grpc.ssl_channel_credentials(), channel_options)
            else:
                channel = grpc.insecure_channel(address, channel_options)
        self._channel = channel
        self._callables: Dict[Tuple[str, bool], Any] = {}
        self.curves = Curves(self)
        self.surfaces = Surfaces(self)

    # ------------------------------------------------------------ lifetime

    def close(self) -> None:
        """Closes the channel; calls in flight are cancelled."""
        self._channel.close()

    def __enter__(self) -> "Client":
        return self

    def __exit__(self, *exception: Any) -> None:
        self.close()

    def wait_until_ready(self, timeout: Optional[float] = None) -> None:
        """Blocks until the channel has connected (FreeformError
        UNAVAILABLE after ``timeout`` seconds, default the client's)."""
        seconds = self.timeout if timeout is None else timeout
        try:
            grpc.channel_ready_future(self._channel).result(timeout=seconds)
        except grpc.FutureTimeoutError:
            raise FreeformError(
                grpc.StatusCode.UNAVAILABLE,
                "not connected within %s s" % seconds) from None

    # --------------------------------------------------------- any RPC

    def call(self, method: str,
             request: Union[_message.Message, Mapping[str, Any]], *,
             timeout: Optional[float] = None) -> _message.Message:
        """Runs the unary RPC ``method`` ("CurveService.ElevateDegree") with
        ``request``: its request message, or a dict in proto3 JSON form
        (the JSON files of examples/ after json.load). Returns the response
        message."""
        descriptor = _method(method)
        if descriptor.server_streaming:
            raise ValueError("%s streams its answers: use stream()" % method)
        response_class = _MESSAGE_CLASSES[descriptor.output_type.full_name]
        return self._unary(_path(descriptor),
                           self._request(descriptor, request),
                           response_class.FromString, timeout)

    def stream(self, method: str,
               request: Union[_message.Message, Mapping[str, Any]], *,
               timeout: Optional[float] = None) -> Stream[_message.Message]:
        """Runs the server-streaming RPC ``method``
        ("SurfaceService.TessellateStream"); yields the response messages."""
        descriptor = _method(method)
        if not descriptor.server_streaming:
            raise ValueError("%s is unary: use call()" % method)
        response_class = _MESSAGE_CLASSES[descriptor.output_type.full_name]
        return self._stream(_path(descriptor),
                            self._request(descriptor, request),
                            response_class.FromString, timeout)

    @staticmethod
    def _request(descriptor, request) -> _message.Message:
        request_class = _MESSAGE_CLASSES[descriptor.input_type.full_name]
        if isinstance(request, Mapping):
            return json_format.ParseDict(request, request_class())
        if not isinstance(request, request_class):
            raise TypeError("%s takes a %s, not %s" % (
                descriptor.full_name, request_class.__name__,
                type(request).__name__))
        return request

    # ------------------------------------------------------- transport

    def _callable(self, path: str, streaming: bool):
        key = (path, streaming)
        callable_ = self._callables.get(key)
        if callable_ is None:
            make = (self._channel.unary_stream if streaming else
                    self._channel.unary_unary)
            # The answers stay bytes here: the services' wrappers read
            # their arrays from those bytes (freeform._wire).
            callable_ = make(path, request_serializer=_serialize,
                             response_deserializer=None)
            self._callables[key] = callable_
        return callable_

    def _timeout(self, timeout: Optional[float]) -> Optional[float]:
        return self.timeout if timeout is None else timeout

    def _unary(self, path: str, request: _message.Message,
               convert: Callable[[bytes], T],
               timeout: Optional[float]) -> T:
        try:
            answer = self._callable(path, False)(
                request, timeout=self._timeout(timeout),
                metadata=self.metadata or None)
        except grpc.RpcError as error:
            raise FreeformError.from_rpc_error(error) from None
        return converted(convert, answer)

    def _stream(self, path: str, request: _message.Message,
                convert: Callable[[bytes], T],
                timeout: Optional[float]) -> Stream[T]:
        call = self._callable(path, True)(
            request, timeout=self._timeout(timeout),
            metadata=self.metadata or None)
        return Stream(call, convert)

    def _rpc(self, method: str, request: _message.Message,
             convert: Callable[[View], T], timeout: Optional[float]) -> T:
        """The unary ``method``, its answer converted from its View."""
        descriptor = _method(method)
        response_class = _MESSAGE_CLASSES[descriptor.output_type.full_name]
        return self._unary(
            _path(descriptor), request,
            lambda data: convert(View.parse(data, response_class)), timeout)

    def _rpc_stream(self, method: str, request: _message.Message,
                    convert: Callable[[View], T],
                    timeout: Optional[float]) -> Stream[T]:
        """The server-streaming ``method``, each answer converted."""
        descriptor = _method(method)
        response_class = _MESSAGE_CLASSES[descriptor.output_type.full_name]
        return self._stream(
            _path(descriptor), request,
            lambda data: convert(View.parse(data, response_class)), timeout)
