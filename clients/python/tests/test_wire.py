"""The byte-level conversions, against protobuf's own parser (no server).

Every valid encoding of a repeated number must give what protobuf parses:
packed or not, in several runs, inside a submessage sent in pieces, among
unknown fields.
"""

import struct
import unittest

import numpy as np

import freeform
from freeform._wire import View, decode_varints
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


def unpacked_doubles(number, values):
    return b"".join(tag(number, 1) + struct.pack("<d", value)
                    for value in values)


class DoublesTest(unittest.TestCase):
    def check_points(self, data):
        message = geometry_pb2.Points.FromString(data)
        values = View(data, message).doubles("coordinates")
        np.testing.assert_array_equal(values, list(message.coordinates))
        self.assertTrue(values.flags.aligned and values.flags.writeable)
        return values

    def test_packed(self):
        values = self.check_points(tag(1, 0) + varint(2) +
                                   packed_doubles(2, [0.5, -1, 1e300, 3]))
        np.testing.assert_array_equal(values, [0.5, -1, 1e300, 3])

    def test_unpacked_and_in_runs(self):
        data = (unpacked_doubles(2, [1, 2]) + packed_doubles(2, [3, 4]) +
                tag(1, 0) + varint(2) + packed_doubles(2, [5, 6]) +
                unpacked_doubles(2, [7]))
        np.testing.assert_array_equal(self.check_points(data),
                                      [1, 2, 3, 4, 5, 6, 7])

    def test_unknown_fields_are_stepped_over(self):
        data = (tag(99, 0) + varint(2 ** 63) + length_delimited(98, b"xyz") +
                tag(97, 5) + b"abcd" + tag(96, 1) + b"12345678" +
                packed_doubles(2, [1.25]) + tag(1, 0) + varint(1))
        np.testing.assert_array_equal(self.check_points(data), [1.25])

    def test_a_submessage_in_pieces_is_merged(self):
        # ClosestPointResponse.points (field 7) sent twice: protobuf merges
        # the two Points, concatenating their coordinates.
        data = (length_delimited(7, tag(1, 0) + varint(2) +
                                 packed_doubles(2, [1, 2])) +
                packed_doubles(2, [0.5]) +
                length_delimited(7, packed_doubles(2, [3, 4])))
        message = query_pb2.ClosestPointResponse.FromString(data)
        view = View(data, message)
        np.testing.assert_array_equal(
            view.submessage("points").doubles("coordinates"), [1, 2, 3, 4])
        np.testing.assert_array_equal(view.doubles("distances"), [0.5])

    def test_repeated_submessages(self):
        derivative = [tag(1, 0) + varint(1) + packed_doubles(2, [k, k + 0.5])
                      for k in range(3)]
        data = (tag(1, 0) + varint(1) + tag(3, 0) + varint(2) +
                b"".join(length_delimited(4, d) for d in derivative))
        message = curve_service_pb2.EvaluateCurveResponse.FromString(data)
        views = View(data, message).submessages("derivatives")
        self.assertEqual(len(views), 3)
        for k, view in enumerate(views):
            np.testing.assert_array_equal(view.doubles("coordinates"),
                                          [k, k + 0.5])

    def test_bytes_that_disagree_fall_back_to_the_parsed_message(self):
        data = packed_doubles(2, [1, 2, 3])
        message = geometry_pb2.Points.FromString(data)
        # A View told the wrong ranges still answers the parsed values.
        for ranges in ([], [(0, 2)], [(1, len(data))]):
            np.testing.assert_array_equal(
                View(data, message, ranges).doubles("coordinates"), [1, 2, 3])


class VarintsTest(unittest.TestCase):
    VALUES = [0, 1, 127, 128, 300, 2 ** 14, 2 ** 21 - 1, 2 ** 28, 2 ** 32 - 1]

    def test_packed_and_unpacked_triangles(self):
        packed = length_delimited(2, b"".join(map(varint, self.VALUES)))
        unpacked = b"".join(tag(2, 0) + varint(value)
                            for value in self.VALUES[:4])
        for data in (packed, unpacked + packed):
            message = surface_service_pb2.TessellateSurfaceResponse.FromString(
                data)
            values = View(data, message).varints("triangles", np.int64)
            np.testing.assert_array_equal(values, list(message.triangles))

    def test_truncated_as_protobuf_truncates(self):
        # A uint32 field sent with a 64-bit varint keeps the low 32 bits.
        data = length_delimited(2, varint(2 ** 40 + 5))
        message = surface_service_pb2.TessellateSurfaceResponse.FromString(
            data)
        values = View(data, message).varints("triangles", np.uint32)
        self.assertEqual(list(values), list(message.triangles))

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


if __name__ == "__main__":
    unittest.main()
