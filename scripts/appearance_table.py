#!/usr/bin/env python3
"""The quality table of appearance-bench results, each metric checked with scikit-image.

appearance_table.py RESULTS --strips FOLDER --out TABLE.md [--doc DOC.md [--marker NAME]]
  RESULTS    appearance-bench JSON lines (a header, then one row per method, view and light)
  FOLDER     the strips the bench wrote (reference | averages | sggx | six | faithful | ours [| ours_lod], side by
             side): MSE and
             SSIM are recomputed from them with scikit-image (structural_similarity with
             Wang's parameters: gaussian_weights, sigma 1.5, use_sample_covariance off,
             data_range 255, channel_axis) and must agree with the tool's
  TABLE.md   per scene and resolution: the mean over views and lights of each method's MSE,
             foreground MSE, SSIM, bytes a voxel and precompute time, and the issue's targets
             (ours: MSE at most half of averages', SSIM at least averages' + 0.03; ours_lod, ours
             re-sampled from twice the resolution: MSE at most 1.10 x ours', SSIM at least ours' - 0.01)
  --doc      also put the table between <!-- NAME-table:begin --> and :end --> of DOC.md
  --marker   NAME (default: appearance)
"""
import argparse
import json
import pathlib
import re
import sys

import numpy as np
from skimage.io import imread
from skimage.metrics import mean_squared_error, structural_similarity


METHODS = ["averages", "sggx", "six", "faithful", "ours", "ours_lod"]  # the strips' order


def load(path):
    lines = [json.loads(l) for l in open(path) if l.strip()]
    return lines[0], lines[1:]


def strip_name(row):
    folder = row["scene"].split("/")[0]
    return "%s_%d_view%d_%s.png" % (folder, row["resolution"], row["view"], row["light"])


def metrics(reference, got):
    """MSE (in 0..1) and SSIM of two sRGB pictures, by scikit-image, SSIM with Wang's parameters."""
    mse = mean_squared_error(reference / 255.0, got / 255.0)
    ssim = structural_similarity(reference, got, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                                 data_range=255, channel_axis=-1)
    return mse, ssim


def put_in_doc(path, marker, text):
    """Replaces what lies between <!-- MARKER-table:begin --> and :end --> in the file at `path`."""
    doc = pathlib.Path(path).read_text()
    begin, end = "<!-- %s-table:begin -->" % marker, "<!-- %s-table:end -->" % marker
    marked = re.sub("(%s\n).*?(%s)" % (re.escape(begin), re.escape(end)),
                    lambda m: m.group(1) + text + m.group(2), doc, flags=re.S)
    if marked == doc and begin not in doc:
        sys.exit("%s has no %s-table markers" % (path, marker))
    pathlib.Path(path).write_text(marked)


def check_strips(rows, strips, name_of, order, script):
    """Recomputes each row's MSE and SSIM from its strip (file name_of(row) in `strips`: the
    reference, then one picture a method in `order`); stops if they differ from the tool's."""
    worst_mse = worst_ssim = 0.0
    for r in rows:
        image = imread(strips / name_of(r))[..., :3]
        size = r["size"]
        parts = [image[:, i * size:(i + 1) * size] for i in range(image.shape[1] // size)]
        mse, ssim = metrics(parts[0], parts[1 + order.index(r["method"])])
        worst_mse, worst_ssim = max(worst_mse, abs(mse - r["mse"])), max(worst_ssim, abs(ssim - r["ssim"]))
    if worst_mse > 1e-9 or worst_ssim > 1e-6:
        sys.exit("%s: the tool's metrics differ from scikit-image's: MSE by %.3g, SSIM by %.3g"
                 % (script, worst_mse, worst_ssim))
    return worst_mse, worst_ssim


def check_with_skimage(rows, strips):
    methods = sorted({r["method"] for r in rows}, key=METHODS.index)
    return check_strips(rows, strips, strip_name, methods, "appearance_table.py")


MEAN_KEYS = ("mse", "mse_foreground", "ssim", "bytes_per_voxel", "precompute_us_per_voxel", "walk_fps",
             "visits_per_ray")


def method_means(rows):
    """(scene, resolution) -> method -> each of MEAN_KEYS, the mean over the rows' views and
    lights, and its voxels."""
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["resolution"]), {}).setdefault(r["method"], []).append(r)
    return {group: {m: dict({k: float(np.mean([r[k] for r in rs])) for k in MEAN_KEYS}, voxels=rs[0]["voxels"])
                    for m, rs in methods.items()}
            for group, methods in groups.items()}


def table(header, rows, agreement):
    out = ["| scene | voxels | method | MSE | MSE foreground | SSIM | bytes a voxel "
           "| precompute µs a voxel (%d threads) "
           "| walk fps (N² pixels × 4 rays at N³, %d threads) | visits a ray | targets |"
           % (rows[0]["precompute_threads"], rows[0]["walk_threads"]),
           "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    missed = 0
    for (scene, res), mean in sorted(method_means(rows).items(), key=lambda g: (g[0][1], g[0][0])):
        for m in METHODS:
            if m not in mean:
                continue
            verdict = ""
            if m == "ours" and "averages" in mean:
                a, o = mean["averages"], mean["ours"]
                mse_ok, ssim_ok = o["mse"] <= 0.5 * a["mse"], o["ssim"] >= a["ssim"] + 0.03
                missed += (not mse_ok) + (not ssim_ok)
                verdict = "MSE ×%.2f %s; SSIM %+.3f %s" % (o["mse"] / a["mse"], "met" if mse_ok else "**missed**",
                                                          o["ssim"] - a["ssim"], "met" if ssim_ok else "**missed**")
            if m == "ours_lod" and "ours" in mean:
                o, l = mean["ours"], mean["ours_lod"]
                mse_ok, ssim_ok = l["mse"] <= 1.10 * o["mse"], l["ssim"] >= o["ssim"] - 0.01
                missed += (not mse_ok) + (not ssim_ok)
                verdict = "vs ours: MSE ×%.2f %s; SSIM %+.4f %s" % (
                    l["mse"] / o["mse"], "met" if mse_ok else "**missed**", l["ssim"] - o["ssim"],
                    "met" if ssim_ok else "**missed**")
            v = mean[m]
            out.append("| %s at %d³ | %d | %s | %.5f | %.5f | %.4f | %.1f | %.1f | %.2f | %.2f | %s |" % (
                scene, res, v["voxels"], m, v["mse"], v["mse_foreground"], v["ssim"], v["bytes_per_voxel"],
                v["precompute_us_per_voxel"], v["walk_fps"], v["visits_per_ray"], verdict))
    shadows = ("cast shadows in the reference, precomputed shadows (one ray a voxel) in every method but six "
               "directions (lit when made, unshadowed)" if any(r.get("shadows") for r in rows) else "no shadows")
    out += ["", "Means over %d views × 2 lights (front, behind); reference: Embree on the triangles at %d samples a "
            "pixel, the same shading, %s. Targets: ours against averages; ours_lod (ours at N re-sampled "
            "through the walk from ours at 2N, its precompute time the re-sampling's alone) against ours. "
            "%d target cells missed. Every MSE and SSIM was recomputed from the "
            "strips with scikit-image (largest differences: MSE %.1g, SSIM %.1g). Machine: %s; commit %s."
            % (len({r["view"] for r in rows}), rows[0]["reference_spp"], shadows, missed, agreement[0], agreement[1],
               header.get("machine", {}).get("cpu_model", "?"), header.get("git_commit", "?")[:10])]
    return "\n".join(out) + "\n"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("results")
    p.add_argument("--strips", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--doc")
    p.add_argument("--marker", default="appearance")
    a = p.parse_args()
    header, rows = load(a.results)
    text = table(header, rows, check_with_skimage(rows, pathlib.Path(a.strips)))
    pathlib.Path(a.out).write_text(text)
    if a.doc:
        put_in_doc(a.doc, a.marker, text)
    print(text)


if __name__ == "__main__":
    main()
