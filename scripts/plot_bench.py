#!/usr/bin/python3
"""Turns a `voxray bench --out` results file (JSON lines) into figures and a markdown table.

usage: plot_bench.py RESULTS.jsonl --out DIR [--readme FILE.md]

Writes DIR/mrays.png (Mrays/s: one panel per scene and ray set, bars grouped by structure
and coloured by backend), DIR/speed_vs_memory.png (Mrays/s against bytes per voxel),
DIR/steps.png (traversal steps per ray) and DIR/table.md. With --readme, the table also
replaces the text between the <!-- bench-table:begin --> and <!-- bench-table:end -->
markers of FILE.md, if it has them.

Paths in the recorded command are written relative to the repository (the machine's
absolute paths never reach the table): see repo_relative().
"""
import argparse
import json
import os
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

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
    if "command" in header:
        header["command"] = repo_relative(header["command"])
    return header, rows


REPO = pathlib.Path(__file__).resolve().parent.parent


def repo_relative(command):
    """The command with every absolute path made relative to the repository it ran in.

    That repository is the one the tool ran from (its path ends in build/voxray), else
    this script's. A path outside the repository and its parent folder (where
    ../shared/data lives) keeps only its file name."""
    words = command.split()
    roots = [REPO]
    if words and words[0].startswith("/") and words[0].endswith("/build/voxray"):
        roots.insert(0, pathlib.PurePosixPath(os.path.normpath(words[0])).parent.parent)

    def relative(word):
        if not word.startswith("/"):
            return word
        path = os.path.normpath(word)
        for root in roots:
            rel = os.path.relpath(path, root)
            if not rel.startswith("../../") and rel != "..":
                return rel
        return os.path.basename(path)

    out = []
    for word in words:
        if word.startswith("--") and "=" in word:
            option, value = word.split("=", 1)
            out.append(f"{option}={relative(value)}")
        else:
            out.append(relative(word))
    return " ".join(out)


def ordered(values):
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def measured(rows):
    return [r for r in rows if "error" not in r]


# One colour per backend, the same in every figure.
BACKEND_COLOURS = {"cpu": "tab:blue", "cpu-scalar": "tab:cyan", "opencl": "tab:orange", "vulkan": "tab:red"}


def backend_colour(backend):
    return BACKEND_COLOURS.get(backend, "tab:gray")


def spans_decades(values):
    """Whether positive values span more than a decade (then a log axis reads better)."""
    positive = [v for v in values if v > 0]
    return len(positive) > 1 and max(positive) / min(positive) > 10


def log_axis(axis):
    """A log y axis labelled at 1, 2 and 5 of every decade, in plain numbers."""
    axis.set_yscale("log")
    axis.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.yaxis.set_minor_formatter(NullFormatter())


def plot_mrays(rows, out):
    """One panel per scene (rows) and ray set (columns); in each, one group of bars per
    structure, one bar per backend, coloured by backend; whiskers span min..max of the runs.
    A bar with mismatches is hatched. Log axis where a panel spans decades."""
    scenes, sets = ordered(r["scene"] for r in rows), ordered(r["ray_set"] for r in rows)
    structures, backends = ordered(r["structure"] for r in rows), ordered(r["backend"] for r in rows)
    width = 0.8 / max(1, len(backends))
    fig, axes = plt.subplots(len(scenes), len(sets), figsize=(5.2 * len(sets), 2.9 * len(scenes)), squeeze=False)
    for i, scene in enumerate(scenes):
        for j, ray_set in enumerate(sets):
            ax = axes[i][j]
            cell = {(r["structure"], r["backend"]): r for r in rows if r["scene"] == scene and r["ray_set"] == ray_set}
            shown = [s for s in structures if any((s, b) in cell for b in backends)]
            for k, backend in enumerate(backends):
                xs, medians, low, high, hatches = [], [], [], [], []
                for g, structure in enumerate(shown):
                    r = cell.get((structure, backend))
                    if r is None:
                        continue
                    xs.append(g - 0.4 + width * (k + 0.5))
                    medians.append(r["mrays_median"])
                    low.append(r["mrays_median"] - r["mrays_min"])
                    high.append(r["mrays_max"] - r["mrays_median"])
                    hatches.append("xx" if r["mismatches"] else "")
                bars = ax.bar(xs, medians, width, yerr=[low, high], color=backend_colour(backend), capsize=1,
                              error_kw={"elinewidth": 0.6}, label=backend)
                for bar, hatch in zip(bars, hatches):
                    bar.set_hatch(hatch)
            if spans_decades(r["mrays_median"] for r in cell.values()):
                log_axis(ax)
            ax.set_xticks(range(len(shown)), shown, rotation=30, ha="right", fontsize=7)
            ax.tick_params(axis="y", labelsize=7)
            ax.set_xlim(-0.6, len(shown) - 0.4)
            ax.grid(axis="y", which="major", alpha=0.3)
            ax.set_title(f"{scene}: {ray_set} rays", fontsize=9)
            if j == 0:
                ax.set_ylabel("Mrays/s", fontsize=8)
    handles = [plt.Rectangle((0, 0), 1, 1, color=backend_colour(b)) for b in backends]
    fig.legend(handles, backends, loc="upper center", ncol=len(backends), fontsize=9,
               title="backend (bar: median of the runs, whisker: min-max; hatched: mismatches)", title_fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.5 / fig.get_figheight()))
    fig.savefig(out, dpi=90)
    plt.close(fig)


def plot_memory(rows, out):
    """Speed against memory: the fastest backend of each structure on each scene, primary
    rays. Colour: structure; marker: scene (two legends, no labels on the points)."""
    fig, ax = plt.subplots(figsize=(8.5, 5))
    best = {}
    for r in rows:
        if r["ray_set"] != "primary" or r.get("bytes_per_voxel") is None:
            continue
        key = (r["scene"], r["structure"])
        if key not in best or r["mrays_median"] > best[key]["mrays_median"]:
            best[key] = r
    structures, scenes = ordered(k[1] for k in best), ordered(k[0] for k in best)
    markers = "osD^vP*Xh<>"
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for a, structure in enumerate(structures):
        for b, scene in enumerate(scenes):
            p = best.get((scene, structure))
            if p is not None:
                ax.scatter(p["bytes_per_voxel"], p["mrays_median"], color=colours[a % len(colours)],
                           marker=markers[b % len(markers)], s=36)
    ax.set_xscale("log")
    if spans_decades(p["mrays_median"] for p in best.values()):
        log_axis(ax)
    ax.set_xlabel("bytes per voxel (log)")
    ax.set_ylabel("Mrays/s, primary rays, fastest backend")
    ax.grid(which="major", alpha=0.3)
    by_structure = [plt.Line2D([], [], color=colours[a % len(colours)], marker="o", linestyle="") for a in range(len(structures))]
    by_scene = [plt.Line2D([], [], color="black", marker=markers[b % len(markers)], linestyle="") for b in range(len(scenes))]
    first = ax.legend(by_structure, structures, title="structure", fontsize=7, title_fontsize=8,
                      loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.add_artist(first)
    ax.legend(by_scene, scenes, title="scene", fontsize=7, title_fontsize=8, loc="lower left", bbox_to_anchor=(1.01, 0.0))
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def plot_steps(rows, out):
    """Traversal steps per ray (the same on every backend): one panel per ray set, one group
    of bars per scene, one bar per structure; a log axis, since they span decades."""
    cells = {}
    for r in rows:
        if r["steps_per_ray"]:
            cells.setdefault(r["ray_set"], {}).setdefault(r["scene"], {})[r["structure"]] = r["steps_per_ray"]
    sets = list(cells)
    scenes = ordered(sc for c in cells.values() for sc in c)
    structures = ordered(s for c in cells.values() for by in c.values() for s in by)
    width = 0.8 / max(1, len(structures))
    fig, axes = plt.subplots(len(sets), 1, figsize=(max(8, 1.9 * len(scenes)), 2.8 * len(sets)), squeeze=False)
    for i, ray_set in enumerate(sets):
        ax = axes[i][0]
        for k, s in enumerate(structures):
            xs = [g - 0.4 + width * (k + 0.5) for g, sc in enumerate(scenes) if s in cells[ray_set].get(sc, {})]
            ys = [cells[ray_set][sc][s] for sc in scenes if s in cells[ray_set].get(sc, {})]
            ax.bar(xs, ys, width, label=s)
        if spans_decades(v for by in cells[ray_set].values() for v in by.values()):
            log_axis(ax)
        ax.set_xticks(range(len(scenes)), scenes, fontsize=8)
        ax.tick_params(axis="y", labelsize=8)
        ax.grid(axis="y", which="major", alpha=0.3)
        ax.set_title(f"{ray_set} rays", fontsize=9)
        ax.set_ylabel("steps per ray", fontsize=8)
    axes[0][0].legend(fontsize=7, ncol=len(structures), loc="lower center", bbox_to_anchor=(0.5, 1.12))
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
    parser.add_argument("--readme", help="markdown file whose bench-table section (if any) is replaced")
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
    replaced = False
    if args.readme:
        readme = pathlib.Path(args.readme)
        if BEGIN in readme.read_text():
            replace_section(readme, BEGIN, END, text)
            replaced = True
        else:  # the table lives in DIR/table.md; the file only links to it
            print(f"{readme}: no {BEGIN} marker, left as it is (the table is {out}/table.md)")
    print(f"wrote {out}/mrays.png, speed_vs_memory.png, steps.png, table.md" + (f", {args.readme}" if replaced else ""))


if __name__ == "__main__":
    main()
