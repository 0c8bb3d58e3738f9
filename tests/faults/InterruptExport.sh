#!/usr/bin/env bash
# An export ended by a signal: starts `cloudvis generate` on a field large enough that writing it
# takes a while, waits until its temporary file (.NAME.tmp-XXXXXX.vti, see
# app/common/public/AtomicFile.h) appears and sends the signal (mode "kill"), or lets the write
# run into a file-size limit of 1 MiB, which the kernel enforces with SIGXFSZ (mode "limit").
# Then checks that cloudvis ended by that signal, as its default action ends a process (not an
# exit status that merely looks like one: a perl parent reports what waitpid saw), that no
# temporary is left, and that the target holds what it held before (the previous file, or
# nothing).
# usage: InterruptExport.sh CLOUDVIS WORK_DIR SIGNAL previous|none kill|limit
set -euo pipefail
# Job control: without it, bash starts background commands with SIGINT and SIGQUIT ignored.
set -m
cloudvis=$1 work=$2 signal=$3 previous=$4 mode=$5
number=$(kill -l "$signal")

rm -rf "$work"
mkdir -p "$work"
cd "$work"
if [ "$previous" = previous ]; then
  printf 'the previous field\n' > out.vti
fi
# SIGQUIT, SIGXFSZ and SIGABRT dump core by default: not here.
ulimit -c 0

temporaries() { compgen -G '.out.vti.tmp-*' || true; }

. "$(dirname "$0")/RunAndRecord.sh"

# 320^3 voxels: about 130 MB of floats to compress, a second or more of writing (7 MB written).
command=("$cloudvis" generate --set field.dimensions=320 --set field.octaves=1 -o out.vti)
if [ "$mode" = limit ]; then
  (ulimit -f 1024 && run_and_record "${command[@]}") > stdout.txt 2> stderr.txt &
else
  run_and_record "${command[@]}" > stdout.txt 2> stderr.txt &
fi
parent=$!

if [ "$mode" = kill ]; then
  has_temporary() { [ -n "$(temporaries)" ]; }
  # Up to 10 minutes, for slow sanitized builds.
  signal_when_ready has_temporary 12000 "its temporary file" "$signal"
fi
wait "$parent"

failed=0
ending=$(cat ending.txt)
if [ "$ending" != "signal $number" ]; then
  echo "FAIL: cloudvis ended with $ending, expected signal $number (SIG$signal)" >&2
  cat stderr.txt >&2
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
  echo "SIG$signal ($mode): ended by signal $number, no temporary left, target as before ($previous)"
fi
exit "$failed"
