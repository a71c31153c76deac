#!/usr/bin/env bash
# Issue 27, end to end: a world built by mpirun -np 2 and -np 4 (oversubscribed here),
# with the dynamic and the static schedule, and by 3 shard jobs at once plus --finish, is
# byte for byte the world one process builds, for a tiled built-in scene and a shared mesh;
# a rank killed (SIGKILL) mid-build and the build run again gives the same world; the
# frames flown through a distributed build are those of a single one; ranks or shards
# given other arguments are refused, naming the difference.
#
#   world_distributed.sh TOOL DATA_DIR WORK_DIR [MPIEXEC]      (Open MPI's: --oversubscribe)
set -euo pipefail
tool=$1 data=$2 work=$3 mpiexec=${4:-mpirun}
source "$(dirname "$0")/expect.sh"
# Root may run mpirun here (CI runs as root); every rank is local.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun=("$mpiexec" --oversubscribe)
rm -rf "$work"
mkdir -p "$work"

same() {  # same REFERENCE FOLDER WHAT
    if diff -r "$1" "$2" > /dev/null; then
        echo "ok   $3: $(find "$2" -type f | wc -l) files, byte for byte"
    else
        echo "FAIL $3: $2 differs from $1:"; diff -rq "$1" "$2" | head -n 5
        failures=$((failures + 1))
    fi
}

scene=(builtin:terrain:256 --tile 3 1 2 --chunk-bits 5)
"$tool" world-build "${scene[@]}" --out "$work/one" > "$work/one.txt" 2>&1
for n in 2 4; do
    "${mpirun[@]}" -np $n "$tool" world-build "${scene[@]}" --out "$work/mpi$n" > "$work/mpi$n.txt" 2>&1
    grep -q "on $n processes" "$work/mpi$n.txt"
    same "$work/one" "$work/mpi$n" "mpirun -np $n, dynamic"
done
"${mpirun[@]}" -np 3 "$tool" world-build "${scene[@]}" --out "$work/static3" --mpi-schedule static > /dev/null 2>&1
same "$work/one" "$work/static3" "mpirun -np 3, static"
for k in 0 1 2; do "$tool" world-build "${scene[@]}" --out "$work/shards" --shard $k/3 > /dev/null 2>&1 & done
wait
"$tool" world-build "${scene[@]}" --out "$work/shards" --finish > /dev/null 2>&1
same "$work/one" "$work/shards" "3 shard jobs at once, then --finish"

if [[ -f "$data/mesh/stanford_bunny.ply" ]]; then
    mesh=("$data/mesh/stanford_bunny.ply" --resolution 160 --chunk-bits 5)
    "$tool" world-build "${mesh[@]}" --out "$work/mesh_one" > /dev/null 2>&1
    "${mpirun[@]}" -np 2 "$tool" world-build "${mesh[@]}" --out "$work/mesh_mpi2" > /dev/null 2>&1
    same "$work/mesh_one" "$work/mesh_mpi2" "a shared mesh, mpirun -np 2"
    for k in 0 1 2; do "$tool" world-build "${mesh[@]}" --out "$work/mesh_shards" --shard $k/3 > /dev/null 2>&1; done
    "$tool" world-build "${mesh[@]}" --out "$work/mesh_shards" --finish > /dev/null 2>&1
    same "$work/mesh_one" "$work/mesh_shards" "a shared mesh, 3 shards then --finish"
else
    echo "FAIL no shared mesh at $data/mesh/stanford_bunny.ply"; failures=$((failures + 1))
fi

# The documented Slurm script (docs/slurm/world_build.sh), with a stand-in sbatch that runs
# the array's jobs and then the finish here.
PATH="$(dirname "$0")/fake_slurm:$PATH" VOXRAY="$tool" bash "$(dirname "$0")/../../docs/slurm/world_build.sh" \
    builtin:terrain:256 "$work/slurm" 4 --tile 3 1 2 --chunk-bits 5 > /dev/null
same "$work/one" "$work/slurm" "docs/slurm/world_build.sh: a 4-job array, then the finish"

# The same frames from a distributed build as from one process.
for w in one mpi2; do
    "$tool" world-fly "$work/$w" --backend cpu --frames 2 --width 64 --height 36 --png-dir "$work/fly_$w" > /dev/null
done
for f in 0 1; do cmp "$work/fly_one/frame_00$f.png" "$work/fly_mpi2/frame_00$f.png"; done
echo "ok   world-fly draws the same frames from the mpirun -np 2 world"

# A rank killed mid-build: the job fails; run again, it resumes and the world is the same.
big=(builtin:terrain:256 --tile 4 1 4 --chunk-bits 4 --threads 1)
"$tool" world-build "${big[@]}" --out "$work/big_one" > /dev/null 2>&1
"${mpirun[@]}" -np 2 "$tool" world-build "${big[@]}" --out "$work/big_killed" > "$work/killed.txt" 2>&1 &
launcher=$!
for _ in $(seq 600); do
    [[ $(find "$work/big_killed" -name '*.vxck' 2> /dev/null | wc -l) -ge 40 ]] && break
    sleep 0.05
done
rank=$(pgrep -P $launcher -f world-build | head -n 1)
[[ -n "$rank" ]] && kill -9 "$rank"
if wait $launcher; then echo "FAIL the killed build exited 0 (the kill came too late?)"; failures=$((failures + 1)); fi
[[ -f "$work/big_killed/world.vxwm" ]] && { echo "FAIL a killed build left a manifest"; failures=$((failures + 1)); }
"${mpirun[@]}" -np 2 "$tool" world-build "${big[@]}" --out "$work/big_killed" > "$work/resumed.txt" 2>&1
awk '$1 == "0" && NF == 6 { exit !($6 > 0) }' "$work/resumed.txt" || { echo "FAIL nothing was resumed"; failures=$((failures + 1)); }
same "$work/big_one" "$work/big_killed" "a rank killed (SIGKILL), the build run again"

# Other arguments: a rank (MPMD launch) or a shard.
expect_failure "a rank with another --density" "density 2 on rank 0, 3 here \(--density\)" \
    "${mpirun[@]}" -np 1 "$tool" world-build "${scene[@]}" --out "$work/mixed" : \
    -np 1 "$tool" world-build "${scene[@]}" --out "$work/mixed" --density 3
"$tool" world-build "${scene[@]}" --out "$work/mixed_shards" --shard 0/2 > /dev/null 2>&1
expect_failure "a shard with another --density" "density 2 there, 3 here \(--density\)" \
    "$tool" world-build "${scene[@]}" --out "$work/mixed_shards" --shard 1/2 --density 3
expect_failure "a shard of another shard count" "shards 2 there, 3 here" \
    "$tool" world-build "${scene[@]}" --out "$work/mixed_shards" --shard 1/3
expect_failure "the finish before every shard" "shard 1 of 2 has not finished" \
    "$tool" world-build "${scene[@]}" --out "$work/mixed_shards" --finish
expect_failure "a bad --shard" "expected K/N" "$tool" world-build "${scene[@]}" --out "$work/x" --shard 3/3
expect_failure "--shard under mpirun" "not for ranks mpirun starts" \
    "${mpirun[@]}" -np 1 "$tool" world-build "${scene[@]}" --out "$work/x" --shard 0/2
finish
