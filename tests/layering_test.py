#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Fails when a file includes a mirage header of a higher layer (STYLE.md Sec. 1)."""
import pathlib
import re
import sys

LAYERS = ["core", "geometry", "channel", "dsp", "estimation", "methods", "eval", "pipeline", "io"]
# Allowed dependencies beyond "everything below": none. The filter core (estimation) knows nothing
# about radio or sound: no channel, no dsp. A method may use them: a method family owns its front
# end (the pulse's CRLB scale, which links it measures, extraction with a count it chooses), so
# that adding a method touches only methods/ (ROADMAP.md "Architecture").
FORBIDDEN = {
    "estimation": {"channel", "dsp"},
}
INCLUDE = re.compile(r'#include\s+"mirage/([a-z_]+)/')


def main(root):
    root = pathlib.Path(root)
    problems = []
    for base in ("include/mirage", "src"):
        for path in sorted((root / base).rglob("*")):
            if path.suffix not in (".h", ".cc"):
                continue
            layer = path.relative_to(root / base).parts[0]
            if layer not in LAYERS:
                problems.append(f"{path}: unknown layer '{layer}'")
                continue
            rank = LAYERS.index(layer)
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                m = INCLUDE.search(line)
                if not m:
                    continue
                target = m.group(1)
                if target not in LAYERS:
                    problems.append(f"{path}:{number}: includes unknown layer '{target}'")
                elif LAYERS.index(target) > rank:
                    problems.append(f"{path}:{number}: layer '{layer}' includes higher layer '{target}'")
                elif target in FORBIDDEN.get(layer, set()):
                    problems.append(f"{path}:{number}: layer '{layer}' must not include '{target}'")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
