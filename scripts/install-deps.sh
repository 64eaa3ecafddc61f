#!/usr/bin/env bash
# Installs the Debian 12 packages passim builds with, if any is missing.
# The Python package (python/): pybind11 and the headers build its module; numpy and matplotlib
# draw the figures (docs/python.md).
# --test: also what the test suite needs beyond the build (Chromium for the HTML report test,
#         pytest and pandas for the Python tests, oiiotool for the image files' widths,
#         clang and its runtime for the libFuzzer targets, Slurm and MUNGE for the one-node
#         cluster the Slurm study test starts: tests/slurm/), python3-snappy for the hostile
#         apitrace cases (tests/hostile/).
set -euo pipefail
packages=(build-essential cmake pkg-config libgl-dev libglm-dev libopenimageio-dev libcli11-dev
          nlohmann-json3-dev libfmt-dev libtinyobjloader-dev libgtest-dev libbenchmark-dev libosmesa6-dev libsnappy-dev fonts-dejavu-core
          libpng-dev python3 python3-dev pybind11-dev python3-numpy python3-matplotlib)
if [ "${1:-}" = "--test" ]; then
  packages+=(chromium clang libclang-rt-14-dev slurm-wlm munge python3-pytest python3-pandas openimageio-tools python3-snappy)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "passim: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "passim: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo=sudo
fi
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
