#!/usr/bin/python3
"""Runs a client example (examples/python or examples/node) against the real
freeformd and checks its answers against the freeform CLI's for the same
requests and against the mathematics.

    clients_test.py python|node --freeformd PATH --cli PATH \\
        --source-dir REPOSITORY --work-dir BUILD_SUBDIR

The example's output is CSV tables under "# <RPC>" lines; numbers are
compared as doubles, exactly. The Node test installs the example's npm
packages (examples/node/package.json) into the work folder. Exit status 77
(ctest's skip) when node or npm is missing.
"""

import argparse
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import time

SKIP = 77
TIME_SCALE = float(os.environ.get("FREEFORM_TEST_TIME_SCALE", "1"))

# The cubic Bezier curve of examples/cubic_bezier.json.
CUBIC = [0, 0, 1, 2, 3, 2, 4, 0]
# The stream request of the examples: the cubic at nine parameters, four
# per chunk.
STREAM_REQUEST = {
    "curve": {"bezier": {"control_points": {"dimension": 2,
                                            "coordinates": CUBIC}}},
    "parameters": {"range": {"count": 9}},
    "chunk_size": 4,
}
# The bad request of the examples: three coordinates in dimension 2.
BAD_REQUEST = {
    "curve": {"bezier": {"control_points": {"dimension": 2,
                                            "coordinates": [0, 0, 1]}}},
    "parameters": {"list": {"values": [0.5]}},
}
BAD_FIELD = "curve.bezier.control_points.coordinates"
# The NURBS unit circle of examples/nurbs_circle_polyline.json: four
# rational quadratic quarters with weights 1, sqrt(1/2), 1.
CIRCLE_POINTS = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1),
                 (1, -1), (1, 0)]
CIRCLE_TOLERANCE = 0.001

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message)
    return condition


def close(a, b, tolerance=1e-12):
    return len(a) == len(b) and all(
        abs(x - y) <= tolerance for x, y in zip(a, b))


def run(command, **kwargs):
    print("$ " + " ".join(command), flush=True)
    result = subprocess.run(command, capture_output=True, text=True,
                            timeout=300 * TIME_SCALE, **kwargs)
    if result.stderr:
        sys.stdout.write(result.stderr)
    return result


def parse_sections(text):
    """{title: [line, ...]} of the "# title" sections."""
    sections = {}
    lines = None
    for line in text.splitlines():
        if line.startswith("# "):
            lines = sections.setdefault(line[2:], [])
        elif lines is not None:
            lines.append(line)
    return sections


def parse_table(lines):
    """The header and the rows (lists of doubles) of a CSV table."""
    if not lines:
        return "", []
    return lines[0], [[float(value) for value in line.split(",")]
                      for line in lines[1:]]


def start_server(freeformd, work_dir):
    """Starts freeformd on a free port; returns the process and HOST:PORT."""
    out_path = os.path.join(work_dir, "freeformd.out")
    with open(out_path, "w") as out, \
            open(os.path.join(work_dir, "freeformd.log"), "w") as log:
        server = subprocess.Popen([freeformd, "--listen=127.0.0.1:0"],
                                  stdout=out, stderr=log)
    deadline = time.monotonic() + 30 * TIME_SCALE
    while time.monotonic() < deadline and server.poll() is None:
        with open(out_path) as out:
            for line in out:
                if line.startswith("freeformd listening on "):
                    return server, line.split()[-1]
        time.sleep(0.05)
    server.kill()
    raise RuntimeError("freeformd did not report its address")


def stop_server(server):
    server.send_signal(signal.SIGTERM)
    check(server.wait(timeout=30 * TIME_SCALE) == 0,
          "freeformd exits 0 on SIGTERM")


def bezier_point(t):
    """The cubic (0,0), (1,2), (3,2), (4,0) at t, in power form."""
    return [3 * t + 3 * t * t - 2 * t ** 3, 6 * t * (1 - t)]


def circle_point(t):
    """The NURBS unit circle at t: quarter q on [q/4, (q+1)/4]."""
    q = min(int(4 * t), 3)
    s = 4 * t - q
    w = math.sqrt(0.5)
    basis = [(1 - s) ** 2, 2 * s * (1 - s) * w, s * s]
    points = CIRCLE_POINTS[2 * q:2 * q + 3]
    denominator = sum(basis)
    return [sum(b * p[j] for b, p in zip(basis, points)) / denominator
            for j in range(2)]


def check_evaluate(section, cli_csv):
    header, rows = parse_table(section)
    cli_header, cli_rows = parse_table(cli_csv.splitlines())
    check(header == "index,x0,x1,d1x0,d1x1", "Evaluate header: " + header)
    check(header == cli_header and rows == cli_rows,
          "Evaluate prints the CLI's numbers: %s vs %s" % (rows, cli_rows))
    # C(0), C(1/2), C(1) and C'(t) = 3 sum_i B(2,i,t) (P_{i+1} - P_i).
    expected = [[0, 0, 0, 3, 6], [1, 2, 1.5, 4.5, 0], [2, 4, 0, 3, -6]]
    check(len(rows) == 3 and all(map(close, rows, expected)),
          "Evaluate gives the cubic's points and derivatives: %s" % rows)


def check_stream(chunk_section, section, cli_csv):
    _, chunks = parse_table(chunk_section)
    next_index = 0
    for first_index, count in chunks:
        check(first_index == next_index and 0 < count <= 4,
              "stream chunk (%d, %d) follows %d" % (first_index, count,
                                                    next_index))
        next_index = first_index + count
    check(next_index == 9 and len(chunks) >= 3,
          "the stream covers 9 parameters in chunks of 4: %s" % chunks)
    header, rows = parse_table(section)
    cli_header, cli_rows = parse_table(cli_csv.splitlines())
    check(header == "index,x0,x1" and header == cli_header and
          rows == cli_rows,
          "EvaluateStream prints the CLI's numbers: %s vs %s" % (rows,
                                                                 cli_rows))
    expected = [[k] + bezier_point(k / 8) for k in range(9)]
    check(len(rows) == 9 and all(map(close, rows, expected)),
          "EvaluateStream gives the cubic at k/8: %s" % rows)


def check_tessellate(section, cli_json):
    header, rows = parse_table(section)
    answer = json.loads(cli_json)
    coordinates = answer["points"]["coordinates"]
    cli_rows = [[i, t, coordinates[2 * i], coordinates[2 * i + 1]]
                for i, t in enumerate(answer["parameters"])]
    check(header == "index,t,x0,x1" and rows == cli_rows,
          "Tessellate prints the CLI's polyline (%d vs %d points)" %
          (len(rows), len(cli_rows)))
    if not check(len(rows) >= 2, "Tessellate gives a polyline"):
        return
    parameters = [row[1] for row in rows]
    check(parameters[0] == 0 and parameters[-1] == 1 and
          all(a < b for a, b in zip(parameters, parameters[1:])),
          "the polyline's parameters rise from 0 to 1")
    for index, t, x, y in rows:
        check(close([x, y], circle_point(t)) and
              abs(math.hypot(x, y) - 1) <= 1e-12,
              "vertex %d (%r, %r) is the circle's point at t = %r" %
              (index, x, y, t))
    # A chord of the unit circle is farthest from the arc at its middle.
    for a, b in zip(rows, rows[1:]):
        sagitta = 1 - math.hypot((a[2] + b[2]) / 2, (a[3] + b[3]) / 2)
        check(sagitta <= CIRCLE_TOLERANCE,
              "chord %d-%d is within the tolerance (%g)" % (a[0], b[0],
                                                            sagitta))


def check_bad_request(section, cli):
    check(cli.returncode == 1, "the CLI refuses the bad request")
    cli_lines = cli.stderr.splitlines()
    cli_status = [line[len("error: "):] for line in cli_lines
                  if line.startswith("error: ")]
    cli_fields = [line.strip() for line in cli_lines
                  if line.startswith("  field ")]
    status = [line[len("status "):] for line in section
              if line.startswith("status ")]
    fields = [line for line in section if line.startswith("field ")]
    check(status == cli_status and status and
          status[0].startswith("INVALID_ARGUMENT: "),
          "INVALID_ARGUMENT with the CLI's message: %s vs %s" % (status,
                                                                 cli_status))
    check(fields == cli_fields and
          any(line.startswith("field %s: " % BAD_FIELD) for line in fields),
          "the BadRequest names %s as the CLI does: %s vs %s" % (
              BAD_FIELD, fields, cli_fields))


def prepare_python(args):
    """Generates the stubs; returns the command that runs the example."""
    stubs = os.path.join(args.work_dir, "stubs")
    shutil.rmtree(stubs, ignore_errors=True)
    result = run([os.path.join(args.source_dir, "scripts", "python_stubs.sh"),
                  stubs])
    if result.returncode != 0:
        raise RuntimeError("scripts/python_stubs.sh failed")
    os.environ["PYTHONPATH"] = stubs
    return [sys.executable,
            os.path.join(args.source_dir, "examples", "python",
                         "freeform_example.py")]


def prepare_node(args):
    """Installs the npm packages; returns the command that runs the example."""
    node, npm = shutil.which("node"), shutil.which("npm")
    if node is None or npm is None:
        print("SKIP: node or npm is missing (scripts/setup.sh installs them)")
        sys.exit(SKIP)
    shutil.copy(os.path.join(args.source_dir, "examples", "node",
                             "package.json"), args.work_dir)
    result = run([npm, "install", "--prefix", args.work_dir, "--no-audit",
                  "--no-fund", "--ignore-scripts"])
    if result.returncode != 0:
        raise RuntimeError("npm install failed")
    os.environ["NODE_PATH"] = os.path.join(args.work_dir, "node_modules")
    return [node, os.path.join(args.source_dir, "examples", "node",
                               "freeform_example.js")]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("language", choices=["python", "node"])
    parser.add_argument("--freeformd", required=True)
    parser.add_argument("--cli", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--work-dir", required=True)
    args = parser.parse_args()
    os.makedirs(args.work_dir, exist_ok=True)
    example = (prepare_python if args.language == "python" else
               prepare_node)(args)

    stream_file = os.path.join(args.work_dir, "stream_request.json")
    bad_file = os.path.join(args.work_dir, "bad_request.json")
    with open(stream_file, "w") as out:
        json.dump(STREAM_REQUEST, out)
    with open(bad_file, "w") as out:
        json.dump(BAD_REQUEST, out)
    examples = os.path.join(args.source_dir, "examples")

    server, address = start_server(args.freeformd, args.work_dir)
    try:
        output = run(example + ["--address", address])
        print(output.stdout)
        check(output.returncode == 0, "the example exits 0")
        cli = [args.cli]
        evaluate = run(cli + ["eval", "--address", address, "--file",
                              os.path.join(examples, "cubic_bezier.json"),
                              "--format", "csv"])
        stream = run(cli + ["eval", "--stream", "--address", address,
                            "--file", stream_file, "--format", "csv"])
        tessellate = run(cli + ["tessellate", "--address", address, "--file",
                                os.path.join(examples,
                                             "nurbs_circle_polyline.json")])
        bad = run(cli + ["eval", "--address", address, "--file", bad_file])
    finally:
        stop_server(server)

    sections = parse_sections(output.stdout)
    check_evaluate(sections.get("CurveService.Evaluate", []), evaluate.stdout)
    check_stream(sections.get("CurveService.EvaluateStream chunks", []),
                 sections.get("CurveService.EvaluateStream", []),
                 stream.stdout)
    check_tessellate(sections.get("CurveService.Tessellate", []),
                     tessellate.stdout)
    check_bad_request(sections.get("INVALID_ARGUMENT", []), bad)
    if failures:
        print("%d checks failed" % len(failures))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
