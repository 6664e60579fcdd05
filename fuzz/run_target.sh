#!/usr/bin/env bash
# Runs one fuzz target over its seed corpus: fuzz/run_target.sh BINARY TARGET LIMIT MODE
#   MODE -runs:           LIMIT inputs (what CI runs, through ctest)
#   MODE -max_total_time: LIMIT seconds (tools/fuzz)
# New inputs go to $GJKLAB_FUZZ_CORPUS/TARGET when set (kept between runs), else to a
# temporary folder; the seed folders are only read. Crash reproducers go to
# $GJKLAB_FUZZ_ARTIFACTS (default: the current folder). Extra libFuzzer flags: $GJKLAB_FUZZ_FLAGS.
set -euo pipefail
binary=$1 target=$2 limit=$3 mode=$4
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")

scratch=$(mktemp -d "${TMPDIR:-/tmp}/gjklab-fuzz-run.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
if [ -n "${GJKLAB_FUZZ_CORPUS:-}" ]; then
  corpus=$GJKLAB_FUZZ_CORPUS/$target
else
  corpus=$scratch/corpus
fi
mkdir -p "$corpus"
seeds=()
[ -d "$here/corpus/$target" ] && seeds+=("$here/corpus/$target")

# Per target: the test data as seeds, the largest input (bytes) and the dictionary.
max_len=4096
extra=()
case $target in
  point_file)
    # The target's first byte picks the extension (fuzz/point_file.cpp): 0 xyz, 1 off, 2 obj,
    # 3 ply, 4 stl.
    mkdir -p "$scratch/points"
    for f in "$root"/tests/data/*.* "$root"/tests/data/meshes/*.* "$root"/tests/regression/data/hostile/*.*; do
      case ${f##*.} in
        xyz) b='\000' ;; off) b='\001' ;; obj) b='\002' ;; ply) b='\003' ;; stl) b='\004' ;; *) continue ;;
      esac
      { printf "$b"; head -c 65536 "$f"; } >"$scratch/points/$(basename "$f")"
    done
    seeds+=("$scratch/points")
    ;;
  closed_mesh)
    # The first byte picks the extension (fuzz/closed_mesh.cpp): 0 off, 1 obj, 2 ply, 3 stl.
    mkdir -p "$scratch/meshes"
    for f in "$root"/tests/data/meshes/*.* "$root"/tests/data/meshes_closed/*.* "$root"/tests/data/meshes_bad/*.*; do
      case ${f##*.} in
        off) b='\000' ;; obj) b='\001' ;; ply) b='\002' ;; stl) b='\003' ;; *) continue ;;
      esac
      { printf "$b"; head -c 65536 "$f"; } >"$scratch/meshes/$(basename "$f")"
    done
    seeds+=("$scratch/meshes")
    ;;
  cases_line)
    seeds+=("$root/tests/regression/data" "$root/tests/regression/data/hostile" "$root/experiments/data")
    max_len=16384
    ;;
  experiment_toml)
    # Not real_objects.toml: it reads 143 meshes from a cache folder (seconds per input).
    mkdir -p "$scratch/experiments"
    for f in "$root"/experiments/*/*.toml; do
      case $(basename "$f") in real_objects.toml) ;; *) cp "$f" "$scratch/experiments/" ;; esac
    done
    seeds+=("$scratch/experiments")
    max_len=8192
    ;;
  bench_config)
    mkdir -p "$scratch/bench"
    cp "$root/experiments/bench/seed_tables.toml" "$scratch/bench/"
    seeds+=("$scratch/bench")
    ;;
  archive)
    # The seed archives are 100 to 260 kB (HDF5 allocates whole chunks; mostly zeros).
    max_len=262144
    ;;
  query)
    max_len=512
    # libFuzzer's leak check after each input that allocated more than it freed runs on most
    # inputs here (memory the libraries keep between calls): measured 3x fewer inputs per
    # second with it. Leaks stay checked by the other targets and by the asan preset's suite.
    extra=(-detect_leaks=0)
    ;;
esac
flags=(-max_len=$max_len -timeout=25 -rss_limit_mb=2560 -print_final_stats=1 "${extra[@]}")
[ -f "$here/dict/$target.dict" ] && flags+=(-dict="$here/dict/$target.dict")
[ -n "${GJKLAB_FUZZ_ARTIFACTS:-}" ] && flags+=(-artifact_prefix="$GJKLAB_FUZZ_ARTIFACTS/$target-")
# shellcheck disable=SC2086
exec "$binary" "${flags[@]}" "$mode=$limit" ${GJKLAB_FUZZ_FLAGS:-} "$corpus" "${seeds[@]}"
