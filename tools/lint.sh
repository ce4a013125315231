#!/usr/bin/env bash
# `make lint` after catkin_lint:
#  1. layout: clang-format (.clang-format) must leave every file of tools/clang_format_checked.txt
#     unchanged, and every tracked C/C++ source outside generated/ must be listed there or in
#     tools/clang_format_generated.txt (checked in as generated), so a new file is placed on purpose;
#  2. naming: clang-tidy's readability-identifier-naming (.clang-tidy) over the C++ nodes, with
#     the workspace's compile_commands.json (`make build` exports it);
#  3. Python: pyflakes (requirements.txt) over every tracked .py file: unused imports and
#     variables, undefined names;
#  4. size: no function over 80 lines (lizard) in the C, C++ and Python outside tests (test/,
#     test_*, *_test.*) and generated/ folders: a longer one is split into the steps it does.
# usage: lint.sh WS
set -uo pipefail
ws=${1:?usage: lint.sh WS}
root=$(cd "$(dirname "$0")/.." && pwd)
checked=$root/tools/clang_format_checked.txt
generated=$root/tools/clang_format_generated.txt
status=0
for tool in clang-format run-clang-tidy; do
  if ! command -v "$tool" > /dev/null; then
    echo "lint: $tool not found; run 'make deps' (tools/apt-packages.txt)" >&2
    exit 2
  fi
done
cd "$root" || exit 2

listed() { sed 's/#.*//; s/[[:space:]]*$//; /^$/d' "$@"; }
unlisted=$(comm -23 <(git ls-files '*.c' '*.cpp' '*.h' '*.hpp' | grep -v '/generated/' | LC_ALL=C sort) \
  <(listed "$checked" "$generated" | LC_ALL=C sort -u))
if [ -n "$unlisted" ]; then
  echo "lint: C/C++ files in neither tools/clang_format_checked.txt nor tools/clang_format_generated.txt:"
  echo "$unlisted" | sed 's/^/  /'
  status=1
fi
mapfile -t files < <(listed "$checked")
missing=0
for f in "${files[@]}"; do
  [ -f "$f" ] || { echo "lint: $f is listed in tools/clang_format_checked.txt but does not exist"; missing=1; }
done
[ $missing -eq 0 ] || status=1
if out=$(clang-format --dry-run --Werror "${files[@]}" 2>&1); then
  echo "lint: clang-format: ${#files[@]} files as .clang-format lays them out"
else
  echo "$out" | grep -E '^[^ ].*(warning|error):' | sed 's/ \[-Wclang-format-violations\]//' | sort -u -t: -k1,1
  echo "lint: clang-format would change the files above (clang-format -i <file>)"
  status=1
fi

db=$ws/build
if [ ! -f "$db/compile_commands.json" ]; then
  echo "lint: $db/compile_commands.json missing; run 'make build'" >&2
  exit 2
fi
# The nodes as the workspace compiles them (through its src/drone_ros link).
nodes="/src/drone_ros/(drone_ros/(common|arduino_link|controller)|microhard_gs|vn200_driver)/src/.*\.cpp$"
if out=$(run-clang-tidy -quiet -j 2 -p "$db" "$nodes" 2>&1); then
  echo "lint: clang-tidy naming: the C++ nodes follow .clang-tidy"
else
  echo "$out" | grep -E 'error:|warning:' | sed 's|.*/src/drone_ros/||' | sort -u
  echo "lint: clang-tidy naming failed (.clang-tidy)"
  status=1
fi

# venv_check TOOL OK_LINE FAIL_LINE ARGS...: runs the venv's TOOL (requirements.txt) over ARGS;
# prints OK_LINE, or TOOL's findings and FAIL_LINE.
venv_check() {
  local tool=$root/.venv/bin/$1 ok=$2 fail=$3 out
  shift 3
  if [ ! -x "$tool" ]; then
    echo "lint: $tool not found; run 'make deps' (requirements.txt)" >&2
    exit 2
  fi
  if out=$("$tool" "$@" 2>&1); then
    echo "lint: $ok"
  else
    echo "$out" | sed "s|^$root/||"
    echo "lint: $fail"
    status=1
  fi
}

mapfile -t pyfiles < <(git ls-files '*.py')
venv_check pyflakes "pyflakes: ${#pyfiles[@]} Python files clean" "pyflakes failed" "${pyfiles[@]}"

mapfile -t sources < <(git ls-files '*.c' '*.cpp' '*.h' '*.py' |
  grep -vE '(^|/)(test|tests|generated)/|(^|/)test_[^/]*$|_test\.[a-z]+$')
venv_check lizard "lizard: no function over 80 lines in ${#sources[@]} source files" \
  "functions over 80 lines (split each into the steps it does)" \
  --length 80 --CCN 1000 --warnings_only "${sources[@]}"
exit $status
