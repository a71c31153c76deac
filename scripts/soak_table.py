#!/usr/bin/env python3
"""The soak run's counts (scripts/soak.sh) as a table: rays, mismatches and ties per
structure x backend pair over every scene and seed, the crashes, and the fuzzer's runs.
Reads FOLDER/checks.jsonl, crashes.txt and fuzz.tsv (format, inputs, seconds, 1 if no
finding); writes FOLDER/summary.json
and docs/soak.md (its table between the markers, the rest of the page kept)."""
import json
import pathlib
import sys

folder = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "docs/soak")
pairs, scenes, runs = {}, set(), 0
for line in (folder / "checks.jsonl").read_text().splitlines():
    if not line.strip():
        continue
    run = json.loads(line)
    runs += 1
    scenes.add(run["scene"])
    for p in run["pairs"]:
        key = (p["structure"], p["backend"])
        total = pairs.setdefault(key, {"rays": 0, "mismatches": 0, "ties": 0, "runs": 0, "edited_rays": 0})
        total["rays"] += p["rays"]
        total["mismatches"] += p["mismatches"]
        total["ties"] += p["ties"]
        total["runs"] += 1
        if run.get("edits", 0):
            total["edited_rays"] += p["rays"]
crash_file = folder / "crashes.txt"
crashes = [l for l in crash_file.read_text().splitlines() if l.strip()] if crash_file.exists() else []
fuzz = []
fuzz_file = folder / "fuzz.tsv"
if fuzz_file.exists():
    for line in fuzz_file.read_text().splitlines():
        if line.strip():
            name, inputs, seconds, ok = line.split()
            fuzz.append({"format": name, "inputs": int(inputs), "seconds": int(seconds), "clean": ok == "1"})

summary = {"scenes": sorted(scenes), "check_runs": runs, "crashes": crashes, "fuzzers": fuzz,
           "pairs": [{"structure": s, "backend": b, **v} for (s, b), v in sorted(pairs.items())]}
(folder / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")

rows = ["| structure | backend | rays | of them after edits | mismatches | ties |", "|---|---|---:|---:|---:|---:|"]
for (s, b), v in sorted(pairs.items()):
    rows.append(f"| {s} | {b} | {v['rays']:,} | {v['edited_rays']:,} | {v['mismatches']} | {v['ties']:,} |")
rows.append("")
rows.append(f"{len(scenes)} scenes, {runs} check runs, {len(crashes)} crashes.")
if fuzz:
    rows += ["", "| fuzzer | inputs | seconds | finding |", "|---|---:|---:|---|"]
    rows += [f"| {f['format']} | {f['inputs']:,} | {f['seconds']} | {'none' if f['clean'] else 'YES'} |" for f in fuzz]
table = "\n".join(rows)

page = pathlib.Path(__file__).resolve().parent.parent / "docs" / "soak.md"
begin, end = "<!-- soak table: scripts/soak_table.py -->", "<!-- end of soak table -->"
text = page.read_text() if page.exists() else f"# Soak run\n\n{begin}\n{end}\n"
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
page.write_text(f"{head}{begin}\n{table}\n{end}{tail}")
print(table)
sys.exit(1 if crashes or any(v["mismatches"] for v in pairs.values()) or not all(f["clean"] for f in fuzz) else 0)
