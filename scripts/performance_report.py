#!/usr/bin/env python3
"""The parsing and the report of scripts/performance.sh (standard library only).

  performance_report.py results GBENCH_JSON...   > results.txt
      prints the project's workload benchmarks (Google Benchmark JSON) as
      RESULT lines, the format the peer programs print
      (bench/peers/peer_result.h):
        RESULT <workload> <implementation> <value> <unit> checksum=<x>
  performance_report.py table RESULTS OPERATIONS_JSON [--about FILE]
                              [--output FILE]
      prints the Markdown table of every workload (freeform, every peer, the
      ratio to the best peer, the target) and the operations without a peer;
      with --output also writes the whole document (docs/performance.md),
      with the lines of --about ("key: value") as the machine's description.
"""
import argparse
import json
import re
import sys

# The project's benchmark of each workload: name pattern -> (workload,
# implementation). W7 is W1, W3 and W4 on every pool thread.
FREEFORM = [
    (r"BM_W1_CubicBSplinePositions$", "W1", "EvaluateBSplineCurve"),
    (r"BM_W2_CubicBSplineFirstDerivative$", "W2", "EvaluateBSplineCurve"),
    (r"BM_W3_BicubicSurfaceGrid$", "W3", "EvaluateBSplineSurface"),
    (r"BM_W4_CubicBezierPositions$", "W4", "EvaluateBezierCurve"),
    (r"BM_W5_GlobalCubicInterpolation/100000$", "W5", "InterpolateCurve"),
    (r"BM_W6_ElevateW1ByOne$", "W6", "ElevateBSplineCurve"),
    (r"BM_W7_CubicBSplinePositionsAllThreads(/real_time)?$", "W7", "W1_all_threads"),
    (r"BM_W7_BicubicSurfaceGridAllThreads(/real_time)?$", "W7", "W3_all_threads"),
    (r"BM_W4_CubicBezierPositionsAllThreads(/real_time)?$", "W7", "W4_all_threads"),
]

# Rows of the table: (row, workload, freeform implementation, what, target).
# A rate's ratio is freeform / best peer, a time's best peer / freeform; W7's
# is freeform on every thread / freeform on one.
ROWS = [
    ("W1", "W1", None, "cubic B-spline, 100 control points, 10^6 positions",
     4.0),
    ("W2", "W2", None, "the W1 curve, positions + first derivatives", 3.0),
    ("W3", "W3", None, "bicubic 20 x 20 B-spline surface, 1000 x 1000 grid",
     3.0),
    ("W4", "W4", None, "cubic Bezier, 10^7 positions", 4.0),
    ("W5", "W5", None, "cubic interpolation of 10^5 points (time)", 2.0),
    ("W6", "W6", None, "degree elevation of W1 by 1 (time)", 3.0),
    ("W7 (W1)", "W7", "W1_all_threads",
     "W1 on every thread / W1 on one thread", 1.8),
    ("W7 (W3)", "W7", "W3_all_threads",
     "W3 on every thread / W3 on one thread", 1.8),
    ("W7 (W4)", "W7", "W4_all_threads",
     "W4 on every thread / W4 on one thread", 1.8),
]

PEERS = [("occt", "OpenCASCADE"), ("eigen", "Eigen"), ("scipy", "scipy")]

TIME_FACTORS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def best_runs(paths):
    """The best repetition of every benchmark (Google Benchmark JSON)."""
    best = {}
    for path in paths:
        with open(path) as file:
            for run in json.load(file)["benchmarks"]:
                if run.get("run_type", "iteration") != "iteration":
                    continue
                name = run["run_name"] if "run_name" in run else run["name"]
                seconds = run["real_time"] * TIME_FACTORS[run["time_unit"]]
                if name not in best or seconds < best[name][0]:
                    best[name] = (seconds, run)
    return best


def as_result(name, seconds, run):
    """(value, unit, checksum) of one benchmark run; rates per wall time."""
    checksum = run.get("checksum", run.get("control_points", 0))
    if "points/s" not in run:
        return seconds, "seconds", checksum
    if name.endswith("/real_time"):
        return run["points/s"], "points_per_s", checksum
    # The counter is per CPU second: back to points per iteration, then per
    # wall second like the peers' figures.
    cpu = run["cpu_time"] * TIME_FACTORS[run["time_unit"]]
    return run["points/s"] * cpu / seconds, "points_per_s", checksum


def command_results(paths):
    best = best_runs(paths)
    for pattern, workload, implementation in FREEFORM:
        for name, (seconds, run) in sorted(best.items()):
            if re.search(pattern, name):
                value, unit, checksum = as_result(name, seconds, run)
                print("RESULT %s freeform:%s %.6e %s checksum=%.12g" %
                      (workload, implementation, value, unit, checksum))


def read_results(path):
    """[(workload, peer, implementation, value, unit, checksum)]."""
    results = []
    with open(path) as file:
        for line in file:
            fields = line.split()
            if len(fields) != 6 or fields[0] != "RESULT":
                continue
            peer, _, implementation = fields[2].partition(":")
            results.append((fields[1], peer, implementation, float(fields[3]),
                            fields[4], fields[5].partition("=")[2]))
    return results


def better(unit, a, b):
    return a > b if unit == "points_per_s" else a < b


def best_of(results, workload, peer, implementation=None):
    """The best (value, unit, implementation) of one peer on a workload."""
    found = None
    for w, p, name, value, unit, _ in results:
        if w != workload or p != peer:
            continue
        if implementation is not None and name != implementation:
            continue
        if found is None or better(unit, value, found[0]):
            found = (value, unit, name)
    return found


def figure(value, unit):
    if unit == "points_per_s":
        return "%.1f M/s" % (value / 1e6)
    if value < 1e-3:
        return "%.1f us" % (value * 1e6)
    if value < 1:
        return "%.2f ms" % (value * 1e3)
    return "%.2f s" % value


def speedup(unit, freeform, other):
    """How many times faster freeform is than `other`."""
    return freeform / other if unit == "points_per_s" else other / freeform


def row_cells(results, row, workload, implementation, target):
    """The cells of one row of the workload table."""
    mine = best_of(results, workload, "freeform", implementation)
    if workload == "W7":
        peers = ["-"] * len(PEERS)
        base = best_of(results, implementation[:2], "freeform")
        other = base[0] if base else None
    else:
        found = [best_of(results, workload, peer) for peer, _ in PEERS]
        peers = [figure(f[0], f[1]) if f else "-" for f in found]
        values = [f[0] for f in found if f]
        other = None
        if values and mine:
            other = values[0]
            for value in values[1:]:
                if better(mine[1], value, other):
                    other = value
    if mine is None or other is None:
        ratio, result = "-", "no figure"
    else:
        r = speedup(mine[1], mine[0], other)
        if workload == "W7":
            r = mine[0] / other
        ratio = "%.2fx" % r
        result = "ok" if r >= target else "below target"
    return [row, figure(mine[0], mine[1]) if mine else "-"] + peers + [
        ratio, ">= %gx" % target, result]


def workload_table(results):
    header = ["workload", "what", "freeform"] + [name for _, name in PEERS] + [
        "freeform / best peer", "target", "result"]
    lines = ["| " + " | ".join(header) + " |",
             "|" + "---|" * len(header)]
    for row, workload, implementation, what, target in ROWS:
        cells = row_cells(results, row, workload, implementation, target)
        cells.insert(1, what)
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def figures_table(results):
    lines = ["| workload | implementation | figure | checksum |",
             "|---|---|---|---|"]
    for workload, peer, name, value, unit, checksum in results:
        lines.append("| %s | %s: `%s` | %s | %s |" % (
            workload, peer, name, figure(value, unit), checksum))
    return lines


def counters(run):
    skip = {"name", "run_name", "run_type", "family_index",
            "per_family_instance_index", "repetitions", "repetition_index",
            "threads", "iterations", "real_time", "cpu_time", "time_unit",
            "aggregate_name", "aggregate_unit", "label", "error_occurred",
            "error_message"}
    shown = []
    for key, value in run.items():
        if key in skip or not isinstance(value, (int, float)):
            continue
        if key.endswith("/s"):
            shown.append("%s %.1f M" % (key, value / 1e6))
        else:
            shown.append("%s %.10g" % (key, value))
    return ", ".join(shown)


def operations_table(path):
    lines = ["| operation | wall time (best) | results |", "|---|---|---|"]
    for name, (seconds, run) in best_runs([path]).items():
        lines.append("| `%s` | %s | %s |" % (
            name, figure(seconds, "seconds"), counters(run)))
    return lines


def document(about, workloads, figures, operations):
    command = about.pop("command", "bash scripts/performance.sh")
    text = ["# Performance: freeform against its peers", "",
            "Written by `scripts/performance.sh` from one run; do not edit "
            "the figures by hand, run the command again:", "",
            "```", command, "```", "",
            "It builds the release configuration with the peer programs "
            "(`-DFREEFORM_PEER_BENCHMARKS=ON`, in `build/peers`), then runs "
            "the project's benchmarks and every peer one after the other on "
            "the same data: the workloads W1-W7 of "
            "[benchmarks.md](benchmarks.md) (LCG data of `bench/workloads.h`), "
            "single thread except W7. Peers: OpenCASCADE "
            "(`bench/peers/occt_workloads_bench.cc`), Eigen's Splines module "
            "(`bench/peers/eigen_workloads_bench.cc`) and scipy "
            "(`bench/peers/scipy_workloads.py`). Each figure is the best wall "
            "time of its runs; rates are points per second. A peer's cell is "
            "its best implementation (all are listed below).", "",
            "Figures move with the machine's load (this is a shared machine: "
            "other builds may run beside the benchmarks) and from machine to "
            "machine, so only ratios measured in the same run mean anything; "
            "compare a figure with one from another run only through its "
            "ratio.", "",
            "Where the cycles go in each workload, and what would close the "
            "gaps to the targets: [performance_profile.md]"
            "(performance_profile.md) (perf profiles, written by hand).", "",
            "## Machine", ""]
    text += ["- %s: %s" % (key, value) for key, value in about.items()]
    text += ["", "## Workloads", ""] + workloads + [
        "", "Ratio: freeform's rate / the best peer's rate (W1-W4), the best "
        "peer's time / freeform's time (W5, W6), freeform on every pool "
        "thread / freeform on one thread (W7). W5's peers use other knot "
        "rules than freeform's averaging knots (OpenCASCADE: knots at the "
        "parameters; scipy: not-a-knot, and averaging knots like freeform), "
        "so only scipy's averaging checksum matches freeform's.", "",
        "## Every figure and its checksum", "",
        "The checksum is the sum of x + y + z over every output point (W1-W4, "
        "W7), the sum of the control points' coordinates (W5, W6): equal "
        "checksums show that the same geometry was computed.", ""] + figures + [
        "", "## Operations without a peer figure", "",
        "`bench/operations_bench.cc` (its header says what each one does); "
        "the checksums are sums of the results' coordinates.", ""] + \
        operations
    return "\n".join(text) + "\n"


def read_about(path):
    about = {}
    if path:
        with open(path) as file:
            for line in file:
                key, _, value = line.rstrip("\n").partition(": ")
                if key:
                    about[key] = value
    return about


def command_table(args):
    results = read_results(args.results)
    workloads = workload_table(results)
    operations = operations_table(args.operations)
    print("\n".join(workloads))
    print()
    print("\n".join(operations))
    if args.output:
        with open(args.output, "w") as file:
            file.write(document(read_about(args.about), workloads,
                                figures_table(results), operations))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    results = commands.add_parser("results")
    results.add_argument("json", nargs="+")
    table = commands.add_parser("table")
    table.add_argument("results")
    table.add_argument("operations")
    table.add_argument("--about")
    table.add_argument("--output")
    args = parser.parse_args()
    if args.command == "results":
        command_results(args.json)
    else:
        command_table(args)


if __name__ == "__main__":
    sys.exit(main())
