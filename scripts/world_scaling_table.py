#!/usr/bin/env python3
"""Issue 27's tables, from scripts/world_scaling.sh's results in FOLDER (default
docs/bench/world_scaling): the measured builds (builds.jsonl: median of the runs of each
label, speed-up against one process on one thread), and from a large build's chunk-job
times (sponza_*_chunks.tsv) the simulated makespan on N ranks with the static and the
dynamic schedule. Writes FOLDER/../world_scaling.md.

The simulation's assumptions (printed with the table):
  - a rank is one core; a chunk job takes the time it took in the measured build;
  - units are cut as the library cuts them (world/build/shard_plan.hpp): the highest LOD
    with at least min(LOD-0 cells, 8 N) units; a unit holds its chunks of LODs up to it;
  - the schedules see an estimate of each unit's work: here its LOD-0 voxels (the library
    uses the source's own: a mesh's triangles, a model's voxels);
  - static: the units in z-y-x order cut into N runs of equal estimate; dynamic: heaviest
    estimate first, each unit to the rank that is free first (a fetch-and-add on rank 0);
  - every rank first loads the source (the measured build's time outside build_world); the
    LODs above the split are shared out level by level, a barrier each; file-system
    contention and MPI's latency (microseconds, against chunk jobs of milliseconds) are not modelled;
  - 64K^3: Sponza's voxels grow with its surface, 16 times from 16384^3 to 65536^3: modelled
    as 16 copies of the measured chunk jobs side by side (4 x 4 in x and z).
"""
import heapq
import json
import re
import pathlib
import statistics
import sys

folder = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "docs/bench/world_scaling")
lines = []

# --- measured builds -------------------------------------------------------------------
rows = [json.loads(l) for l in (folder / "builds.jsonl").read_text().splitlines() if l.strip()]
by_label = {}
for r in rows:
    by_label.setdefault(r["label"], []).append(r)
lines += ["### Measured here (2 cores; ranks of one build thread each, oversubscribed past 2)", "",
          "| world | processes | threads or schedule | seconds (median) | chunks/s | M voxels/s | speed-up vs 1 process, 1 thread |",
          "|---|---|---|---:|---:|---:|---:|"]
scenes = {}
for label, runs in by_label.items():
    world, what = label.split(": ", 1)
    processes, how = what.split(", ", 1)
    seconds = statistics.median(r["seconds"] for r in runs)
    base = by_label.get(f"{world}: 1 process, 1 thread")
    base_seconds = statistics.median(r["seconds"] for r in base) if base else float("nan")
    cps = statistics.median(r["chunks_per_second"] for r in runs)
    vps = statistics.median(r["voxels_per_second"] for r in runs) / 1e6
    lines.append(f"| {world} | {processes} | {how} | {seconds:.2f} | {cps:,.0f} | {vps:.1f} | {base_seconds / seconds:.2f}x |")
    # The scene and its options, without the per-row ones, and with the data folder as the docs name it.
    setup = re.sub(r" --(threads|mpi-schedule) \S+", "", runs[0]["setup"])
    scenes[world] = re.sub(r"\S*/shared/data/", "../shared/data/", setup)
lines += ["", f"Medians of {min(len(r) for r in by_label.values())} runs. Worlds: "
          + "; ".join(f"{w}: `voxray world-build {s}`" for w, s in scenes.items())
          + "; each row adds its `--threads` (1 for ranks) and `--mpi-schedule`, ranks start with "
          "`mpirun --oversubscribe -np N`. This machine is shared: the same build varies by up to 1.7x between runs.", ""]

# --- the simulation --------------------------------------------------------------------
def load_jobs(path):
    jobs = []
    for i, line in enumerate(path.read_text().splitlines()):
        if i == 0 or not line.strip():
            continue
        lod, x, y, z, seconds, voxels = line.split("\t")
        jobs.append((int(lod), (int(x), int(y), int(z)), float(seconds), int(voxels)))
    return jobs

def tiled(jobs, copies):  # copies x copies of the world side by side in x and z
    top = max(j[0] for j in jobs)
    size = [max(j[1][a] for j in jobs if j[0] == 0) + 1 for a in range(3)]
    span = [((s + (1 << top) - 1) >> top) << top for s in size]  # whole top-LOD cells, so LODs stay aligned
    out = []
    for i in range(copies):
        for k in range(copies):
            for lod, c, s, v in jobs:
                out.append((lod, (c[0] + ((i * span[0]) >> lod), c[1], c[2] + ((k * span[2]) >> lod)), s, v))
    return out

def zyx(c):
    return (c[2], c[1], c[0])

def list_schedule(times, ranks):  # each job in turn to the rank free first; the last to finish
    free = [0.0] * ranks
    heapq.heapify(free)
    for t in times:
        heapq.heappush(free, heapq.heappop(free) + t)
    return max(free)

def makespans(jobs, ranks, setup):
    cells0 = sorted({c for lod, c, s, v in jobs if lod == 0}, key=zyx)
    top = max(j[0] for j in jobs) + 1
    want = min(len(cells0), 8 * ranks)
    split = 0
    for lod in range(top, 0, -1):
        if len({(c[0] >> lod, c[1] >> lod, c[2] >> lod) for c in cells0}) >= want:
            split = lod
            break
    units = {}
    levels = {}  # LOD above the split -> its chunk times
    for lod, c, s, v in jobs:
        if lod > split:
            levels.setdefault(lod, []).append(s)
            continue
        shift = split - lod
        u = units.setdefault((c[0] >> shift, c[1] >> shift, c[2] >> shift), [0.0, 0])
        u[0] += s
        if lod == 0:
            u[1] += v
    order = sorted(units, key=zyx)
    total = sum(max(units[u][1], 1) for u in order)
    static = [0.0] * ranks
    before = 0
    for u in order:
        est = max(units[u][1], 1)
        static[min(ranks - 1, (2 * before + est) * ranks // (2 * total))] += units[u][0]
        before += est
    dynamic = list_schedule([units[u][0] for u in sorted(order, key=lambda u: -max(units[u][1], 1))], ranks)
    # Above the split, level by level with a barrier each: static takes every N-th chunk.
    above_static = sum(max(sum(t[r::ranks]) for r in range(ranks)) for t in levels.values())
    above_dynamic = sum(list_schedule(t, ranks) for t in levels.values())
    return setup + max(static) + above_static, setup + dynamic + above_dynamic, split, len(units)

for tsv in sorted(folder.glob("sponza_*_chunks.tsv")):
    resolution = tsv.name.split("_")[1]
    build = [json.loads(l) for l in (folder / f"sponza_{resolution}_build.jsonl").read_text().splitlines() if l.strip()][-1]
    setup = build["seconds"] - build["build_seconds"]
    jobs = load_jobs(tsv)
    work = sum(j[2] for j in jobs)
    lines += [f"### Simulated: Sponza at {resolution}^3 on N ranks", "",
              f"From `docs/bench/world_scaling/{tsv.name}`: {len(jobs):,} chunk jobs, {work:,.0f} s of work "
              f"(measured build: {build['seconds']:.0f} s in all on 2 threads; {setup:.1f} s of it loading the mesh, "
              "which every rank does).", ""]
    times = sorted(j[2] for j in jobs)
    q = lambda p: times[min(len(times) - 1, int(p * len(times)))]
    lines += [f"Chunk-job times: median {q(0.5) * 1e3:.1f} ms, 90th percentile {q(0.9) * 1e3:.1f} ms, "
              f"99th {q(0.99) * 1e3:.1f} ms, longest {times[-1]:.2f} s.", ""]
    for label, js in ((f"{resolution}^3", jobs), ("65536^3 (projected: 16 copies)", tiled(jobs, 4))):
        one = makespans(js, 1, setup)[1]
        lines += [f"**{label}**", "", "| ranks | split LOD | units | static (s) | dynamic (s) | dynamic speed-up | efficiency |",
                  "|---:|---:|---:|---:|---:|---:|---:|"]
        for n in (1, 2, 4, 8, 64, 512):
            st, dy, split, count = makespans(js, n, setup)
            lines.append(f"| {n} | {split} | {count:,} | {st:,.1f} | {dy:,.1f} | {one / dy:.1f}x | {one / dy / n:.0%} |")
        lines.append("")
assumptions = __doc__.split("The simulation's assumptions (printed with the table):")[1]
lines += ["Assumptions of the simulation:", ""]
lines += ["- " + " ".join(item.split()) for item in assumptions.split("\n  - ") if item.strip()]
lines.append("")

page = pathlib.Path(__file__).resolve().parent.parent / "docs" / "distributed.md"
begin, end = "<!-- world scaling: scripts/world_scaling_table.py -->", "<!-- end of world scaling -->"
head, rest = page.read_text().split(begin, 1)
_, tail = rest.split(end, 1)
page.write_text(f"{head}{begin}\n" + "\n".join(lines) + f"\n{end}{tail}")
print("\n".join(lines))
