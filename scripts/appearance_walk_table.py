#!/usr/bin/env python3
"""The tables of appearance-walk-bench results: the precompute's and the compositing walk's speed.

appearance_walk_table.py RESULTS --out TABLE.md [--doc DOC.md]
  RESULTS    appearance-walk-bench JSON lines (a header, then "precompute" rows, one per table made,
             and "walk" rows, one per structure, backend and method)
  TABLE.md   the precompute's: per scene and method, seconds, microseconds a voxel (all threads and
             per thread) and rays a second, the voxel lists' way against every ray through Embree's
             BVH, and the issue's targets (ours at 20 us a voxel per thread or less; the bunny at
             256^3 in 5 s or less). Then the walk's: each structure x backend x method's frames a
             second (median of the runs), nanoseconds and cycles a ray per thread, steps and voxels
             a ray, beside the first-hit kernel's Mrays/s, steps a ray and cycles a ray-step on the
             same rays, and the render target (ours at 27 frames a second or more)
  --doc      also put them between <!-- appearance_precompute-table:begin --> and :end --> and
             <!-- appearance_walk-table:begin --> and :end --> of DOC.md
"""
import argparse
import pathlib

from appearance_table import load, put_in_doc

TARGET_FPS = 27.0
TARGET_US_PER_VOXEL_THREAD = 20.0
TARGET_BUNNY_SECONDS = 5.0  # at 256^3 on 2 threads


def precompute_table(header, rows):
    out = ["| scene | method | rays meet | voxels | seconds | µs a voxel | µs a voxel per thread | Mrays/s "
           "| against Embree's BVH | targets |",
           "|---|---|---|---:|---:|---:|---:|---:|---:|---|"]
    peer = {(r["scene"], r["resolution"], r["method"]): r for r in rows if r["rays_meet"] == "embree_bvh"}
    for r in rows:
        per_thread = r["us_per_voxel"] * r["threads"]
        p = peer.get((r["scene"], r["resolution"], r["method"]))
        speedup = "×%.2f" % (p["seconds"] / r["seconds"]) if p and p is not r else ""
        verdict = []
        if r["method"] == "ours" and r["rays_meet"] == "voxel_lists":
            short = per_thread / TARGET_US_PER_VOXEL_THREAD
            verdict.append("%.1f µs per thread %s" % (per_thread, "met" if short <= 1 else
                                                         "**missed** (×%.2f)" % short))
            if "bunny" in r["scene"] and r["resolution"] == 256 and r["threads"] == 2:
                over = r["seconds"] / TARGET_BUNNY_SECONDS
                verdict.append("%.2f s %s" % (r["seconds"], "met" if over <= 1 else "**missed** (×%.2f)" % over))
        out.append("| %s at %d³ | %s | %s | %d | %.2f | %.2f | %.2f | %.2f | %s | %s |" % (
            r["scene"], r["resolution"], r["method"], r["rays_meet"].replace("_", " "), r["voxels"], r["seconds"],
            r["us_per_voxel"], per_thread, r["rays_per_second"] * 1e-6, speedup, "; ".join(verdict)))
    r0 = rows[0]
    out += ["", "%d threads; the rays of each voxel: 150 sampling rays, and ours also 108 opacity rays. *voxel lists*: "
            "each voxel's rays against the triangles that reach it, gathered by Embree's point query; *embree bvh*: "
            "every ray through Embree's BVH from the root (`rtcIntersect1`). The paper: about 200 µs a voxel on one "
            "thread. Machine: %s; commit %s." % (r0["threads"], header.get("machine", {}).get("cpu_model", "?"),
                                                 header.get("git_commit", "?")[:10])]
    return "\n".join(out) + "\n"


def table(header, rows):
    out = ["| scene | structure | backend (lanes) | method | walk fps | ns a ray (a thread) | cycles a ray "
           "| steps a ray | visits a ray | first hit Mrays/s | first hit steps a ray | first hit cycles a ray-step "
           "| target (≥ 27 fps) |",
           "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    best = {}
    for r in rows:
        ours = r["method"] == "ours"
        short = TARGET_FPS / r["walk_fps"]
        verdict = ("met" if short <= 1 else "**missed** (×%.1f short)" % short) if ours else ""
        out.append("| %s at %d³ | %s | %s (%d) | %s | %.2f | %.0f | %.0f | %.1f | %.2f | %.1f | %.1f | %.0f | %s |" % (
            r["scene"], r["resolution"], r["structure"], r["backend"], r["simd_width"], r["method"], r["walk_fps"],
            r["ns_per_ray_thread"], r["cycles_per_ray"], r["steps_per_ray"], r["visits_per_ray"],
            r["first_hit_mrays"], r["first_hit_steps_per_ray"], r["first_hit_cycles_per_ray_step"], verdict))
        if ours:
            key = (r["scene"], r["resolution"])
            best[key] = max(best.get(key, 0.0), r["walk_fps"])
    r0 = rows[0]
    fastest = "; ".join("%s at %d³: %.1f fps" % (s, n, f) for (s, n), f in sorted(best.items()))
    out += ["", "One view (%d² pixels × %d rays, lit from the front), %d threads, median of %d timed walks after a "
            "warm-up; cycles at the clock the kernel reports (%.2f GHz). Fastest ours: %s. Machine: %s; commit %s."
            % (r0["size"], r0["rays_per_pixel"], r0["threads"], len(r0["walk_fps_runs"]),
               header.get("machine", {}).get("clock_hz", 0) * 1e-9, fastest,
               header.get("machine", {}).get("cpu_model", "?"), header.get("git_commit", "?")[:10])]
    return "\n".join(out) + "\n"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("results")
    p.add_argument("--out", required=True)
    p.add_argument("--doc")
    a = p.parse_args()
    header, rows = load(a.results)
    precompute = precompute_table(header, [r for r in rows if r.get("row") == "precompute"])
    walk = table(header, [r for r in rows if r.get("row", "walk") == "walk"])
    pathlib.Path(a.out).write_text(precompute + "\n" + walk)
    if a.doc:
        put_in_doc(a.doc, "appearance_precompute", precompute)
        put_in_doc(a.doc, "appearance_walk", walk)
    print(precompute + "\n" + walk)


if __name__ == "__main__":
    main()
