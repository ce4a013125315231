# Sourced (not run) by check_user_workspace.sh (`make check-user-ws`) and check_install_space.sh
# (`make check-install`): both build a fresh clone of this repository's HEAD in a new catkin
# workspace the way a user would, from a clean login environment, so nothing of this checkout's
# .build, venv or sourced workspace can stand in for what the clone lacks.

# The login environment: no workspace sourced, no venv or pyenv on PATH.
login_env=(env -i HOME="$HOME" LANG=C.UTF-8 PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin)

# new_workspace CHECK NAME [DIR]: sets ws to DIR (default: a new folder /tmp/drone_ros_NAME_ws.*),
# removed on exit unless KEEP=1, and clones the HEAD of $root (the caller's checkout) into
# $ws/src/drone_ros.
new_workspace() {
  local check=$1 name=$2
  ws=${3:-$(mktemp -d "/tmp/drone_ros_${name}_ws.XXXXXX")}
  if [ -z "${KEEP:-}" ]; then trap 'rm -rf "$ws"' EXIT; fi
  mkdir -p "$ws/src"
  git clone -q "$root" "$ws/src/drone_ros"
  echo "$check: clone of $(git -C "$ws/src/drone_ros" rev-parse --short HEAD) in $ws/src/drone_ros"
}

# build_workspace CHECK ARG...: `catkin_make ARG...` in $ws from the login environment, its output
# in $ws/catkin_make.log; sets build_s to its seconds. On failure the log's tail is shown and the
# check ends.
build_workspace() {
  local check=$1 start
  shift
  start=$(date +%s)
  if ! (cd "$ws" && "${login_env[@]}" catkin_make "$@" > "$ws/catkin_make.log" 2>&1); then
    tail -n 60 "$ws/catkin_make.log"
    echo "$check: catkin_make failed in $ws (KEEP=1 keeps the workspace)"
    exit 1
  fi
  build_s=$(( $(date +%s) - start ))
}
