#!/usr/bin/env bash
# A full disk under every writer: cloudvis runs with WriteFailure.c preloaded, which lets a few
# bytes reach the files of the working directory (or those whose names end with a suffix) and
# then fails each write with ENOSPC (or, for the *_fsync cases, lets every write through and
# fails fsync with EIO). The output must be refused: status 1, one error line
# naming the output and the OS reason, the previous output byte for byte as it was, and no
# temporary or other file left behind (AtomicFile.h). Case "vdb_tmpfs" fills a real 16 KiB tmpfs
# instead, and exits 77 (skipped) where mounting one is not permitted (not root, no
# CAP_SYS_ADMIN).
# usage: FullDisk.sh CLOUDVIS SHIM WORK_DIR SCENES CASE
set -euo pipefail
cloudvis=$1 shim=$2 work=$3 scenes=$4 case=$5

rm -rf "$work"
mkdir -p "$work/run" "$work/probe"
cd "$work/run"

fields=(generate --set field.dimensions=32)
render=(render "$scenes/sphere.json" --size 32x24 --set field.dimensions=8 --set render.accumulate=1)
limit=3000 suffix= fsync= outputs=() command=() stderr=
case $case in
  vti) outputs=(out.vti) command=("${fields[@]}" -o out.vti)
    stderr="out\\.vti: cannot write the field: No space left on device" ;;
  vti_fsync) outputs=(out.vti) command=("${fields[@]}" -o out.vti) limit= fsync=1
    stderr="out\\.vti: cannot write the field: Input/output error \\(fsync\\)" ;;
  pvti) outputs=(out.pvti out_0.vti out_1.vti) command=("${fields[@]}" --pieces 2 -o out.pvti)
    stderr="out_[01]\\.vti: cannot write the field: No space left on device" ;;
  pvti_text) outputs=(out.pvti out_0.vti) command=("${fields[@]}" -o out.pvti) limit=10
    suffix=/out.pvti
    stderr="out\\.pvti: cannot write the parallel image data file: No space left on device" ;;
  vdb) outputs=(out.vdb) command=("${fields[@]}" -o out.vdb)
    stderr="out\\.vdb: cannot write the field as OpenVDB: No space left on device" ;;
  vdb_last_bytes) outputs=(out.vdb) command=("${fields[@]}" -o out.vdb) limit=all_but_one
    stderr="out\\.vdb: cannot write the field as OpenVDB: No space left on device" ;;
  vdb_fsync) outputs=(out.vdb) command=("${fields[@]}" -o out.vdb) limit= fsync=1
    stderr="out\\.vdb: cannot write the field as OpenVDB: Input/output error \\(fsync\\)" ;;
  vdb_tmpfs) outputs=(out.vdb) command=("${fields[@]}" -o out.vdb)
    stderr="out\\.vdb: cannot write the field as OpenVDB: No space left on device" ;;
  png) outputs=(out.png) command=("${render[@]}" -o out.png) limit=300
    stderr="out\\.png: cannot write the PNG image: No space left on device" ;;
  exr) outputs=(out.exr) command=("${render[@]}" -o out.exr) limit=300
    stderr="out\\.exr: cannot write the EXR image: No space left on device" ;;
  animate) outputs=(frames/frame_0000.png frames/frame_0001.png) limit=300
    command=(animate "$scenes/sphere.json" --frames 2 --turntable --size 32x24
      --set field.dimensions=8 --set render.accumulate=1 -o frames)
    stderr="frames/frame_0000\\.png: cannot write the PNG image: No space left on device" ;;
  scene) outputs=(out.json) limit=100
    command=(view --set field.dimensions=8 --size 64x64 --play empty.log --save-scene-on-exit
      out.json)
    stderr="out\\.json: cannot write the scene: No space left on device" ;;
  *) echo "unknown case $case" >&2; exit 2 ;;
esac

# All but the last byte of the .vdb, as a run that succeeds writes it.
if [ "$limit" = all_but_one ]; then
  (cd ../probe && "$cloudvis" "${command[@]}" > /dev/null)
  limit=$(($(stat -c %s ../probe/out.vdb) - 1))
fi
if [ "$case" = vdb_tmpfs ]; then
  mkdir disk
  if ! mount -t tmpfs -o size=16k tmpfs disk 2> mount.txt; then
    echo "SKIP: cannot mount a tmpfs here ($(cat mount.txt)); the preloaded cases cover this"
    exit 77
  fi
  trap 'cd "$work/run" && umount disk' EXIT
  cd disk
fi
printf '# StreamVersion 1.1\n' > empty.log
for output in "${outputs[@]}"; do
  mkdir -p "$(dirname "$output")"
  printf 'previous %s\n' "$output" > "$output"
done
before=$(ls -AR)

status=0
if [ "$case" = vdb_tmpfs ]; then
  "$cloudvis" "${command[@]}" > "$work/stdout.txt" 2> "$work/stderr.txt" || status=$?
else
  env CLOUDVIS_TEST_WRITE_LIMIT=$limit CLOUDVIS_TEST_WRITE_DIR="$PWD" \
    ${suffix:+CLOUDVIS_TEST_WRITE_SUFFIX=$suffix} ${fsync:+CLOUDVIS_TEST_FAIL_FSYNC=1} \
    LD_PRELOAD="$shim${LD_PRELOAD:+:$LD_PRELOAD}" \
    "$cloudvis" "${command[@]}" > "$work/stdout.txt" 2> "$work/stderr.txt" || status=$?
fi
failed=0
fail() {
  echo "FAIL: $*" >&2
  failed=1
}
[ "$status" -eq 1 ] || fail "exit status $status, expected 1"
grep -Eq "^cloudvis: error: $stderr\$" "$work/stderr.txt" || fail "stderr does not match /$stderr/"
[ "$(grep -c "cloudvis: error:" "$work/stderr.txt")" -eq 1 ] || fail "not exactly one error line"
grep -q "^wrote" "$work/stdout.txt" && fail "stdout says it wrote"
for output in "${outputs[@]}"; do
  printf 'previous %s\n' "$output" | cmp -s - "$output" || fail "$output is not the previous file"
done
after=$(ls -AR)
[ "$after" = "$before" ] || fail "files changed: before: $before; after: $after"
if [ "$failed" -ne 0 ]; then
  echo "--- stdout" >&2
  cat "$work/stdout.txt" >&2
  echo "--- stderr" >&2
  cat "$work/stderr.txt" >&2
  exit 1
fi
echo "PASS: $(cat "$work/stderr.txt")"
