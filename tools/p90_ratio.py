#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Compares the position-error percentile of two configurations run on the same seeds, e.g. SLAM
from the anchors alone against SLAM with every VA known (the "within 1.3x" target).

Each DIR is the `--csv` output of one `mirage run` (its tracks.csv); the i-th --test DIR and the
i-th --reference DIR must come from the same seed, so their run k saw the same signals. For each
trajectory it prints, per seed, the two percentiles and their ratio with a bootstrap standard
error, and pooled over all seeds the ratio with a 95 % confidence interval.

Why a bootstrap: a percentile of 25 runs is itself a random number. Resampling runs (whole runs,
as a run's steps are correlated; the same runs for both configurations, as they share the
signals) gives its spread without assuming a distribution. The ratio's interval is the 2.5 and
97.5 percentiles of the resampled ratios (the percentile bootstrap). Every draw comes from
--seed, so the output is reproducible.

Usage:
  p90_ratio.py --test A_s1 A_s2 ... --reference K_s1 K_s2 ... [--percentile 90] [--limit 1.3]
               [--bootstrap 1000] [--seed 1]
Percentiles interpolate linearly between order statistics, as the JSON report's do. Exit status
0 on success, 2 on bad input (with file, line and value)."""
import argparse
import csv
import math
import os
import random
import statistics
import sys


class InputError(Exception):
    pass


def percentile(values, q):
    """q in [0, 100], linear between order statistics (mirage::eval::Percentile)."""
    v = sorted(values)
    pos = (len(v) - 1) * q / 100.0
    lo = int(math.floor(pos))
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def read_tracks(directory):
    """{trajectory: {run: [error_m, ...]}} from DIR/tracks.csv."""
    path = os.path.join(directory, "tracks.csv")
    try:
        f = open(path, newline="")
    except OSError as e:
        raise InputError(f"{path}: cannot open: {e.strerror}")
    runs = {}
    try:
        with f:
            read_rows(path, csv.reader(f), runs)
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: not UTF-8 text ({e.reason} at byte {e.start})")
    except csv.Error as e:
        raise InputError(f"{path}: not CSV ({e})")
    if not runs:
        raise InputError(f"{path}: no rows")
    return runs


def read_rows(path, reader, runs):
    """Adds the rows of `reader` (over path) to runs; reader.line_num is the file's line."""
    header = next(reader, None)
    if header is None:
        raise InputError(f"{path}:1: empty file (expected a header with trajectory, run, error_m)")
    col = {}
    for key in ("trajectory", "run", "error_m"):
        if key not in header:
            raise InputError(f"{path}:1: header has no column '{key}'")
        col[key] = header.index(key)
    for row in reader:
        where = f"{path}:{reader.line_num}"
        if len(row) != len(header):
            raise InputError(f"{where}: {len(row)} fields, the header has {len(header)}")
        trajectory = row[col["trajectory"]]
        try:
            run = int(row[col["run"]])
        except ValueError:
            raise InputError(f"{where}: run '{row[col['run']]}' is not an integer")
        text = row[col["error_m"]]
        try:
            error_m = float(text)
        except ValueError:
            raise InputError(f"{where}: error_m '{text}' is not a number")
        if not math.isfinite(error_m) or error_m < 0:
            raise InputError(f"{where}: error_m '{text}' is not a finite value >= 0")
        runs.setdefault(trajectory, {}).setdefault(run, []).append(error_m)


def pooled(errors, keys):
    return [e for key in keys for e in errors[key]]


def percentiles(test, ref, keys, q):
    """(test's, reference's, their ratio) over the runs `keys`."""
    p_test = percentile(pooled(test, keys), q)
    p_ref = percentile(pooled(ref, keys), q)
    return p_test, p_ref, p_test / p_ref if p_ref > 0 else math.inf


def ratio(test, ref, keys, q):
    return percentiles(test, ref, keys, q)[2]


def resampled_ratios(test, ref, keys, q, draws, rng):
    """Ratios over `draws` resamplings of the runs (with replacement, paired)."""
    out = []
    for _ in range(draws):
        sample = [keys[rng.randrange(len(keys))] for _ in keys]
        out.append(ratio(test, ref, sample, q))
    return sorted(out)


def compare(test_dirs, ref_dirs, q, limit, draws, seed, out):
    if len(test_dirs) != len(ref_dirs):
        raise InputError(f"{len(test_dirs)} --test directories but {len(ref_dirs)} --reference "
                         "directories (one of each per seed)")
    test_sets = [read_tracks(d) for d in test_dirs]
    ref_sets = [read_tracks(d) for d in ref_dirs]
    rng = random.Random(seed)
    trajectories = sorted(set().union(*(s.keys() for s in test_sets)))
    for i, (t, r) in enumerate(zip(test_sets, ref_sets)):
        if sorted(t) != sorted(r):
            raise InputError(f"{test_dirs[i]} and {ref_dirs[i]}: different trajectories "
                             f"({', '.join(sorted(t))} against {', '.join(sorted(r))})")
        for name in t:
            if sorted(t[name]) != sorted(r[name]):
                raise InputError(f"{test_dirs[i]} and {ref_dirs[i]}: {name} has different runs "
                                 f"({len(t[name])} against {len(r[name])})")
    summary = []
    for name in trajectories:
        test, ref, keys = {}, {}, []
        out.write(f"{name}: p{q:g} test / reference (m), ratio, bootstrap SE of the ratio\n")
        over = 0
        for i, (t, r) in enumerate(zip(test_sets, ref_sets)):
            if name not in t:
                raise InputError(f"{test_dirs[i]}: no {name}")
            set_keys = [(i, run) for run in sorted(t[name])]
            for (_, run) in set_keys:
                test[(i, run)] = t[name][run]
                ref[(i, run)] = r[name][run]
            keys += set_keys
            p_test, p_ref, value = percentiles(test, ref, set_keys, q)
            over += value > limit
            se = statistics.pstdev(resampled_ratios(test, ref, set_keys, q, draws, rng))
            out.write(f"  {test_dirs[i]} / {ref_dirs[i]}: {p_test:.4f} / {p_ref:.4f}, {value:.3f}, {se:.3f}\n")
        value = ratio(test, ref, keys, q)
        draws_sorted = resampled_ratios(test, ref, keys, q, draws, rng)
        lo = percentile(draws_sorted, 2.5)
        hi = percentile(draws_sorted, 97.5)
        out.write(f"  pooled over {len(test_sets)} seeds ({len(keys)} runs): {value:.3f}, 95 % CI "
                  f"{lo:.3f}-{hi:.3f}; {over} of {len(test_sets)} seeds over {limit:g}\n")
        summary.append((name, value, lo, hi, over))
    return summary


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--test", nargs="+", required=True, metavar="DIR")
    parser.add_argument("--reference", nargs="+", required=True, metavar="DIR")
    parser.add_argument("--percentile", type=float, default=90.0)
    parser.add_argument("--limit", type=float, default=1.3)
    parser.add_argument("--bootstrap", type=int, default=1000, help="resamplings (default 1000)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the resampling (default 1)")
    args = parser.parse_args(argv)
    if not 0 <= args.percentile <= 100:
        parser.error(f"--percentile {args.percentile:g} is not in [0, 100]")
    if args.bootstrap < 1:
        parser.error(f"--bootstrap {args.bootstrap} must be at least 1")
    try:
        compare(args.test, args.reference, args.percentile, args.limit, args.bootstrap, args.seed,
                sys.stdout)
    except InputError as e:
        print(f"p90_ratio.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
