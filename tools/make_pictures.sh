#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Renders the README's pictures into docs/images/ with `elan view --screenshot` and `--frames`
# (off screen; under Xvfb when there is no display), and assembles two animations with
# ImageMagick: a pyramid knocked down by a ball, and a pile of a thousand bodies forming.
#   tools/make_pictures.sh [path/to/elan]     (default: build/release/tools/elan)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
elan=${1:-build/release/tools/elan}
out=docs/images
mkdir -p "$out"
[ -x "$elan" ] || { echo "make_pictures: no elan binary at $elan (build it: tools/setup.sh)" >&2; exit 2; }
command -v convert >/dev/null || { echo "make_pictures: ImageMagick's convert is missing (apt-get install imagemagick)" >&2; exit 2; }
# Without a display, everything runs in one Xvfb server (Mesa's software renderer).
if [ -z "${DISPLAY:-}" ]; then
  command -v xvfb-run >/dev/null || { echo "make_pictures: no display and no xvfb-run (apt-get install xvfb xauth)" >&2; exit 2; }
  exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$0" "$@"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# A picture: SCENE NAME STEPS CAMERA. Reduced to 256 colours (flat-shaded scenes lose nothing
# visible) so each PNG stays well under 200 KB.
shot() {
  "$elan" view "$1" --screenshot "$tmp/$2.png" --steps "$3" --size 800x450 --camera "$4" >/dev/null
  convert "$tmp/$2.png" -dither None -colors 256 "PNG8:$out/$2.png"
  echo "$out/$2.png: $(stat -c %s "$out/$2.png") bytes"
}
shot scenes/pyramid20.json pyramid 0 "24,17,34,0,7,0"
shot scenes/pile1k.json pile 600 "0,30,18,0,0,0"
shot scenes/ragdolls.json ragdolls 150 "5,7,12,1,0.5,-1"
shot scenes/geometry_demo.json geometry_demo 100 "7,8,13,-1,1,0"

# An animation: SCENE NAME STEPS EVERY CAMERA; 480x270 frames at 25 frames a second.
animate() {
  rm -rf "$tmp/frames"
  "$elan" view "$1" --frames "$tmp/frames" --steps "$3" --every "$4" --size 480x270 --camera "$5" >/dev/null
  convert -delay 4 -loop 0 "$tmp"/frames/frame_*.png -dither None -colors 96 -layers Optimize "$out/$2.gif"
  echo "$out/$2.gif: $(stat -c %s "$out/$2.gif") bytes"
}
# A pyramid of ten rows, and a heavy ball rolled into its base.
cat > "$tmp/pyramid_hit.json" <<'JSON'
{
  "bodies": [
    {"name": "ground", "motion": "static", "shape": {"type": "box", "half_extents": [30, 1, 30]},
     "position": [0, -1, 0]},
    {"name": "ball", "shape": {"type": "sphere", "radius": 1.2}, "density": 3000,
     "position": [-14, 1.2, 0], "linear_velocity": [16, 0, 0]}
  ],
  "generators": [{"type": "pyramid", "base": 10, "half_extent": 0.5, "origin": [0, 0, 0]}]
}
JSON
animate "$tmp/pyramid_hit.json" pyramid_falling 210 3 "6,8,20,0,3,0"
animate scenes/pile1k.json pile_forming 360 5 "0,30,20,0,2,0"
