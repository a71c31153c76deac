#!/usr/bin/python3
"""Turns a `voxray bench --out` results file (JSON lines) into figures and a markdown table.

usage: plot_bench.py RESULTS.jsonl --out DIR [--readme README.md]

Writes DIR/mrays.png (Mrays/s per structure x backend, one panel per scene and ray set),
DIR/speed_vs_memory.png (Mrays/s against bytes per voxel), DIR/steps.png (traversal steps
per ray) and DIR/table.md. With --readme, the table replaces the text between the
<!-- bench-table:begin --> and <!-- bench-table:end --> markers of that file.
"""
import argparse
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

BEGIN, END = "<!-- bench-table:begin -->", "<!-- bench-table:end -->"


def load(path):
    header, rows = None, []
    for number, line in enumerate(open(path), 1):
        if not line.strip():
            continue
        record = json.loads(line)
        if record.get("type") == "header":
            header = record
        elif record.get("type") == "row":
            rows.append(record)
        else:
            sys.exit(f"{path}:{number}: neither a header nor a row")
    if header is None:
        sys.exit(f"{path}: no header line (is it a voxray bench results file?)")
    return header, rows


def ordered(values):
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def measured(rows):
    return [r for r in rows if "error" not in r]


def plot_mrays(rows, out):
    scenes, sets = ordered(r["scene"] for r in rows), ordered(r["ray_set"] for r in rows)
    fig, axes = plt.subplots(len(scenes), len(sets), figsize=(4.2 * len(sets), 3.2 * len(scenes)), squeeze=False)
    for i, scene in enumerate(scenes):
        for j, ray_set in enumerate(sets):
            ax = axes[i][j]
            cell = [r for r in rows if r["scene"] == scene and r["ray_set"] == ray_set]
            labels = [f'{r["structure"]}\n{r["backend"]}' for r in cell]
            medians = [r["mrays_median"] for r in cell]
            low = [r["mrays_median"] - r["mrays_min"] for r in cell]
            high = [r["mrays_max"] - r["mrays_median"] for r in cell]
            colours = ["tab:red" if r["mismatches"] else "tab:blue" for r in cell]
            ax.bar(range(len(cell)), medians, yerr=[low, high], color=colours, capsize=2)
            ax.set_xticks(range(len(cell)), labels, rotation=90, fontsize=6)
            ax.set_title(f"{scene}: {ray_set}", fontsize=9)
            ax.set_ylabel("Mrays/s (median, min-max)", fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def plot_memory(rows, out):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    best = {}
    for r in rows:  # the fastest backend of each structure on each scene, primary rays
        if r["ray_set"] != "primary" or r.get("bytes_per_voxel") is None:
            continue
        key = (r["scene"], r["structure"])
        if key not in best or r["mrays_median"] > best[key]["mrays_median"]:
            best[key] = r
    for structure in ordered(k[1] for k in best):
        points = [r for k, r in best.items() if k[1] == structure]
        ax.scatter([p["bytes_per_voxel"] for p in points], [p["mrays_median"] for p in points], label=structure)
        for p in points:
            ax.annotate(p["scene"], (p["bytes_per_voxel"], p["mrays_median"]), fontsize=6)
    ax.set_xscale("log")
    ax.set_xlabel("bytes per voxel (log)")
    ax.set_ylabel("Mrays/s, primary rays, fastest backend")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def plot_steps(rows, out):
    cells = {}
    for r in rows:  # steps do not depend on the backend: one bar per structure x scene x set
        if r["steps_per_ray"]:
            cells.setdefault((r["scene"], r["ray_set"]), {})[r["structure"]] = r["steps_per_ray"]
    structures = ordered(s for c in cells.values() for s in c)
    keys = list(cells)
    fig, ax = plt.subplots(figsize=(max(6, 0.9 * len(keys)), 4))
    width = 0.8 / max(1, len(structures))
    for k, s in enumerate(structures):
        ax.bar([i + k * width for i in range(len(keys))], [cells[key].get(s, 0) for key in keys], width, label=s)
    ax.set_xticks([i + 0.4 - width / 2 for i in range(len(keys))], [f"{a}\n{b}" for a, b in keys], fontsize=6, rotation=45)
    ax.set_ylabel("traversal steps per ray")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def table(header, rows, errors):
    """One line per scene x structure x backend, one Mrays/s column per ray set."""
    m = header["machine"]
    sets = ordered(r["ray_set"] for r in rows)
    lines = [
        f'Results of `{header["command"]}` at commit `{header["git_commit"][:12]}` ({header["started_utc"]}), '
        f'{m["cpu_model"]}, {m["cores"]} cores, {m["clock_hz"] / 1e9:.2f} GHz, {m["simd_width"]}-lane CPU stream, '
        f'{header["compiler"]}, {header["build_type"]}. Mrays/s: median (min-max) of the timed runs; steps per ray '
        f'and cycles per ray-step for {sets[0]} rays; mismatches against the dense grid on the CPU over all ray '
        "sets, counted while measuring.",
        "",
        "| scene | voxels | structure | backend | " + " | ".join(f"{s} Mrays/s" for s in sets)
        + " | steps/ray | cycles/step | bytes/voxel | build s | mismatches |",
        "|---|---:|---|---|" + "---:|" * len(sets) + "---:|---:|---:|---:|---:|",
    ]
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["structure"], r["backend"]), {})[r["ray_set"]] = r
    for (scene, structure, backend), by_set in groups.items():
        first = next(iter(by_set.values()))
        lead = by_set.get(sets[0], first)
        speeds = [
            f'{by_set[s]["mrays_median"]:.2f} ({by_set[s]["mrays_min"]:.2f}-{by_set[s]["mrays_max"]:.2f})' if s in by_set else "-"
            for s in sets
        ]
        cycles = lead.get("cycles_per_ray_step")
        per_voxel = "-" if lead["bytes_per_voxel"] is None else f'{lead["bytes_per_voxel"]:.1f}'
        mism = str(sum(r["mismatches"] for r in by_set.values()))
        labelled = sum(r.get("limitation_rays", 0) for r in by_set.values())
        if labelled:
            mism += f' (+{labelled} labelled: {first["limitation"]})'
        lines.append(
            f'| {scene} | {first["voxels"]:,} | {structure} | {backend} | ' + " | ".join(speeds)
            + f' | {lead["steps_per_ray"]:.1f} | {"-" if cycles is None else f"{cycles:.0f}"} | {per_voxel} | '
            f'{lead["build_seconds"]:.2f} | {mism} |'
        )
    for r in errors:
        lines.append(f'\nError in {r["scene"]} / {r["structure"]} / {r["backend"]} / {r["ray_set"]}: {r["error"]}')
    return "\n".join(lines) + "\n"


def replace_section(path, begin, end, text):
    """Replaces what lies between the marker lines `begin` and `end` of file `path` with `text`."""
    content = path.read_text()
    if begin not in content or end not in content:
        sys.exit(f"{path}: no {begin} ... {end} markers")
    head, rest = content.split(begin, 1)
    path.write_text(head + begin + "\n" + text + end + rest.split(end, 1)[1])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results")
    parser.add_argument("--out", required=True, help="folder for the PNGs and table.md")
    parser.add_argument("--readme", help="markdown file whose bench-table section is replaced")
    args = parser.parse_args()
    header, rows = load(args.results)
    ok = measured(rows)
    if not ok:
        sys.exit(f"{args.results}: no measured row")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plot_mrays(ok, out / "mrays.png")
    plot_memory(ok, out / "speed_vs_memory.png")
    plot_steps(ok, out / "steps.png")
    text = table(header, ok, [r for r in rows if "error" in r])
    (out / "table.md").write_text(text)
    if args.readme:
        replace_section(pathlib.Path(args.readme), BEGIN, END, text)
    print(f"wrote {out}/mrays.png, speed_vs_memory.png, steps.png, table.md" + (f", {args.readme}" if args.readme else ""))


if __name__ == "__main__":
    main()
