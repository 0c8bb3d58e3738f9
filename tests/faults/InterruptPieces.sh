#!/usr/bin/env bash
# A .pvti generation interrupted by a signal, in one process or under mpirun: the output is
# replaced as one (app/fields/public/FieldPieces.h), so whatever the moment the signal lands
# before the new output is complete, the previous output stays byte for byte as it was (or there
# is none), no temporary (the run's directory .out.pvti.tmp-RUN/ or anything in it) is left, and
# `cloudvis info` reads the previous field.
#
# The previous output is a field of the same lattice and piece count with another seed, so a
# piece of the new run among the old ones would assemble without complaint from VTK: the mixed
# output the issue found, which `info` accepted.
#
# Moments:
#   during    as soon as the run's directory of temporaries appears (real timing: the first
#             piece is being generated; the field is large enough that a piece takes seconds,
#             more than the second Open MPI's mpirun waits before it passes SIGTERM on)
#   writing   as soon as the first piece's temporary appears in it (it is being written)
#   pausedK   once K pieces are written as temporaries (CLOUDVIS_TEST_PAUSE_AFTER_PIECE makes
#             each process announce each piece and pause): K = 1 of 2 is between the pieces,
#             K = all is after the last piece, before the renames
# usage: InterruptPieces.sh CLOUDVIS WORK_DIR SIGNAL previous|none single|MPIRUN MOMENT
set -euo pipefail
# Job control: without it, bash starts background commands with SIGINT and SIGQUIT ignored.
set -m
cloudvis=$1 work=$2 signal=$3 previous=$4 launcher=$5 moment=$6
number=$(kill -l "$signal")

rm -rf "$work"
mkdir -p "$work"
cd "$work"
ulimit -c 0

# Open MPI in a container, as root, on one machine (as tests/app/MpiGeneration.cmake).
export OMPI_MCA_plm_rsh_agent= OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_oob_tcp_if_include=lo OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

if [ "$moment" = during ] || [ "$moment" = writing ]; then
  # 2 pieces of 400 x 400 x 200 voxels, 8 octaves: 3 s or more each to generate and compress on
  # a 2-core machine, 7 s for the whole under mpirun -np 2.
  dimensions=400,400,400
  octaves=8
else
  dimensions=64,48,40
  octaves=2
fi
field=(--set "field.dimensions=$dimensions" --set "field.octaves=$octaves")
output="$work/out.pvti"

if [ "$previous" = previous ]; then
  "$cloudvis" generate "${field[@]}" --set field.seed=11 -o "$output" --pieces 2 > /dev/null
fi
snapshot() { find . -maxdepth 1 -name 'out*' -type f -printf '%f\n' | sort | xargs -r sha256sum; }
before=$(snapshot)
temporaries() { compgen -G '.out*.tmp-*' || true; }

. "$(dirname "$0")/RunAndRecord.sh"

command=("$cloudvis" generate "${field[@]}" --set field.seed=22 -o "$output" --pieces 2)
if [ "$launcher" != single ]; then
  command=("$launcher" --oversubscribe -np 2 "${command[@]}")
fi
# Long enough for the signal to land during the pause: mpirun passes it on as SIGTERM after 1 s.
pause=0
case "$moment" in
  paused*) pause=$([ "$launcher" = single ] && echo 6 || echo 30) ;;
esac
CLOUDVIS_TEST_PAUSE_AFTER_PIECE=$pause run_and_record "${command[@]}" > stdout.txt 2> stderr.txt &
parent=$!

ready() {
  case "$moment" in
    during) [ -n "$(compgen -G '.out.pvti.tmp-*' || true)" ] ;;
    writing) [ -n "$(compgen -G '.out.pvti.tmp-*/out_0.vti' || true)" ] ;;
    paused*) [ "$(grep -c "paused after piece" stderr.txt || true)" -ge "${moment#paused}" ] ;;
  esac
}
# Up to 5 minutes, for slow sanitized builds.
signal_when_ready ready 6000 "the moment ($moment)" "$signal"
wait "$parent"
# Under mpirun, wait until no process of this run is left: a rank that went on after mpirun
# returned would still be writing.
for _ in $(seq 1 600); do
  if ! pgrep -f -- "-o $output" > /dev/null; then
    break
  fi
  sleep 0.05
done

failed=0
ending=$(cat ending.txt)
if [ "$launcher" = single ] && [ "$ending" != "signal $number" ]; then
  echo "FAIL: cloudvis ended with $ending, expected signal $number (SIG$signal)" >&2
  failed=1
elif [ "$ending" = "exit 0" ]; then
  echo "FAIL: mpirun exited 0 although interrupted" >&2
  failed=1
fi
if pgrep -f -- "-o $output" > /dev/null; then
  echo "FAIL: processes of the interrupted run are still running: $(pgrep -f -- "-o $output")" >&2
  failed=1
fi
left=$(temporaries)
if [ -n "$left" ]; then
  echo "FAIL: temporaries left behind: $left" >&2
  failed=1
fi
after=$(snapshot)
if [ "$after" != "$before" ]; then
  echo "FAIL: the output changed although the generation was interrupted" >&2
  echo "before:" >&2
  echo "$before" >&2
  echo "after:" >&2
  echo "$after" >&2
  failed=1
fi
if [ "$previous" = previous ]; then
  if ! "$cloudvis" info "$output" > info.txt 2>&1; then
    echo "FAIL: info refuses the previous output:" >&2
    cat info.txt >&2
    failed=1
  fi
fi
if [ "$failed" -ne 0 ]; then
  echo "stderr of the interrupted run:" >&2
  cat stderr.txt >&2
else
  echo "SIG$signal ($launcher, $moment): $ending, no temporary left, output as before ($previous)"
fi
exit "$failed"
