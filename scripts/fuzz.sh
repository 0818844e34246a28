#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Coverage-guided fuzzing of the C++ readers of user files (libFuzzer + AddressSanitizer + UBSan,
# Debian unstable's clang) in the root of scripts/host.sh. Not part of CI (docs/fuzzing.md).
#   bash scripts/fuzz.sh build                   installs clang once, builds build-fuzz/fuzz_*
#   bash scripts/fuzz.sh run TARGET SECONDS      fuzzes one reader on one core from its corpus
#   bash scripts/fuzz.sh repro TARGET FILE...    runs the target once on each FILE
# TARGET: law_table (.rjt), height_grid (text height grid), xyz (XYZ point list).
set -euo pipefail
export ROCKJOINT_DOLFINX=0.11  # clang with libFuzzer from the same Debian unstable root
source "$(dirname "${BASH_SOURCE[0]}")/host.sh"
out="$rj_repo/build-fuzz"
targets=(law_table height_grid xyz)

# What each target compiles besides itself: the reader and what it calls, nothing more.
sources_of() {
  case "$1" in
    law_table) echo constitutive/law_table_file.cpp constitutive/tabulated_law.cpp \
                    constitutive/adaptive_knots.cpp constitutive/closure_law.cpp ;;
    height_grid|xyz) echo topography/surface_io.cpp topography/surface.cpp topography/units.cpp ;;
    *) echo "fuzz.sh: unknown target '$1' (use: ${targets[*]})" >&2; return 2 ;;
  esac
}

fuzz_install() {  # clang, compiler-rt (libFuzzer, the sanitizers), llvm-symbolizer (stack traces)
  rj_setup
  rj_run bash -c 'command -v clang++ >/dev/null && command -v llvm-symbolizer >/dev/null && ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1' && return 0
  rj_log "installing clang, libclang-rt-dev and llvm for fuzzing"
  rj_run env DEBIAN_FRONTEND=noninteractive apt-get "${rj_apt_opts[@]}" update -qq
  rj_run env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    clang libclang-rt-dev llvm >/dev/null
}

fuzz_build() {
  fuzz_install
  # Headers as <rockjoint/<folder>/...> (the layout of the build tree), pointing at the sources.
  mkdir -p "$out/include/rockjoint"
  ln -sfn "$rj_repo/constitutive" "$out/include/rockjoint/constitutive"
  ln -sfn "$rj_repo/topography" "$out/include/rockjoint/topography"
  local t flags=(-std=c++20 -g -O1 -fno-omit-frame-pointer
                 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
                 -I"$out/include" -I/usr/include/eigen3)
  for t in "${targets[@]}"; do
    # shellcheck disable=SC2046
    (cd "$rj_repo" && rj_run clang++ "${flags[@]}" fuzz/fuzz_"$t".cpp $(sources_of "$t") \
       -o "$out/fuzz_$t")
    rj_log "built $out/fuzz_$t"
  done
}

fuzz_run() {  # one core, a fresh working corpus seeded from fuzz/corpus/TARGET
  local t="$1" seconds="$2" dict=()
  sources_of "$t" >/dev/null
  [ -x "$out/fuzz_$t" ] || fuzz_build
  mkdir -p "$out/corpus/$t" "$out/artifacts/$t"
  [ -f "$rj_repo/fuzz/$t.dict" ] && dict=(-dict="$rj_repo/fuzz/$t.dict")
  # Hangs (10 s per input) and memory above 2 GB count as failures like crashes.
  rj_run env ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$out/fuzz_$t" "$out/corpus/$t" "$rj_repo/fuzz/corpus/$t" "${dict[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$out/artifacts/$t/"
}

case "${1:-}" in
  build) fuzz_build ;;
  run) [ $# -eq 3 ] || { echo "usage: fuzz.sh run TARGET SECONDS" >&2; exit 2; }; fuzz_run "$2" "$3" ;;
  repro) [ $# -ge 3 ] || { echo "usage: fuzz.sh repro TARGET FILE..." >&2; exit 2; }
         t="$2"; shift 2; [ -x "$out/fuzz_$t" ] || fuzz_build; rj_run "$out/fuzz_$t" "$@" ;;
  *) sed -n '2,7p' "$0" >&2; exit 2 ;;
esac
