#!/usr/bin/env bash
# Builds tests/fuzz/fuzz_vox.cpp with libFuzzer + ASan + UBSan and fuzzes the .vox reader
# for a fixed time, seeded with the shared .vox scenes when the data folder exists.
# Fails on any crash, sanitizer report, hang or leak. Called by ctest (label `fuzz`):
#
#   run_fuzz.sh CLANGXX INCLUDE_DIR GLM_INCLUDE_DIR WORK_DIR DATA_DIR SECONDS REQUIRE
#
# CLANGXX empty: clang++-14 was not found; exits 77 (ctest: skipped), or 1 when REQUIRE
# is ON (VOXRAY_REQUIRE_ALL_BACKENDS). $VOXRAY_DATA_DIR overrides DATA_DIR.
set -euo pipefail

clangxx=$1 include_dir=$2 glm_dir=$3 work_dir=$4 data_dir=$5 seconds=$6 require=$7
here=$(cd "$(dirname "$0")" && pwd)

if [[ -z "$clangxx" || ! -x "$clangxx" ]]; then
    echo "fuzz_vox_reader: clang++-14 not found (install clang-14 and libclang-rt-14-dev)"
    case "$require" in
        ON|on|1|TRUE|true|YES|yes) echo "fuzz_vox_reader: FAILED because VOXRAY_REQUIRE_ALL_BACKENDS is ON"; exit 1 ;;
        *) exit 77 ;;
    esac
fi

mkdir -p "$work_dir"
binary="$work_dir/fuzz_vox"
glm_flags=()
[[ -n "$glm_dir" && "$glm_dir" != *NOTFOUND* ]] && glm_flags=(-idirafter "$glm_dir")  # after the system dirs: /usr/include must keep its place
echo "fuzz_vox_reader: compiling $binary"
"$clangxx" -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I"$include_dir" "${glm_flags[@]}" "$here/fuzz_vox.cpp" -o "$binary"

corpus=$(mktemp -d "${TMPDIR:-/tmp}/voxray-fuzz-corpus.XXXXXX")
trap 'rm -rf "$corpus"' EXIT
data_dir=${VOXRAY_DATA_DIR:-$data_dir}
if [[ -d "$data_dir/vox" ]]; then
    cp "$data_dir"/vox/*.vox "$corpus"/ 2>/dev/null || true
    echo "fuzz_vox_reader: seeded with $(ls "$corpus" | wc -l) files from $data_dir/vox"
else
    echo "fuzz_vox_reader: no data folder at $data_dir; starting from an empty corpus"
fi

# Chunk ids and dictionary keys help the mutator build valid-looking files.
dict="$corpus.dict"
trap 'rm -rf "$corpus" "$dict"' EXIT
for token in "VOX " MAIN PACK SIZE XYZI RGBA MATL nTRN nGRP nSHP LAYR rOBJ rCAM NOTE IMAP \
             _t _r _f _hidden _type _rough _metal _ior _ri _emit _flux _trans _alpha \
             _diffuse _glass _emit _media _cloud _blend; do
    printf '"%s"\n' "$token" >> "$dict"
done

mkdir -p "$work_dir/artifacts"
# -max_len keeps mutations cheap (bigger seeds are cut, which still exercises the
# truncation paths); -timeout turns a hang into a failure.
"$binary" "$corpus" -dict="$dict" -max_total_time="$seconds" -max_len=65536 -timeout=20 \
    -rss_limit_mb=4096 -print_final_stats=1 -artifact_prefix="$work_dir/artifacts/"
echo "fuzz_vox_reader: no crash in ${seconds}s"
