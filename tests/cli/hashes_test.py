#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Byte-identity of every example's results: the SHA-256 of tracks.csv and runs.csv for each
example at seeds 1-3 (a few runs each) must equal the recorded values in tests/golden/.

A change that must not change results (a refactor) keeps this test green; a change that does
(a bug fix, a new default) updates the golden file with --update in the same commit and says so.

Usage: hashes_test.py MIRAGE_BINARY EXAMPLES_DIR GOLDEN_FILE WORK_DIR [--update]
"""
import hashlib
import pathlib
import shutil
import subprocess
import sys

SEEDS = (1, 2, 3)
# Runs per trajectory (per variant for a grid): enough to cover different start offsets while the
# whole test stays within seconds.
RUNS = {"coop_room": 2, "recorded": 1, "recorded_acoustic": 1}  # a recording is one run
DEFAULT_RUNS = 5


def examples(root: pathlib.Path):
    files = sorted(root.glob("*.yaml")) + sorted(root.glob("*/scenario.yaml"))
    for f in files:
        name = f.parent.name if f.name == "scenario.yaml" else f.stem
        yield name, f


def sha256(path: pathlib.Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def main() -> int:
    args = [a for a in sys.argv[1:] if a != "--update"]
    update = "--update" in sys.argv[1:]
    if len(args) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    mirage, root, golden, work = pathlib.Path(args[0]), pathlib.Path(args[1]), pathlib.Path(args[2]), pathlib.Path(args[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    lines = []
    for name, scenario in examples(root):
        runs = RUNS.get(name, DEFAULT_RUNS)
        for seed in SEEDS:
            out = work / f"{name}_seed{seed}"
            cmd = [str(mirage), "run", str(scenario), "--seed", str(seed), "--runs", str(runs), "--quiet", "--csv", str(out)]
            done = subprocess.run(cmd, capture_output=True, text=True)
            if done.returncode != 0:
                print(f"FAIL {name} seed {seed}: exit {done.returncode}: {done.stderr.strip()}")
                return 1
            lines.append(f"{name} {seed} {runs} {sha256(out / 'tracks.csv')} {sha256(out / 'runs.csv')}")
    if update:
        golden.write_text("# example seed runs sha256(tracks.csv) sha256(runs.csv); tests/cli/hashes_test.py --update\n" +
                          "\n".join(lines) + "\n")
        print(f"wrote {len(lines)} hashes to {golden}")
        return 0
    expected = [l for l in golden.read_text().splitlines() if l and not l.startswith("#")]
    failures = 0
    for line in sorted(set(expected) | set(lines)):
        if line in expected and line in lines:
            continue
        failures += 1
        print(("expected " if line in expected else "got      ") + line)
    keys_expected = {tuple(l.split()[:3]) for l in expected}
    keys_got = {tuple(l.split()[:3]) for l in lines}
    if keys_expected != keys_got:
        print(f"the examples differ from the golden file's: missing {sorted(keys_expected - keys_got)}, "
              f"new {sorted(keys_got - keys_expected)}")
    print(f"{len(lines) - failures // 2} of {len(lines)} example/seed results byte-identical")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
