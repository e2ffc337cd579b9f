"""Repeated numbers of a received message as numpy arrays, by one copy.

protobuf's Python messages hand out a packed ``repeated double`` one Python
float at a time (about a microsecond each: seconds for 10^6 points). The
bytes that arrived hold the same numbers little-endian, one after another,
so this module finds where each repeated field's numbers lie in the
received bytes and copies them into an aligned numpy array in one move.

A ``View`` pairs those bytes with the message protobuf parsed from them,
and every array is checked against the parsed message: the count must be
the parsed field's length. The bytes are located by reading only the tags
and lengths of the wire format (varint keys; fixed 8- and 4-byte values;
length-delimited values), which is all it takes to step over a field. A
field that appears several times (merged submessages, or a repeated field
sent unpacked) is the concatenation of its pieces, as protobuf defines.
Should the bytes ever disagree with the parsed message, the numbers are
taken from the parsed message instead (slowly, but right).
"""

from __future__ import annotations

import functools
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
from google.protobuf import message as _message

# Wire types of the protobuf encoding.
_VARINT, _FIXED64, _LENGTH_DELIMITED, _FIXED32 = 0, 1, 2, 5
_DOUBLE = np.dtype("<f8")

# (wire type, first byte, one past the last byte) of one field occurrence.
Span = Tuple[int, int, int]
# Fields of fewer values are read from the parsed message: below about 64
# values that costs less than locating their bytes (a few microseconds).
SMALL_FIELD = 64


class WireError(ValueError):
    """The bytes do not read as the message protobuf parsed from them."""


def _read_varint(data: bytes, position: int, end: int) -> Tuple[int, int]:
    """The varint at ``position`` and the position after it."""
    result = shift = 0
    while True:
        if position >= end or shift > 63:
            raise WireError("a varint runs past its message")
        byte = data[position]
        position += 1
        result |= (byte & 0x7F) << shift
        if byte < 0x80:
            return result, position
        shift += 7


def _scan(data: bytes, start: int, end: int) -> Dict[int, List[Span]]:
    """The occurrences of every field of the message in data[start:end]."""
    fields: Dict[int, List[Span]] = {}
    position = start
    while position < end:
        key, position = _read_varint(data, position, end)
        wire_type = key & 7
        value_start = position
        if wire_type == _VARINT:
            _, position = _read_varint(data, position, end)
        elif wire_type == _FIXED64:
            position += 8
        elif wire_type == _LENGTH_DELIMITED:
            length, value_start = _read_varint(data, position, end)
            position = value_start + length
        elif wire_type == _FIXED32:
            position += 4
        else:
            raise WireError("wire type %d is not used by proto3" % wire_type)
        if position > end:
            raise WireError("field %d runs past its message" % (key >> 3))
        fields.setdefault(key >> 3, []).append((wire_type, value_start,
                                                position))
    return fields


def decode_varints(data: np.ndarray, count: int) -> np.ndarray:
    """The ``count`` unsigned varints packed in the uint8 array ``data``."""
    last_bytes = np.flatnonzero(data < 0x80)
    if last_bytes.size != count or (count and last_bytes[-1] != data.size - 1):
        raise WireError("expected %d varints in %d bytes" % (count, data.size))
    starts = np.empty_like(last_bytes)
    starts[:1] = 0
    starts[1:] = last_bytes[:-1] + 1
    lengths = last_bytes - starts + 1
    if lengths.max(initial=1) > 10:
        raise WireError("a varint is longer than 10 bytes")
    values = (data[starts] & 0x7F).astype(np.uint64)
    for k in range(1, int(lengths.max(initial=1))):
        longer = lengths > k
        values[longer] |= ((data[starts[longer] + k] & 0x7F).astype(np.uint64)
                           << np.uint64(7 * k))
    return values


class View:
    """One message: its parsed form and where its fields lie in the bytes.

    A singular submessage may arrive in several pieces (protobuf merges
    them), so a View covers a list of byte ranges, found when first needed:
    a field of fewer than SMALL_FIELD values is read from the parsed
    message, where it costs less than finding its bytes.
    """

    def __init__(self, data: bytes, message: _message.Message,
                 ranges: Optional[Sequence[Tuple[int, int]]] = None,
                 locate: Optional[Callable[[], Sequence[Tuple[int, int]]]]
                 = None):
        self.data = data
        self.message = message
        self._ranges = ranges
        self._locate = locate
        self._fields: Optional[Dict[int, List[Span]]] = None

    @classmethod
    def parse(cls, data: bytes, message_class: Any) -> "View":
        """Parses ``data`` as ``message_class`` and keeps the bytes."""
        return cls(data, message_class.FromString(data))

    def _spans(self, name: str) -> List[Span]:
        """The occurrences of field ``name`` (none when unreadable)."""
        number = self.message.DESCRIPTOR.fields_by_name[name].number
        if self._fields is None:
            if self._ranges is None:
                self._ranges = (self._locate() if self._locate else
                                [(0, len(self.data))])
            self._fields = {}
            try:
                for start, end in self._ranges:
                    for field, spans in _scan(self.data, start, end).items():
                        self._fields.setdefault(field, []).extend(spans)
            except WireError:
                # Every field of this message then comes from the parsed
                # message.
                self._fields = {}
        return self._fields.get(number, [])

    def _message_spans(self, name: str) -> List[Tuple[int, int]]:
        """The byte ranges of the message field ``name``'s occurrences
        (none when they are not all length-delimited)."""
        spans = self._spans(name)
        if any(wire_type != _LENGTH_DELIMITED for wire_type, _, _ in spans):
            return []
        return [(start, end) for _, start, end in spans]

    def submessage(self, name: str) -> "View":
        """The singular message field ``name`` (all its pieces)."""
        return View(self.data, getattr(self.message, name),
                    locate=lambda: self._message_spans(name))

    def submessages(self, name: str) -> List["View"]:
        """The repeated message field ``name``, one View per element."""
        parsed = getattr(self.message, name)

        def element(index: int) -> List[Tuple[int, int]]:
            ranges = self._message_spans(name)
            # Unreadable unless there is one range per parsed element.
            return [ranges[index]] if len(ranges) == len(parsed) else []

        return [View(self.data, message,
                     locate=functools.partial(element, index))
                for index, message in enumerate(parsed)]

    def _pieces(self, name: str, wire_type: int, width: int) -> List[Span]:
        spans = self._spans(name)
        for span_type, start, end in spans:
            if span_type not in (wire_type, _LENGTH_DELIMITED) or (
                    width and (end - start) % width):
                raise WireError("field %s is not a packed %s" %
                                (name, "double" if width else "varint"))
        return spans

    def doubles(self, name: str, out: Optional[np.ndarray] = None
                ) -> np.ndarray:
        """The repeated double field ``name`` as a float64 array (into the
        flat C-contiguous ``out`` when given, which must fit exactly)."""
        parsed = getattr(self.message, name)
        count = len(parsed)
        if out is None:
            out = np.empty(count, dtype=np.float64)
        elif out.size != count:
            raise WireError("field %s has %d values, not %d" %
                            (name, count, out.size))
        if count < SMALL_FIELD:
            out[:] = np.fromiter(parsed, np.float64, count)
            return out
        try:
            position = 0
            for _, start, end in self._pieces(name, _FIXED64, 8):
                piece = (end - start) // 8
                if position + piece > count:
                    raise WireError("field %s has more values than parsed" %
                                    name)
                out[position:position + piece] = np.frombuffer(
                    self.data, _DOUBLE, piece, start)
                position += piece
            if position != count:
                raise WireError("field %s has fewer values than parsed" % name)
        except WireError:
            out[:] = np.fromiter(parsed, np.float64, count)
        return out

    def varints(self, name: str, dtype: Any) -> np.ndarray:
        """The repeated unsigned integer (or enum, or bool) field ``name``."""
        parsed = getattr(self.message, name)
        count = len(parsed)
        if count < SMALL_FIELD:
            return np.fromiter(parsed, dtype, count)
        try:
            pieces = [np.frombuffer(self.data, np.uint8, end - start, start)
                      for _, start, end in self._pieces(name, _VARINT, 0)]
            data = (np.concatenate(pieces) if pieces else
                    np.empty(0, np.uint8))
            # astype truncates as protobuf's parser does (uint32, enums).
            return decode_varints(data, count).astype(dtype)
        except WireError:
            return np.fromiter(parsed, dtype, count)
