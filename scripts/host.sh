#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Where rockjoint builds and runs, for the DOLFINx version chosen by ROCKJOINT_DOLFINX:
#   0.11 (default)  Debian unstable ("sid"): DOLFINx 0.11.0.post0, PETSc 3.25.5, gmsh 4.15.2
#   0.9             Debian 13 ("trixie"):    DOLFINx 0.9.0,        PETSc 3.22.4, gmsh 4.13.1
# natively where the host already is that Debian, otherwise inside a root of it that this file
# bootstraps once per machine and version (git-ignored .debian-sid/ or .debian13/) and reuses.
# Sourced by build.sh, demo.sh, test.sh and run.sh.
#
#   rj_run CMD...   runs CMD in the chosen userland (the repository sits at the same path in the
#                   root and on the host, so paths and build trees agree).
#   rj_setup        installs what is missing (on a foreign host, the root first).
#
# Variables:
#   ROCKJOINT_DOLFINX    0.11 (default) or 0.9
#   ROCKJOINT_ROOT       where the root lives (default <repo>/.debian-sid or <repo>/.debian13)
#   ROCKJOINT_BUILD_DIR  build tree (default <repo>/build for 0.11, <repo>/build-0.9 for 0.9)
#   ROCKJOINT_MIRROR     Debian mirror for debootstrap and apt (default: the host's apt mirror)
#   ROCKJOINT_NATIVE=1   use a DOLFINx already installed (conda-forge, the official container
#                        image): no root, no apt; python3 from PATH (or ROCKJOINT_PYTHON)

rj_repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rj_dolfinx="${ROCKJOINT_DOLFINX:-0.11}"

# The FE stack of each version, pinned to the Debian versions it was tested with (docs/install.md).
case "$rj_dolfinx" in
  0.11)
    rj_suite=sid; rj_root_name=.debian-sid; rj_build_name=build
    # sid on a snapshot archive: its Release file may be past its Valid-Until date.
    rj_apt_opts=(-o Acquire::Check-Valid-Until=false)
    rj_pins=(python3-dolfinx=1:0.11.0.post0-7 libdolfinx-dev=1:0.11.0.post0-7
             python3-basix=0.11.0-2+b2 python3-ufl=2026.1.0-3
             python3-petsc4py=3.25.5-2 python3-gmsh=4.15.2+ds1-1)
    # The API reference (scripts/docs.sh) and the pip install test are built on 0.11 only.
    rj_tools=(python3-sphinx furo python3-myst-parser python3-breathe doxygen
              python3-scikit-build-core python3-venv python3-pip) ;;
  0.9)
    rj_suite=trixie; rj_root_name=.debian13; rj_build_name=build-0.9
    rj_apt_opts=()
    rj_pins=(python3-dolfinx=1:0.9.0-7 libdolfinx-dev=1:0.9.0-7
             python3-basix=0.9.0-2+b2 python3-ufl=2024.2.0-3
             python3-petsc4py=3.22.4-1 python3-gmsh=4.13.1+ds1-6)
    rj_tools=() ;;
  *)
    echo "rockjoint set-up: ROCKJOINT_DOLFINX='$rj_dolfinx' is not supported: use 0.11 or 0.9" >&2
    return 2 2>/dev/null || exit 2 ;;
esac
rj_chroot="${ROCKJOINT_ROOT:-$rj_repo/$rj_root_name}"
rj_build_dir="${ROCKJOINT_BUILD_DIR:-$rj_repo/$rj_build_name}"

# Compilers, libraries, and what the tests, demos and scenes use (unpinned: any version of the suite).
rj_packages=(
  build-essential cmake pkg-config libgtest-dev
  libeigen3-dev libgsl-dev libfftw3-dev libsuitesparse-dev pybind11-dev
  python3-dev python3-numpy python3-scipy python3-matplotlib python3-pytest python3-h5py
  python3-meshio python3-yaml python3-mpi4py openmpi-bin
  "${rj_pins[@]}" "${rj_tools[@]}"
)

rj_log() { echo "rockjoint set-up: $*" >&2; }

rj_sudo() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

rj_host_suite() {  # trixie, sid (also forky/sid) or another, from the host's /etc/debian_version
  local v
  v="$(cat /etc/debian_version 2>/dev/null || echo 0)"
  case "$v" in
    13.*|trixie*) echo trixie ;;
    */sid|sid*) echo sid ;;
    *) echo other ;;
  esac
}

# Native when the host is the chosen suite (or the user says so).
rj_native() {
  [ "${ROCKJOINT_NATIVE:-0}" = 1 ] && return 0
  [ "$(rj_host_suite)" = "$rj_suite" ]
}

rj_missing_packages() {  # prints the entries of rj_packages (name or name=version) not installed
  local p name want have
  for p in "${rj_packages[@]}"; do
    name="${p%%=*}"; want="${p#*=}"; [ "$want" = "$p" ] && want=""
    have="$(dpkg-query -W -f='${Status} ${Version}' "$name" 2>/dev/null)"
    case "$have" in
      "install ok installed "*) [ -z "$want" ] || [ "${have##* }" = "$want" ] || echo "$p" ;;
      *) echo "$p" ;;
    esac
  done
}

rj_check_pins() {  # every pinned version still in the archive, or a clear error naming it
  local p name want missing=()
  for p in "${rj_pins[@]}"; do
    name="${p%%=*}"; want="${p#*=}"
    apt-cache madison "$name" 2>/dev/null | awk -F'|' '{gsub(/ /, "", $2); print $2}' | grep -qxF "$want" ||
      missing+=("$name $want (archive has: $(apt-cache madison "$name" 2>/dev/null | awk -F'|' '{gsub(/ /, "", $2); print $2}' | tr '\n' ' '))")
  done
  if [ "${#missing[@]}" -gt 0 ]; then
    printf 'rockjoint set-up: the Debian archive no longer has the pinned version of:\n' >&2
    printf '  %s\n' "${missing[@]}" >&2
    printf 'rockjoint is tested with these versions (scripts/host.sh, docs/install.md).\n' >&2
    return 1
  fi
}

rj_host_mirror() {  # the mirror the host's apt already uses
  local uri
  uri="$(grep -h -E '^(URIs:|deb )' /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null |
         grep -v -E 'security|google|nodesource' | head -1 | awk '{print $2}')"
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
  awk -v r="$rj_chroot/" 'index($2, r) == 1 {print $2}' /proc/mounts | sort -r | while read -r m; do
    rj_sudo umount -l "$m" 2>/dev/null || true
  done
  return 0
}

rj_bootstrap() {  # the root of the chosen suite, once per machine (reused while its stamp is there)
  [ -f "$rj_chroot/.rockjoint-root" ] && return 0
  local t0=$SECONDS mirror log="$rj_chroot.log"
  mirror="$(rj_host_mirror)"
  command -v debootstrap >/dev/null || {
    rj_log "installing debootstrap on the host"
    rj_sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive rj_sudo apt-get install -y -qq --no-install-recommends debootstrap >/dev/null
  }
  rj_log "bootstrapping a Debian $rj_suite root in $rj_chroot from $mirror (once per machine)"
  # A half-built root may still have /dev, /sys, /proc or this repository bound inside it:
  # deleting through a bind mount would delete the host's files. Unmount, and refuse otherwise.
  rj_umount
  if rj_mounts_inside; then
    rj_log "refusing to delete $rj_chroot: something is still mounted inside it (see /proc/mounts)"
    return 1
  fi
  rj_sudo rm -rf --one-file-system "$rj_chroot"
  rj_sudo debootstrap --variant=minbase "$rj_suite" "$rj_chroot" "$mirror" >"$log" 2>&1 || {
    rj_log "debootstrap failed; see $log"; tail -5 "$log" >&2; return 1; }
  echo "deb $mirror $rj_suite main" | rj_sudo tee "$rj_chroot/etc/apt/sources.list" >/dev/null
  rj_sudo touch "$rj_chroot/.rockjoint-root"
  rj_log "root bootstrapped in $((SECONDS - t0)) s"
}

rj_install_packages() {  # in the current userland (the root's, or a native host's)
  local missing
  missing="$(rj_run bash -c "$(declare -p rj_packages); $(declare -f rj_missing_packages); rj_missing_packages" | tr '\n' ' ')"
  if [ -z "${missing// /}" ]; then return 0; fi
  local t0=$SECONDS
  rj_log "installing Debian $rj_suite packages for DOLFINx $rj_dolfinx: $missing"
  rj_run env DEBIAN_FRONTEND=noninteractive apt-get "${rj_apt_opts[@]}" update -qq
  rj_run bash -c "$(declare -p rj_pins); $(declare -f rj_check_pins); rj_check_pins" || return 1
  # shellcheck disable=SC2086
  rj_run env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    --allow-downgrades $missing >/dev/null
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
             ROCKJOINT_DOLFINX ROCKJOINT_REQUIRE_FE OMP_NUM_THREADS CTEST_OUTPUT_ON_FAILURE \
             ROCKJOINT_FFT_THREADS; do
      [ -n "${!v+x}" ] && envs+=("$v=${!v}")
    done
    rj_sudo chroot "$rj_chroot" /usr/bin/env -i "${envs[@]}" bash -c 'cd "$0" 2>/dev/null || cd /; exec "$@"' "$PWD" "$@"
  fi
}

rj_setup() {
  if [ "${ROCKJOINT_NATIVE:-0}" = 1 ]; then
    return 0  # the user's own DOLFINx (conda-forge, container image): nothing to install
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
export ROCKJOINT_DOLFINX="$rj_dolfinx" ROCKJOINT_BUILD_DIR="$rj_build_dir"
