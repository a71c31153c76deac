#!/usr/bin/python3
"""Memory and build figures of one structure against the others built in the same run of
`voxray bench`: per scene, the structure's geometry and attribute bytes (from its row's
"figures", where it reports them), its whole size against the brickmap, NAADF and the dense
grid, the merging ratio (octree nodes / DAG nodes) and the build rate in input voxels/s.

usage: memory_table.py RESULTS.jsonl --structure svdag [--blocks svdag-colours] [--readme README.md]

--blocks NAME adds the attribute bytes and the largest colour error of structure NAME
(the same DAG with Aokana's colour blocks).

With --readme, the table replaces the text between <!-- memory-table:STRUCTURE:begin -->
and <!-- memory-table:STRUCTURE:end --> in that file; it is always printed.
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from plot_bench import load, measured, ordered, replace_section  # noqa: E402


def mib(n):
    return f"{n / 2**20:.2f}"


def memory_table(header, rows, structure, blocks=None):
    lines = [
        f'`{structure}` against the structures built in the same run: `{header["command"]}` at commit '
        f'`{header["git_commit"][:12]}` ({header["started_utc"]}). Bytes of the blob each structure '
        "hands the backends; build times are one build on the tool's threads.",
        "",
        "| scene | voxels | geometry MiB (B/voxel) | attributes MiB | "
        + (f"{blocks} attributes MiB (max error) | " if blocks else "")
        + "÷ brickmap (geometry) | ÷ naadf (whole) | ÷ dense (whole) | octree ÷ DAG nodes | build M voxels/s |",
        "|---|---:|---:|---:|" + ("---:|" if blocks else "") + "---:|---:|---:|---:|---:|",
    ]
    # Sizes do not depend on the ray set or backend: the first row of each pair will do.
    first = {}
    for r in rows:
        first.setdefault((r["scene"], r["structure"]), r)
    for scene in ordered(r["scene"] for r in rows):
        mine = first.get((scene, structure))
        if mine is None:
            continue
        figures = mine.get("figures") or {}
        voxels = mine["voxels"]
        geometry = figures.get("geometry_bytes", mine["bytes"])
        attributes = figures.get("attribute_bytes", 0)

        def size_ratio(other, mine_bytes):
            o = first.get((scene, other))
            return f'{mine_bytes / o["bytes"]:.3f}×' if o else "-"

        rate = voxels / mine["build_seconds"] / 1e6 if mine["build_seconds"] > 0 else float("nan")
        dedup = figures.get("dedup_ratio")
        block_cell = ""
        if blocks:
            b = first.get((scene, blocks))
            bf = (b or {}).get("figures") or {}
            block_cell = (f'{mib(bf["attribute_bytes"])} ({bf.get("colour_error_max", 0):.3f}) | '
                          if "attribute_bytes" in bf else "- | ")
        lines.append(
            f"| {scene} | {voxels} | {mib(geometry)} ({geometry / voxels:.3f}) | {mib(attributes)} | {block_cell}"
            f'{size_ratio("brickmap", geometry)} | {size_ratio("naadf", mine["bytes"])} | '
            f'{size_ratio("dense", mine["bytes"])} | {"-" if dedup is None else f"{dedup:.2f}"} | {rate:.1f} |'
        )
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results")
    parser.add_argument("--structure", required=True)
    parser.add_argument("--blocks", help="the colour-block variant of the structure, for its attribute bytes")
    parser.add_argument("--readme", help="markdown file whose memory-table:STRUCTURE section is replaced")
    args = parser.parse_args()
    header, rows = load(args.results)
    text = memory_table(header, measured(rows), args.structure, args.blocks)
    print(text)
    if args.readme:
        begin, end = f"<!-- memory-table:{args.structure}:begin -->", f"<!-- memory-table:{args.structure}:end -->"
        replace_section(pathlib.Path(args.readme), begin, end, text)


if __name__ == "__main__":
    main()
