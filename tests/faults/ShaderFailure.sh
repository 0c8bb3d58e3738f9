#!/usr/bin/env bash
# A march shader the driver refuses: Mesa can dump every shader it compiles
# (MESA_SHADER_DUMP_PATH, files named <stage>_<sha1>.glsl) and replace a shader by the file of
# the same name in MESA_SHADER_READ_PATH. A first render dumps the shaders; the one declaring
# EmptyDistanceTexture is the mapper's march pass; a second render reads a broken copy in its
# place and must fail with status 1, the mapper's message, and no image. This needs no change to
# the mapper. Exits 77 (skipped) when the driver is not Mesa or does not dump shaders.
# usage: ShaderFailure.sh CLOUDVIS WORK_DIR SCENE
set -euo pipefail
cloudvis=$1 work=$2 scene=$3

rm -rf "$work"
mkdir -p "$work/dump" "$work/read"
cd "$work"
render=("$cloudvis" render "$scene" -o r.png --size 64x48 --set render.accumulate=1
  --set field.dimensions=16)

MESA_SHADER_DUMP_PATH="$work/dump" "${render[@]}" > /dev/null
march=$(grep -l "EmptyDistanceTexture" dump/FS_*.glsl 2> /dev/null | head -n 1 || true)
if [ -z "$march" ]; then
  echo "SKIP: the driver dumped no march shader (not Mesa, or MESA_SHADER_DUMP_PATH unsupported)"
  exit 77
fi
printf '#version 150\nthis line is not GLSL;\n' > "read/$(basename "$march")"
rm -f r.png

status=0
MESA_SHADER_READ_PATH="$work/read" "${render[@]}" > stdout.txt 2> stderr.txt || status=$?
failed=0
if [ "$status" -ne 1 ]; then
  echo "FAIL: exit status $status, expected 1" >&2
  failed=1
fi
if ! grep -q "the march shader failed to compile or link" stderr.txt; then
  echo "FAIL: stderr does not name the shader failure:" >&2
  cat stderr.txt >&2
  failed=1
fi
if ! grep -q "(VTK: .*shader" stderr.txt; then
  echo "FAIL: stderr does not quote VTK's report of the failed shader:" >&2
  cat stderr.txt >&2
  failed=1
fi
if [ -e r.png ]; then
  echo "FAIL: an image was written although the shader failed" >&2
  failed=1
fi
[ "$failed" -eq 0 ] && echo "march shader replaced by a broken one: $(cat stderr.txt)"
exit "$failed"
