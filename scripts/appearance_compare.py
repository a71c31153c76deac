#!/usr/bin/env python3
"""Two appearance-bench runs side by side: the walk before and after a change of its rules.

appearance_compare.py BEFORE AFTER --out TABLE.md [--doc DOC.md --marker NAME]
  BEFORE, AFTER  appearance-bench JSON lines (a header, then one row per method, view and light)
  TABLE.md       per scene and resolution in both, for averages, sggx and ours: the mean over
                 views and lights of MSE, SSIM and visits a ray, before and after
  --doc          also put the table between <!-- NAME-table:begin --> and :end --> of DOC.md
"""
import argparse

from appearance_table import load, method_means, put_in_doc

METHODS = ["averages", "sggx", "ours"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--out", required=True)
    parser.add_argument("--doc")
    parser.add_argument("--marker")
    args = parser.parse_args()
    (head_b, rows_b), (head_a, rows_a) = load(args.before), load(args.after)
    before, after = method_means(rows_b), method_means(rows_a)
    lines = ["| scene | method | MSE before | MSE after | SSIM before | SSIM after | visits a ray before | after |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    for (scene, resolution), methods in sorted(after.items()):
        for method in sorted(m for m in methods if m in METHODS and m in before.get((scene, resolution), {})):
            b, a = before[(scene, resolution)][method], methods[method]
            lines.append("| %s at %d³ | %s | %.5f | %.5f | %.4f | %.4f | %.2f | %.2f |"
                         % (scene, resolution, method, b["mse"], a["mse"], b["ssim"], a["ssim"], b["visits_per_ray"],
                            a["visits_per_ray"]))
    lines.append("")
    commit = lambda head: head["git_commit"][:10] + (" with changes" if head["git_commit"].endswith("-dirty") else "")
    lines.append("Means over views × lights; before: commit %s, after: commit %s (%s, %s)."
                 % (commit(head_b), commit(head_a), head_a["machine"]["cpu_model"], head_a["started_utc"][:10]))
    text = "\n".join(lines) + "\n"
    with open(args.out, "w") as f:
        f.write(text)
    if args.doc:
        put_in_doc(args.doc, args.marker, text)


if __name__ == "__main__":
    main()
