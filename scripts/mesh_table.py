#!/usr/bin/env python3
"""The chunk mesher's table, plot and level-of-detail pictures from a mesh-bench results file.

mesh_table.py RESULTS --out FOLDER [--doc DOC.md] [--plies FOLDER]
  FOLDER/mesh_table.md          the table (and, with --doc, between the markers
                                <!-- mesh-table:begin --> and <!-- mesh-table:end --> of DOC.md)
  FOLDER/mesh_levels.png        quads drawn and overdraw per level of detail, per scene
  FOLDER/mesh_lod_levels.png    with --plies: terrain64_<level>.ply drawn for each level
"""
import argparse
import json
import pathlib
import struct

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from mpl_toolkits.mplot3d.art3d import Poly3DCollection


def load(path):
    lines = [json.loads(l) for l in open(path) if l.strip()]
    return lines[0], [l for l in lines[1:] if l.get("type") == "mesh"]


def table(header, rows):
    out = ["| scene | chunks | µs min / median / p95 | faces → quads | bytes/quad | ns/face | POP ns/quad | "
           "AO µs | mask µs | overdraw max (before pass) | chunks/s 1 → %d threads | meshopt simplify ms (sloppy) at level 2 |"
           % rows[0]["threads"],
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        peer = next(p for p in r["meshoptimizer"] if p["level"] == 2)
        out.append("| %s | %d | %.1f / %.1f / %.1f | %d → %d (%.2f) | %d | %.2f | %.2f | %.0f | %.2f | %.3f (%.3f) | %.0f → %.0f (%.2f×) | %.2f (%.2f) |" % (
            r["scene"], r["chunks"], r["us_min"], r["us_median"], r["us_p95"], r["faces"], r["quads"], r["faces_per_quad"],
            r["bytes_per_quad"], r["ns_per_face"], r["pop_ns_per_quad"], r["us_median_ao"], r["mask_us"],
            r["overdraw_max"], r["overdraw_max_before_squashed"], r["chunks_per_s_1"], r["chunks_per_s"], r["thread_scaling"],
            peer["ms"], peer["sloppy_ms"]))
    if all("pop_image_rmse" in p for r in rows for p in r["meshoptimizer"]):
        out += ["", "Image error against the level-0 picture of the same chunks (RMS of 8-bit colour differences over "
                "the covered pixels, one grey, 512 × 288, the Vulkan raster path): POP level / meshopt simplify / "
                "simplifySloppy at the level's triangle count:", "",
                "| scene | " + " | ".join("level %d" % p["level"] for p in rows[0]["meshoptimizer"]) + " |",
                "|---|" + "---:|" * len(rows[0]["meshoptimizer"])]
        for r in rows:
            out.append("| %s | %s |" % (r["scene"], " | ".join(
                "%.1f / %.1f / %.1f" % (p["pop_image_rmse"], p["image_rmse"], p["sloppy_image_rmse"])
                for p in r["meshoptimizer"])))
    if all(r.get("remesh") for r in rows):
        out += ["", "Remeshing after edits (rounds of one random edit on the structure, then the chunks it can "
                "change read through the structure's `read_box` and meshed again):", "",
                "| scene | structure | read a chunk µs | remesh µs a chunk | chunks an edit | edit µs |",
                "|---|---|---:|---:|---:|---:|"]
        for r in rows:
            for name, f in r["remesh"].items():
                out.append("| %s | %s | %.0f | %.0f | %.1f | %.0f |" % (r["scene"], name, f["read_us_median"],
                           f["remesh_us_per_chunk_median"], f["chunks_per_edit"], f["edit_us_median"]))
    if all(r.get("kernel") for r in rows):
        backends = [k["backend"] for k in rows[0]["kernel"]]
        out += ["", "The mesher kernel (the GPU mesher, `meshing/kernel.h`) on every backend of this machine, up to 8 "
                "chunks at once, meshes read back: ms per chunk, wall time of the median run; ✓ where every word "
                "equals the CPU mesher's (%s):" % "; ".join("%s: %s" % (k["backend"], k["device"])
                                                            for k in rows[0]["kernel"]), "",
                "| scene | chunks | " + " | ".join(backends) + " |",
                "|---|---:|" + "---:|" * len(backends)]
        for r in rows:
            by = {k["backend"]: k for k in r["kernel"]}
            out.append("| %s | %d | %s |" % (r["scene"], r["kernel"][0]["chunks"], " | ".join(
                "%.2f %s" % (by[b]["us_per_chunk"] / 1e3, "✓" if by[b]["equal_to_cpu"] else "✗") for b in backends)))
    machine = header["machine"]
    out.append("")
    out.append("%s, %d cores, %s, commit %s; `%s`. Per chunk: µs of meshing with POP order (mask apart: `mask µs`, "
               "%s path); POP ns/quad: median with POP minus median without, per quad. Table: %d bytes a chunk."
               % (machine["cpu_model"], machine["cores"], header["compiler"], header["git_commit"][:7], header["command"],
                  rows[0]["mask_path"], rows[0]["table_bytes"]))
    return "\n".join(out) + "\n"


def plot_levels(rows, path):
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    for r in rows:
        left.semilogy(range(7), [max(q, 0.5) for q in r["quads_per_level"]], marker="o", label=r["scene"])
        right.plot(range(7), r["overdraw_per_level"], marker="o", linestyle=":", color=left.lines[-1].get_color())
        right.plot(range(7), r["overdraw_per_level_after_squashed"], marker="s", color=left.lines[-1].get_color())
    left.set_xlabel("level of detail"), left.set_ylabel("quads drawn"), left.legend(fontsize=7)
    right.set_xlabel("level of detail"), right.set_ylabel("overdraw (dotted: before the squashed-face pass)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def read_ply(path):
    data = open(path, "rb").read()
    head, body = data.split(b"end_header\n", 1)
    head = head.decode()
    vertices = int(head.split("element vertex ")[1].split()[0])
    corners = [struct.unpack_from("<3f4B", body, 16 * i) for i in range(vertices)]
    quads = []
    for q in range(vertices // 4):
        c = corners[4 * q:4 * q + 4]
        quads.append(([v[:3] for v in c], tuple(x / 255 for x in c[0][3:6])))
    return quads


def plot_lods(folder, path):
    fig = plt.figure(figsize=(14, 2.6))
    for level in range(7):
        ax = fig.add_subplot(1, 7, level + 1, projection="3d")
        quads = read_ply(pathlib.Path(folder) / ("terrain64_%d.ply" % level))
        if quads:
            ax.add_collection3d(Poly3DCollection([q for q, _ in quads], facecolors=[c for _, c in quads],
                                                 edgecolors=(0, 0, 0, 0.25), linewidths=0.1))
        ax.set_xlim(0, 64), ax.set_ylim(0, 64), ax.set_zlim(0, 64)
        ax.view_init(elev=35, azim=-60)
        ax.set_axis_off()
        ax.set_title("level %d: %d quads" % (level, len(quads)), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("results")
    p.add_argument("--out", required=True)
    p.add_argument("--doc")
    p.add_argument("--plies")
    a = p.parse_args()
    header, rows = load(a.results)
    out = pathlib.Path(a.out)
    text = table(header, rows)
    (out / "mesh_table.md").write_text(text)
    plot_levels(rows, out / "mesh_levels.png")
    if a.plies:
        plot_lods(a.plies, out / "mesh_lod_levels.png")
    if a.doc:
        doc = pathlib.Path(a.doc).read_text()
        begin, end = "<!-- mesh-table:begin -->\n", "<!-- mesh-table:end -->"
        doc = doc[:doc.index(begin) + len(begin)] + text + doc[doc.index(end):]
        pathlib.Path(a.doc).write_text(doc)


if __name__ == "__main__":
    main()
