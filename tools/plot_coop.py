#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plot of a cooperative grid (mirage run on a method: coop scenario).

Usage: plot_coop.py DATA.json OUT.png  (DATA.json is written by mirage next to OUT.png)
Left: the room (walls of the provided plan solid, walls missing from it dashed), the agents'
true tracks and the estimate of the first run of the largest variant. Right top: p50/p90 of the
position error per variant with the posterior bound (RMS); right bottom: mean error per step.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    if len(sys.argv) != 3:
        print("usage: plot_coop.py DATA.json OUT.png", file=sys.stderr)
        return 2
    with open(sys.argv[1], encoding="utf-8") as f:
        data = json.load(f)
    fig = plt.figure(figsize=(15, 8))
    room = fig.add_subplot(1, 2, 1)
    for x0, y0, x1, y1, _label, in_plan in data["walls"]:
        room.plot([x0, x1], [y0, y1], color="k" if in_plan else "tab:red", lw=2 if in_plan else 1.5,
                  ls="-" if in_plan else "--")
    for cx, cy, r in data["obstacles"]:
        room.add_patch(plt.Circle((cx, cy), r, color="0.6"))
    colors = ["tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink"]
    for m, track in enumerate(data["truth"]):
        xs, ys = zip(*track)
        room.plot(xs, ys, color=colors[m % len(colors)], lw=1, alpha=0.6, label=f"agent {m + 1} truth")
        room.plot(xs[0], ys[0], "o", color=colors[m % len(colors)])
    for m, track in enumerate(data["estimate"]):
        xs, ys = zip(*track)
        room.plot(xs, ys, ":", color=colors[m % len(colors)], lw=1.5, label=f"agent {m + 1} estimate")
    if data["anchor"] is not None:
        room.plot(data["anchor"][0], data["anchor"][1], "k^", ms=9, label=f"anchor {data['anchor'][2]}")
    room.set_aspect("equal")
    room.set_xlabel("x (m)")
    room.set_ylabel("y (m)")
    room.set_title(f"{data['title']}: first run of {data['estimate_variant']}\n(red dashed: walls not in the plan)")
    room.legend(fontsize=7, loc="upper right")

    names = [v["name"] for v in data["variants"]]
    bars = fig.add_subplot(2, 2, 2)
    xs = range(len(names))
    bars.bar([x - 0.2 for x in xs], [100 * v["p50"] for v in data["variants"]], width=0.4, label="p50")
    bars.bar([x + 0.2 for x in xs], [100 * v["p90"] for v in data["variants"]], width=0.4, label="p90")
    bars.plot(list(xs), [100 * v["peb"] for v in data["variants"]], "k_", ms=14, mew=2, label="bound (RMS)")
    for x, v in zip(xs, data["variants"]):
        if v["diverged"]:
            bars.annotate(f"{v['diverged']} div", (x, 100 * v["p90"]), ha="center", va="bottom", fontsize=7)
    bars.set_xticks(list(xs))
    bars.set_xticklabels(names, rotation=60, ha="right", fontsize=7)
    bars.set_ylabel("position error per agent (cm)")
    bars.set_yscale("log")
    bars.legend(fontsize=8)
    bars.grid(True, axis="y", alpha=0.3)

    steps = fig.add_subplot(2, 2, 4)
    for v in data["variants"]:
        steps.plot([100 * e for e in v["error_by_step"]], lw=1, label=v["name"])
    steps.set_xlabel("step")
    steps.set_ylabel("mean error (cm)")
    steps.set_yscale("log")
    if len(names) <= 12:
        steps.legend(fontsize=6, ncol=2)
    steps.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
