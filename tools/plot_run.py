#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Renders the picture of a `mirage run --plot FILE`, for every method: floor plan (if any),
anchors and the simulated channel's VAs with the method's map of each agent's central run
(3-sigma ellipses), true and estimated tracks with error ellipses (magnified to be seen), the error CDFs, and for a
grid the mean error per step of every variant. Reads FILE.json written by the CLI.
Usage: plot_run.py DATA.json OUT.png"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle, Ellipse  # noqa: E402

COLORS = ["tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown"]


def draw_room(ax, data):
    for x1, y1, x2, y2, coeff, _label in data["walls"]:
        ax.plot([x1, x2], [y1, y2], color=plt.cm.Greys(0.35 + 0.65 * coeff), lw=2.0, solid_capstyle="butt")
    for cx, cy, r in data["obstacles"]:
        ax.add_patch(Circle((cx, cy), r, facecolor="0.6", edgecolor="k", lw=0.8))
    for x, y, name in data["anchors"]:
        ax.plot(x, y, "k^", ms=9)
        ax.annotate(name, (x, y), textcoords="offset points", xytext=(5, 5), fontsize=9)


def ellipse_scale(data, extent_m):
    """The magnification of the error ellipses: the largest of 1, 2, 5, 10, 20, 50 at which the
    median ellipse's semi-major axis stays below 3 % of the view (20 for centimetre errors in a
    room of metres, 2 for decimetre errors in a hall)."""
    axes_m = [np.sqrt(max(np.linalg.eigvalsh(np.array([[sxx, sxy], [sxy, syy]])).max(), 0.0))
              for traj in data["trajectories"] for _x, _y, sxx, sxy, syy in traj["ellipses"]]
    if not axes_m or np.median(axes_m) <= 0.0:
        return 20
    fitting = [k for k in (1, 2, 5, 10, 20, 50) if k * np.median(axes_m) <= 0.03 * extent_m]
    return fitting[-1] if fitting else 1


def main(data_path, out_path):
    with open(data_path, encoding="utf-8") as f:
        data = json.load(f)
    fig, axes = plt.subplots(1, 3, figsize=(18, 6.5), gridspec_kw={"width_ratios": [1.1, 1.1, 1.0]})

    ax = axes[0]
    draw_room(ax, data)
    # The room, not a diverged run, sets the view; without a floor plan the anchors and truth do.
    if data["walls"]:
        walls = np.array([w[:4] for w in data["walls"]])
        xs, ys = np.concatenate([walls[:, 0], walls[:, 2]]), np.concatenate([walls[:, 1], walls[:, 3]])
    else:
        points = [[a[0], a[1]] for a in data["anchors"]]
        for traj in data["trajectories"]:
            points += traj["truth"]
        points = np.array(points)
        xs, ys = points[:, 0], points[:, 1]
    margin = 0.05 * max(np.ptp(xs), np.ptp(ys))
    scale = ellipse_scale(data, max(np.ptp(xs), np.ptp(ys)))
    for t, traj in enumerate(data["trajectories"]):
        color = COLORS[t % len(COLORS)]
        for run in traj["runs"]:
            est = np.array(run["estimate"])
            if len(est):
                ax.plot(est[:, 0], est[:, 1], color=color, lw=0.5, alpha=0.35)
        truth = np.array(traj["truth"])
        if len(truth):
            ax.plot(truth[:, 0], truth[:, 1], "k--", lw=1.2)
            ax.plot(truth[0, 0], truth[0, 1], "ko", ms=5)
        for x, y, sxx, sxy, syy in traj["ellipses"]:
            vals, vecs = np.linalg.eigh(np.array([[sxx, sxy], [sxy, syy]]))
            vals = np.maximum(vals, 0.0)
            angle = np.degrees(np.arctan2(vecs[1, 1], vecs[0, 1]))
            ax.add_patch(Ellipse((x, y), 2 * scale * np.sqrt(vals[1]), 2 * scale * np.sqrt(vals[0]), angle=angle,
                                 fill=False, color=color, lw=0.8))
        ax.plot([], [], color=color, label=f"{traj['name']} (estimates, all runs)")
    ax.plot([], [], "k--", label="truth (central run)")
    ax.set_xlim(xs.min() - margin, xs.max() + margin)
    ax.set_ylim(ys.min() - margin, ys.max() + margin)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{data['title']}: tracks, 1-sigma ellipses x{scale} every 20th step")
    ax.legend(loc="upper right", fontsize=7)

    ax = axes[1]
    if data.get("variants"):
        # A grid: the mean error per step of every variant, the bound dotted.
        for v, variant in enumerate(data["variants"]):
            color = plt.cm.tab20(v % 20)
            ax.plot(variant["error_by_step"], color=color, lw=0.9, label=variant["name"])
            if any(variant["peb_by_step"]):
                ax.plot(variant["peb_by_step"], color=color, lw=0.6, ls=":")
        ax.set_yscale("log")
        ax.set_xlabel("step")
        ax.set_ylabel("mean position error (m); bound dotted")
        ax.set_title("error per step, every variant")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(loc="upper left", fontsize=5, ncol=2)
        draw_cdf(axes[2], data)
        finish(fig, data, out_path)
        return
    draw_room(ax, data)
    vas = np.array([v[:3] for v in data["vas"]]) if data["vas"] else np.zeros((0, 3))
    markers = {1: ("o", 12), 2: (".", 3), 3: (".", 1)}
    for order in sorted(set(vas[:, 2].astype(int))) if len(vas) else []:
        sel = vas[vas[:, 2] == order]
        m, s = markers.get(order, (".", 1))
        ax.scatter(sel[:, 0], sel[:, 1], marker=m, s=s, label=f"order-{order} VAs ({len(sel)})", alpha=0.7)
    has_map = False
    for t, traj in enumerate(data["trajectories"]):
        color = COLORS[t % len(COLORS)]
        for va in traj.get("map", []):
            has_map = True
            sxx, sxy, syy = va["cov"]
            vals, vecs = np.linalg.eigh(np.array([[sxx, sxy], [sxy, syy]]))
            vals = np.maximum(vals, 0.0)
            angle = np.degrees(np.arctan2(vecs[1, 1], vecs[0, 1]))
            ax.add_patch(Ellipse((va["x"], va["y"]), 2 * 3 * np.sqrt(vals[1]), 2 * 3 * np.sqrt(vals[0]), angle=angle,
                                 fill=False, color=color, lw=0.6))
            marker = "x" if va["discovered"] else "+"
            ax.plot(va["x"], va["y"], marker, color=color, ms=6, alpha=0.4 if va["filtered"] else 1.0)
        if traj.get("map"):
            ax.plot([], [], "x", color=color, label=f"{traj['name']}: discovered VAs (x), prior VAs (+), 3-sigma")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    if has_map:
        ax.set_title("floor plan, true VAs and the SLAM map (central run)")
    elif data["walls"] or len(vas):
        ax.set_title("floor plan and virtual anchors")
    else:
        ax.set_title("anchors (no floor plan)")
    if ax.get_legend_handles_labels()[1]:
        ax.legend(loc="upper right", fontsize=7)

    draw_cdf(axes[2], data)
    finish(fig, data, out_path)


def draw_cdf(ax, data):
    if data.get("variants"):
        # A grid: one CDF per variant (method), from the quantiles the report gives.
        for v, variant in enumerate(data["variants"]):
            cdf = np.array(variant.get("error_cdf", []))
            if len(cdf):
                ax.plot(cdf[:, 0], cdf[:, 1], color=plt.cm.tab20(v % 20), lw=0.9, label=variant["name"])
    else:
        for t, traj in enumerate(data["trajectories"]):
            e = np.sort(np.array(traj["errors"]))
            if len(e):
                ax.plot(e, np.arange(1, len(e) + 1) / len(e), color=COLORS[t % len(COLORS)], label=traj["name"])
    ax.axhline(0.9, color="0.5", lw=0.6, ls=":")
    ax.set_xscale("log")
    ax.set_xlabel("position error (m)")
    ax.set_ylabel("CDF over all steps and runs")
    ax.set_title("error CDF" + (", every variant" if data.get("variants") else ""))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper left" if data.get("variants") else "lower right", fontsize=5 if data.get("variants") else 8)


def finish(fig, data, out_path):
    fig.text(0.01, 0.005, data["table"], family="monospace", fontsize=6.5, va="bottom")
    fig.tight_layout(rect=(0, 0.17, 1, 1))
    fig.savefig(out_path, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_run.py DATA.json OUT.png")
    main(sys.argv[1], sys.argv[2])
