#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Seeds for fuzz/recorded_data_fuzzer.cc from a recording directory: the fuzzer's input is
anchors.csv, ranges.csv and truth.csv joined by NUL bytes. Writes the recording cut short, without
truth, and with one bad row of each kind the readers reject.
Usage: recorded_fuzz_seeds.py RECORDING_DIR OUT_DIR"""
import pathlib
import sys


def main(src, out):
    src, out = pathlib.Path(src), pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    anchors = (src / "anchors.csv").read_text()
    ranges = "".join((src / "ranges.csv").read_text().splitlines(keepends=True)[:60])
    truth = "".join((src / "truth.csv").read_text().splitlines(keepends=True)[:12])
    seeds = {
        "full": (anchors, ranges, truth),
        "no_truth": (anchors, ranges, ""),
        "missing_field": (anchors, ranges + "1,A1\n", truth),
        "unknown_anchor": (anchors, ranges + "9,ZZ,1.0,0.1\n", truth),
        "backwards": (anchors, ranges + "0,A1,1.0,0.1\n", truth),
        "negative": (anchors, ranges + "9,A1,-1.0,0.1\n", truth),
        "nan": (anchors, ranges + "9,A1,nan,0.1\n", truth),
        "z_column": ("anchor_id,x_m,y_m,z_m\nA1,0.5,7,2.5\nA2,5.2,2.3,2.5\n", ranges, truth),
    }
    for name, parts in seeds.items():
        (out / name).write_bytes("\0".join(parts).encode())


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: recorded_fuzz_seeds.py RECORDING_DIR OUT_DIR")
    main(sys.argv[1], sys.argv[2])
