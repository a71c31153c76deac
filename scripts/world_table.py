#!/usr/bin/env python3
"""The open-world table: for each StreamingFactor, the resident memory along the camera
path as a share of the whole world on disk (peak and mean, from `voxray world-fly --json`),
and the SSIM of its frames against the all-LOD-0 frames of the same path (scikit-image's
structural_similarity, on the luminance of the PNGs).

  world_table.py FLY.jsonl --frames DIR [--out table.md]

FLY.jsonl holds the world-fly lines of one world; DIR holds one folder of PNG frames per
run: lod0/ and factor_<F>/ (as scripts/world_study.sh writes them)."""
import argparse
import collections
import json
import os
import sys

import numpy as np
from matplotlib import image as mpimg
from skimage.metrics import structural_similarity


def luminance(path):
    rgb = mpimg.imread(path)[..., :3].astype(np.float64)
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def mean_ssim(reference_dir, frames_dir):
    scores = []
    for name in sorted(os.listdir(reference_dir)):
        if name.endswith(".png") and os.path.exists(os.path.join(frames_dir, name)):
            scores.append(structural_similarity(luminance(os.path.join(reference_dir, name)),
                                                luminance(os.path.join(frames_dir, name)), data_range=1.0))
    if not scores:
        sys.exit(f"no frames of {reference_dir} in {frames_dir}")
    return float(np.mean(scores)), float(np.min(scores)), len(scores)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fly")
    p.add_argument("--frames", required=True)
    p.add_argument("--out")
    a = p.parse_args()
    runs = collections.defaultdict(list)
    with open(a.fly) as f:
        for line in f:
            row = json.loads(line)
            runs["lod0" if row["lod0"] else f"{row['factor']:.1f}"].append(row)
    if "lod0" not in runs:
        sys.exit("no --lod0 run in " + a.fly)
    lines = ["| StreamingFactor | resident, peak | resident, mean | resident chunks, peak | trace ms, median | SSIM vs LOD 0, mean (min) |",
             "|---|---|---|---|---|---|"]
    for key in sorted(runs, key=lambda k: (k != "lod0", float(k) if k != "lod0" else 0)):
        rows = runs[key]
        share = [r["resident_bytes"] / r["disk_bytes"] for r in rows]
        chunks = max(r["resident_chunks"] for r in rows)
        trace = float(np.median([r["trace_ms"] for r in rows]))
        if key == "lod0":
            ssim = "1 (reference)"
            label = "all LOD 0"
        else:
            m, lo, n = mean_ssim(os.path.join(a.frames, "lod0"), os.path.join(a.frames, "factor_" + key))
            ssim = f"{m:.3f} ({lo:.3f}), {n} frames"
            label = key
        lines.append(f"| {label} | {100 * max(share):.1f} % | {100 * np.mean(share):.1f} % | {chunks} | {trace:.0f} | {ssim} |")
    text = "\n".join(lines) + "\n"
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    print(text, end="")


if __name__ == "__main__":
    main()
