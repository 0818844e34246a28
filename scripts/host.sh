#!/usr/bin/env bash
# Where rockjoint builds and runs: natively on a Debian 13 host, or inside a Debian 13 root that
# this file bootstraps once on a Debian 12 host. Sourced by build.sh, demo.sh and test.sh.
#
#   rj_run CMD...   runs CMD in the Debian 13 userland (the repository sits at the same path in
#                   the root and on the host, so paths and build trees agree).
#   rj_setup        installs what is missing (Debian packages; on Debian 12, the root first).
#
# The target is DOLFINx 0.9 as Debian 13 packages it (docs/install.md). Variables:
#   ROCKJOINT_DEBIAN13_ROOT  where the root lives (default <repo>/.debian13, git-ignored)
#   ROCKJOINT_MIRROR         Debian mirror for debootstrap (default: the host's apt mirror)
#   ROCKJOINT_NATIVE=1       use the DOLFINx 0.9 already installed (conda-forge, the official
#                            container image): no root, no apt; python3 from PATH (or ROCKJOINT_PYTHON)

rj_repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rj_chroot="${ROCKJOINT_DEBIAN13_ROOT:-$rj_repo/.debian13}"

# The Debian 13 packages: DOLFINx 0.9 stack, compilers, and what the tests, demos and scenes use.
rj_packages=(
  build-essential cmake pkg-config libgtest-dev
  libeigen3-dev libgsl-dev libfftw3-dev pybind11-dev
  python3-dev python3-numpy python3-scipy python3-matplotlib python3-pytest python3-h5py
  python3-meshio python3-yaml
  python3-dolfinx libdolfinx-dev python3-gmsh python3-mpi4py python3-petsc4py
  openmpi-bin
)

rj_log() { echo "rockjoint set-up: $*" >&2; }

rj_sudo() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

# Native when the host is Debian 13 or newer (or the user says so).
rj_native() {
  [ "${ROCKJOINT_NATIVE:-0}" = 1 ] && return 0
  local major
  major="$(cut -d. -f1 /etc/debian_version 2>/dev/null || echo 0)"
  [[ "$major" =~ ^[0-9]+$ ]] && [ "$major" -ge 13 ] && return 0
  grep -q -E '^(trixie|forky|sid)' /etc/debian_version 2>/dev/null
}

rj_missing_packages() {  # prints the packages of rj_packages not installed (in the current userland)
  local p
  for p in "${rj_packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}

rj_host_mirror() {  # the mirror the host's apt already uses
  local uri
  uri="$(grep -h -E '^(URIs:|deb )' /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null |
         grep -v -E 'security|google|nodesource' | head -1 | awk '{print ($1=="deb") ? $2 : $2}')"
  echo "${ROCKJOINT_MIRROR:-${uri:-http://deb.debian.org/debian}}"
}

rj_is_mounted() { mountpoint -q "$1" 2>/dev/null; }

rj_mounts_inside() {  # any mount point below the root (bind mounts of the host)
  awk -v r="$rj_chroot/" 'index($2, r) == 1 {found = 1} END {exit !found}' /proc/mounts
}

rj_mount() {  # /proc, /sys, /dev (MPI needs them) and the repository at its own path
  rj_is_mounted "$rj_chroot/proc" || rj_sudo mount -t proc proc "$rj_chroot/proc"
  rj_is_mounted "$rj_chroot/sys" || { rj_sudo mount --rbind /sys "$rj_chroot/sys"; rj_sudo mount --make-rslave "$rj_chroot/sys"; }
  rj_is_mounted "$rj_chroot/dev" || { rj_sudo mount --rbind /dev "$rj_chroot/dev"; rj_sudo mount --make-rslave "$rj_chroot/dev"; }
  rj_sudo mkdir -p "$rj_chroot$rj_repo"
  rj_is_mounted "$rj_chroot$rj_repo" || rj_sudo mount --bind "$rj_repo" "$rj_chroot$rj_repo"
  rj_sudo cp -L /etc/resolv.conf "$rj_chroot/etc/resolv.conf" 2>/dev/null || true
}

rj_root_in_use() {  # another process (a concurrent build or test) runs inside the root
  local link pid
  for link in /proc/[0-9]*/root; do
    pid="${link#/proc/}"; pid="${pid%/root}"
    [ "$pid" = "$$" ] && continue
    [ "$(readlink "$link" 2>/dev/null)" = "$rj_chroot" ] && return 0
  done
  return 1
}

rj_umount() {  # every mount below the root, deepest first, once no other run works inside it
  rj_root_in_use && return 0
  local m
  # (other checkouts sharing the root through ROCKJOINT_DEBIAN13_ROOT bind their own paths too)
  awk -v r="$rj_chroot/" 'index($2, r) == 1 {print $2}' /proc/mounts | sort -r | while read -r m; do
    rj_sudo umount -l "$m" 2>/dev/null || true
  done
  return 0
}

rj_bootstrap() {  # the Debian 13 root, once per machine (reused while its stamp is there)
  [ -f "$rj_chroot/.rockjoint-root" ] && return 0
  local t0=$SECONDS mirror
  mirror="$(rj_host_mirror)"
  command -v debootstrap >/dev/null || {
    rj_log "installing debootstrap (Debian 12)"
    rj_sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive rj_sudo apt-get install -y -qq --no-install-recommends debootstrap >/dev/null
  }
  rj_log "bootstrapping a Debian 13 root in $rj_chroot from $mirror (once per machine)"
  # A half-built root may still have /dev, /sys, /proc or this repository bound inside it:
  # deleting through a bind mount would delete the host's files. Unmount, and refuse otherwise.
  rj_umount
  if rj_mounts_inside; then
    rj_log "refusing to delete $rj_chroot: something is still mounted inside it (see /proc/mounts)"
    return 1
  fi
  rj_sudo rm -rf --one-file-system "$rj_chroot"
  rj_sudo debootstrap --variant=minbase trixie "$rj_chroot" "$mirror" >"$rj_repo/.debian13.log" 2>&1 || {
    rj_log "debootstrap failed; see $rj_repo/.debian13.log"; tail -5 "$rj_repo/.debian13.log" >&2; return 1; }
  echo "deb $mirror trixie main" | rj_sudo tee "$rj_chroot/etc/apt/sources.list" >/dev/null
  rj_sudo touch "$rj_chroot/.rockjoint-root"
  rj_log "root bootstrapped in $((SECONDS - t0)) s"
}

rj_install_packages() {  # in the current userland (the root's, or a Debian 13 host's)
  local missing
  missing="$(rj_run bash -c "$(declare -p rj_packages); $(declare -f rj_missing_packages); rj_missing_packages" | tr '\n' ' ')"
  if [ -z "${missing// /}" ]; then return 0; fi
  local t0=$SECONDS
  rj_log "installing Debian 13 packages: $missing"
  rj_run env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  # shellcheck disable=SC2086
  rj_run env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null
  rj_log "packages installed in $((SECONDS - t0)) s"
}

rj_run() {
  if rj_native; then
    "$@"
  else
    rj_mount
    local envs=(PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8)
    local v
    for v in PYTHONPATH MPLBACKEND CI OMPI_ALLOW_RUN_AS_ROOT OMPI_ALLOW_RUN_AS_ROOT_CONFIRM \
             OMPI_MCA_btl OMPI_MCA_pml OMPI_MCA_rmaps_base_oversubscribe ROCKJOINT_BUILD_DIR \
             OMP_NUM_THREADS CTEST_OUTPUT_ON_FAILURE; do
      [ -n "${!v+x}" ] && envs+=("$v=${!v}")
    done
    rj_sudo chroot "$rj_chroot" /usr/bin/env -i "${envs[@]}" bash -c 'cd "$0" 2>/dev/null || cd /; exec "$@"' "$PWD" "$@"
  fi
}

rj_setup() {
  if [ "${ROCKJOINT_NATIVE:-0}" = 1 ]; then
    return 0  # the user's own DOLFINx 0.9 (conda-forge, container image): nothing to install
  fi
  if ! rj_native; then
    rj_bootstrap
    trap rj_umount EXIT
  fi
  rj_install_packages
}

# The Python that imports DOLFINx: Debian's /usr/bin/python3, or the user's with ROCKJOINT_NATIVE=1.
if [ "${ROCKJOINT_NATIVE:-0}" = 1 ]; then
  rj_python="${ROCKJOINT_PYTHON:-$(command -v python3)}"
else
  rj_python="${ROCKJOINT_PYTHON:-/usr/bin/python3}"
fi

# Open MPI as root, on shared memory only (the TCP transport warns about unreachable interface
# pairs inside the root and is not needed on one machine).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"
