#!/usr/bin/env bash
# Renders the pictures of docs/user-guide.md with cloudvis itself, so the guide shows what the
# program really draws. Every command here is one the guide prints; rerun this script after a
# change to the renderer, look at the images, and commit them.
#
#   docs/scripts/make-guide-images.sh [-s WxH] [-g WxH] [-a FRAMES] [-d VOXELS] [CLOUDVIS [OUTPUT_DIR]]
#
# CLOUDVIS defaults to ./build/bin/cloudvis, OUTPUT_DIR to docs/images (both relative to the
# current directory). -s sets the image size (default 480x360; compare panels are half as wide
# and high), -g the size of the cloud-type gallery (default 1280x720; each of its pictures prints
# the seconds it took), -a the frames accumulated (default 8), -d overrides field.dimensions
# (default: the scenes' own). The tests run it at a tiny size into a scratch folder. Without
# $DISPLAY it runs itself again under xvfb-run.
set -euo pipefail
. "$(dirname "$0")/ImageScripts.sh"

size=480x360
accumulate=8
dimensions=""
gallery=1280x720
read_options "s=size g=gallery a=accumulate d=dimensions" 6,14 "$@"
cloudvis=${operands[0]:-./build/bin/cloudvis}
out=${operands[1]:-docs/images}
on_a_display "$@"
require_cloudvis "$cloudvis"

scenes=$(cd "$(dirname "$0")/../../data/scenes" && pwd)
mkdir -p "$out"
common=(--set "render.accumulate=$accumulate")
if [[ -n "$dimensions" ]]; then
  common+=(--set "field.dimensions=$dimensions")
fi
width=${size%x*}
height=${size#*x}
half="$((width / 2))x$((height / 2))"

# render NAME SCENE [OPTIONS...]: one picture, $out/NAME.png.
render() {
  local name=$1 scene=$2
  shift 2
  "$cloudvis" render "$scenes/$scene" -o "$out/$name.png" --size "$size" "${common[@]}" "$@"
}

# The picture at the top of the guide (and the README): the cumulus make demo renders.
render hero cumulus.json

# Cloud types and cloudscapes (the cloud density model), and the old default beside the cumulus,
# both under the light march.
render clouds-cumulus cumulus.json
render clouds-fbm-sphere fbm-sphere.json --lighting march \
  --set 'background={"type": "sky", "sun": [0.5, 0.8, 0.3]}' --set 'ambient={"strength": 0.6}' \
  --set 'lights=[{"type": "directional", "position": [0.5, 0.8, 0.3], "intensity": 1.2}]' \
  --set 'camera.orbit={"azimuth": 20, "elevation": 2, "distance": 6.5}' \
  --set render.display=filmic --exposure auto

# The gallery of cloud types (docs/user-guide.md), each from its scene's own camera, a viewpoint
# a photographer would choose, at the gallery's size.
for scene in cumulus congestus cumulonimbus altocumulus stratocumulus stratus cloudscape-ground; do
  started=$SECONDS
  "$cloudvis" render "$scenes/$scene.json" -o "$out/gallery-$scene.png" --size "$gallery" \
    "${common[@]}"
  echo "gallery-$scene.png: $((SECONDS - started)) s"
done
# And the cloudscape straight from above, beside the statistics it is measured by.
render clouds-cloudscape-above cloudscape-above.json

# Droplet optics (docs/lighting.md): the cloudbow and the glory, path traced.
# Square, as the ring is round; 64 paths per pixel for every frame the other pictures accumulate.
"$cloudvis" render "$scenes/cloudbow.json" -o "$out/cloudbow.png" --size "${height}x${height}" \
  --spp "$((64 * accumulate))"

# The tour: the article's cloud as its scene says (the directional derivative), closer than the
# default camera, then with the other two lighting models, then all three side by side.
closer=(--set 'camera.orbit={"distance": 6}')
render tour-render fbm-sphere.json "${closer[@]}"
render tour-none fbm-sphere.json "${closer[@]}" --lighting none
render tour-march fbm-sphere.json "${closer[@]}" --lighting march
if "$cloudvis" --help | grep -q '^  compare '; then
  "$cloudvis" compare "$scenes/fbm-sphere.json" -o "$out/tour-compare.png" --size "$half" \
    --lighting none,derivative,march "${closer[@]}" "${common[@]}"
fi

# Transfer-function presets. fbm-sphere.json spells out its transfer function, and a scene's own
# keys win over a preset's, so the whole section is replaced.
for preset in cloud-dusk thin-haze paraview-example; do
  render "preset-$preset" fbm-sphere.json "${closer[@]}" \
    --set "transfer_function={\"preset\": \"$preset\"}"
done
render preset-density-heat fbm-sphere.json "${closer[@]}" --lighting none \
  --set 'transfer_function={"preset": "density-heat"}'

# Backgrounds and the camera orbit.
render background-gradient fbm-sphere.json "${closer[@]}" \
  --set 'background={"type": "gradient", "top": [0.1, 0.2, 0.45], "bottom": [0.8, 0.6, 0.5]}'
render background-sky fbm-sphere.json \
  --set 'background={"type": "sky"}' \
  --set 'camera.orbit={"azimuth": 35, "elevation": -12, "distance": 7}'
render camera-orbit fbm-sphere.json \
  --set 'camera.orbit={"azimuth": 60, "elevation": 35, "distance": 6}'

# Pictures are committed: keep them small (the gallery's, at 1280 x 720, under 600 KB).
for image in "$out"/*.png; do
  bytes=$(stat -c %s "$image")
  limit=150
  if [[ "$(basename "$image")" == gallery-* ]]; then
    limit=600
  fi
  if ((bytes > limit * 1024)); then
    echo "make-guide-images.sh: warning: $image is $((bytes / 1024)) KB (keep it under $limit KB)" >&2
  fi
done
