#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Fails when one expression of the library draws twice from a random generator.

The order in which a function's (or a constructor's) arguments, or the operands of + and *, are
evaluated is unspecified in C++: g++ evaluates constructor arguments last first, clang first
first. `Vec2(rng.Uniform(), rng.Uniform())` is therefore a different vector under each compiler,
and the same seed would give different results. One draw per statement fixes the order. Braced
initialiser lists (evaluated in order) and the branches of ?: are the exceptions a reader can see;
write those as separate statements too, so that this check stays simple.
"""
import pathlib
import re
import sys

DRAW = re.compile(r"\b\w*rng\w*\s*(?:\.|->)\s*(?:Uniform|UniformInt|Normal|ComplexNormal|Poisson|Bernoulli|NextU64)\s*\(")


def main(root):
    root = pathlib.Path(root)
    failures = []
    for folder in ("src", "include", "apps"):
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".cc", ".h"):
                continue
            text = re.sub(r"//[^\n]*", "", path.read_text())
            offset = 0
            for statement in re.split(r"([;{}])", text):
                if len(DRAW.findall(statement)) >= 2:
                    line = text.count("\n", 0, offset + len(statement) - len(statement.lstrip())) + 1
                    failures.append(f"{path.relative_to(root)}:{line}: two random draws in one statement: "
                                    f"{' '.join(statement.split())[:120]}")
                offset += len(statement)
    for f in failures:
        print(f)
    print(f"{len(failures)} statements draw twice")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
