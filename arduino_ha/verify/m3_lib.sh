# Cortex-M3 build steps shared by verify/cross_size.sh and pil/build_pil_image.sh (sourced).

# m3_compile OBJ_DIR SRC...: compiles each source with the caller's m3_cflags array into OBJ_DIR
# (run there, so -fstack-usage and -fcallgraph-info files land beside the objects) and appends
# the objects to the caller's m3_objects array.
m3_compile() {
  local dir=$1 src obj
  shift
  for src in "$@"; do
    obj=$dir/$(basename "${src%.c}").o
    (cd "$dir" && arm-none-eabi-gcc "${m3_cflags[@]}" -c "$src" -o "$obj")
    m3_objects+=("$obj")
  done
}

# m3_sizes ELF: prints "text data bss" of a linked image (text with .ARM.exidx).
m3_sizes() {
  arm-none-eabi-size -A "$1" | awk '
    $1 == ".text" || $1 == ".ARM.exidx" { t += $2 } $1 == ".data" { d += $2 } $1 == ".bss" { b += $2 }
    END { print t + 0, d + 0, b + 0 }'
}
