#!/usr/bin/env bash
# Frama-C WP for every component (make prove-<c>; the inputs are declared in <c>'s make.mk).
# Proves the ACSL contracts of the selected functions (with WP's runtime-error guards, -wp-rte)
# and prints one line per contract, then `goals: N proved of M`. Exits non-zero on any goal not
# proved, any analysis error, or a negative control whose planted defects were proved.
# Full logs: OUT_DIR/<run>.log.
#
# usage: wp.sh NAME OUT_DIR [options] -- SOURCE...
#   -I DIR            include directory (repeatable)
#   -D DEFINE         preprocessor definition (repeatable); the sources' contracts are read only
#                     under the definitions given here (the core guards them with HA_WP)
#   --fct F1,F2,...   the functions whose contracts are proved (with everything they call)
#   --driver FILE     a WP driver (logic symbols mapped onto WP's own)
#   --negative SRC    a deliberately wrong program: each of its goals named planted_* must stay
#                     unproved with the same settings, so the setup cannot pass vacuously
#   --negative-fct F1,...  the negative control's functions (default: all it defines)
#   --timeout S       per goal and prover, seconds (default 10); the negative control's false
#                     goals get 10, since no time proves them
# Models: Typed memory (no pointer casts), machine integers (C's wrapping; signed overflow is
# a goal of the RTE guards), IEEE-754 floats (Why3's ieee_float: NaN and the
# infinities included). Provers: CVC4 (integers) and Z3 (floats), one process at a time.
set -euo pipefail
name=${1:?usage: wp.sh NAME OUT_DIR [options] -- SOURCE...}
out=${2:?usage: wp.sh NAME OUT_DIR [options] -- SOURCE...}
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
cpp_args=()
fct=""
driver=""
negative=""
negative_fct=""
timeout=10
while [ $# -gt 0 ]; do
  case $1 in
    -I) cpp_args+=("-I$2"); shift 2 ;;
    -D) cpp_args+=("-D$2"); shift 2 ;;
    --fct) fct=$2; shift 2 ;;
    --driver) driver=$2; shift 2 ;;
    --negative) negative=$2; shift 2 ;;
    --negative-fct) negative_fct=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "wp.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
sources=("$@")
if [ ${#sources[@]} -eq 0 ] || [ -z "$fct" ]; then
  echo "prove-$name: no sources or no --fct" >&2
  exit 2
fi
for tool in frama-c why3 z3 cvc4; do
  if ! command -v "$tool" > /dev/null; then
    echo "prove-$name: $tool not found; run 'make deps' (the components' apt-packages.txt)" >&2
    exit 2
  fi
done
rm -rf "$out/session"  # every run proves afresh: no result is taken from a cache
mkdir -p "$out"
# A configuration of our own, so the provers found are this machine's and no user's settings
# (time or memory limits) change what is proved.
why3 config detect -C "$out/why3.conf" > "$out/why3-detect.log" 2>&1
export WHY3CONFIG=$out/why3.conf
common=(-machdep gcc_x86_32 -c11 -cpp-extra-args="${cpp_args[*]}"
  -wp -wp-rte -wp-model Typed+int+float -wp-prover cvc4,z3 -wp-par 1
  -wp-session "$out/session" -wp-cache none -wp-warn-key "pedantic-assigns=inactive")
if [ -n "$driver" ]; then common+=(-wp-driver "$driver"); fi

# Runs WP over the given functions and sources; sets run_proved, run_total, run_ok.
run_wp() {
  local run=$1 fcts=$2 rc=0
  shift 2
  local log=$out/$run.log select=()
  if [ -n "$fcts" ]; then select=(-wp-fct "$fcts"); fi
  frama-c "${common[@]}" "${select[@]}" "$@" > "$log" 2>&1 || rc=$?
  read -r run_proved run_total < <(sed -n 's/^\[wp\] Proved goals: *\([0-9]*\) *\/ *\([0-9]*\).*/\1 \2/p' "$log" | tail -n 1) || true
  run_ok=1
  if [ "$rc" -ne 0 ] || [ -z "${run_total:-}" ] || [ "${run_total:-0}" -eq 0 ] \
     || grep -qE "\[kernel\].*(error|Error)|user error|Ignoring (global|loop|logic|code) annotation|^\[wp\] Failure" "$log"; then
    echo "prove-$name[$run]: analysis did not complete (rc=$rc); see $log"
    grep -E "error|Error|Ignoring|Failure" "$log" | sed "s|$root/||g" | head -n 20 || true
    run_ok=0
    run_proved=${run_proved:-0}
    run_total=${run_total:-1}
  fi
}

# Every goal of a log as "NAME Valid" or "NAME Failed" (a failed goal's line has no status).
goal_lines() {
  sed -n 's/^\[wp\] \[[^]]*\] Goal \([A-Za-z0-9_]*\)\( : Valid\)\{0,1\}.*$/\1 \2/p' "$1" \
    | awk '{ print $1, $2 == ":" ? "Valid" : "Failed" }'
}

# One line per contract: goals are named <model>_<function>_<kind>_<property>[_partN].
summarize() {
  local log=$1 fcts=$2
  goal_lines "$log" | awk -v fcts="$fcts" '
      BEGIN { n = split(fcts, f, ",") }
      { goal = $1; ok = ($2 == "Valid"); key = goal
        for (i = 1; i <= n; ++i) { p = index(goal, "_" f[i] "_")
          if (p > 0) { key = f[i] ": " substr(goal, p + length(f[i]) + 2); break } }
        sub(/_part[0-9]+$/, "", key); sub(/_2$|_[0-9]+$/, "", key)
        if (!(key in total)) order[++k] = key
        total[key]++; proved[key] += ok }
      END { for (i = 1; i <= k; ++i) printf "  %-78s %d of %d%s\n", order[i], proved[order[i]],
              total[order[i]], proved[order[i]] == total[order[i]] ? "" : "  NOT PROVED" }'
}

if [ -n "$negative" ]; then
  # Every goal the negative control plants must fail, and there must be some.
  run_wp negative "$negative_fct" -wp-timeout 10 "$negative"
  planted=$(goal_lines "$out/negative.log" | awk '$1 ~ /_ensures_planted_/' | wc -l)
  planted_proved=$(goal_lines "$out/negative.log" | awk '$1 ~ /_ensures_planted_/ && $2 == "Valid"' | wc -l)
  if [ "$run_ok" -ne 1 ] || [ "$planted" -eq 0 ] || [ "$planted_proved" -ne 0 ]; then
    echo "prove-$name: the negative control's planted defects were not all flagged ($planted_proved of $planted proved); the setup is broken (see $out/negative.log)" >&2
    exit 1
  fi
  echo "prove-$name: negative control: $planted planted contracts, none proved"
fi

start=$(date +%s)
run_wp contracts "$fct" -wp-timeout "$timeout" "${sources[@]}"
summarize "$out/contracts.log" "$fct" | sed "s|$root/||g"
echo "goals: $run_proved proved of $run_total"
echo "metric: wp_${name}_goals $run_total goals"
echo "metric: wp_${name}_unproved $((run_total - run_proved)) goals"
echo "metric: wp_${name}_seconds $(( $(date +%s) - start )) s"
if [ "$run_ok" -ne 1 ] || [ "$run_proved" -ne "$run_total" ]; then
  echo "prove-$name: WP FAILED: some goal not proved (logs in $out)"
  exit 1
fi
echo "prove-$name: every goal proved (logs in $out)"
