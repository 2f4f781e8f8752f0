#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Keeps the generated tables of docs/scenario.md equal to `mirage describe NAME --markdown`.

Each generated block sits between the markers
    <!-- mirage describe NAME --markdown -->
    ...
    <!-- end of mirage describe NAME -->
Without --update the script prints the difference and exits 1 when a block differs (the test
docs_scenario_reference); with --update it rewrites the blocks in place.

Usage: scenario_doc.py MIRAGE_BINARY DOC [--update]
"""
import difflib
import re
import subprocess
import sys

BLOCK = re.compile(r"(<!-- mirage describe (\S+) --markdown -->\n)(.*?)(<!-- end of mirage describe \2 -->)", re.S)


def describe(mirage: str, name: str) -> str:
    out = subprocess.run([mirage, "describe", name, "--markdown"], check=True, capture_output=True, text=True).stdout
    return out if out.endswith("\n") else out + "\n"


def main() -> int:
    args = [a for a in sys.argv[1:] if a != "--update"]
    update = "--update" in sys.argv[1:]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    mirage, doc_path = args
    with open(doc_path, encoding="utf-8") as f:
        doc = f.read()
    names = [m.group(2) for m in BLOCK.finditer(doc)]
    if not names:
        print(f"{doc_path}: no generated blocks found", file=sys.stderr)
        return 1
    generated = BLOCK.sub(lambda m: m.group(1) + describe(mirage, m.group(2)) + m.group(4), doc)
    if generated == doc:
        print(f"{doc_path}: {len(names)} generated blocks agree with mirage describe ({', '.join(names)})")
        return 0
    if update:
        with open(doc_path, "w", encoding="utf-8") as f:
            f.write(generated)
        print(f"{doc_path}: rewrote the generated blocks")
        return 0
    sys.stdout.writelines(difflib.unified_diff(doc.splitlines(True), generated.splitlines(True), doc_path,
                                               "mirage describe"))
    print(f"{doc_path} differs from `mirage describe`; run: python3 tools/scenario_doc.py {mirage} {doc_path} --update",
          file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
