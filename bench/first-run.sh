#!/usr/bin/env bash
# The first run as a new user has it (issue 24): `make demo` from a fresh clone on a fresh Debian 12
# machine, apt included, and again from a second fresh clone once the packages are there.
#
#   sudo bench/first-run.sh [ROOT]      (ROOT: a scratch folder, default /srv/cloudvis-first-run)
#
# The fresh machine is a minimal Debian 12 (bookworm) made by debootstrap in ROOT, with only what a
# user needs to have cloned the repository: git, make and CA certificates. The clone is of this
# repository's HEAD. Each `make demo` runs under chroot at nice -19 (NICE to change it), so that
# other work on a shared machine barely slows it; no ccache is installed in the chroot, so every
# file is compiled. Prints each time with the target it is measured against (8 and 6 minutes).
# Needs root, debootstrap and network access to deb.debian.org; leaves ROOT in place (delete it
# with `umount ROOT/{proc,sys,dev/pts,dev}; rm -rf ROOT`).
set -euo pipefail
root=${1:-/srv/cloudvis-first-run}
nice=${NICE:--19}
repo=$(cd "$(dirname "$0")/.." && pwd)
[ "$(id -u)" -eq 0 ] || { echo "bench/first-run.sh: needs root (debootstrap, chroot)" >&2; exit 1; }
[ ! -e "$root" ] || { echo "bench/first-run.sh: $root exists: the machine must be fresh" >&2; exit 1; }
command -v debootstrap > /dev/null || apt-get install -y -q debootstrap > /dev/null

echo "fresh Debian 12 in $root (debootstrap, not timed)"
debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian > "$root.debootstrap.log"
cp /etc/resolv.conf "$root/etc/"
mount -t proc proc "$root/proc"
mount -t sysfs sys "$root/sys"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
chroot "$root" bash -c 'apt-get update -q && apt-get install -y -q --no-install-recommends git make ca-certificates' > /dev/null

# Times `make demo` in a fresh clone at /root/NAME; prints seconds to the end, to the configured
# build (apt done) and to the binary.
demo() {
  local name=$1 clone="$root/root/$1"
  git clone -q "$repo" "$clone"
  local start end
  start=$(date +%s.%N)
  nice -n "$nice" chroot "$root" bash -c "cd /root/$name && make demo" > "$root/root/$name.log" 2>&1
  end=$(date +%s.%N)
  python3 - "$start" "$end" "$(stat -c %Y "$clone/build/CMakeCache.txt")" \
    "$(stat -c %Y "$clone/build/bin/cloudvis")" "$name" "$2" <<'PY'
import sys
start, end, configured, binary = map(float, sys.argv[1:5])
name, target = sys.argv[5], float(sys.argv[6])
print(f"{name:18} make demo {end - start:6.0f} s  (configured after {configured - start:.0f} s, "
      f"binary after {binary - start:.0f} s)  target {target:.0f} s  ratio {(end - start) / target:.2f}")
PY
}
echo "commit $(git -C "$repo" log --oneline -1)"
demo fresh-machine 480
demo packages-present 360
