#!/usr/bin/python3
"""Primary rays in 8x8 Z-order tiles against rows: the same `voxray bench` matrix run once
with `--pixel-order rows` and once with tiles (the default), a markdown table of Mrays/s per
scene, ray set and structure, and each structure's ratio to the best Embree baseline of its
own run (so the machine's drift between the two runs cancels).

usage: order_table.py ROWS.jsonl TILES.jsonl --structures naadf,svdag [--readme docs/benchmarks.md]

With --readme, the table replaces the text between <!-- order-table:begin --> and
<!-- order-table:end --> in that file; it is always printed.
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from plot_bench import load, measured, ordered, replace_section  # noqa: E402

EMBREE = ("embree-quads", "embree-boxes")


def rates(rows):
    """(scene, ray set, structure) -> median Mrays/s of the CPU backend."""
    return {(r["scene"], r["ray_set"], r["structure"]): r["mrays_median"] for r in measured(rows) if r["backend"] == "cpu"}


def best_embree(rate, scene, ray_set):
    found = [rate[(scene, ray_set, e)] for e in EMBREE if (scene, ray_set, e) in rate]
    return max(found) if found else None


def order_table(runs, structures):
    (rows_header, rows), (tiles_header, tiles) = runs
    for found, want in ((rows, "rows"), (tiles, "tiles")):
        orders = {r.get("pixel_order") for r in found if r["ray_set"] == "primary"}
        if orders != {want}:
            sys.exit(f"expected primary rays in {want} order, the file has {sorted(map(str, orders))}")
    by_rows, by_tiles = rates(rows), rates(tiles)
    lines = [
        f'Rows: `{rows_header["command"]}` at commit `{rows_header["git_commit"][:12]}` ({rows_header["started_utc"]}); '
        f'tiles: `{tiles_header["command"]}` at commit `{tiles_header["git_commit"][:12]}` ({tiles_header["started_utc"]}). '
        "Median Mrays/s on `cpu`; in brackets, the ratio to the best Embree baseline of the same run.",
        "",
        "| scene | rays | structure | rows Mrays/s (÷ Embree) | tiles Mrays/s (÷ Embree) | tiles ÷ rows | ratio to Embree, tiles ÷ rows |",
        "|---|---|---|---:|---:|---:|---:|",
    ]
    for scene in ordered(r["scene"] for r in tiles):
        for ray_set in ordered(r["ray_set"] for r in tiles if r["scene"] == scene):
            for s in structures:
                key = (scene, ray_set, s)
                if key not in by_rows or key not in by_tiles:
                    continue
                e_rows, e_tiles = best_embree(by_rows, scene, ray_set), best_embree(by_tiles, scene, ray_set)
                a, b = by_rows[key], by_tiles[key]
                cell = lambda rate, e: f"{rate:.2f} ({rate / e:.2f}×)" if e and s not in EMBREE else f"{rate:.2f}"
                relative = f"{(b / e_tiles) / (a / e_rows):.2f}×" if e_rows and e_tiles and s not in EMBREE else ""
                lines.append(f"| {scene} | {ray_set} | {s} | {cell(a, e_rows)} | {cell(b, e_tiles)} | {b / a:.2f}× | {relative} |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("rows", type=pathlib.Path)
    parser.add_argument("tiles", type=pathlib.Path)
    parser.add_argument("--structures", required=True, help="comma-separated, in the table's order")
    parser.add_argument("--readme", type=pathlib.Path)
    args = parser.parse_args()
    text = order_table((load(args.rows), load(args.tiles)), args.structures.split(","))
    print(text, end="")
    if args.readme:
        replace_section(args.readme, "<!-- order-table:begin -->", "<!-- order-table:end -->", text)


if __name__ == "__main__":
    main()
