#!/usr/bin/env bash
# Builds a libFuzzer target of tests/fuzz with ASan + UBSan and fuzzes for a fixed time.
# Fails on any crash, sanitizer report, hang or leak. Called by ctest (label `fuzz`) and
# by scripts/soak.sh:
#
#   run_fuzz.sh CLANGXX INCLUDE_DIR GLM_INCLUDE_DIR WORK_DIR DATA_DIR SECONDS REQUIRE [FORMATS]
#
# FORMATS empty: fuzz_vox.cpp, the .vox reader with its options varied, seeded with the
# shared .vox scenes when the data folder exists. FORMATS "all" or a list ("vxck vxwm"):
# fuzz_formats.cpp, SECONDS for each of those formats of the malformed-input test
# (tests/malformed/formats.hpp), seeded with its valid samples; "all" is every format
# but vox. CLANGXX empty: clang++-14 was not found; exits 77 (ctest: skipped), or 1 when
# REQUIRE is ON (VOXRAY_REQUIRE_ALL_BACKENDS). $VOXRAY_DATA_DIR overrides DATA_DIR.
set -euo pipefail

clangxx=$1 include_dir=$2 glm_dir=$3 work_dir=$4 data_dir=$5 seconds=$6 require=$7 formats=${8:-}
here=$(cd "$(dirname "$0")" && pwd)

if [[ -z "$clangxx" || ! -x "$clangxx" ]]; then
    echo "run_fuzz: clang++-14 not found (install clang-14 and libclang-rt-14-dev)"
    case "$require" in
        ON|on|1|TRUE|true|YES|yes) echo "run_fuzz: FAILED because VOXRAY_REQUIRE_ALL_BACKENDS is ON"; exit 1 ;;
        *) exit 77 ;;
    esac
fi

target=fuzz_vox
[[ -n "$formats" ]] && target=fuzz_formats
mkdir -p "$work_dir/artifacts"
binary="$work_dir/$target"
glm_flags=()
[[ -n "$glm_dir" && "$glm_dir" != *NOTFOUND* ]] && glm_flags=(-idirafter "$glm_dir")  # after the system dirs: /usr/include must keep its place
echo "run_fuzz: compiling $binary"
"$clangxx" -std=c++20 -O1 -g -pthread -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I"$include_dir" -I"$here/../support" "${glm_flags[@]}" "$here/$target.cpp" -o "$binary"

scratch=$(mktemp -d "${TMPDIR:-/tmp}/voxray-fuzz.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

# -max_len keeps mutations cheap (bigger seeds are cut, which still exercises the
# truncation paths); -timeout turns a hang into a failure. -error_exitcode=1: libFuzzer's
# own default, 77, is ctest's skip code, so a finding would have read as a skipped test.
fuzz() {  # fuzz CORPUS [libFuzzer options...]
    local corpus=$1
    shift
    "$binary" "$corpus" "$@" -max_total_time="$seconds" -max_len=65536 -timeout=20 -rss_limit_mb=4096 \
        -print_final_stats=1 -error_exitcode=1 -artifact_prefix="$work_dir/artifacts/"
}

if [[ "$target" == fuzz_vox ]]; then
    corpus=$scratch/vox
    mkdir -p "$corpus"
    data_dir=${VOXRAY_DATA_DIR:-$data_dir}
    if [[ -d "$data_dir/vox" ]]; then
        cp "$data_dir"/vox/*.vox "$corpus"/ 2>/dev/null || true
        echo "run_fuzz: vox seeded with $(ls "$corpus" | wc -l) files from $data_dir/vox"
    else
        echo "run_fuzz: no data folder at $data_dir; starting from an empty corpus"
    fi
    # Chunk ids and dictionary keys help the mutator build valid-looking files.
    dict=$scratch/vox.dict
    for token in "VOX " MAIN PACK SIZE XYZI RGBA MATL nTRN nGRP nSHP LAYR rOBJ rCAM NOTE IMAP \
                 _t _r _f _hidden _type _rough _metal _ior _ri _emit _flux _trans _alpha \
                 _diffuse _glass _emit _media _cloud _blend; do
        printf '"%s"\n' "$token" >> "$dict"
    done
    echo "run_fuzz: vox for ${seconds}s"
    fuzz "$corpus" -dict="$dict"
    echo "run_fuzz: vox: no crash in ${seconds}s"
    exit 0
fi

if [[ "$formats" == all ]]; then
    formats=$(VOXRAY_FUZZ_LIST=1 "$binary" | grep -vx vox | tr '\n' ' ')
fi
for format in $formats; do
    corpus=$scratch/$format
    mkdir -p "$corpus"
    echo "run_fuzz: $format for ${seconds}s"
    VOXRAY_FUZZ_FORMAT=$format VOXRAY_FUZZ_SEEDS=$corpus fuzz "$corpus"
    echo "run_fuzz: $format: no crash in ${seconds}s"
done
