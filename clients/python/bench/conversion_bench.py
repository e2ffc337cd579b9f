#!/usr/bin/python3
"""What the freeform package's numpy conversions cost, against the other
ways of reading and writing the same packed fields.

    conversion_bench.py --freeformd build/release/server/freeformd
    conversion_bench.py --address 127.0.0.1:50051 [--points N] [--rounds R]

Answers: CurveService.Evaluate of the worked cubic at N uniform parameters
(default 10^6) with its first derivative, 32 bytes per parameter, read
  - as bytes only (gRPC's own cost, the floor),
  - as a parsed message (the generated stub, no numpy),
  - by freeform (client.curves.evaluate: arrays of shape (2, N, 2)),
  - from the parsed message by np.array and by np.fromiter.
The same answer decoded from its bytes without a call (protobuf's parse
alone, freeform, and the parse with np.array or np.fromiter). Requests: N
3D points into a Points message, by freeform.to_points and by
RepeatedScalarContainer.extend. numpy operations on the aligned arrays
freeform returns and on views of the received bytes, which are misaligned
(why freeform copies). Small calls: the cubic at 3 parameters,
p50 of sequential calls, by freeform and by the generated stub.

Each figure: best and median seconds of the rounds; Python's peak
allocation during one call (tracemalloc); and the growth of the resident
set's peak (VmHWM) over one call, each measured in a fresh process.
Needs the package installed (tests/clients/python_package_test.py's venv,
or docs/clients.md).
"""

import argparse
import gc
import statistics
import subprocess
import sys
import time
import tracemalloc

import grpc
import numpy as np

import freeform
from freeform._answers import curve_samples
from freeform._wire import View
from freeform.v1 import curve_service_pb2, geometry_pb2

METHOD = "/freeform.v1.CurveService/Evaluate"
CUBIC = [[0, 0], [1, 2], [3, 2], [4, 0]]
MB = 1e6


def request(count):
    message = curve_service_pb2.EvaluateCurveRequest(
        curve=freeform.bezier(CUBIC), derivative_order=1)
    message.parameters.range.count = count
    return message


def answer_readers(address, count):
    """{name: a function that makes the call and reads its answer}."""
    channel = grpc.insecure_channel(address, [
        ("grpc.max_receive_message_length", 256 << 20)])
    serialize = curve_service_pb2.EvaluateCurveRequest.SerializeToString
    as_bytes = channel.unary_unary(METHOD, request_serializer=serialize,
                                   response_deserializer=None)
    parse = curve_service_pb2.EvaluateCurveResponse.FromString
    as_message = channel.unary_unary(METHOD, request_serializer=serialize,
                                     response_deserializer=parse)
    client = freeform.Client(address, timeout=120,
                             max_receive_message_bytes=256 << 20)
    message = request(count)

    def by_numpy(convert):
        response = as_message(message, timeout=120)
        return [convert(points.coordinates) for points in response.derivatives]

    return {
        "bytes only (gRPC)": lambda: as_bytes(message, timeout=120),
        "parsed message": lambda: as_message(message, timeout=120),
        "freeform": lambda: client.curves.evaluate(
            freeform.bezier(CUBIC), freeform.Range(count), 1),
        "message + np.array": lambda: by_numpy(np.array),
        "message + np.fromiter": lambda: by_numpy(
            lambda values: np.fromiter(values, np.float64, len(values))),
    }


def answer_decoders(readers):
    """{name: a function that decodes one received answer}."""
    data = readers["bytes only (gRPC)"]()
    parse = curve_service_pb2.EvaluateCurveResponse.FromString

    def by_numpy(convert):
        return [convert(points.coordinates)
                for points in parse(data).derivatives]

    return {
        "protobuf parse": lambda: parse(data),
        "freeform": lambda: curve_samples(View.parse(
            data, curve_service_pb2.EvaluateCurveResponse)),
        "parse + np.array": lambda: by_numpy(np.array),
        "parse + np.fromiter": lambda: by_numpy(
            lambda values: np.fromiter(values, np.float64, len(values))),
    }


def answer_arrays(readers):
    """The derivatives of one answer as freeform's array and as a view of
    the received bytes (the second Points' doubles start at an offset that
    is not a multiple of 8)."""
    data = readers["bytes only (gRPC)"]()
    view = View.parse(data, curve_service_pb2.EvaluateCurveResponse)
    aligned = curve_samples(view).derivatives
    points = view.submessages("derivatives")[1]
    _, start, end = points._pieces("coordinates", 1, 8)[0]
    misaligned = np.frombuffer(data, "<f8", (end - start) // 8, start)
    if misaligned.flags.aligned:
        raise RuntimeError("the answer's doubles happen to be aligned")
    return aligned[1].reshape(-1), misaligned


def request_writers(count):
    points = np.random.default_rng(1).normal(size=(count, 3))

    def by_extend():
        message = geometry_pb2.Points(dimension=3)
        message.coordinates.extend(points.reshape(-1))
        return message

    return {"freeform.to_points": lambda: freeform.to_points(points),
            "Points.coordinates.extend": by_extend}


def peak_resident_bytes():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    return 0


def timed(call, rounds):
    seconds = []
    for _ in range(rounds):
        start = time.perf_counter()
        call()
        seconds.append(time.perf_counter() - start)
    return min(seconds), statistics.median(seconds)


def traced_peak(call):
    gc.collect()
    tracemalloc.start()
    call()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def resident_growth(args, kind, name):
    """VmHWM growth over one call, in a fresh process."""
    output = subprocess.run(
        [sys.executable, __file__, "--address", args.address, "--points",
         str(args.points), "--resident", kind, name],
        check=True, capture_output=True, text=True).stdout
    return int(output)


def measure_resident(args):
    kind, name = args.resident
    calls = (answer_readers(args.address, args.points) if kind == "answer"
             else request_writers(args.points))
    if kind == "answer":
        answer_readers(args.address, 1000)[name]()  # connected and warm
    before = peak_resident_bytes()
    result = calls[name]()
    print(peak_resident_bytes() - before)
    del result


def table(rows):
    print("| | best s | median s | Python peak MB | resident peak growth MB |")
    print("|---|---|---|---|---|")
    for name, (best, median), peak, resident in rows:
        print("| %s | %.3f | %.3f | %.1f | %s |" % (
            name, best, median, peak / MB,
            "%.1f" % (resident / MB) if resident else "-"))


def run(args):
    readers = answer_readers(args.address, args.points)
    readers["freeform"]()  # connected and warm
    print("Answers: the cubic at %d parameters with its first derivative "
          "(%.1f MB of doubles), %d rounds\n" % (args.points,
                                                 args.points * 32 / MB,
                                                 args.rounds))
    table([(name, timed(call, args.rounds), traced_peak(call),
            resident_growth(args, "answer", name))
           for name, call in readers.items()])
    print("\nThe same answer decoded from its received bytes (no call)\n")
    table([(name, timed(call, args.rounds), traced_peak(call), 0)
           for name, call in answer_decoders(readers).items()])
    print("\nnumpy on the answer's first derivative, 10^6 x 2 doubles: "
          "freeform's aligned array against a view of the received bytes "
          "(misaligned)\n")
    aligned, misaligned = answer_arrays(readers)
    print("| | aligned s | misaligned view s | ratio |")
    print("|---|---|---|---|")
    for name, operation in (("sum", np.sum), ("x * 2", lambda x: x * 2),
                            ("x @ x", lambda x: x @ x), ("copy", np.copy)):
        fast = timed(lambda: operation(aligned), args.rounds)[0]
        slow = timed(lambda: operation(misaligned), args.rounds)[0]
        print("| %s | %.4f | %.4f | %.1f |" % (name, fast, slow, slow / fast))
    print("\nRequests: %d 3D points into a Points message (%.1f MB)\n" %
          (args.points, args.points * 24 / MB))
    table([(name, timed(call, args.rounds), traced_peak(call),
            resident_growth(args, "request", name))
           for name, call in request_writers(args.points).items()])
    client = freeform.Client(args.address)
    cubic = freeform.bezier(CUBIC)
    small = request(3)
    small.parameters.Clear()
    small.parameters.list.values.extend([0, 0.5, 1])
    stub = grpc.insecure_channel(args.address).unary_unary(
        METHOD,
        request_serializer=curve_service_pb2.EvaluateCurveRequest
        .SerializeToString,
        response_deserializer=curve_service_pb2.EvaluateCurveResponse
        .FromString)
    print("\nSmall calls (the cubic at 3 parameters), p50 of 500:\n")
    for name, call in (("freeform", lambda: client.curves.evaluate(
            cubic, [0, 0.5, 1], 1)), ("generated stub", lambda: stub(
                small, timeout=10))):
        call()
        seconds = []
        for _ in range(500):
            start = time.perf_counter()
            call()
            seconds.append(time.perf_counter() - start)
        print("- %s: %.0f us" % (name, statistics.median(seconds) * 1e6))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--address")
    parser.add_argument("--freeformd")
    parser.add_argument("--points", type=int, default=10 ** 6)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--resident", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.resident:
        measure_resident(args)
        return 0
    server = None
    if args.address is None:
        if args.freeformd is None:
            parser.error("give --address or --freeformd")
        server = subprocess.Popen([args.freeformd,
                                   "--listen=127.0.0.1:0",
                                   "--log_level=warn"],
                                  stdout=subprocess.PIPE, text=True)
        for line in server.stdout:
            if line.startswith("freeformd listening on "):
                args.address = line.split()[-1]
                break
        else:
            server.wait()
            raise RuntimeError("freeformd did not report its address")
    try:
        run(args)
    finally:
        if server is not None:
            server.terminate()
            server.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
