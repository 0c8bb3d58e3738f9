#!/usr/bin/env bash
# Makes docs/images/paraview-gui.png, the picture of docs/paraview.md's "In the ParaView window":
# ParaView's own window with the plugin's cloud in the render view, the Cloud Density source in
# the pipeline browser and the Cloud Volume representation's Cloud Lighting group in the
# Properties panel. The real `paraview` binary draws it on a private Xvfb display (no $DISPLAY
# needed), driven as the test of the window drives it (tests/paraview/paraview_gui.py, the scene
# in tests/paraview/gui_scene.py); the picture is a capture of that screen. Rerun it after a change
# to the plugin or the renderer, look at the picture, and commit it.
#
#   docs/scripts/make-paraview-image.sh [BUILD_DIR [OUTPUT.png]]
#
# BUILD_DIR is a cloudvis build with the plugin (CLOUDVIS_PARAVIEW, the default; ./build if not
# given), OUTPUT defaults to docs/images/paraview-gui.png. Needs Xvfb, ImageMagick and xdotool
# (cmake/debian-packages.txt).
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
out=${2:-docs/images/paraview-gui.png}
here=$(cd "$(dirname "$0")" && pwd)

plugin="$build/paraview/lib/paraview-5.11/plugins/CloudVis/CloudVis.so"
python_path="$build/paraview-prefix/python/usr/lib/python3/dist-packages"
if [[ ! -f "$plugin" || ! -d "$python_path" ]]; then
  echo "make-paraview-image.sh: no ParaView plugin in $build (build the target cloudvis-paraview)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Debian's python3, which has numpy, whatever python3 comes first on PATH.
CLOUDVIS_PARAVIEW_PLUGIN="$plugin" PYTHONPATH="$python_path" \
  /usr/bin/python3 "$here/../../tests/paraview/paraview_gui.py" picture "$out" "$work"
