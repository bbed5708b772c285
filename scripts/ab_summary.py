#!/usr/bin/env python3
"""Summarises scripts/device/ab_bench.sh: for each scene and preset, the median GPU time per
frame (frames 16+, debug-view copies left out) of the whole frame and of the GI chain (cache-*
and gi-* passes), for each build and round, and the ratio new / base.

Usage: scripts/ab_summary.py DIR   (DIR holds the unpacked <scene>-<preset>-<new|base>-<round>.json)
"""
import glob
import json
import os
import statistics
import sys
from collections import defaultdict


def per_frame_totals(path):
    with open(path) as f:
        rows = json.load(f)["timings"]
    frame, chain = defaultdict(float), defaultdict(float)
    for row in rows:
        if row["frame"] < 16 or row["pass"].startswith("debug-view:"):
            continue
        frame[row["frame"]] += row["ms"]
        if row["pass"].startswith(("cache-", "gi-")):
            chain[row["frame"]] += row["ms"]
    return statistics.median(frame.values()), statistics.median(chain.values())


def main(directory):
    runs = defaultdict(lambda: defaultdict(list))
    for path in sorted(glob.glob(os.path.join(directory, "*.json"))):
        scene, preset, build, _round = os.path.basename(path)[:-5].rsplit("-", 3)
        runs[(scene, preset)][build].append(per_frame_totals(path))
    print("| scene | preset | frame base (ms) | frame new (ms) | ratio | GI chain base | GI chain new | ratio |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for (scene, preset), builds in sorted(runs.items()):
        base = [statistics.mean(v) for v in zip(*builds["base"])]
        new = [statistics.mean(v) for v in zip(*builds["new"])]
        print(f"| {scene} | {preset} | {base[0]:.3f} | {new[0]:.3f} | {new[0] / base[0]:.3f} | "
              f"{base[1]:.3f} | {new[1]:.3f} | {new[1] / base[1]:.3f} |")


if __name__ == "__main__":
    main(sys.argv[1])
