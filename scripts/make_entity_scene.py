#!/usr/bin/env python3
"""Writes a scene file (docs/entities.md) of COUNT moving instances over a world: models
from ../shared/data when present (a deer, a tree), built-ins otherwise; seeded, so the same
arguments give the same file. Used by scripts/demo.sh and scripts/entity_bench.sh.

    make_entity_scene.py OUT.json --world builtin:terrain --count 3000 --extent 256 256 64
"""
import argparse
import json
import math
import os
import random


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("--world", default="builtin:terrain", help="world scene (path or builtin:NAME)")
    p.add_argument("--count", type=int, default=3000)
    p.add_argument("--extent", type=float, nargs=3, default=[256, 256, 64],
                   help="the box (from 0) the instances start in, world voxels")
    p.add_argument("--data", default="../shared/data", help="the shared data folder (relative to the repository)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--model", action="append", metavar="NAME=FILE",
                   help="a model (FILE under --data); the first is placed 19 times in 20, the second (at half"
                        " scale) the 20th; default deer=vox/bevy_deer_v200.vox tree=vox/minecraft_tree.vox")
    p.add_argument("--model-fields", choices=["bricks", "none"], default="bricks",
                   help="whether model walks cross empty bricks by distance fields")
    a = p.parse_args()

    out_dir = os.path.dirname(os.path.abspath(a.out))
    def ref(path):  # a path as the scene file names it: relative to the file
        return path if path.startswith("builtin:") else os.path.relpath(os.path.abspath(path), out_dir)

    models = {}
    chosen = [("deer", "vox/bevy_deer_v200.vox", "builtin:sphere30"), ("tree", "vox/minecraft_tree.vox", "builtin:checker")]
    if a.model:
        chosen = [(m.split("=", 1)[0], m.split("=", 1)[1], "builtin:sphere30") for m in a.model]
    for name, file, fallback in chosen:
        path = os.path.join(a.data, file)
        models[name] = {"file": ref(path) if os.path.exists(path) else fallback, "fields": a.model_fields}
    world = a.world if a.world.startswith("builtin:") else ref(a.world)

    g = random.Random(a.seed)
    instances = []
    for i in range(a.count):
        second = i % 20 == 0 and len(chosen) > 1
        inst = {"model": chosen[1 if second else 0][0],
                "position": [round(g.uniform(0, e), 2) for e in a.extent],
                "rotation": [round(x, 4) for x in (g.uniform(-1, 1), 0, 0, g.uniform(-1, 1))]}
        if inst["rotation"] == [0, 0, 0, 0]:
            inst["rotation"] = [1, 0, 0, 0]
        if second:
            inst["scale"] = 0.5
        kind = i % 3
        if kind == 0:
            angle = g.uniform(0, 2 * math.pi)
            inst["motion"] = {"linear": [round(math.cos(angle), 3), round(math.sin(angle), 3), 0]}
        elif kind == 1:
            inst["motion"] = {"spin": [0, 0, 1, round(g.uniform(-0.2, 0.2), 3)]}
        else:
            centre = [round(e / 2, 1) for e in a.extent]
            inst["motion"] = {"orbit": centre + [round(g.uniform(0.005, 0.02), 4)]}
        instances.append(inst)
    with open(a.out, "w") as f:
        json.dump({"world": world, "models": models, "instances": instances}, f, separators=(",", ":"))
        f.write("\n")
    print(f"wrote {a.out}: {a.count} instances of {len(models)} models over {world}")


if __name__ == "__main__":
    main()
