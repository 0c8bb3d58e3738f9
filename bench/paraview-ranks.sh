#!/usr/bin/env bash
# cloudvis in ParaView on 1, 2 and 4 ranks (docs/performance.md, "ParaView across ranks"): the
# time per frame of pvbatch drawing one field as a Cloud Volume with the march on each rank count,
# its ratio to one rank, the peak memory of each rank, and `cloudvis render --benchmark` of the
# same scene on one process beside them.
# Usage: bench/paraview-ranks.sh [BUILD_DIR] [FRAMES] [DIMENSIONS]
#   (default build, 12 frames, 128,512,128: tests/paraview/scenes/shadow.json's slab and cloud)
# Run it under Xvfb (xvfb-run -a -s "-screen 0 1280x1024x24 -noreset") without a display.
set -euo pipefail
build=${1:-build}
frames=${2:-12}
dimensions=${3:-128,512,128}
here=$(cd "$(dirname "$0")" && pwd)
scene="$here/../tests/paraview/scenes/shadow.json"
export CLOUDVIS_PARAVIEW_PLUGIN="$build/paraview/lib/paraview-5.11/plugins/CloudVis/CloudVis.so"
export PYTHONPATH="$build/paraview-prefix/python/usr/lib/python3/dist-packages:$here/../tests/paraview"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Open MPI on one machine, as the tests run it (tests/paraview/RunPvbatch.cmake).
export OMPI_MCA_plm_rsh_agent= OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

"$build/bin/cloudvis" generate "$scene" --set "field.dimensions=$dimensions" -o "$work/field.vti" > /dev/null
echo "field: $dimensions voxels (float), scene $scene, $frames frames, each marched anew"
printf 'cloudvis render, one process: '
"$build/bin/cloudvis" render "$scene" --set "field.dimensions=$dimensions" -o "$work/cloudvis.png" -q \
  --benchmark "$frames" | tail -1
one=""
for ranks in 1 2 4; do
  line=$(mpirun -np "$ranks" pvbatch --symmetric --force-offscreen-rendering "$here/paraview/ranks.py" \
    "$work/field.vti" "$scene" "$frames" 2> /dev/null | grep "^ranks")
  ms=$(echo "$line" | sed -E 's/^ranks [0-9]+: ([0-9.]+) ms.*/\1/')
  one=${one:-$ms}
  echo "$line; $(awk -v a="$ms" -v b="$one" 'BEGIN { printf "%.2fx the time of one rank", a / b }')"
done
