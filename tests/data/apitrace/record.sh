#!/usr/bin/env bash
# Re-records the apitrace test data (README.md): builds each program in programs/, runs it
# under `apitrace trace` in Xvfb with Debian 12's Mesa (llvmpipe), and keeps NAME.trace and
# the reference images the program saved itself with glReadPixels. Not run by the tests:
# they use the committed files. Needs: apitrace xvfb xauth libgl-dev libx11-dev libopenimageio-dev.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for src in "$here"/programs/*.cpp; do
  name="$(basename "$src" .cpp)"
  g++ -std=c++20 -O1 -Wall "$src" -o "$work/$name" $(pkg-config --cflags --libs OpenImageIO) -lGL -lX11
  mkdir -p "$work/run-$name"
  (cd "$work/run-$name" &&
   xvfb-run -a -s "-screen 0 640x480x24" apitrace trace -o "$here/$name.trace" "$work/$name" >/dev/null)
  cp "$work/run-$name"/*.png "$here/"
  echo "recorded $name.trace ($(stat -c %s "$here/$name.trace") bytes) and $(ls "$work/run-$name" | tr '\n' ' ')"
done
apitrace version 2>/dev/null || dpkg-query -W -f='apitrace ${Version}\n' apitrace
dpkg-query -W -f='Mesa ${Version}\n' libgl1-mesa-dri
