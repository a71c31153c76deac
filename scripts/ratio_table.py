#!/usr/bin/python3
"""One structure against the others measured in the same run of `voxray bench`: a markdown
table of ratios per scene and ray set (speed against the best Embree baseline, the dense
grid and the brickmap; steps per ray, cycles per ray-step and bytes per voxel beside).

usage: ratio_table.py RESULTS.jsonl --structure naadf [--backend cpu] [--versus svdag] [--readme README.md]

--versus NAME adds a column "NAME ÷ STRUCTURE" per named structure (the NAADF paper's
NAADF-to-SVDAG ratio, say).

With --readme, the table replaces the text between <!-- ratio-table:STRUCTURE:begin -->
and <!-- ratio-table:STRUCTURE:end --> in that file; it is always printed.
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from plot_bench import load, measured, ordered, replace_section  # noqa: E402

EMBREE = ("embree-quads", "embree-boxes")


def ratio_table(header, rows, structure, backend, inverse_of=()):
    m = header["machine"]
    lines = [
        f'`{structure}` on `{backend}` against the others of the same run: `{header["command"]}` at commit '
        f'`{header["git_commit"][:12]}` ({header["started_utc"]}), {m["cpu_model"]}, {m["cores"]} cores, '
        f'{m["clock_hz"] / 1e9:.2f} GHz, {m["simd_width"]}-lane CPU stream. Ratios of median Mrays/s; '
        "every row validated against the dense grid while measuring.",
        "",
        f"| scene | rays | {structure} Mrays/s | best Embree | ÷ best Embree | ÷ dense | ÷ brickmap | "
        + "".join(f"{v} ÷ {structure} | " for v in inverse_of)
        + "steps/ray | cycles/ray-step | bytes/voxel (÷ brickmap) | mismatches |",
        "|---|---|---:|---|---:|---:|---:|" + "---:|" * len(inverse_of) + "---:|---:|---:|---:|",
    ]
    cell = {(r["scene"], r["ray_set"], r["structure"], r["backend"]): r for r in rows}
    for scene in ordered(r["scene"] for r in rows):
        for ray_set in ordered(r["ray_set"] for r in rows):
            mine = cell.get((scene, ray_set, structure, backend))
            if mine is None:
                continue
            speed = mine["mrays_median"]
            embree = [cell[k] for k in ((scene, ray_set, e, "cpu") for e in EMBREE) if k in cell]
            best = max(embree, key=lambda r: r["mrays_median"], default=None)

            def versus(name):
                other = cell.get((scene, ray_set, name, backend))
                return f'{speed / other["mrays_median"]:.2f}×' if other else "-"

            def inverse(name):
                other = cell.get((scene, ray_set, name, backend))
                return f'{other["mrays_median"] / speed:.2f}×' if other else "-"

            brick = cell.get((scene, ray_set, "brickmap", backend))
            memory = f'{mine["bytes_per_voxel"]:.2f}'
            if brick:
                memory += f' ({mine["bytes_per_voxel"] / brick["bytes_per_voxel"]:.2f}×)'
            cycles = mine.get("cycles_per_ray_step")
            lines.append(
                f'| {scene} | {ray_set} | {speed:.2f} | '
                + (f'{best["structure"]} {best["mrays_median"]:.2f} | {speed / best["mrays_median"]:.2f}× | ' if best else "- | - | ")
                + f'{versus("dense")} | {versus("brickmap")} | '
                + "".join(f"{inverse(v)} | " for v in inverse_of)
                + f'{mine["steps_per_ray"]:.2f} | '
                + f'{"-" if cycles is None else f"{cycles:.0f}"} | {memory} | {mine["mismatches"]} |'
            )
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results")
    parser.add_argument("--structure", required=True)
    parser.add_argument("--backend", default="cpu")
    parser.add_argument("--versus", default="", help="comma-separated structures for NAME ÷ STRUCTURE columns")
    parser.add_argument("--readme", help="markdown file whose ratio-table:STRUCTURE section is replaced")
    args = parser.parse_args()
    header, rows = load(args.results)
    versus = [v for v in args.versus.split(",") if v]
    text = ratio_table(header, measured(rows), args.structure, args.backend, versus)
    print(text)
    if args.readme:
        begin, end = f"<!-- ratio-table:{args.structure}:begin -->", f"<!-- ratio-table:{args.structure}:end -->"
        replace_section(pathlib.Path(args.readme), begin, end, text)


if __name__ == "__main__":
    main()
