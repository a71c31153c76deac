#!/usr/bin/env python3
"""The frame-time table of the GPU-driven passes: for each backend, the median over the
frames of a camera path of each pass's milliseconds (from `voxray world-fly --passes
--json`), with the chunks in view, the tile-chunk pairs marched, and the trace time of
the same path traced ray by ray (world-fly without --passes, in the same file).

  world_passes_table.py PASSES.jsonl [--skip 1] [--out table.md]

The first --skip frames of each backend are left out: the first frame compiles pipelines
and has no previous Hi-Z to cull with."""
import argparse
import collections
import json
import statistics

# Columns: the passes each sums (their names in frame_stats::pass_names).
GROUPS = [
    ("select (chunks, tiles, again)", ["select chunks", "select tiles", "select again"]),
    ("march (both)", ["march", "march again"]),
    ("Hi-Z (both)", ["build hi-z", "build hi-z again"]),
    ("clear + resolve", ["clear", "resolve"]),
]


def passes_table(path, skip=1):
    """The table's markdown, from a world-fly --json file."""
    runs = collections.defaultdict(list)
    traced = collections.defaultdict(list)  # the same path traced ray by ray: trace ms per frame
    with open(path) as f:
        for line in f:
            row = json.loads(line)
            if "passes" in row:
                runs[(row["backend"], row["width"], row["height"])].append(row)
            else:
                traced[row["backend"]].append(row)
    lines = ["| backend | screen | frames | " + " | ".join(g for g, _ in GROUPS) +
             " | frame ms | chunks in view | tile-chunk pairs | ray by ray: trace ms (primary + shadow) |",
             "|---|---|---:|" + "---:|" * (len(GROUPS) + 4)]
    def later(rows):
        return sorted(rows, key=lambda r: r["frame"])[skip:] or rows
    for (backend, w, h), rows in runs.items():
        rows = later(rows)
        med = lambda f: statistics.median(f(r) for r in rows)
        cells = [f"{med(lambda r: sum(r['passes'][n] for n in names)):.1f}" for _, names in GROUPS]
        total = med(lambda r: sum(r["passes"].values()))
        trace = later(traced[backend])
        trace_ms = f"{statistics.median(r['trace_ms'] for r in trace):.1f}" if trace else "–"
        lines.append(f"| {backend} | {w}×{h} | {len(rows)} | " + " | ".join(cells) +
                     f" | {total:.1f} | {med(lambda r: r['visible_chunks']):.0f} |"
                     f" {med(lambda r: r['pairs'] + r['pairs_again']):.0f} | {trace_ms} |")
    return "\n".join(lines) + "\n"


def emit(text, out):
    """Prints a generated table, and writes it to `out` when one is named."""
    print(text, end="")
    if out:
        with open(out, "w") as f:
            f.write(text)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("passes")
    p.add_argument("--skip", type=int, default=1)
    p.add_argument("--out")
    a = p.parse_args()
    emit(passes_table(a.passes, a.skip), a.out)


if __name__ == "__main__":
    main()
