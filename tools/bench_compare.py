#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Compare two mirage_bench binaries (a reference commit and this one) in one session.

Repetitions are interleaved (reference, test, reference, test, ...) so that a change of the
machine's load hits both alike; the result per benchmark is the median CPU time of each and the
ratio of the medians (test / reference).

    python3 tools/bench_compare.py REFERENCE_BENCH TEST_BENCH [--filter REGEX] [--repetitions N]
        [--min-time SECONDS]
"""
import argparse
import json
import statistics
import subprocess
import sys


def run_once(binary, bench_filter, min_time):
    out = subprocess.run([binary, f"--benchmark_filter={bench_filter}", f"--benchmark_min_time={min_time}",
                          "--benchmark_format=json"], check=True, capture_output=True, text=True).stdout
    return {b["name"]: b["cpu_time"] * {"ns": 1e-3, "us": 1.0, "ms": 1e3}[b["time_unit"]]
            for b in json.loads(out)["benchmarks"] if b.get("run_type", "iteration") == "iteration"}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("reference")
    parser.add_argument("test")
    parser.add_argument("--filter", default="BM_MintAnchorStep$|BM_SlamStep40Vas/joseph:0|BM_CoopStepTwoAgents/30")
    parser.add_argument("--repetitions", type=int, default=7)
    parser.add_argument("--min-time", default="0.5", help="seconds per repetition and benchmark")
    args = parser.parse_args()
    times = {"reference": {}, "test": {}}
    for repetition in range(args.repetitions):
        for which in ("reference", "test"):
            for name, cpu_us in run_once(getattr(args, which), args.filter, args.min_time).items():
                times[which].setdefault(name, []).append(cpu_us)
        print(f"repetition {repetition + 1}/{args.repetitions} done", file=sys.stderr)
    print(f"{'benchmark':40} {'reference us':>13} {'test us':>10} {'ratio':>7}")
    worst = 0.0
    for name in sorted(times["test"]):
        if name not in times["reference"]:
            print(f"{name:40} {'-':>13} {statistics.median(times['test'][name]):10.1f} {'-':>7}")
            continue
        reference = statistics.median(times["reference"][name])
        test = statistics.median(times["test"][name])
        worst = max(worst, test / reference)
        print(f"{name:40} {reference:13.1f} {test:10.1f} {test / reference:7.3f}")
    print(f"(median CPU time of {args.repetitions} interleaved repetitions; worst ratio {worst:.3f})")


if __name__ == "__main__":
    main()
