#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Seeds for fuzz/recorded_data_fuzzer.cc from a range recording directory and, optionally, an
acoustic one and a pairwise-TDOA one: the fuzzer's input is anchors.csv, ranges.csv, truth.csv,
mics.csv, toa.csv and tdoa.csv joined by NUL bytes. Writes the recordings cut short, without
truth, and with one bad row of each kind the readers reject.
Usage: recorded_fuzz_seeds.py RECORDING_DIR OUT_DIR [ACOUSTIC_RECORDING_DIR [TDOA_RECORDING_DIR]]"""
import pathlib
import sys


def head(path, n):
    return "".join(path.read_text().splitlines(keepends=True)[:n])


def acoustic_seeds(src):
    """Seeds of the stamp readers: no anchors or ranges, the acoustic truth, mics, toa."""
    mics = (src / "mics.csv").read_text()
    toa = head(src / "toa.csv", 80)
    truth = head(src / "truth.csv", 6)
    last_t = toa.splitlines()[-1].split(",")[0]
    return {
        "stamps_full": ("", "", truth, mics, toa),
        "stamps_no_truth": ("", "", "", mics, toa),
        "stamps_missing_z": ("", "", truth, "receiver_id,x_m,y_m\nM1,0.6,0.6\n", toa),
        "stamps_duplicate_mic": ("", "", truth, mics + "M1,1,1,3\n", toa),
        "stamps_unknown_mic": ("", "", truth, mics, toa + f"{last_t},ZZ,1.0\n"),
        "stamps_backwards": ("", "", truth, mics, toa + "0,M1,1.0\n"),
        "stamps_text": ("", "", truth, mics, toa + f"{last_t},M1,0.5s\n"),
        "stamps_nan": ("", "", truth, mics, toa + f"{last_t},M1,nan\n"),
    }


def tdoa_seeds(src):
    """Seeds of the TDOA reader: the 3-D anchors, no ranges, the truth, no mics or toa, tdoa."""
    anchors = (src / "anchors.csv").read_text()
    tdoa = (src / "tdoa.csv").read_text()
    truth = (src / "truth.csv").read_text()
    last_t = tdoa.splitlines()[-1].split(",")[0]
    flat = "".join(",".join(row.split(",")[:3]) + "\n" for row in anchors.splitlines())

    def seed(a, t, tr=truth):
        return (a, "", tr, "", "", t)

    return {
        "tdoa_full": seed(anchors, tdoa),
        "tdoa_no_truth": seed(anchors, tdoa, ""),
        "tdoa_outlier": seed(anchors, tdoa + f"{last_t},A0,A1,-42.5\n"),
        "tdoa_anchors_without_z": seed(flat, tdoa),
        "tdoa_unknown_id": seed(anchors, tdoa + f"{last_t},A0,ZZ,0.1\n"),
        "tdoa_same_ids": seed(anchors, tdoa + f"{last_t},A3,A3,0.1\n"),
        "tdoa_backwards": seed(anchors, tdoa + "0,A0,A1,0.1\n"),
        "tdoa_nan": seed(anchors, tdoa + f"{last_t},A0,A1,nan\n"),
        "tdoa_missing_field": seed(anchors, tdoa + f"{last_t},A0,A1\n"),
    }


def main(src, out, acoustic=None, tdoa=None):
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
    if acoustic is not None:
        seeds.update(acoustic_seeds(pathlib.Path(acoustic)))
    if tdoa is not None:
        seeds.update(tdoa_seeds(pathlib.Path(tdoa)))
    for name, parts in seeds.items():
        (out / name).write_bytes("\0".join(parts).encode())


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4, 5):
        sys.exit("usage: recorded_fuzz_seeds.py RECORDING_DIR OUT_DIR [ACOUSTIC_RECORDING_DIR [TDOA_RECORDING_DIR]]")
    main(*sys.argv[1:])
