#!/usr/bin/env bash
# A field of real LES size (docs/performance.md, "A field of 1 GiB"): a 1024 x 1024 x 256 float
# `ql` in kg/kg (1 GiB, bench/make-les-time-series.py) read by `cloudvis info` with its
# statistics, drawn by `cloudvis render` and opened by `cloudvis view` until its first picture has
# converged. Prints each one's wall time and peak resident memory (bench/peak-memory.py: all its
# processes summed, since the isolated read's child holds the file's values while the parent
# receives them), and the ratio of the peak to the field's 1 GiB. Its peer is ParaView's NetCDF
# reader on the same file (pvbatch, reading and drawing it as a volume), where pvbatch is
# installed.
# Usage: bench/large-field.sh [BUILD_DIR] [FIELD.nc]   (run under Xvfb: xvfb-run -a -s ...)
set -euo pipefail
build=${1:-build}
field=${2:-/tmp/cloudvis-les-1gib.nc}
here=$(cd "$(dirname "$0")" && pwd)
cloudvis="$build/bin/cloudvis"
if [ ! -f "$field" ]; then
  echo "writing $field (1024 x 1024 x 256 floats, about a minute)"
  /usr/bin/python3 "$here/make-les-time-series.py" "$field" 1024 1 256
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
field_mib=$(( $(stat -c %s "$field") / 1048576 ))
report() { # NAME "SECONDS KIB"
  read -r seconds kib <<< "$2"
  printf '%-40s %7.2f s  peak %6d MiB  (%.2fx the field)\n' "$1" "$seconds" $(( kib / 1024 )) \
    "$(echo "$kib / 1024 / $field_mib" | bc -l)"
}
peak="/usr/bin/python3 $here/peak-memory.py"
echo "field: $field, $field_mib MiB; peak: the resident memory of all the command's processes"
report "cloudvis info (statistics)" "$($peak "$cloudvis" info "$field")"
report "cloudvis render 800x600" "$($peak "$cloudvis" render "$field" -o "$work/render.png" -q)"
report "cloudvis view, to a converged picture" \
  "$($peak --until-converged "$work/state.json" "$cloudvis" view "$field" --state-file "$work/state.json")"
if command -v pvbatch > /dev/null; then
  paraview_python=$(sed -n 's/^CLOUDVIS_PARAVIEW_PYTHONPATH:INTERNAL=//p' "$build/CMakeCache.txt")
  report "ParaView: read and draw as a volume" "$($peak env PYTHONPATH="$paraview_python" pvbatch \
    --force-offscreen-rendering "$here/paraview/time_steps.py" "$field" 0)"
fi
