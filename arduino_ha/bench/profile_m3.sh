#!/usr/bin/env bash
# Where the HA step's Cortex-M3 instructions go: runs the benchmark timeline of run_bench.sh
# under QEMU with an execution log and charges every executed block to its function
# (profile_m3.py). For the core's owner when the step gets too slow; not part of make bench-ha.
# Takes about half a minute; the log streams through a FIFO and is never stored.
# usage: profile_m3.sh [out_dir]        (HA_CORE_DIR=<copy> to profile a patched core)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:-$root/.build/arduino_ha_profile}
core=${HA_CORE_DIR:-$ha/src/core}
floor=$root/common/src  # the ground floor the core runs on: geodesy, the HP command's CRC
rm -rf "$out"
mkdir -p "$out"
mapfile -t core_sources < <(find "$core" -maxdepth 1 -name '*.c' | LC_ALL=C sort)
core_sources+=("$floor/geo_wgs84.c" "$floor/hp_command.c")
arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -Os -std=c99 -ffunction-sections -fdata-sections \
  -Wall -Wextra -Werror -I"$core" -I"$floor" -I"$here" -nostartfiles --specs=nano.specs -Wl,--gc-sections \
  -T "$here/mps2_an385.ld" "$here/startup_m3.c" "$here/semihost.c" "$here/insn_timer.c" \
  "$here/bench_inputs.c" "$here/bench_m3.c" "${core_sources[@]}" -lm -lc -lgcc \
  -o "$out/bench_m3.elf"
mkfifo "$out/qemu.log"
python3 "$here/profile_m3.py" "$out/bench_m3.elf" "$out/qemu.log" > "$out/profile.txt" &
reader=$!
timeout 300 qemu-system-arm -M mps2-an385 -cpu cortex-m3 -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native -d in_asm,exec,nochain -D "$out/qemu.log" \
  -kernel "$out/bench_m3.elf" > "$out/bench_m3.txt" 2>&1 || true
wait "$reader"
rm -f "$out/qemu.log"
cat "$out/profile.txt"
