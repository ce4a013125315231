#!/usr/bin/env bash
# make bench-ha: instructions per HA control step on a Cortex-M3 (QEMU mps2-an385, counted
# with -icount, method checked first by calibrate_m3.c) and ns per step on the host. Bounded:
# every QEMU run has a timeout and ends itself through semihosting.
# usage: run_bench.sh [out_dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:-$root/.build/arduino_ha_bench}
core=${HA_CORE_DIR:-$ha/src/core}  # override only to try a patched copy of the core
floor=$root/common/src  # the ground floor the core runs on: geodesy, the HP command's CRC
for tool in arm-none-eabi-gcc qemu-system-arm gcc; do
  if ! command -v "$tool" > /dev/null; then
    echo "run_bench: $tool not found; run 'make deps' (arduino_ha/apt-packages.txt)" >&2
    exit 2
  fi
done
rm -rf "$out"
mkdir -p "$out"
mapfile -t core_sources < <(find "$core" -maxdepth 1 -name '*.c' | LC_ALL=C sort)
core_sources+=("$floor/geo_wgs84.c" "$floor/hp_command.c")

m3_flags=(-mcpu=cortex-m3 -mthumb -Os -std=c99 -ffunction-sections -fdata-sections
  -Wall -Wextra -Werror -I"$core" -I"$floor" -I"$here")
m3_link=(-nostartfiles --specs=nano.specs -Wl,--gc-sections -T "$here/mps2_an385.ld")
qemu=(timeout 120 qemu-system-arm -M mps2-an385 -cpu cortex-m3 -nographic -monitor none
  -serial none -semihosting-config enable=on,target=native -icount shift=0,align=off,sleep=off)
startup=("$here/startup_m3.c" "$here/semihost.c" "$here/insn_timer.c")

arm-none-eabi-gcc "${m3_flags[@]}" "${m3_link[@]}" "${startup[@]}" "$here/calibrate_m3.c" \
  -lc -lgcc -o "$out/calibrate_m3.elf"
if ! "${qemu[@]}" -kernel "$out/calibrate_m3.elf" > "$out/calibrate.txt" 2>&1; then
  cat "$out/calibrate.txt"
  echo "run_bench: instruction counting does not match loops of known length; not benchmarking" >&2
  exit 1
fi
sed 's/^/  /' "$out/calibrate.txt"

arm-none-eabi-gcc "${m3_flags[@]}" "${m3_link[@]}" "${startup[@]}" "$here/bench_inputs.c" \
  "$here/bench_m3.c" "${core_sources[@]}" -lm -lc -lgcc -o "$out/bench_m3.elf"
if ! "${qemu[@]}" -kernel "$out/bench_m3.elf" > "$out/bench_m3.txt" 2>&1; then
  cat "$out/bench_m3.txt"
  echo "run_bench: the Cortex-M3 benchmark failed or timed out" >&2
  exit 1
fi
cat "$out/bench_m3.txt"

gcc -O2 -std=c99 -Wall -Wextra -Werror -I"$core" -I"$floor" -I"$here" "$here/bench_inputs.c" \
  "$here/bench_host.c" "${core_sources[@]}" -lm -o "$out/bench_host"
"$out/bench_host"

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
echo "machine: $(uname -m), ${cpu:-unknown cpu}, $(nproc) cores, $(qemu-system-arm --version | head -n 1), $(arm-none-eabi-gcc --version | head -n 1), host $(gcc --version | head -n 1)"
