#!/usr/bin/env bash
# An export interrupted by a signal: starts `cloudvis generate` on a field large enough that
# writing it takes a while, waits until its temporary file (.NAME.tmp-XXXXXX.vti, see
# app/common/public/AtomicFile.h) appears, sends the signal, then checks that cloudvis exited with
# 128 + signal, that no temporary is left, and that the target holds what it held before
# (the previous file, or nothing).
# usage: InterruptExport.sh CLOUDVIS WORK_DIR SIGNAL(INT|TERM) EXPECTED_STATUS previous|none
set -euo pipefail
# Job control: without it, bash starts background commands with SIGINT ignored.
set -m
cloudvis=$1 work=$2 signal=$3 expected=$4 previous=$5

rm -rf "$work"
mkdir -p "$work"
cd "$work"
if [ "$previous" = previous ]; then
  printf 'the previous field\n' > out.vti
fi

temporaries() { compgen -G '.out.vti.tmp-*' || true; }

# 320^3 voxels: about 130 MB of floats to compress, a second or more of writing.
"$cloudvis" generate --set field.dimensions=320 --set field.octaves=1 -o out.vti \
  > stdout.txt 2> stderr.txt &
pid=$!
for _ in $(seq 1 12000); do # up to 10 minutes, for slow sanitized builds
  if [ -n "$(temporaries)" ]; then
    break
  fi
  if ! kill -0 "$pid" 2> /dev/null; then
    echo "FAIL: cloudvis ended before its temporary file appeared" >&2
    cat stderr.txt >&2
    exit 1
  fi
  sleep 0.05
done
if [ -z "$(temporaries)" ]; then
  echo "FAIL: no temporary file appeared" >&2
  kill -KILL "$pid"
  exit 1
fi
kill -s "$signal" "$pid"
status=0
wait "$pid" || status=$?

failed=0
if [ "$status" -ne "$expected" ]; then
  echo "FAIL: exit status $status, expected $expected" >&2
  failed=1
fi
left=$(temporaries)
if [ -n "$left" ]; then
  echo "FAIL: temporary left behind: $left" >&2
  failed=1
fi
if [ "$previous" = previous ]; then
  if [ "$(cat out.vti)" != "the previous field" ]; then
    echo "FAIL: the previous target was changed" >&2
    failed=1
  fi
elif [ -e out.vti ]; then
  echo "FAIL: a target appeared although the export was interrupted" >&2
  failed=1
fi
if [ "$failed" -eq 0 ]; then
  echo "SIG$signal: exit status $status, no temporary left, target as before ($previous)"
fi
exit "$failed"
