#!/usr/bin/env bash
# Installs what drone_ros needs on a Debian 12 machine: Debian packages (apt, as root or via
# sudo) and PyPI packages into .venv. Idempotent: a second run checks and installs nothing.
set -euo pipefail
shopt -s nullglob
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

mapfile -t wanted < <(cat tools/apt-packages.txt */apt-packages.txt */*/apt-packages.txt | sed 's/#.*//' | tr -s ' \t' '\n' | grep -v '^$' | sort -u)
missing=()
for pkg in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install_deps: apt installing ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

venv=.venv
if [ ! -x "$venv/bin/python" ]; then
  /usr/bin/python3 -m venv --system-site-packages "$venv"
fi
stamp="$venv/.requirements.sha256"
sum=$(cat requirements.txt */requirements.txt */*/requirements.txt | sha256sum | cut -d' ' -f1)
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$sum" ]; then
  echo "install_deps: pip installing requirements into $venv"
  cat requirements.txt */requirements.txt */*/requirements.txt > "$venv/requirements.all.txt"
  "$venv/bin/pip" install -q --disable-pip-version-check -r "$venv/requirements.all.txt"
  echo "$sum" > "$stamp"
fi
