#!/usr/bin/env bash
# Renders the pictures of docs/viewer.md with the viewer itself: each picture is a short session
# (the key presses and clicks written below, in vtkInteractorEventRecorder's format) played into
# `cloudvis view --play` with --window-image, which saves the whole window as the session left
# it. Clicks go where the viewer says its points and views are: a first playback writes
# --state-file, whose pixel positions the session then uses. Rerun after a change to the viewer,
# look at every image, and commit them.
#
#   docs/scripts/make-viewer-images.sh [-s WxH] [-d VOXELS] [CLOUDVIS [OUTPUT_DIR]]
#
# CLOUDVIS defaults to ./build/bin/cloudvis, OUTPUT_DIR to docs/images (both relative to the
# current directory). -s sets the window size (default 560x480), -d field.dimensions (default
# 96). The tests run it small into a scratch folder. Without $DISPLAY it runs itself again under
# xvfb-run.
set -euo pipefail
. "$(dirname "$0")/ImageScripts.sh"

size=560x480
dimensions=96
read_options "s=size d=dimensions" 9,14 "$@"
cloudvis=${operands[0]:-./build/bin/cloudvis}
out=${operands[1]:-docs/images}
on_a_display "$@"
require_cloudvis "$cloudvis"
mkdir -p "$out"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# The default cloud, seen from above and to the side, lit by the directional derivative.
common=(--size "$size" --set "field.dimensions=$dimensions" --set render.accumulate=8
  --set render.lighting=derivative --set 'camera.orbit={"azimuth": 35, "elevation": 25}')

# session NAME [VIEW OPTIONS...] < EVENTS: plays the events (one per line, no header) and saves
# the window as $out/NAME.png; the viewer's state as it ended is in $scratch/NAME.json.
session() {
  local name=$1
  shift
  { echo "# StreamVersion 1.1"; cat; } > "$scratch/$name.log"
  "$cloudvis" view "${common[@]}" "$@" --play "$scratch/$name.log" \
    --state-file "$scratch/$name.json" --window-image "$out/$name.png" > /dev/null
}

# key SYMBOL: a key press event ("m", "4", "Return"); its character is the symbol's first byte.
key() {
  local code
  case "$1" in
    Return) code=13 ;;
    space) code=32 ;;
    period) code=46 ;;
    *) code=$(printf '%d' "'$1") ;;
  esac
  echo "KeyPressEvent 10 10 0 $code 1 $1"
}

# click X Y: a left click at window pixels from the bottom left.
click() {
  echo "MouseMoveEvent $1 $2 0 0 0 0"
  echo "LeftButtonPressEvent $1 $2 0 0 0 0"
  echo "LeftButtonReleaseEvent $1 $2 0 0 0 0"
}

# probe X Y: a Control+left click (modifier bit 2), which probes a slice in the 3D view.
probe() {
  echo "MouseMoveEvent $1 $2 0 0 0 0"
  echo "LeftButtonPressEvent $1 $2 2 0 0 0"
  echo "LeftButtonReleaseEvent $1 $2 2 0 0 0"
}

# pixel NAME KEY LINE: the LINE-th "x y" of state NAME KEY, in whole pixels.
pixel() {
  local x y
  read -r x y <<< "$(state "$1" "$2" | sed -n "$3p")"
  echo "${x%.*} ${y%.*}"
}

# state NAME KEY: the numbers of a JSON array of arrays in the state of session NAME, as
# "x y" lines ("opacity_point_pixels") or of an object's array ("axial").
state() {
  grep -o "\"$2\":\[[^]]*\(\]\(,\[[^]]*\]\)*\]\)\?" "$scratch/$1.json" | head -1 |
    sed -e "s/\"$2\"://" -e 's/\],\[/\n/g' -e 's/[][]//g' -e 's/,/ /g'
}

# The 3D view with the slice across z and a probed voxel, whose readout stays at the bottom.
session viewer-3d <<< "$(key z)"
read -r x0 y0 x1 y1 <<< "$(state viewer-3d 3d)"
session viewer-3d <<< "$(key z; probe $(((x0 + x1) / 2 + (x1 - x0) / 40)) $(((y0 + y1) / 2 + (y1 - y0) / 40)))"
grep -q '"valid":true' "$scratch/viewer-3d.json" || { echo "make-viewer-images.sh: the probe missed the slice" >&2; exit 1; }

# Four views: a click in the axial view moves the crosshair (the other two slices) there.
session viewer-four <<< "$(key 4)"
read -r x0 y0 x1 y1 <<< "$(state viewer-four axial)"
session viewer-four <<< "$(key 4; key x; key y; key z; click $(((x0 + x1) / 2 + (x1 - x0) / 20)) $(((y0 + y1) / 2 + (y1 - y0) / 30)))"

# The editor: the middle opacity point selected (its values in the editor's info line), then
# Enter and new values typed, not yet applied.
session viewer-editor < /dev/null
read -r px py <<< "$(pixel viewer-editor opacity_point_pixels 3)"
session viewer-editor <<< "$(click "$px" "$py"; key Return; key 0; key period; key 4; key 5; key space; key 0; key period; key 6)"
grep -q '"typing":true' "$scratch/viewer-editor.json" || { echo "make-viewer-images.sh: no point was selected at $px $py" >&2; exit 1; }

# The color palette: the middle color point selected shows it, and a click on a swatch (the
# eighth hue, an azure) gives the point that color.
session viewer-palette < /dev/null
read -r cx cy <<< "$(pixel viewer-palette color_point_pixels 2)"
session viewer-palette <<< "$(click "$cx" "$cy")"
grep -q '"palette_visible":true' "$scratch/viewer-palette.json" || { echo "make-viewer-images.sh: no color point was selected at $cx $cy" >&2; exit 1; }
read -r x0 y0 x1 y1 <<< "$(state viewer-palette palette_pixels)"
x0=${x0%.*}
y1=${y1%.*}
session viewer-palette <<< "$(click "$cx" "$cy"; click $((x0 + 91)) $((y1 - 8)))"

# The help: its first page, the key list in two columns, and its second, the mouse.
session viewer-help <<< "$(key h)"
session viewer-help-mouse <<< "$(key h; key h)"

for image in viewer-3d viewer-four viewer-editor viewer-palette viewer-help viewer-help-mouse; do
  bytes=$(stat -c %s "$out/$image.png")
  if ((bytes > 200 * 1024)); then
    echo "make-viewer-images.sh: warning: $out/$image.png is $((bytes / 1024)) KB (keep them under 200 KB)" >&2
  fi
done
