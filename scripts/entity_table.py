#!/usr/bin/env python3
"""The entity table of docs/entities.md from `voxray bench SCENE.json` results
(scripts/entity_bench.sh): per instance count, world kind, backend and ray set, the rates
with no scene, with the instances off the rays' paths and in view, the overhead of entities
off the paths against the world alone, Embree's instancing peer on the same rays, and the
per-frame update with every instance moving; candidates found by the BVH (the default).
Then the BVH against the chunk lists (the other way to find candidates) on the same rays,
and, where the results hold scenes whose models have no distance fields (scene files named
*_none.json), model walks by brick fields against walks voxel by voxel.

    entity_table.py docs/bench/entities/herd_*.jsonl --out docs/bench/entities/table.md
"""
import argparse
import json


def rows_of(path):
    with open(path) as f:
        lines = [json.loads(line) for line in f if line.strip()]
    rows = [r for r in lines if r.get("type") in ("row", "update")]
    for r in rows:  # results from before the chunk lists: the BVH; from before model fields: none
        r.setdefault("candidates", "-" if r.get("placement") == "none" else "bvh")
        r.setdefault("model_fields", "none")
    return rows


def fields_table(rows):
    """Model walks by brick distance fields against voxel by voxel: in-view rates and steps."""
    out = ["", "Entity models with brick distance fields against walks voxel by voxel (in view; the scenes "
           "alternate in one run; ratio > 1: the fields are faster):", "",
           "| scene | world | backend | candidates | rays | voxel by voxel | fields | ratio | steps/ray voxel by voxel "
           "| fields |", "|---|---|---|---|---|---:|---:|---:|---:|---:|"]
    groups = {}
    for r in rows:
        if (r["type"] == "row" and r["placement"] == "in-view" and r["model_fields"] in ("bricks", "none")
                and r["candidates"] != "embree"):
            scene = r["scene"].rsplit("/", 1)[-1].replace("_none.json", ".json")
            key = (scene, r["world"], r["backend"], r["candidates"], r["ray_set"])
            groups.setdefault(key, {}).setdefault(r["model_fields"], []).append(r)
    found = False
    for key in sorted(groups):
        by = groups[key]
        if "bricks" not in by or "none" not in by:
            continue
        found = True
        rate = {k: sorted(x["mrays_median"] for x in v)[len(v) // 2] for k, v in by.items()}
        out.append(f"| {' | '.join(key)} | {rate['none']:.2f} | {rate['bricks']:.2f} | {rate['bricks'] / rate['none']:.2f}x "
                   f"| {by['none'][0]['steps_per_ray']:.1f} | {by['bricks'][0]['steps_per_ray']:.1f} |")
    return out if found else []


def candidates_table(rows, counts):
    """The BVH against the chunk lists: rates off the paths and in view, steps in view."""
    out = ["", "Finding candidate instances: the BVH against the chunk lists (same rays, same run; ratio > 1: the "
           "chunk lists are faster):", "",
           "| instances | world | backend | rays | off paths BVH | chunk lists | ratio | in view BVH | chunk lists "
           "| ratio | steps/ray BVH | chunk lists |",
           "|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    found = False
    for n in counts:
        scene_rows = [r for r in rows if r["type"] == "row" and r["entities"] == n and r["placement"] != "none"
                      and not r["scene"].endswith("_none.json")]
        keys = sorted({(r["world"], r["backend"], r["ray_set"]) for r in scene_rows if r["candidates"] == "chunk-lists"})
        for world, backend, ray_set in keys:
            by = {(r["candidates"], r["placement"]): r for r in scene_rows
                  if (r["world"], r["backend"], r["ray_set"]) == (world, backend, ray_set)}
            need = [(c, p) for c in ("bvh", "chunk-lists") for p in ("off-paths", "in-view")]
            if not all(k in by for k in need):
                continue
            found = True
            rate = {k: by[k]["mrays_median"] for k in need}
            out.append(f"| {n:,} | {world} | {backend} | {ray_set} "
                       f"| {rate['bvh', 'off-paths']:.2f} | {rate['chunk-lists', 'off-paths']:.2f} "
                       f"| {rate['chunk-lists', 'off-paths'] / rate['bvh', 'off-paths']:.2f}x "
                       f"| {rate['bvh', 'in-view']:.2f} | {rate['chunk-lists', 'in-view']:.2f} "
                       f"| {rate['chunk-lists', 'in-view'] / rate['bvh', 'in-view']:.2f}x "
                       f"| {by['bvh', 'in-view']['steps_per_ray']:.1f} | {by['chunk-lists', 'in-view']['steps_per_ray']:.1f} |")
    return out if found else []


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("results", nargs="+")
    p.add_argument("--out", required=True)
    a = p.parse_args()

    rows = []
    for path in a.results:
        rows += rows_of(path)
    rows.sort(key=lambda r: r["entities"] if r.get("placement") != "none" else 0)
    counts = sorted({r["entities"] for r in rows if r["type"] == "update"})

    out = ["| instances | world | backend | rays | Mrays/s alone | off paths | overhead | in view | steps/ray in view "
           "| cycles/step | Embree instances in view | vs Embree | mismatches |",
           "|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for n in counts:
        group = [r for r in rows if r["type"] == "row" and (r["entities"] == n or r.get("placement") == "none")
                 and r.get("scene", "").endswith(f"_{n}.json") and r["candidates"] in ("-", "bvh", "embree")]
        embree = {r["ray_set"]: r for r in group if r["structure"] == "embree-instances" and r["placement"] == "in-view"}
        keys = sorted({(r["world"], r["backend"], r["ray_set"]) for r in group if r["structure"] != "embree-instances"})
        for world, backend, ray_set in keys:
            by = {r["placement"]: r for r in group if (r["world"], r["backend"], r["ray_set"]) == (world, backend, ray_set)}
            if not all(k in by for k in ("none", "off-paths", "in-view")):
                continue
            alone, off, view = (by[k]["mrays_median"] for k in ("none", "off-paths", "in-view"))
            e = embree.get(ray_set)
            cycles = by["in-view"].get("cycles_per_ray_step")
            mismatches = sum(by[k]["mismatches"] for k in by)
            cycles_text = f"{cycles:.1f}" if isinstance(cycles, (int, float)) and cycles == cycles else "–"
            if e and backend == "cpu":
                embree_text = f"{e['mrays_median']:.2f} | {view / e['mrays_median']:.2f}x"
            else:
                embree_text = "– | –"
            out.append(f"| {n:,} | {world} | {backend} | {ray_set} | {alone:.2f} | {off:.2f} | {100 * (alone / off - 1):+.1f} % "
                       f"| {view:.2f} | {by['in-view']['steps_per_ray']:.1f} | {cycles_text} | {embree_text} | {mismatches} |")
    peer = [r for r in rows if r["type"] == "row" and r["structure"] == "embree-instances"]
    if peer:
        rays = sum(r["rays"] * r["runs"] for r in peer)
        disagree = sum(r.get("status_disagreements", 0) for r in peer)
        out += ["", f"Embree's instancing peer (float quads, compared by hit status only): {disagree:,} of {rays:,} "
                f"timed rays disagree with voxray's hits."]
    out += candidates_table(rows, counts)
    out += fields_table(rows)
    out += ["", "Update per frame, every instance moving (host: scene.move of the batch + tracer.update):", "",
            "| instances | world | backend | candidates | update ms | bytes sent |", "|---:|---|---|---|---:|---:|"]
    for n in counts:
        for r in rows:
            if r["type"] == "update" and r["entities"] == n:
                out.append(f"| {n:,} | {r['world']} | {r['backend']} | {r['candidates']} | {r['update_ms_median']:.2f} | "
                           f"{r['update_bytes_median']:,.0f} |")
    with open(a.out, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
