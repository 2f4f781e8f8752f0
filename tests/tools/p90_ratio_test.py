#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Tests of tools/p90_ratio.py on small tracks.csv files written here: the percentile, the
paired bootstrap, the per-seed count over the limit, reproducibility and bad input.
Usage: p90_ratio_test.py PROJECT_SOURCE_DIR"""
import io
import os
import pathlib
import random
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(sys.argv.pop(1)) / "tools"))
import p90_ratio  # noqa: E402

HEADER = "trajectory,run,step,error_m\n"


def write_tracks(directory, rows, header=HEADER):
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "tracks.csv"), "w") as f:
        f.write(header)
        for trajectory, run, step, error_m in rows:
            f.write(f"{trajectory},{run},{step},{error_m}\n")
    return directory


def random_rows(rng, runs, steps, scale=1.0, trajectory="trajectory_1"):
    return [(trajectory, r, s, scale * rng.random()) for r in range(runs) for s in range(steps)]


class PercentileTest(unittest.TestCase):
    def test_linear_between_order_statistics(self):
        self.assertAlmostEqual(p90_ratio.percentile(list(range(11)), 90), 9.0)
        self.assertAlmostEqual(p90_ratio.percentile([4.0, 1.0, 3.0, 2.0], 90), 3.7)
        self.assertAlmostEqual(p90_ratio.percentile([5.0], 90), 5.0)


class CompareTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def run_compare(self, test, ref, **kw):
        out = io.StringIO()
        args = dict(q=90.0, limit=1.3, draws=200, seed=1)
        args.update(kw)
        summary = p90_ratio.compare(test, ref, args["q"], args["limit"], args["draws"], args["seed"], out)
        return summary, out.getvalue()

    def test_paired_runs_give_an_exact_ratio_and_a_collapsed_interval(self):
        # The test configuration's error is 1.25x the reference's at every step of every run, so
        # every paired resampling has the ratio 1.25; an unpaired one would scatter widely.
        rng = random.Random(7)
        ref_rows = random_rows(rng, runs=25, steps=40)
        test_rows = [(t, r, s, 1.25 * e) for t, r, s, e in ref_rows]
        ref = write_tracks(f"{self.root}/k1", ref_rows)
        test = write_tracks(f"{self.root}/a1", test_rows)
        (summary,), text = self.run_compare([test], [ref])
        name, value, lo, hi, over = summary
        self.assertEqual(name, "trajectory_1")
        self.assertAlmostEqual(value, 1.25, places=12)
        self.assertAlmostEqual(lo, 1.25, places=12)
        self.assertAlmostEqual(hi, 1.25, places=12)
        self.assertEqual(over, 0)
        self.assertIn("pooled over 1 seeds (25 runs): 1.250, 95 % CI 1.250-1.250", text)

    def test_counts_the_seeds_over_the_limit_and_pools_the_rest(self):
        rng = random.Random(3)
        ref1, ref2 = random_rows(rng, 20, 30), random_rows(rng, 20, 30)
        dirs = [write_tracks(f"{self.root}/k1", ref1), write_tracks(f"{self.root}/k2", ref2)]
        tests = [write_tracks(f"{self.root}/a1", [(t, r, s, 1.5 * e) for t, r, s, e in ref1]),
                 write_tracks(f"{self.root}/a2", [(t, r, s, 1.1 * e) for t, r, s, e in ref2])]
        (summary,), text = self.run_compare(tests, dirs)
        _, value, lo, hi, over = summary
        self.assertEqual(over, 1)
        self.assertIn("1 of 2 seeds over 1.3", text)
        # Pooled, the ratio lies between the two seeds' and the interval around it.
        self.assertTrue(1.1 < value < 1.5, value)
        self.assertTrue(1.1 <= lo <= value <= hi <= 1.5, (lo, value, hi))

    def test_interval_covers_the_true_ratio_of_noisy_runs(self):
        # Independent errors with p90 0.9 * scale: test scale 1.2, reference 1.0.
        rng = random.Random(11)
        ref = write_tracks(f"{self.root}/k1", random_rows(rng, 100, 50, 1.0))
        test = write_tracks(f"{self.root}/a1", random_rows(rng, 100, 50, 1.2))
        (summary,), _ = self.run_compare([test], [ref], draws=300)
        _, value, lo, hi, _ = summary
        self.assertTrue(lo < 1.2 < hi, (lo, value, hi))
        self.assertLess(hi - lo, 0.1)

    def test_same_seed_same_output(self):
        rng = random.Random(5)
        ref = write_tracks(f"{self.root}/k1", random_rows(rng, 10, 20))
        test = write_tracks(f"{self.root}/a1", random_rows(rng, 10, 20, 1.3))
        _, first = self.run_compare([test], [ref], seed=4)
        _, second = self.run_compare([test], [ref], seed=4)
        self.assertEqual(first, second)


class BadInputTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        self.good = write_tracks(f"{self.root}/good", [("trajectory_1", 0, 0, 0.01), ("trajectory_1", 0, 1, 0.02)])

    def tearDown(self):
        self.tmp.cleanup()

    def expect_exit_2(self, args, message):
        stderr = io.StringIO()
        saved, sys.stderr = sys.stderr, stderr
        try:
            status = p90_ratio.main(args)
        finally:
            sys.stderr = saved
        self.assertEqual(status, 2)
        self.assertIn(message, stderr.getvalue())

    def test_missing_column(self):
        bad = write_tracks(f"{self.root}/bad", [], header="trajectory,run,step\n")
        self.expect_exit_2(["--test", bad, "--reference", self.good],
                           f"{bad}/tracks.csv:1: header has no column 'error_m'")

    def test_nan_error_with_line(self):
        bad = write_tracks(f"{self.root}/bad", [("trajectory_1", 0, 0, 0.01), ("trajectory_1", 0, 1, "nan")])
        self.expect_exit_2(["--test", bad, "--reference", self.good], f"{bad}/tracks.csv:3: error_m 'nan'")

    def test_short_row_with_line(self):
        bad = write_tracks(f"{self.root}/bad", [("trajectory_1", 0, 0, 0.01)])
        with open(f"{bad}/tracks.csv", "a") as f:
            f.write("trajectory_1,0\n")
        self.expect_exit_2(["--test", bad, "--reference", self.good], f"{bad}/tracks.csv:3: 2 fields")

    def test_missing_directory(self):
        self.expect_exit_2(["--test", f"{self.root}/none", "--reference", self.good],
                           f"{self.root}/none/tracks.csv: cannot open")

    def test_unpaired_directories(self):
        self.expect_exit_2(["--test", self.good, self.good, "--reference", self.good],
                           "2 --test directories but 1 --reference directories")

    def test_corrupted_files_exit_0_or_2_never_raise(self):
        # A small fuzz: 300 seeded corruptions of a good tracks.csv (bytes flipped, inserted or
        # cut, NUL and non-UTF-8 bytes included). Each must either be read (exit 0) or be
        # reported as bad input (exit 2, a message naming the file or its directory), never end in a traceback.
        rng = random.Random(2026)
        with open(f"{self.good}/tracks.csv", "rb") as f:
            good = f.read() + b"trajectory_1,1,0,0.5\ntrajectory_1,1,1,0.25\n"
        ref = write_tracks(f"{self.root}/ref", [("trajectory_1", 0, 0, 0.01), ("trajectory_1", 0, 1, 0.02),
                                                 ("trajectory_1", 1, 0, 0.5), ("trajectory_1", 1, 1, 0.25)])
        for i in range(300):
            data = bytearray(good)
            for _ in range(rng.randint(1, 4)):
                op, at = rng.randrange(3), rng.randrange(len(data) + 1)
                if op == 0 and at < len(data):
                    data[at] = rng.choice([0, 0x22, 0x2C, 0x0A, 0xFF, 0x80, rng.randrange(256)])
                elif op == 1:
                    data[at:at] = bytes([rng.randrange(256)])
                else:
                    del data[at:at + rng.randint(1, 8)]
            bad = f"{self.root}/fuzz{i}"
            os.makedirs(bad)
            with open(f"{bad}/tracks.csv", "wb") as f:
                f.write(bytes(data))
            stderr, stdout = io.StringIO(), io.StringIO()
            saved = sys.stderr, sys.stdout
            sys.stderr, sys.stdout = stderr, stdout
            try:
                status = p90_ratio.main(["--test", bad, "--reference", ref, "--bootstrap", "5"])
            finally:
                sys.stderr, sys.stdout = saved
            self.assertIn(status, (0, 2), bytes(data))
            if status == 2:
                self.assertIn(bad, stderr.getvalue())

    def test_different_runs(self):
        other = write_tracks(f"{self.root}/other", [("trajectory_1", 1, 0, 0.01)])
        self.expect_exit_2(["--test", other, "--reference", self.good], "trajectory_1 has different runs")


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]])
