#!/usr/bin/env python3
"""The table of appearance-walk-bench results: the compositing walk's speed.

appearance_walk_table.py RESULTS --out TABLE.md [--doc DOC.md]
  RESULTS    appearance-walk-bench JSON lines (a header, then one row per structure, backend and method)
  TABLE.md   per scene: each structure x backend x method's frames a second (median of the runs),
             nanoseconds and cycles a ray per thread, steps and voxels a ray, beside the first-hit
             kernel's Mrays/s, steps a ray and cycles a ray-step on the same rays, and the issue's
             render target (ours at 27 frames a second or more)
  --doc      also put the table between <!-- appearance_walk-table:begin --> and :end --> of DOC.md
"""
import argparse
import pathlib

from appearance_table import load, put_in_doc

TARGET_FPS = 27.0


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
    text = table(header, rows)
    pathlib.Path(a.out).write_text(text)
    if a.doc:
        put_in_doc(a.doc, "appearance_walk", text)
    print(text)


if __name__ == "__main__":
    main()
