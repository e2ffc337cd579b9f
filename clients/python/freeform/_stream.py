"""Stream: the answers of a server-streaming call, as an iterator."""

from __future__ import annotations

from typing import Any, Callable, Iterator, TypeVar

import grpc
from google.protobuf.message import DecodeError

from freeform._errors import FreeformError
from freeform._wire import WireError

T = TypeVar("T")


class Stream(Iterator[T]):
    """The answers of a server-streaming call, as they arrive.

    Iterating ends with the stream; a failure raises FreeformError. Leaving
    a ``with`` block or calling ``cancel()`` cancels the call, so stopping
    early does not leave the server computing.
    """

    def __init__(self, call: Any, convert: Callable[[Any], T]):
        self._call = call
        self._convert = convert

    def __iter__(self) -> "Stream[T]":
        return self

    def __next__(self) -> T:
        try:
            answer = next(self._call)
        except grpc.RpcError as error:
            raise FreeformError.from_rpc_error(error) from None
        return converted(self._convert, answer)

    def cancel(self) -> None:
        """Cancels the call (no effect once it has ended)."""
        self._call.cancel()

    def __enter__(self) -> "Stream[T]":
        return self

    def __exit__(self, *exception: Any) -> None:
        self.cancel()


def converted(convert: Callable[[Any], T], answer: Any) -> T:
    """convert(answer); a malformed answer is FreeformError DATA_LOSS."""
    try:
        return convert(answer)
    except (DecodeError, WireError) as error:
        raise FreeformError(grpc.StatusCode.DATA_LOSS,
                            "malformed answer: %s" % error) from None
