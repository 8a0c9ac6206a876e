#!/usr/bin/env bash
# Installs the Debian packages that building, testing and rendering need.
# Idempotent: when everything is present it only asks dpkg and returns.
set -euo pipefail
packages=(g++ cmake make git libeigen3-dev libcli11-dev libboost-test-dev nlohmann-json3-dev
          paraview-dev libpython3-dev python3-paraview paraview xvfb xauth imagemagick
          libopenmpi-dev openmpi-bin)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "setup: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
