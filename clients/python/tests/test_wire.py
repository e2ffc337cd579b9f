"""The byte-level conversions, against protobuf's own parser (no server).

Every valid encoding of a repeated number must give what protobuf parses:
packed or not, in several runs, inside a submessage sent in pieces, among
unknown fields. The fields hold at least SMALL_FIELD values (smaller ones
are read from the parsed message), and np.fromiter, the package's value by
value path, is made to fail so that a test passes only through the bytes.
"""

import struct
import unittest
from unittest import mock

import numpy as np

import freeform
from freeform._wire import SMALL_FIELD, View, decode_varints
from freeform.v1 import curve_service_pb2, geometry_pb2, query_pb2
from freeform.v1 import surface_service_pb2


def varint(value):
    out = bytearray()
    while value > 0x7F:
        out.append(value & 0x7F | 0x80)
        value >>= 7
    out.append(value)
    return bytes(out)


def tag(number, wire_type):
    return varint(number << 3 | wire_type)


def length_delimited(number, payload):
    return tag(number, 2) + varint(len(payload)) + payload


def packed_doubles(number, values):
    return length_delimited(number, struct.pack("<%dd" % len(values),
                                                *values))


def values(first, count=SMALL_FIELD):
    """count distinct doubles from first (none of them a short decimal)."""
    return [first + k / 7 for k in range(count)]


def through_bytes():
    """No value-by-value reading while it is active."""
    return mock.patch.object(np, "fromiter",
                             side_effect=AssertionError("value by value"))


def unpacked_doubles(number, values):
    return b"".join(tag(number, 1) + struct.pack("<d", value)
                    for value in values)


class DoublesTest(unittest.TestCase):
    def check_points(self, data, expected):
        message = geometry_pb2.Points.FromString(data)
        with through_bytes():
            array = View(data, message).doubles("coordinates")
        np.testing.assert_array_equal(array, list(message.coordinates))
        np.testing.assert_array_equal(array, expected)
        self.assertTrue(array.flags.aligned and array.flags.writeable)

    def test_packed(self):
        expected = values(0.5) + [-1, 1e300, 3]
        self.check_points(tag(1, 0) + varint(2) +
                          packed_doubles(2, expected), expected)

    def test_unpacked_and_in_runs(self):
        a, b, c, d = (values(k, 20) for k in range(4))
        data = (unpacked_doubles(2, a) + packed_doubles(2, b) + tag(1, 0) +
                varint(2) + packed_doubles(2, c) + unpacked_doubles(2, d))
        self.check_points(data, a + b + c + d)

    def test_unknown_fields_are_stepped_over(self):
        expected = values(1.25)
        data = (tag(99, 0) + varint(2 ** 63) + length_delimited(98, b"xyz") +
                tag(97, 5) + b"abcd" + tag(96, 1) + b"12345678" +
                packed_doubles(2, expected) + tag(1, 0) + varint(1))
        self.check_points(data, expected)

    def test_a_submessage_in_pieces_is_merged(self):
        # ClosestPointResponse.points (field 7) sent twice: protobuf merges
        # the two Points, concatenating their coordinates.
        first, second, distances = values(1, 40), values(2, 40), values(3)
        data = (length_delimited(7, tag(1, 0) + varint(2) +
                                 packed_doubles(2, first)) +
                packed_doubles(2, distances) +
                length_delimited(7, packed_doubles(2, second)))
        message = query_pb2.ClosestPointResponse.FromString(data)
        view = View(data, message)
        with through_bytes():
            np.testing.assert_array_equal(
                view.submessage("points").doubles("coordinates"),
                first + second)
            np.testing.assert_array_equal(view.doubles("distances"),
                                          distances)

    def test_repeated_submessages(self):
        derivatives = [values(k) for k in range(3)]
        data = (tag(1, 0) + varint(1) + tag(3, 0) + varint(SMALL_FIELD) +
                b"".join(length_delimited(4, tag(1, 0) + varint(1) +
                                          packed_doubles(2, derivative))
                         for derivative in derivatives))
        message = curve_service_pb2.EvaluateCurveResponse.FromString(data)
        views = View(data, message).submessages("derivatives")
        self.assertEqual(len(views), 3)
        with through_bytes():
            for view, derivative in zip(views, derivatives):
                np.testing.assert_array_equal(view.doubles("coordinates"),
                                              derivative)

    def test_bytes_that_disagree_fall_back_to_the_parsed_message(self):
        expected = values(1)
        data = packed_doubles(2, expected)
        message = geometry_pb2.Points.FromString(data)
        # A View told the wrong ranges still answers the parsed values.
        for ranges in ([], [(0, 2)], [(1, len(data))], [(0, len(data) - 8)]):
            np.testing.assert_array_equal(
                View(data, message, ranges).doubles("coordinates"), expected)


class VarintsTest(unittest.TestCase):
    VALUES = [0, 1, 127, 128, 300, 2 ** 14, 2 ** 21 - 1, 2 ** 28,
              2 ** 32 - 1] * 8

    def test_packed_and_unpacked_triangles(self):
        packed = length_delimited(2, b"".join(map(varint, self.VALUES)))
        unpacked = b"".join(tag(2, 0) + varint(value)
                            for value in self.VALUES[:4])
        for data in (packed, unpacked + packed):
            message = surface_service_pb2.TessellateSurfaceResponse.FromString(
                data)
            with through_bytes():
                array = View(data, message).varints("triangles", np.int64)
            np.testing.assert_array_equal(array, list(message.triangles))

    def test_truncated_as_protobuf_truncates(self):
        # A uint32 field sent with 64-bit varints keeps the low 32 bits.
        data = length_delimited(2, varint(2 ** 40 + 5) * SMALL_FIELD)
        message = surface_service_pb2.TessellateSurfaceResponse.FromString(
            data)
        with through_bytes():
            array = View(data, message).varints("triangles", np.uint32)
        self.assertEqual(list(array), list(message.triangles))
        self.assertEqual(array[0], 5)

    def test_decode_random_values(self):
        random = np.random.default_rng(3)
        values = [int(v) for v in random.integers(0, 2 ** 63, 1000)]
        values += [int(v) for v in random.integers(0, 300, 1000)]
        data = np.frombuffer(b"".join(map(varint, values)), np.uint8)
        np.testing.assert_array_equal(decode_varints(data, len(values)),
                                      np.array(values, dtype=np.uint64))


class EncodeTest(unittest.TestCase):
    def test_to_points_writes_what_extend_writes(self):
        array = np.arange(12.0).reshape(4, 3) / 7
        for layout in (array, np.asfortranarray(array), array[::-1],
                       array.astype(np.float32), np.arange(12).reshape(4, 3)):
            expected = geometry_pb2.Points(dimension=3)
            expected.coordinates.extend(
                np.asarray(layout, dtype=np.float64).reshape(-1).tolist())
            self.assertEqual(freeform.to_points(layout).SerializeToString(),
                             expected.SerializeToString())

    def test_round_trip(self):
        array = np.random.default_rng(5).normal(size=(1000, 3))
        np.testing.assert_array_equal(
            freeform.to_array(freeform.to_points(array)), array)
        net = array.reshape(10, 100, 3)
        np.testing.assert_array_equal(
            freeform.to_array(freeform.to_control_net(net)), net)
        np.testing.assert_array_equal(
            freeform.to_array(freeform.bezier_surface(net)), net)

    def test_parameters(self):
        self.assertEqual(list(freeform._geometry.parameters(0.25).list.values),
                         [0.25])
        message = freeform._geometry.parameters(freeform.Range(5, end=2))
        self.assertEqual(message.range.count, 5)
        self.assertFalse(message.range.HasField("start"))
        self.assertEqual(message.range.end, 2)
        # An empty list is still a list (the server names it).
        self.assertEqual(freeform._geometry.parameters([]).WhichOneof("kind"),
                         "list")

    def test_every_kind_has_its_points(self):
        # A kind added to geometry.proto fails here until to_array knows
        # which of its fields holds the points.
        for message, table in ((geometry_pb2.Curve,
                                freeform._geometry._CURVE_POINTS),
                               (geometry_pb2.Surface,
                                freeform._geometry._SURFACE_POINTS)):
            kinds = message.DESCRIPTOR.oneofs_by_name["kind"].fields
            self.assertEqual({field.name for field in kinds}, set(table))
            for field in kinds:
                self.assertIn(table[field.name],
                              field.message_type.fields_by_name)


if __name__ == "__main__":
    unittest.main()
