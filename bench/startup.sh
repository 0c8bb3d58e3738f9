#!/usr/bin/env bash
# Start-up cost of cloudvis, and what MPI adds when mpirun starts it (docs/performance.md,
# "Start-up and MPI"): the median wall time of N runs of each command, in milliseconds.
# Usage: bench/startup.sh [CLOUDVIS] [N]   (default build/bin/cloudvis, 15 runs)
set -euo pipefail
cloudvis=${1:-build/bin/cloudvis}
runs=${2:-15}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Open MPI on one machine, as the test does (tests/app/MpiGeneration.cmake).
export OMPI_MCA_plm_rsh_agent= OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
median() { # command...: the median of $runs wall times in ms
  local times=()
  for _ in $(seq "$runs"); do
    local start end
    start=$(date +%s%N)
    "$@" > /dev/null 2>&1
    end=$(date +%s%N)
    times+=($(( (end - start) / 1000 )))
  done
  printf '%s\n' "${times[@]}" | sort -n | awk '{ a[NR] = $1 } END { printf "%.1f", a[int((NR + 1) / 2)] / 1000 }'
}
field=(--set field.dimensions=8 -o "$work/x.pvti")
printf '%-52s %8s ms\n' "cloudvis --help" "$(median "$cloudvis" --help)"
printf '%-52s %8s ms\n' "cloudvis generate (8^3, .pvti), no MPI" "$(median "$cloudvis" generate "${field[@]}")"
printf '%-52s %8s ms\n' "mpirun -np 1 /bin/true (the launcher alone)" "$(median mpirun -np 1 /bin/true)"
printf '%-52s %8s ms\n' "mpirun -np 1 cloudvis generate (MPI_Init, Finalize)" "$(median mpirun -np 1 "$cloudvis" generate "${field[@]}")"
printf '%-52s %8s ms\n' "mpirun -np 2 cloudvis generate" "$(median mpirun -np 2 "$cloudvis" generate "${field[@]}")"
