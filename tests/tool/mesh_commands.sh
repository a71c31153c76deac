#!/usr/bin/env bash
# The chunk mesher through the tool: check --mesh on built-in and real scenes (exit 0 and
# "0 mismatches" last), mesh-bench rows with the keys the docs and the acceptance checks
# read, mesh's PLY and glTF exports holding the quads it reports, and its pictures drawn by
# the Vulkan raster path.
# Usage: mesh_commands.sh TOOL DATA_DIR WORK_DIR
set -euo pipefail
tool=$1 data=$2 work=$3
mkdir -p "$work"
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

for scene in builtin:terrain64 builtin:noise50 "$data/vox/minecraft_tree.vox"; do
    out=$("$tool" check "$scene" --mesh --mesh-views 300 2>/dev/null) || fail "check --mesh $scene: exit $?"
    last=$(tail -n 1 <<< "$out")
    [[ $last =~ ": 0 mismatches"$ ]] && echo "ok   $last" || fail "check --mesh $scene: last line '$last'"
    kernels=$(grep -c "^mesher kernel on .*, 0 differing" <<< "$out" || true)
    [[ $kernels == 3 ]] && echo "ok   mesher kernel equal on 3 backends" ||
        fail "check --mesh $scene: mesher kernel equal on $kernels backends, not 3"
    raster=$(grep "^raster at level 0" <<< "$out" || true)
    [[ $raster =~ "; 0 mismatches" ]] && echo "ok   $raster" || fail "check --mesh $scene: raster line '$raster'"
done

"$tool" mesh-bench builtin:sphere30 builtin:checker --seconds 0.02 --kernel-runs 1 --json "$work/mesh.jsonl" > /dev/null 2>&1 ||
    fail "mesh-bench: exit $?"
python3 - "$work/mesh.jsonl" <<'PY' || fail "mesh-bench rows"
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
assert lines[0]["type"] == "header", lines[0]
rows = lines[1:]
assert [r["scene"] for r in rows] == ["builtin:sphere30", "builtin:checker"], rows
need = ["scene", "chunks", "us_median", "us_p95", "faces", "quads", "bytes_per_quad", "pop_ns_per_quad", "overdraw_max"]
for r in rows:
    missing = [k for k in need if k not in r]
    assert not missing, missing
    assert r["bytes_per_quad"] == 8 and r["faces"] >= r["quads"] > 0, r
assert rows[1]["faces"] == rows[1]["quads"] == 64 ** 3 // 2 * 6, rows[1]  # a checkerboard merges nothing
for r in rows:  # the mesher kernel on every backend, equal to the CPU mesher
    assert sorted(k["backend"] for k in r["kernel"]) == ["cpu-scalar", "opencl", "vulkan"], r["kernel"]
    assert all(k["equal_to_cpu"] and k["us_per_chunk"] > 0 for k in r["kernel"]), r["kernel"]
for r in rows:  # remeshing after edits, on both editable structures
    for structure in ("brickmap", "naadf"):
        f = r["remesh"][structure]
        assert f["edits"] == 20 and f["chunks_per_edit"] >= 1 and f["remesh_us_per_chunk_median"] > 0, (structure, f)
        assert f["read_us_median"] > 0, (structure, f)
for r in rows:  # the peer's image error beside the POP levels' (the Vulkan raster path)
    levels = r["meshoptimizer"]
    for p in levels:
        for key in ("pop_image_rmse", "image_rmse", "sloppy_image_rmse"):
            assert 0 <= p[key] < 256, (r["scene"], p)
    assert 0 < levels[0]["pop_image_rmse"] < levels[-1]["pop_image_rmse"], (r["scene"], levels)
print("ok   mesh-bench: %d rows with every key, image errors growing from level 1 to 6" % len(rows))
PY

out=$("$tool" mesh builtin:sphere30 --ply "$work/sphere.ply" --gltf "$work/sphere.glb" 2>/dev/null) || fail "mesh: exit $?"
quads=$(awk '$1 == 0 && NF == 5 { print $2 }' <<< "$out")
python3 - "$work/sphere.ply" "$work/sphere.glb" "$quads" <<'PY' || fail "mesh exports"
import json, struct, sys
ply, glb, quads = sys.argv[1], sys.argv[2], int(sys.argv[3])
header = open(ply, "rb").read(1024).split(b"end_header")[0].decode()
faces = int(header.split("element face ")[1].split()[0])
assert faces == quads, (faces, quads)
data = open(glb, "rb").read()
magic, version, length = struct.unpack_from("<4sII", data)
assert magic == b"glTF" and version == 2 and length == len(data), (magic, version, length)
size, kind = struct.unpack_from("<I4s", data, 12)
doc = json.loads(data[20:20 + size])
triangles = doc["accessors"][doc["meshes"][0]["primitives"][0]["indices"]]["count"] // 3
assert triangles == 2 * quads, (triangles, quads)
print("ok   exports: %d quads in the PLY, %d triangles in the glTF" % (faces, triangles))
PY

# Pictures by the raster path: the size asked for, and fewer quads
# at a coarser level of detail.
for bias in 64 2; do
    out=$("$tool" mesh builtin:terrain64 --png "$work/raster_$bias.png" --lod-bias $bias --width 200 --height 120 \
        2>/dev/null) || fail "mesh --png: exit $?"
    grep -o "[0-9]* quads at LOD bias $bias" <<< "$out" | cut -d' ' -f1 > "$work/quads_$bias" ||
        fail "mesh --png $bias: no raster line in '$out'"
done
python3 - "$work/raster_64.png" "$work/quads_64" "$work/quads_2" <<'PY' || fail "mesh --png picture"
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", data[:8]
width, height, depth, kind = struct.unpack(">IIBB", data[16:26])
assert (width, height, depth, kind) == (200, 120, 8, 2), (width, height, depth, kind)
idat, at = b"", 8
while at < len(data):
    size, tag = struct.unpack(">I4s", data[at:at + 8])
    if tag == b"IDAT": idat += data[at + 8:at + 8 + size]
    at += 12 + size
rows = zlib.decompress(idat)
assert len(rows) == height * (1 + 3 * width), len(rows)
fine, coarse = int(open(sys.argv[2]).read()), int(open(sys.argv[3]).read())
assert 0 < coarse < fine, (fine, coarse)
print("ok   mesh --png: a 200 x 120 picture; %d quads drawn at level 0, %d at bias 2" % (fine, coarse))
PY
if "$tool" mesh builtin:terrain64 --png "$work/raster.xyz" > "$work/err.txt" 2>&1; then
    fail "mesh --png raster.xyz: exit 0"
elif grep -q -- "--png" "$work/err.txt"; then
    echo "ok   mesh --png raster.xyz: $(tail -n 1 "$work/err.txt")"
else
    fail "mesh --png raster.xyz: '$(cat "$work/err.txt")'"
fi

echo "$failures case(s) failed"
[[ $failures -eq 0 ]]
