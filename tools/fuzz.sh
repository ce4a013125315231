#!/usr/bin/env bash
# libFuzzer (clang, ASan + UBSan) for every component: make fuzz-<c> / fuzz-smoke-<c> build and
# run the harnesses <c>'s make.mk declares (tools/kit.mk turns the declarations into targets).
#
# usage: fuzz.sh build BINARY [FLAG...] -- SOURCE...
#          .c sources with clang -std=c99, the rest with clang++ -std=c++17, linked by clang++;
#          every FLAG goes to every compile (include directories, definitions).
#        fuzz.sh run NAME BINARY SECONDS SEED_DIR [LIBFUZZER_FLAG...]
#          runs BINARY for SECONDS on a working corpus in BINARY's folder seeded from SEED_DIR
#          (new inputs and crash reproducers stay in .build; the committed seeds are never
#          written); the console gets the executions and the verdict, the log the rest.
set -euo pipefail
clang_c=$(command -v clang-14 || command -v clang || true)
clang_cxx=$(command -v clang++-14 || command -v clang++ || true)
sanitize=(-g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -Wall -Wextra -Werror)

build() {
  local binary=$1
  shift
  local flags=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do flags+=("$1"); shift; done
  shift || true
  if [ -z "$clang_c" ] || [ -z "$clang_cxx" ]; then
    echo "fuzz: clang not found; run 'make deps' (Debian clang-14, libclang-rt-14-dev, in the components' apt-packages.txt)" >&2
    exit 2
  fi
  local objdir=$binary.obj
  rm -rf "$objdir" && mkdir -p "$objdir"
  local objects=() src obj
  for src in "$@"; do
    obj=$objdir/$(basename "$src").o
    case $src in
      *.c) "$clang_c" -std=c99 "${sanitize[@]}" "${flags[@]}" -c "$src" -o "$obj" ;;
      *) "$clang_cxx" -std=c++17 "${sanitize[@]}" "${flags[@]}" -c "$src" -o "$obj" ;;
    esac
    objects+=("$obj")
  done
  "$clang_cxx" "${sanitize[@]}" "${objects[@]}" -o "$binary"
}

run() {
  local name=$1 binary=$2 seconds=$3 seeds=$4
  shift 4
  local dir
  dir=$(dirname "$binary")
  local harness
  harness=$(basename "$binary")
  local corpus=$dir/corpus_$harness artifacts=$dir/artifacts_$harness/ log=$dir/$harness.log
  mkdir -p "$corpus" "$artifacts"
  echo "fuzz-$name: $harness for $seconds s (log: $log)"
  if ! "$binary" -max_total_time="$seconds" -print_final_stats=1 -artifact_prefix="$artifacts" "$@" \
       "$corpus" "$seeds" > "$log" 2>&1; then
    tail -n 40 "$log"
    echo "fuzz-$name: $harness FAILED: reproducer in $artifacts, log $log"
    exit 1
  fi
  grep -E 'stat::(number_of_executed_units|average_exec_per_sec)' "$log" | sed 's/^/  /'
  echo "fuzz-$name: $harness, no crash in $seconds s"
}

cmd=${1:-}
shift || true
case $cmd in
  build) build "$@" ;;
  run) run "$@" ;;
  *) sed -n '2,12p' "$0" >&2; exit 2 ;;
esac
